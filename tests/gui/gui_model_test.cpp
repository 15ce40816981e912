// The console window's model, without a display: completion, the parameter line, history,
// menus, fill-in sheets from the command table, the operator's dialogs, scripted actions and
// the preview camera.
#include <GLFW/glfw3.h>  // key codes
#include <gtest/gtest.h>

#include <thread>

#include "camera.hpp"
#include "command_line.hpp"
#include "fill_sheet.hpp"
#include "gantry/session/operator_io.hpp"
#include "jog_press.hpp"
#include "test_script.hpp"
#include "window_size.hpp"

namespace {

using namespace gantry;
using namespace gantry::ui;

const CommandTable& table() {
  return CommandTable::standard();
}

std::vector<std::string> codes(const std::vector<const CommandSpec*>& specs) {
  std::vector<std::string> out;
  for (const CommandSpec* s : specs) out.emplace_back(s->code);
  return out;
}

// ---- command line ----------------------------------------------------------------------------

TEST(GuiCommandLine, CompletesTheCodeFromTheTable) {
  EXPECT_EQ(complete(table(), "mx"), "MX, ");  // takes parameters: its comma follows
  EXPECT_EQ(complete(table(), "sa"), "SA");    // takes none
  EXPECT_EQ(complete(table(), "ma"), "MA, ");
  EXPECT_EQ(complete(table(), "q"), "q");  // no code starts with Q: unchanged
  EXPECT_EQ(complete(table(), "MX, 5"), "MX, 5");
  // One letter: every code of it, in table order, and no common second letter to add.
  const std::vector<std::string> m = codes(completions(table(), "m"));
  ASSERT_GE(m.size(), 5u);
  EXPECT_EQ(m[0], "MX");
  for (const std::string& c : m) EXPECT_EQ(c[0], 'M');
  EXPECT_EQ(complete(table(), "m"), "M");
}

TEST(GuiCommandLine, FindsTheCommandALineStartsWith) {
  EXPECT_EQ(command_of(table(), "MX, 5")->code, "MX");
  EXPECT_EQ(command_of(table(), "  j2 1,2")->code, "J2");
  EXPECT_EQ(command_of(table(), "MX")->code, "MX");
  EXPECT_EQ(command_of(table(), "MXY"), nullptr);
  EXPECT_EQ(command_of(table(), "&D = 2"), nullptr);
  EXPECT_EQ(command_of(table(), "PRINT 3"), nullptr);
}

TEST(GuiCommandLine, ParameterLineMarksTheParameterUnderTheCursor) {
  const CommandSpec& j2 = *table().find("J2");
  ParamLine pl = param_line(j2, Dialect::SB3, "J2, 1, ", 7);
  EXPECT_EQ(pl.current, 1);
  EXPECT_NE(pl.text.find("[" + std::string(j2.params[1].name)), std::string::npos) << pl.text;
  EXPECT_NE(pl.help.find(j2.params[1].help), std::string::npos);
  pl = param_line(j2, Dialect::SB3, "J2", 2);
  EXPECT_EQ(pl.current, -1);  // still on the code: the command's own help
  EXPECT_EQ(pl.help, j2.help);
  pl = param_line(j2, Dialect::SB3, "J2, 1, 2, 3, 4, 5, 6, 7, 8", 26);
  EXPECT_EQ(pl.current, static_cast<int>(j2.params.size()) - 1);  // past the end: the last
}

TEST(GuiCommandLine, EnterOnABareCodeOpensItsSheet) {
  EXPECT_EQ(enter_action(table(), "MX"), EnterAction::OpenSheet);
  EXPECT_EQ(enter_action(table(), "mx,"), EnterAction::OpenSheet);
  EXPECT_EQ(enter_action(table(), "MX, 5"), EnterAction::Run);
  EXPECT_EQ(enter_action(table(), "SA"), EnterAction::Run);  // nothing to ask for
  EXPECT_EQ(enter_action(table(), "&D = 1"), EnterAction::Run);
  EXPECT_EQ(enter_action(table(), "   "), EnterAction::Nothing);
}

TEST(GuiCommandLine, HistoryWalksBackAndKeepsTheDraft) {
  History h(3);
  for (const char* l : {"MX, 1", "MX, 1", "MY, 2", " ", "MZ, 3", "J2, 4, 4"}) h.add(l);
  EXPECT_EQ(h.lines(), (std::vector<std::string>{"MY, 2", "MZ, 3", "J2, 4, 4"}));  // capped
  EXPECT_EQ(h.up("draft"), "J2, 4, 4");
  EXPECT_EQ(h.up("J2, 4, 4"), "MZ, 3");
  EXPECT_EQ(h.up("MZ, 3"), "MY, 2");
  EXPECT_EQ(h.up("MY, 2"), std::nullopt);
  EXPECT_EQ(h.down(), "MZ, 3");
  EXPECT_EQ(h.down(), "J2, 4, 4");
  EXPECT_EQ(h.down(), "draft");
  EXPECT_EQ(h.down(), std::nullopt);
}

TEST(GuiCommandLine, MenusFollowTheGroupsWithTheirHotKeys) {
  const std::vector<Menu> m = menus(table());
  std::vector<std::string> titles;
  for (const Menu& x : m) titles.push_back(x.title);
  const std::vector<std::string> sb3 = {"Cuts",   "File",     "Jog",   "Move",      "Zero",
                                        "Values", "Settings", "Tools", "Utilities", "Help"};
  ASSERT_GE(titles.size(), sb3.size());
  EXPECT_EQ(std::vector<std::string>(titles.begin(), titles.begin() + 10), sb3);
  auto key = [&](const std::string& t) {
    for (const Menu& x : m)
      if (x.title == t) return x.key;
    return '?';
  };
  EXPECT_EQ(key("Move"), 'M');
  EXPECT_EQ(key("Jog"), 'J');
  EXPECT_EQ(key("Zero"), 'Z');
  EXPECT_EQ(key("Values"), 'V');
  EXPECT_EQ(key("File"), 'F');
  std::size_t all = 0;
  for (const Menu& x : m) all += x.commands.size();
  EXPECT_EQ(all, table().all().size());  // every command is in one menu
}

// ---- fill-in sheets --------------------------------------------------------------------------

TEST(GuiFillSheet, FieldsComeFromTheTable) {
  const CommandSpec& mx = *table().find("MX");
  FillSheet s(mx, Dialect::SB3, "in");
  ASSERT_EQ(s.fields().size(), mx.params.size());
  const SheetField& f = s.fields()[0];
  EXPECT_EQ(f.label, mx.params[0].name);
  EXPECT_EQ(f.type, "distance");
  EXPECT_EQ(f.unit, "in");
  // FP: a file name (text), then numbers with defaults shown as hints, ranges in words.
  FillSheet fp(*table().find("FP"), Dialect::SB3, "mm");
  EXPECT_EQ(fp.fields()[0].type, "filename");
  EXPECT_EQ(fp.fields()[0].hint, "required");
  EXPECT_EQ(fp.fields()[1].hint, "1");
  bool ranged = false;
  for (const SheetField& x : fp.fields()) ranged = ranged || x.range == "0 to 1";
  EXPECT_TRUE(ranged);
}

TEST(GuiFillSheet, ValidatesAgainstRangesAndComposesTheLine) {
  FillSheet fp(*table().find("FP"), Dialect::SB3, "in");
  EXPECT_FALSE(fp.validate());  // the file name is required
  EXPECT_EQ(fp.fields()[0].error, "required: this parameter has no default");
  fp.fields()[0].value = "part.sbp";
  fp.fields()[7].value = "2";  // tab feature: 0 or 1
  EXPECT_FALSE(fp.validate());
  EXPECT_EQ(fp.fields()[7].error, "out of range: 0 to 1");
  fp.fields()[7].value = "0.5";
  fp.validate();
  EXPECT_EQ(fp.fields()[7].error, "must be a whole number");
  fp.fields()[7].value = "1";
  fp.fields()[4].value = "&REPS";  // an expression: the controller's check evaluates it
  EXPECT_TRUE(fp.validate());
  EXPECT_EQ(fp.line(), "FP, part.sbp, , , , &REPS, , , 1");
  fp.fields()[2].value = "#";
  EXPECT_FALSE(fp.validate());
  EXPECT_EQ(fp.fields()[2].error, "must be a number");
}

TEST(GuiFillSheet, FillsFromATypedLineAndPlacesTheControllersErrors) {
  FillSheet j2(*table().find("J2"), Dialect::SB3, "in");
  j2.fill_from("J2, 1.5, \"a,b\"");
  EXPECT_EQ(j2.fields()[0].value, "1.5");
  EXPECT_EQ(j2.fields()[1].value, "\"a,b\"");  // a comma inside quotes stays in its field
  j2.fields()[1].value = "40";
  // "J2, 1.5, 40": the error at column 10 is the second field's; one at the code is not.
  auto file = std::make_shared<const std::string>("console");
  const std::vector<Diagnostic> errors = {
      {SourceLoc{file, 1, 10}, Severity::Error, "Y 40 is past the table's edge"},
      {SourceLoc{file, 1, 1}, Severity::Error, "the machine is in E-stop"}};
  const std::vector<std::string> rest = j2.place_errors(errors);
  EXPECT_EQ(j2.fields()[1].error, "Y 40 is past the table's edge");
  EXPECT_EQ(j2.fields()[0].error, "");
  EXPECT_EQ(rest, std::vector<std::string>{"the machine is in E-stop"});
}

// ---- the operator's dialogs ------------------------------------------------------------------

TEST(GuiWindowIO, QuestionsWaitForTheWindowsAnswer) {
  session::OperatorMailbox io(false, {});
  std::optional<std::string> got;
  std::thread job([&] { got = io.ask("Depth?", "&D", "0.25", {}); });
  while (!io.question()) std::this_thread::yield();
  const session::Question q = *io.question();
  EXPECT_EQ(q.kind, session::Question::Kind::Input);
  EXPECT_EQ(q.variable, "&D");
  EXPECT_EQ(q.default_value, "0.25");
  io.answer("0.5");
  job.join();
  EXPECT_EQ(got, "0.5");
  EXPECT_FALSE(io.question());
  // MSGBOX cancelled: its last button. PAUSE cancelled: false.
  std::string pressed;
  std::thread box([&] { pressed = io.choose("Go?", {"Yes", "No"}, 0, "Title", {}); });
  while (!io.question()) std::this_thread::yield();
  EXPECT_GT(io.question()->id, q.id);  // a new question has a new id
  io.cancel();
  box.join();
  EXPECT_EQ(pressed, "No");
  bool go = true;
  std::thread pause([&] { go = io.confirm("Check the bit", {}); });
  while (!io.question()) std::this_thread::yield();
  io.cancel();
  pause.join();
  EXPECT_FALSE(go);
}

TEST(GuiWindowIO, ScriptedAnswersNeedNoWindow) {
  session::OperatorMailbox io(true, {{"&D", "3"}});
  EXPECT_TRUE(io.confirm("x", {}));
  EXPECT_EQ(io.ask("", "&D", "", {}), "3");
  io.print("hello\n");
  EXPECT_EQ(io.take_output(), "hello\n");
  EXPECT_EQ(io.take_output(), "");
}

// ---- scripted actions ------------------------------------------------------------------------

TEST(GuiScript, ParsesEveryAction) {
  std::vector<Action> a;
  std::string error;
  ASSERT_TRUE(
      parse_script("# comment\ntype MX, 5\nkey ctrl+Enter\nhold Right 0.5\nclick Start\n"
                   "wait idle\nwait frames 3\nwait dialog\nhover 0.5 0.25\n"
                   "screenshot a.png\ndump s.json\nquit\ntap Enter\n",
                   "s", a, error))
      << error;
  ASSERT_EQ(a.size(), 12u);
  EXPECT_EQ(a[0].kind, Action::Kind::Type);
  EXPECT_EQ(a[0].text, "MX, 5");
  EXPECT_EQ(a[1].key, GLFW_KEY_ENTER);
  EXPECT_EQ(a[1].mods, GLFW_MOD_CONTROL);
  EXPECT_EQ(a[2].kind, Action::Kind::Hold);
  EXPECT_EQ(a[2].a, 0.5);
  EXPECT_EQ(a[3].text, "Start");
  EXPECT_EQ(a[5].a, 3);
  EXPECT_EQ(a[7].b, 0.25);
  EXPECT_EQ(a[10].kind, Action::Kind::Quit);
  EXPECT_EQ(a[10].line, 12);
  EXPECT_EQ(a[11].kind, Action::Kind::Tap);
  EXPECT_EQ(a[11].key, GLFW_KEY_ENTER);
}

TEST(GuiScript, ErrorsNameTheLine) {
  std::vector<Action> a;
  std::string error;
  EXPECT_FALSE(parse_script("type x\nkey Hyper\n", "s.txt", a, error));
  EXPECT_EQ(error.substr(0, 9), "s.txt:2: ");
  EXPECT_NE(error.find("unknown key 'Hyper'"), std::string::npos);
  EXPECT_FALSE(parse_script("hover 2 0\n", "s.txt", a, error));
  EXPECT_FALSE(parse_script("wait forever\n", "s.txt", a, error));
  EXPECT_FALSE(parse_script("fly\n", "s.txt", a, error));
  EXPECT_EQ(key_code("PageDown"), GLFW_KEY_PAGE_DOWN);
  EXPECT_EQ(key_code("f12"), GLFW_KEY_F12);
  EXPECT_EQ(key_code("k"), GLFW_KEY_K);
}

// ---- camera ----------------------------------------------------------------------------------

Eigen::Vector3f ndc(const Camera& c, float aspect, const Eigen::Vector3f& p) {
  const Eigen::Vector4f q = c.projection(aspect) * c.view() * p.homogeneous();
  return q.head<3>() / q.w();
}

TEST(GuiCamera, FitShowsTheWholeBoxInEveryView) {
  const Eigen::AlignedBox3f box(Eigen::Vector3f(0, 0, -1), Eigen::Vector3f(24, 18, 0.5f));
  for (bool persp : {false, true})
    for (View v : {View::Top, View::Front, View::Side, View::Iso})
      for (float aspect : {0.5f, 1.0f, 2.0f}) {
        Camera c;
        c.perspective = persp;
        c.set_view(v);
        c.fit(box, aspect);
        float reach = 0;
        for (int k = 0; k < 8; ++k) {
          const Eigen::Vector3f p =
              ndc(c, aspect, box.corner(static_cast<Eigen::AlignedBox3f::CornerType>(k)));
          EXPECT_LE(std::abs(p.x()), 1.0f) << persp << static_cast<int>(v) << aspect;
          EXPECT_LE(std::abs(p.y()), 1.0f);
          EXPECT_LE(std::abs(p.z()), 1.0f);  // within the clip planes
          reach = std::max({reach, std::abs(p.x()), std::abs(p.y())});
        }
        EXPECT_GT(reach, 0.25f);  // and not lost in the middle
      }
}

TEST(GuiCamera, PresetViewsLookAlongTheirAxes) {
  Camera c;
  c.set_view(View::Top);
  c.fit(Eigen::AlignedBox3f(Eigen::Vector3f(0, 0, 0), Eigen::Vector3f(10, 10, 1)), 1);
  // From the top, +X is to the right and +Y up the screen.
  const Eigen::Vector3f o = ndc(c, 1, {5, 5, 0}), x = ndc(c, 1, {6, 5, 0}),
                        y = ndc(c, 1, {5, 6, 0});
  EXPECT_GT(x.x(), o.x());
  EXPECT_NEAR(x.y(), o.y(), 1e-5);
  EXPECT_GT(y.y(), o.y());
  c.set_view(View::Front);  // +Z up the screen, +X to the right
  EXPECT_GT(ndc(c, 1, {5, 5, 1}).y(), ndc(c, 1, {5, 5, 0}).y());
  EXPECT_GT(ndc(c, 1, {6, 5, 0}).x(), ndc(c, 1, {5, 5, 0}).x());
  c.set_view(View::Side);  // from +X: +Y to the right
  EXPECT_GT(ndc(c, 1, {5, 6, 0}).x(), ndc(c, 1, {5, 5, 0}).x());
  // Zoom in: the same point moves away from the centre.
  c.set_view(View::Top);
  const float before = ndc(c, 1, {6, 5, 0}).x();
  c.zoom(0.5f);
  EXPECT_NEAR(ndc(c, 1, {6, 5, 0}).x(), 2 * before, 1e-4);
}

// ---- the keypad's taps and holds (continuous mode) -------------------------------------------

TEST(GuiJogPress, ATapIsOneStepAndAHoldJogsUntilLetGo) {
  using namespace std::chrono_literals;
  const JogPress::Clock::time_point t0{};
  JogPress p;  // 500 ms
  // A tap: the step is the press's (the window jogs it); let go at 150 ms, nothing to release,
  // and no continuous jog starts later.
  p.press(1, t0);
  EXPECT_FALSE(p.start_continuous(t0 + 100ms, true));
  EXPECT_FALSE(p.release(1));
  EXPECT_FALSE(p.start_continuous(t0 + 2s, true));
  // Held: the jog starts once the threshold has passed and the step has played.
  p.press(1, t0);
  EXPECT_FALSE(p.start_continuous(t0 + 499ms, true));
  EXPECT_FALSE(p.start_continuous(t0 + 600ms, false));  // the step still moves
  EXPECT_TRUE(p.start_continuous(t0 + 700ms, true));
  EXPECT_FALSE(p.start_continuous(t0 + 800ms, true));  // once
  EXPECT_TRUE(p.continuous());
  EXPECT_FALSE(p.release(2));  // another key's release is not this one's
  EXPECT_TRUE(p.release(1));   // let go: release the jog
  EXPECT_EQ(p.id(), -1);
  // A stop or refusal forgets the press: its key's release releases nothing.
  p.press(3, t0);
  EXPECT_TRUE(p.start_continuous(t0 + 1s, true));
  p.reset();
  EXPECT_FALSE(p.release(3));
  // Another key is a press of its own.
  p.press(1, t0);
  p.press(2, t0 + 300ms);
  EXPECT_FALSE(p.start_continuous(t0 + 700ms, true));
  EXPECT_TRUE(p.start_continuous(t0 + 800ms, true));
}

// ---- window size -----------------------------------------------------------------------------

// Issue 25: `gui --size` took a width only (16:10), so 1024 x 600 could not be asked for.
TEST(GuiWindowSize, TakesWidthByHeightOrAWidthAlone) {
  const std::optional<WindowSize> wh = parse_window_size("1024x600", nullptr);
  ASSERT_TRUE(wh);
  EXPECT_EQ(wh->width, 1024);
  EXPECT_EQ(wh->height, 600);
  const std::optional<WindowSize> w = parse_window_size("1280", nullptr);
  ASSERT_TRUE(w);
  EXPECT_EQ(w->height, 800);  // 16:10, as before
  std::string why;
  EXPECT_FALSE(parse_window_size("1024x", &why));
  EXPECT_NE(why.find("WIDTHxHEIGHT"), std::string::npos) << why;
  EXPECT_FALSE(parse_window_size("100x100", &why));
  EXPECT_NE(why.find("320 to 8192"), std::string::npos) << why;
}

TEST(GuiWindowSize, TheScaleGrowsPast1280By800) {
  EXPECT_EQ(window_scale(1024, 600), 1.0f);  // small windows keep the text readable
  EXPECT_EQ(window_scale(1280, 800), 1.0f);
  EXPECT_EQ(window_scale(1920, 1200), 1.5f);
  EXPECT_EQ(window_scale(3840, 2160), 2.5f);  // 2.7, in quarters
  EXPECT_EQ(window_scale(1921, 1201), 1.5f);  // a few pixels do not rebuild the fonts
}

}  // namespace
