// Keys, macros and the gamepad's steps as the pendant: action and key names, the profile's key
// bindings (a bad one told at its line and left out), the events keys make at a terminal (no
// release: the dead-man rule) and in a window, the macros from the profile, the XHC Lead knob
// and display frame, and a gamepad's D-pad as exact steps, on the controller and the
// simulated card.
#include <gtest/gtest.h>
#include <linux/input-event-codes.h>

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <thread>

#include "gantry/interp/operator_io.hpp"
#include "gantry/lang/script.hpp"
#include "gantry/session/console_help.hpp"
#include "gantry/session/gamepad_pendant.hpp"
#include "gantry/session/key_bindings.hpp"
#include "gantry/session/pendant_action.hpp"
#include "gantry/session/pendant_input.hpp"
#include "gantry/session/pendant_profile.hpp"
#include "gantry/session/pendant_xhc.hpp"
#include "pendant/xhc_protocol.hpp"
#include "pendant_bench.hpp"  // Bench, FakeClock, report
#include "sim/sim_card.hpp"

namespace gantry::session {
namespace {

using namespace std::chrono_literals;
namespace fs = std::filesystem;
using Clock = KeyPendant::Clock;

// ---- names ---------------------------------------------------------------------------------

TEST(PendantAction, NamesButtonsContinuousJogsAndStepJogs) {
  auto e = pendant_action_named("Feed +");
  ASSERT_TRUE(e);
  EXPECT_EQ(e->kind, PendantEvent::Kind::Button);
  EXPECT_EQ(e->button, PendantButton::FeedPlus);
  e = pendant_action_named("macro 10");
  ASSERT_TRUE(e);
  EXPECT_EQ(e->button, PendantButton::Macro);
  EXPECT_EQ(e->macro, 10);
  e = pendant_action_named("jog z- 50%");
  ASSERT_TRUE(e);
  EXPECT_EQ(e->kind, PendantEvent::Kind::Wheel);
  EXPECT_EQ(e->axis, 2);
  EXPECT_EQ(e->delta, -1);
  EXPECT_EQ(e->step, 0);
  EXPECT_EQ(e->percent, 50);
  e = pendant_action_named("  STEP  a+  ");
  ASSERT_TRUE(e);
  EXPECT_EQ(e->axis, 3);
  EXPECT_EQ(e->delta, 1);
  EXPECT_EQ(e->step, kKeypadStep);
  e = pendant_action_named("step y- 0.01");
  ASSERT_TRUE(e);
  EXPECT_DOUBLE_EQ(e->step, 0.01);
  for (const char* bad : {"fly", "macro 11", "macro 0", "jog q+", "jog x", "jog x+ 150%",
                          "step x+ -1", "step x+ 0.1 2", "macro"})
    EXPECT_FALSE(pendant_action_named(bad)) << bad;
}

TEST(KeyNames, AreWrittenOneWayWhateverTheProfileSaid) {
  std::string why;
  EXPECT_EQ(key_name("ctrl+right", &why), "Ctrl+Right");
  EXPECT_EQ(key_name("f5", &why), "F5");
  EXPECT_EQ(key_name("Shift+F5", &why), "Shift+F5");
  EXPECT_EQ(key_name("alt + ctrl + pgup", &why), "Ctrl+Alt+PageUp");
  EXPECT_EQ(key_name("Shift+a", &why), "A");
  EXPECT_EQ(key_name("a", &why), "a");
  EXPECT_EQ(key_name("+", &why), "+");
  EXPECT_EQ(key_name("ctrl+g", &why), "Ctrl+G");
  EXPECT_EQ(key_name("esc", &why), "Escape");
  EXPECT_FALSE(key_name("F13", &why));
  EXPECT_NE(why.find("is not a key"), std::string::npos) << why;
  EXPECT_FALSE(key_name("Ctrl+C", &why));  // the console's E-stop
  EXPECT_NE(why.find("E-stop"), std::string::npos) << why;
  EXPECT_FALSE(key_name("!", &why));
  EXPECT_FALSE(key_name("F12", &why));  // the window's E-stop
  EXPECT_FALSE(key_name("Hyper+x", &why));
  EXPECT_FALSE(key_name("Ctrl+5", &why));
}

TEST(KeyBindings, ABadItemIsAProblemAndLeftOutTheOthersBind) {
  std::vector<KeyBindings::Problem> problems;
  const KeyBindings b = KeyBindings::parse(
      {"F5 = start/pause", "F99 = stop", "F6 = fly", "f5 = stop", "Ctrl+Right = jog x+", "F7"},
      &problems);
  ASSERT_EQ(problems.size(), 4u);
  EXPECT_EQ(problems[0].item, 1u);
  EXPECT_EQ(problems[1].item, 2u);
  EXPECT_NE(problems[1].message.find("\"fly\" is not an action"), std::string::npos);
  EXPECT_EQ(problems[2].item, 3u);
  EXPECT_NE(problems[2].message.find("bound twice"), std::string::npos);
  EXPECT_EQ(problems[3].item, 5u);
  ASSERT_EQ(b.all().size(), 2u);
  ASSERT_TRUE(b.find("F5"));
  EXPECT_EQ(b.find("F5")->button, PendantButton::StartPause);
  ASSERT_TRUE(b.find("Ctrl+Right"));
  EXPECT_EQ(b.find("Ctrl+Right")->axis, 0);
  EXPECT_FALSE(b.find("F6"));
}

// The help lists a bound key's action as the profile may write it: read back, the same event.
TEST(PendantAction, EveryActionsTextReadsBackAsTheSameEvent) {
  for (const char* name :
       {"reset",          "stop",         "start/pause",  "feed +",       "feed -",
        "spindle +",      "spindle -",    "machine home", "safe z",       "work home",
        "spindle on/off", "probe z",      "macro 1",      "macro 10",     "jog x+",
        "jog c- 50%",     "jog y+ 12.5%", "step a+",      "step z- 0.01", "step b+ 2.5"}) {
    const std::optional<PendantEvent> e = pendant_action_named(name);
    ASSERT_TRUE(e) << name;
    EXPECT_EQ(pendant_action_text(*e), name);
    const std::optional<PendantEvent> back = pendant_action_named(pendant_action_text(*e));
    ASSERT_TRUE(back) << name;
    EXPECT_EQ(back->kind, e->kind) << name;
    EXPECT_EQ(back->button, e->button) << name;
    EXPECT_EQ(back->macro, e->macro) << name;
    EXPECT_EQ(back->axis, e->axis) << name;
    EXPECT_EQ(back->delta, e->delta) << name;
    EXPECT_EQ(back->step, e->step) << name;
    EXPECT_EQ(back->percent, e->percent) << name;
  }
  EXPECT_EQ(pendant_action_text({.kind = PendantEvent::Kind::Lost}), "");
}

// HELP at both front ends lists the bound keys from the bindings, after the front end's keys.
TEST(KeyBindings, TheFrontEndsHelpListsTheBoundKeysFromTheBindings) {
  const KeyBindings b = KeyBindings::parse(
      {"F5 = start/pause", "alt+x = step y+ 0.5", "Ctrl+Right = jog x+ 30%"}, nullptr);
  const std::string list = bound_keys_help(b);
  EXPECT_EQ(list,
            "Keys bound in the profile's [pendant] keys (they act in every mode):\n"
            "  Alt+x       step y+ 0.5\n"
            "  Ctrl+Right  jog x+ 30%\n"
            "  F5          start/pause\n");
  for (const FrontEnd f : {FrontEnd::Terminal, FrontEnd::Window}) {
    const std::string all = keys_help(f, &b);
    EXPECT_EQ(all, keys_help(f) + list);
    EXPECT_EQ(help_answer(f, "", &b).text, all);
  }
  EXPECT_EQ(bound_keys_help(KeyBindings{}), "");
  EXPECT_EQ(keys_help(FrontEnd::Terminal, nullptr), keys_help(FrontEnd::Terminal));
}

// ---- the events keys make ------------------------------------------------------------------

KeyBindings bindings(const std::vector<std::string>& items) {
  std::vector<KeyBindings::Problem> problems;
  KeyBindings b = KeyBindings::parse(items, &problems);
  EXPECT_TRUE(problems.empty());
  return b;
}

TEST(KeyPendant, AtATerminalAJogKeyReportsEachRepeatAndOtherKeysActOncePerPress) {
  KeyPendant k(bindings({"Right = jog x+", "F5 = start/pause", "F6 = step y+ 0.5"}), 600ms);
  const Clock::time_point t0{};
  std::vector<PendantEvent> out;
  EXPECT_FALSE(k.key("Left", t0, out));  // not bound: the console's own
  for (int i = 0; i < 5; ++i) EXPECT_TRUE(k.key("Right", t0 + i * 30ms, out));
  ASSERT_EQ(out.size(), 5u);  // each repeat keeps the jog alive (the dead-man rule ends it)
  EXPECT_EQ(out[4].kind, PendantEvent::Kind::Wheel);
  EXPECT_EQ(out[4].step, 0);
  out.clear();
  // F5 held: pressed at 1 s, the terminal repeats from 1.5 s every 30 ms: one start/pause.
  EXPECT_TRUE(k.key("F5", t0 + 1000ms, out));
  for (int i = 0; i < 10; ++i) EXPECT_TRUE(k.key("F5", t0 + 1500ms + i * 30ms, out));
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].button, PendantButton::StartPause);
  out.clear();
  EXPECT_TRUE(k.key("F5", t0 + 3000ms, out));  // pressed again later: acts again
  EXPECT_TRUE(k.key("F6", t0 + 3010ms, out));
  EXPECT_TRUE(k.key("F6", t0 + 3040ms, out));  // its repeat: no second step
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[1].kind, PendantEvent::Kind::Wheel);
  EXPECT_DOUBLE_EQ(out[1].step, 0.5);
}

TEST(KeyPendant, InAWindowAHeldJogKeyReportsEvery40MsAndItsReleaseEndsTheJog) {
  KeyPendant k(bindings({"Ctrl+Up = jog y+ 30%", "F5 = stop"}));
  const Clock::time_point t0{};
  std::vector<PendantEvent> out;
  EXPECT_TRUE(k.press("Ctrl+Up", false, t0, out));
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].axis, 1);
  EXPECT_EQ(out[0].percent, 30);
  EXPECT_TRUE(k.press("Ctrl+Up", true, t0 + 20ms, out));  // the system's repeat: nothing more
  k.tick(t0 + 20ms, out);
  EXPECT_EQ(out.size(), 1u);
  k.tick(t0 + 40ms, out);
  k.tick(t0 + 60ms, out);
  k.tick(t0 + 80ms, out);
  EXPECT_EQ(out.size(), 3u);
  EXPECT_TRUE(k.release("Ctrl+Up", out));
  ASSERT_EQ(out.size(), 4u);
  EXPECT_EQ(out[3].kind, PendantEvent::Kind::Release);
  k.tick(t0 + 200ms, out);
  EXPECT_EQ(out.size(), 4u);
  EXPECT_TRUE(k.press("F5", false, t0, out));
  EXPECT_TRUE(k.release("F5", out));  // a button's release: nothing
  ASSERT_EQ(out.size(), 5u);
  EXPECT_EQ(out[4].button, PendantButton::Stop);
}

// ---- on the controller ---------------------------------------------------------------------

TEST(KeyPendant, AStepKeyMovesExactlyItsStepOrVdsKeypadStep) {
  Bench b;
  b.settings.display.keypad_step = 0.125;
  KeyPendant k(bindings({"F6 = step x+ 0.25", "F7 = step y+"}));
  std::vector<PendantEvent> out;
  k.key("F6", Clock::time_point{}, out);
  k.key("F7", Clock::time_point{} + 1ms, out);
  b.send(out);
  b.settle();
  const ControllerStatus s = b.c.status();
  EXPECT_EQ(s.steps[0], b.steps(0.25));
  EXPECT_EQ(s.steps[1], b.steps(0.125, 1));
  EXPECT_EQ(s.state, MachineState::Idle);
}

// A terminal has no key release: the jog runs while the repeats come and the pendant's
// dead-man rule ends it 100 ms after the last.
TEST(KeyPendant, AtATerminalAHeldJogKeyEndsByTheDeadManRuleOnceItsRepeatsStop) {
  Bench b(/*realtime=*/true);
  KeyPendant k(bindings({"Ctrl+Right = jog x+ 30%"}));
  std::vector<PendantEvent> out;
  for (int ms = 0; ms <= 300; ms += 10) {
    b.clock.ms = ms;
    if (ms % 30 == 0) {
      k.key("Ctrl+Right", Clock::time_point{} + std::chrono::milliseconds(ms), out);
      b.send(out);
      out.clear();
    }
    b.in().tick();
    ASSERT_EQ(b.c.status().state, MachineState::Jogging) << ms << " " << b.last_told();
  }
  b.clock.ms = 390;  // 90 ms after the last repeat: still held
  b.in().tick();
  EXPECT_EQ(b.c.status().state, MachineState::Jogging);
  b.clock.ms = 400;  // 100 ms: released
  b.in().tick();
  EXPECT_NE(b.c.status().state, MachineState::Jogging);
  ASSERT_TRUE(b.c.wait_for(5s));
  EXPECT_GT(b.c.status().steps[0], 0);
}

// ---- macros --------------------------------------------------------------------------------

TEST(PendantMacros, AMacroIsALineOrAPartFilesFpLine) {
  EXPECT_EQ(macro_line("C3", "/p"), "C3");
  EXPECT_EQ(macro_line(" MZ, 1 ", "/p"), "MZ, 1");
  EXPECT_EQ(macro_line("", "/p"), "");
  EXPECT_EQ(macro_line("corner.sbp", "/p"), "FP, /p/corner.sbp");
  EXPECT_EQ(macro_line("jobs/../corner.SBP", "/p"), "FP, /p/corner.SBP");
  EXPECT_EQ(macro_line("/jobs/a.nc", "/p"), "FP, /jobs/a.nc");
  const char* home = std::getenv("HOME");
  EXPECT_EQ(macro_line("~/a.sbp", "/p"), "FP, " + (fs::path(home ? home : "") / "a.sbp").string());
}

TEST(PendantMacros, ABoundMacroRunsAtRestAnUnboundOneSaysSoAndARunningFileRefusesIt) {
  Bench b;
  b.bindings.macros[0] = "MX, 0.5";
  b.in().handle({.kind = PendantEvent::Kind::Button, .button = PendantButton::Macro, .macro = 1});
  ASSERT_TRUE(b.c.wait_for(5s));
  EXPECT_EQ(b.c.status().steps[0], b.steps(0.5)) << b.last_told();
  b.in().handle({.kind = PendantEvent::Kind::Button, .button = PendantButton::Macro, .macro = 2});
  EXPECT_EQ(b.last_told(), "macro 2 is not bound (the profile's [pendant] section)");
  // A long move runs (in real time): the macro is refused with the reason.
  Bench r(/*realtime=*/true);
  r.bindings.macros[0] = "MX, 0.5";
  ASSERT_TRUE(r.c.run_typed(Script::from_text("MX, 20", "console")));
  r.in().handle({.kind = PendantEvent::Kind::Button, .button = PendantButton::Macro, .macro = 1});
  EXPECT_NE(r.last_told().find("macro 1 (MX, 0.5): "), std::string::npos) << r.last_told();
  r.c.stop();
  ASSERT_TRUE(r.c.wait_for(10s));
}

class TempDir {
 public:
  TempDir() : path_(fs::temp_directory_path() / ("gantry_keys_" + std::to_string(getpid()))) {
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  fs::path operator/(const std::string& name) const { return path_ / name; }
  void write(const std::string& name, const std::string& text) const {
    std::ofstream(path_ / name) << text;
  }

 private:
  fs::path path_;
};

TEST(PendantProfile, ABadKeyIsAnErrorAtItsLineAndMacrosComeFromTheProfile) {
  TempDir dir;
  // Lines: the default profile, then [pendant] and its keys one a line.
  std::string text = default_profile_text();
  if (text.back() != '\n') text += '\n';
  const int first = static_cast<int>(std::count(text.begin(), text.end(), '\n')) + 1;
  text +=
      "[pendant]\n"                 // first
      "macro_1 = \"corner.sbp\"\n"  // first + 1
      "macro_2 = \"MZ, 1\"\n"       // first + 2
      "keys = [\n"                  // first + 3
      "  \"F5 = start/pause\",\n"   // first + 4
      "  \"Hyper+F5 = stop\",\n"    // first + 5
      "  \"F6 = step x+ 0.25\",\n"  // first + 6
      "]\n";
  dir.write("profile.toml", text);
  const SettingsLoad load = load_settings_file((dir / "profile.toml").string());
  ASSERT_TRUE(load.ok()) << load.errors.front().message;
  std::vector<Diagnostic> problems;
  const PendantProfile p =
      pendant_profile(load.settings, (dir / "profile.toml").string(), &problems);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_EQ(problems[0].severity, Severity::Error);
  EXPECT_EQ(problems[0].loc.line, first + 5);
  ASSERT_TRUE(problems[0].loc.file);
  EXPECT_EQ(*problems[0].loc.file, (dir / "profile.toml").string());
  EXPECT_NE(problems[0].message.find("\"Hyper+F5\" is not a key"), std::string::npos)
      << problems[0].message;
  EXPECT_NE(problems[0].message.find("left unbound"), std::string::npos);
  EXPECT_EQ(p.keys.all().size(), 2u);
  EXPECT_EQ(p.buttons.macros[0], "FP, " + (dir / "corner.sbp").string());
  EXPECT_EQ(p.buttons.macros[1], "MZ, 1");
  EXPECT_EQ(p.buttons.macros[2], "");
  EXPECT_EQ(load.settings.pendant.xhc_coordinates, "work");
}

TEST(PendantProfile, TheXhcDisplaysFrameIsWorkOrMachine) {
  std::string text = default_profile_text() + "\n[pendant]\nxhc_coordinates = \"machine\"\n";
  SettingsLoad load = parse_settings(text, "p.toml");
  ASSERT_TRUE(load.ok());
  EXPECT_EQ(load.settings.pendant.xhc_coordinates, "machine");
  text = default_profile_text() + "\n[pendant]\nxhc_coordinates = \"table\"\n";
  load = parse_settings(text, "p.toml");
  ASSERT_FALSE(load.ok());
  EXPECT_NE(load.errors.front().message.find("must be \"work\" or \"machine\""), std::string::npos)
      << load.errors.front().message;
}

// ---- the XHC pendant: Lead, the display's frame ----------------------------------------------

using pendant::XhcKey;
using pendant::XhcReport;

TEST(PendantXhcLead, TheWheelAtLeadIsTheSpindlesInBothModesAndOnEitherLeadCode) {
  XhcTranslator t;
  auto e = t.events(report(XhcKey::None, XhcKey::None, 0x1c, 0x11, 2));
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0].kind, PendantEvent::Kind::Lead);
  EXPECT_EQ(e[0].delta, 2);
  t.events(report(XhcKey::Continuous, XhcKey::None, 0x9b, 0x06, 0));  // axis OFF, 0x9b
  e = t.events(report(XhcKey::None, XhcKey::None, 0x9b, 0x06, -1));
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0].kind, PendantEvent::Kind::Lead);
  EXPECT_EQ(e[0].delta, -1);
}

TEST(PendantXhcLead, LeadChangesTheSpindleSpeedAtRestAndSaysThereIsNoLiveOverrideOtherwise) {
  Bench b;
  ASSERT_TRUE(b.c.run_typed(Script::from_text("TR, 10000", "console")));
  ASSERT_TRUE(b.c.wait_for(5s));
  b.in().handle({.kind = PendantEvent::Kind::Lead, .delta = 2});
  ASSERT_TRUE(b.c.wait_for(5s));
  EXPECT_DOUBLE_EQ(b.c.modal().spindle_rpm, 12000) << b.last_told();
  b.in().handle({.kind = PendantEvent::Kind::Lead, .delta = -1});
  ASSERT_TRUE(b.c.wait_for(5s));
  EXPECT_DOUBLE_EQ(b.c.modal().spindle_rpm, 10800);
  Bench r(/*realtime=*/true);
  ASSERT_TRUE(r.c.run_typed(Script::from_text("TR, 10000\nSO, 1, 1\nMX, 20", "console")));
  std::this_thread::sleep_for(50ms);
  r.in().handle({.kind = PendantEvent::Kind::Lead, .delta = 1});
  EXPECT_NE(r.last_told().find("no live spindle override"), std::string::npos) << r.last_told();
  r.c.stop();
  ASSERT_TRUE(r.c.wait_for(10s));
}

TEST(PendantXhcDisplay, Macro10SwitchesWorkAndMachineCoordinatesFnMacro10IsMacro10) {
  XhcTranslator t;
  EXPECT_FALSE(t.machine_coordinates());
  EXPECT_TRUE(t.events(report(XhcKey::Macro10, XhcKey::None, 0x0e, 0x11, 0)).empty());
  EXPECT_TRUE(t.machine_coordinates());
  EXPECT_TRUE(t.events(report(XhcKey::Macro10, XhcKey::None, 0x0e, 0x11, 0)).empty());  // held
  EXPECT_TRUE(t.machine_coordinates());
  t.events(report(XhcKey::None, XhcKey::None, 0x0e, 0x11, 0));
  t.events(report(XhcKey::Macro10, XhcKey::None, 0x0e, 0x11, 0));
  EXPECT_FALSE(t.machine_coordinates());
  t.events(report(XhcKey::None, XhcKey::None, 0x0e, 0x11, 0));
  const auto e = t.events(report(XhcKey::Fn, XhcKey::Macro10, 0x0e, 0x11, 0));
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0].button, PendantButton::Macro);
  EXPECT_EQ(e[0].macro, 10);
  EXPECT_FALSE(t.machine_coordinates());
  EXPECT_TRUE(XhcTranslator(/*machine=*/true).machine_coordinates());  // the profile's
}

// Machine coordinates X 250.5, Y -3.0001, Z 0 in continuous mode, feed 50 %, no spindle. The
// 21 data bytes by hand: fe fd (header), fe (seed), 00 (flags: continuous 0, no reset, bit 7
// clear: machine coordinates); X: 250 = fa 00, 5000 = 0x1388: 88 13; Y: 3 = 03 00, 1 | sign
// 0x8000 = 0x8001: 01 80; Z: 00 00 00 00; feed 50 = 32 00; spindle 00 00; pad 00. In sevens,
// each led by 06.
TEST(PendantXhcDisplay, MachineCoordinatesClearTheWorkFlagGoldenBytes) {
  ControllerStatus s;
  s.feed_override = 0.5;
  Vec6 machine;
  machine << 250.5, -3.0001, 0, 7, 8, 9;
  pendant::XhcDisplay d = xhc_display(s, machine, /*step_mode=*/false, 1, /*machine=*/true);
  EXPECT_FALSE(d.work_coordinates);
  d.seed = 0xfe;
  const auto blocks = pendant::encode_display(d);
  using pendant::DisplayBlock;
  EXPECT_EQ(blocks[0], (DisplayBlock{0x06, 0xfe, 0xfd, 0xfe, 0x00, 0xfa, 0x00, 0x88}));
  EXPECT_EQ(blocks[1], (DisplayBlock{0x06, 0x13, 0x03, 0x00, 0x01, 0x80, 0x00, 0x00}));
  EXPECT_EQ(blocks[2], (DisplayBlock{0x06, 0x00, 0x00, 0x32, 0x00, 0x00, 0x00, 0x00}));
  EXPECT_TRUE(xhc_display(s, machine, false, 1).work_coordinates);  // the work frame: 0x80
  EXPECT_EQ(pendant::encode_display(xhc_display(s, machine, false, 1))[0][4], 0x80);
}

// ---- a gamepad's D-pad and shoulders as exact steps -------------------------------------------

GamepadEvent pad(GamepadEvent::Kind kind, int code, double value) {
  GamepadEvent e;
  e.kind = kind;
  e.code = code;
  e.value = value;
  return e;
}

TEST(GamepadSteps, TheDpadAndShouldersBoundAsStepsMoveExactlyTheirSteps) {
  std::string error;
  const auto b = GamepadBindings::parse(
      {},
      "ABS_HAT0X+ = step x+ 0.01, ABS_HAT0X- = step x- 0.01, ABS_HAT0Y- = step y+ 0.1, "
      "BTN_TL = step z- 0.1, BTN_TR = step z+ 0.1, BTN_DPAD_RIGHT = step x+ 1",
      &error);
  ASSERT_TRUE(b) << error;
  for (const auto& s : b->jog[0]) EXPECT_NE(s.code, ABS_HAT0X);  // the hat steps, no longer jogs
  for (const auto& s : b->jog[1]) EXPECT_NE(s.code, ABS_HAT0Y);
  GamepadPendant g(*b);
  std::vector<PendantEvent> out;
  using K = GamepadEvent::Kind;
  for (int i = 0; i < 3; ++i) {  // the hat right three times: three steps of 0.01
    g.event(pad(K::Axis, ABS_HAT0X, 1), out);
    g.event(pad(K::Axis, ABS_HAT0X, 0), out);
  }
  g.event(pad(K::Axis, ABS_HAT0X, -1), out);  // and left once
  g.event(pad(K::Axis, ABS_HAT0X, -1), out);  // held: nothing more
  g.event(pad(K::Axis, ABS_HAT0X, 0), out);
  g.event(pad(K::Axis, ABS_HAT0Y, -1), out);  // the hat up (evdev: negative): Y+ 0.1
  g.event(pad(K::Button, BTN_TL, 1), out);    // L1: Z- 0.1
  g.event(pad(K::Button, BTN_TL, 0), out);
  g.event(pad(K::Button, BTN_DPAD_RIGHT, 1), out);  // a D-pad with buttons: X+ 1
  g.event(pad(K::Button, BTN_DPAD_RIGHT, 0), out);
  g.tick(out);  // nothing held: no report
  ASSERT_EQ(out.size(), 7u);
  for (const PendantEvent& e : out) EXPECT_GT(e.step, 0);
  Bench bench;
  bench.send(out);
  bench.settle();
  const ControllerStatus s = bench.c.status();
  EXPECT_EQ(s.steps[0], bench.steps(1.02));
  EXPECT_EQ(s.steps[1], bench.steps(0.1, 1));
  EXPECT_EQ(s.steps[2], bench.steps(-0.1, 2));
}

TEST(GamepadSteps, AButtonBoundToAContinuousJogJogsWhileHeldAndItsReleaseEndsIt) {
  std::string error;
  const auto b = GamepadBindings::parse({}, "BTN_NORTH = jog z+ 20%", &error);
  ASSERT_TRUE(b) << error;
  GamepadPendant g(*b);
  std::vector<PendantEvent> out;
  g.event(pad(GamepadEvent::Kind::Button, BTN_NORTH, 1), out);
  g.tick(out);
  g.tick(out);
  g.event(pad(GamepadEvent::Kind::Button, BTN_NORTH, 0), out);
  g.tick(out);
  ASSERT_EQ(out.size(), 4u);
  EXPECT_EQ(out[0].axis, 2);
  EXPECT_EQ(out[0].percent, 20);
  EXPECT_EQ(out[2].kind, PendantEvent::Kind::Wheel);
  EXPECT_EQ(out[3].kind, PendantEvent::Kind::Release);
  EXPECT_FALSE(GamepadBindings::parse({}, "ABS_X+ = step x+", &error));  // a stick is no button
  EXPECT_NE(error.find("is not a button"), std::string::npos) << error;
}

}  // namespace
}  // namespace gantry::session
