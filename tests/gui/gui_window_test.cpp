// `gantry gui` end to end: the window under Xvfb (Mesa's software OpenGL), driven by
// scripted actions (type, key, click, wait), on the simulated card. Each test reads the
// window's state dumps and its screenshots.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <stb_image.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// One Xvfb server for the test program, on a display it chooses itself (-displayfd).
class Xvfb : public ::testing::Environment {
 public:
  static std::string display;

  void SetUp() override {
    int fds[2];
    if (pipe(fds) != 0) return;
    pid_ = fork();
    if (pid_ == 0) {
      close(fds[0]);
      const std::string fd = std::to_string(fds[1]);
      execlp("Xvfb", "Xvfb", "-displayfd", fd.c_str(), "-screen", "0", "3840x2160x24", "-nolisten",
             "tcp", static_cast<char*>(nullptr));
      _exit(127);
    }
    close(fds[1]);
    std::string number;
    pollfd p{fds[0], POLLIN, 0};
    char c = 0;
    while (poll(&p, 1, 10000) > 0 && read(fds[0], &c, 1) == 1 && c != '\n') number += c;
    close(fds[0]);
    if (!number.empty()) display = ":" + number;
  }
  void TearDown() override {
    if (pid_ > 0) {
      kill(pid_, SIGTERM);
      waitpid(pid_, nullptr, 0);
    }
  }

 private:
  pid_t pid_ = -1;
};
std::string Xvfb::display;
const auto* const kXvfb = ::testing::AddGlobalTestEnvironment(new Xvfb);

class GuiWindow : public ::testing::Test {
 protected:
  void SetUp() override {
    if (Xvfb::display.empty()) GTEST_SKIP() << "Xvfb is not installed (scripts/setup.sh)";
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / fmt::format("gantry_gui_{}_{}", getpid(), info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "config");
  }
  void TearDown() override {
    if (!HasFailure() && !dir_.empty()) fs::remove_all(dir_);
  }

  void write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
  }

  // Runs the window on `script` with `args`; returns its exit status (output in out_).
  int gui(const std::string& script, const std::string& args = "") {
    write("script.txt", script);
    const std::string cmd = fmt::format(
        "cd '{}' && DISPLAY={} XDG_CONFIG_HOME='{}/config' HOME='{}' '{}' gui {} --card sim "
        "--persistent p.json --script script.txt 2>&1",
        dir_.string(), Xvfb::display, dir_.string(), dir_.string(), GANTRY_BIN, args);
    FILE* p = popen(cmd.c_str(), "r");
    out_.clear();
    char buf[4096];
    for (std::size_t n; (n = fread(buf, 1, sizeof buf, p)) > 0;) out_.append(buf, n);
    const int status = pclose(p);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }

  json state(const std::string& name) {
    std::ifstream in(dir_ / name);
    EXPECT_TRUE(in) << name << " was not written; output:\n" << out_;
    json j;
    if (in) in >> j;
    return j;
  }

  struct Image {
    int w = 0, h = 0;
    std::vector<unsigned char> rgb;
    // Pixels in the rectangle for which `match(r, g, b)` holds.
    int count(int x0, int y0, int x1, int y1,
              const std::function<bool(int, int, int)>& match) const {
      int n = 0;
      for (int y = std::max(y0, 0); y < std::min(y1, h); ++y)
        for (int x = std::max(x0, 0); x < std::min(x1, w); ++x) {
          const unsigned char* p = &rgb[static_cast<std::size_t>((y * w + x) * 3)];
          n += match(p[0], p[1], p[2]) ? 1 : 0;
        }
      return n;
    }
  };
  Image image(const std::string& name) {
    Image im;
    int n = 0;
    unsigned char* data = stbi_load((dir_ / name).c_str(), &im.w, &im.h, &n, 3);
    EXPECT_NE(data, nullptr) << name;
    if (data) im.rgb.assign(data, data + im.w * im.h * 3);
    stbi_image_free(data);
    return im;
  }

  // The documentation's figures are screenshots of passing tests: with GANTRY_FIGURES set
  // (scripts/figures.sh), a test's screenshot is copied there under the figure's name.
  void figure(const std::string& shot, const std::string& name) {
    const char* dir = std::getenv("GANTRY_FIGURES");
    if (dir == nullptr || HasFailure()) return;
    fs::copy_file(dir_ / shot, fs::path(dir) / name, fs::copy_options::overwrite_existing);
  }

  static bool has_line(const json& log, const std::string& text) {
    for (const json& l : log)
      if (l.get<std::string>().find(text) != std::string::npos) return true;
    return false;
  }

  fs::path dir_;
  std::string out_;
};

// The preview's rectangle in a 1280 x 800 window (right of the 370-pixel column, above the
// 250-pixel console, below the menu bar and the preview's tool bar).
constexpr int kPx0 = 380, kPy0 = 70, kPx1 = 1270, kPy1 = 540;
bool orange(int r, int g, int b) {
  return r > 200 && g > 110 && g < 190 && b < 80;
}  // cuts
bool blue(int r, int g, int b) {
  return r < 140 && g > 140 && b > 200;
}  // jogs

TEST_F(GuiWindow, ATypedLineMovesAndTheReadoutShowsIt) {
  ASSERT_EQ(gui("wait idle\ntype MX, 5\nkey Enter\nwait idle\ntype j2, 1.5, 2.25\nkey Enter\n"
                "wait idle\nkey Up\nwait frames 2\ndump s.json\nscreenshot s.png\n"),
            0)
      << out_;
  const json s = state("s.json");
  EXPECT_EQ(s["state"], "idle");
  EXPECT_EQ(s["position"], json({1.5, 2.25, 0, 0, 0, 0}));
  EXPECT_EQ(s["units"], "in");
  EXPECT_TRUE(has_line(s["log"], "> MX, 5"));
  EXPECT_EQ(s["history"], json({"MX, 5", "j2, 1.5, 2.25"}));
  EXPECT_EQ(s["command_line"], "j2, 1.5, 2.25");  // Up: the last line again
  const Image im = image("s.png");
  EXPECT_EQ(im.w, 1280);
  EXPECT_EQ(im.h, 800);
  // The tool's red cross is drawn in the preview, over the table.
  EXPECT_GT(im.count(kPx0, kPy0, kPx1, kPy1,
                     [](int r, int g, int b) { return r > 220 && g < 80 && b < 80; }),
            10);
}

TEST_F(GuiWindow, ABareCodeOpensItsFillInSheet) {
  ASSERT_EQ(gui("type MX\nkey Enter\nwait frames 3\ndump open.json\n"
                "type #\nwait frames 2\nkey Enter\nwait frames 2\ndump bad.json\n"
                "key Backspace\ntype 7\nkey Enter\nwait idle\ndump ran.json\n"
                "type MY\nkey Enter\nwait frames 3\ntype 4\nkey Escape\nwait idle\n"
                "dump closed.json\n"
                "type J2\nkey Enter\nwait frames 3\ntype 1\nkey Tab\ntype 40\nkey Enter\n"
                "wait frames 3\ndump refused.json\nscreenshot sheet.png\n"),
            0)
      << out_;
  const json open = state("open.json");
  ASSERT_TRUE(open.contains("sheet")) << open.dump(2);
  EXPECT_EQ(open["sheet"]["code"], "MX");
  EXPECT_EQ(open["sheet"]["fields"][0]["type"], "distance");
  EXPECT_EQ(open["sheet"]["fields"][0]["unit"], "in");
  const json bad = state("bad.json");  // Enter with a bad field: the sheet stays, says why
  ASSERT_TRUE(bad.contains("sheet"));
  EXPECT_EQ(bad["sheet"]["fields"][0]["error"], "must be a number");
  EXPECT_EQ(bad["position"][0], 0);
  const json ran = state("ran.json");
  EXPECT_FALSE(ran.contains("sheet"));
  EXPECT_EQ(ran["position"][0], 7);
  EXPECT_TRUE(has_line(ran["log"], "> MX, 7"));
  const json closed = state("closed.json");  // Esc: nothing ran
  EXPECT_FALSE(closed.contains("sheet"));
  EXPECT_EQ(closed["position"][1], 0);
  // The controller's check refuses Y 40 (the table is 18 in deep): the sheet stays open
  // with the error, and nothing moved.
  const json refused = state("refused.json");
  ASSERT_TRUE(refused.contains("sheet")) << refused.dump(2);
  EXPECT_EQ(refused["sheet"]["line"], "J2, 1, 40");
  std::string errors = refused["sheet"]["errors"].dump();
  for (const json& f : refused["sheet"]["fields"]) errors += f["error"].get<std::string>();
  EXPECT_NE(errors.find("40"), std::string::npos) << errors;
  EXPECT_EQ(refused["position"], json({7, 0, 0, 0, 0, 0}));
  figure("sheet.png", "console_sheet.png");
}

TEST_F(GuiWindow, TheValuesWindowEditsThroughTheCommandsSheets) {
  ASSERT_EQ(gui("wait idle\nclick Values window\nwait frames 3\ndump open.json\n"
                "click VS\nwait frames 3\ndump sheet.json\ntype -1\nkey Enter\nwait frames 3\n"
                "dump bad.json\nkey Backspace\nkey Backspace\ntype 2.5\nkey Enter\nwait idle\n"
                "dump ran.json\n"),
            0)
      << out_;
  EXPECT_TRUE(state("open.json")["values_window"]);
  const json sheet = state("sheet.json");
  ASSERT_TRUE(sheet.contains("sheet")) << sheet.dump(2);
  EXPECT_EQ(sheet["sheet"]["code"], "VS");
  const json bad = state("bad.json");  // a negative speed: the sheet says why, nothing changes
  ASSERT_TRUE(bad.contains("sheet")) << bad.dump(2);
  EXPECT_FALSE(bad["sheet"]["fields"][0]["error"].get<std::string>().empty()) << bad.dump(2);
  EXPECT_EQ(bad["speeds"]["move_xy"], state("open.json")["speeds"]["move_xy"]);
  const json ran = state("ran.json");
  EXPECT_FALSE(ran.contains("sheet"));
  EXPECT_EQ(ran["speeds"]["move_xy"], 2.5);
  EXPECT_TRUE(has_line(ran["log"], "> VS, 2.5"));
}

TEST_F(GuiWindow, AltAndAGroupsLetterOpensItsMenu) {
  ASSERT_EQ(gui("wait idle\ntype MX, 3\nkey Enter\nwait idle\nkey alt+z\nwait frames 3\n"
                "dump zero.json\nclick ZX\nwait idle\nwait frames 2\ndump zeroed.json\n"
                "key alt+m\nwait frames 3\ndump move.json\n"),
            0)
      << out_;
  EXPECT_EQ(state("zero.json")["group_menu"], "Zero");
  const json zeroed = state("zeroed.json");  // ZX from the menu: X 3 is working 0 now
  EXPECT_EQ(zeroed["group_menu"], "");
  EXPECT_EQ(zeroed["position"][0], 0);
  EXPECT_EQ(state("move.json")["group_menu"], "Move");
}

TEST_F(GuiWindow, RunsAFileOnTheSimCardWithItsPreview) {
  ASSERT_EQ(gui("wait idle\nscreenshot before.png\ndump loaded.json\nclick Start\nwait idle\n"
                "dump after.json\n",
                fmt::format("'{}/parts/demo.sbp'", GANTRY_SOURCE_DIR)),
            0)
      << out_;
  const json loaded = state("loaded.json");
  EXPECT_GT(loaded["preview"]["segments"].get<int>(), 30);
  EXPECT_EQ(loaded["preview"]["violations"], 0);
  const json after = state("after.json");
  EXPECT_EQ(after["state"], "idle");
  EXPECT_GT(after["progress"]["lines"].get<int>(), 30);
  EXPECT_EQ(after["progress"]["line"], after["progress"]["lines"]);
  EXPECT_TRUE(has_line(after["log"], "> start"));
  EXPECT_FALSE(has_line(after["log"], "stopped"));
  EXPECT_EQ(after["position"], json({12, 9, 1, 0, 0, 0}));  // where the file parks
  // The preview is not blank: cuts in orange, jogs in blue.
  const Image im = image("before.png");
  EXPECT_GT(im.count(kPx0, kPy0, kPx1, kPy1, orange), 300);
  EXPECT_GT(im.count(kPx0, kPy0, kPx1, kPy1, blue), 50);
}

// Issue 25: the program listing. A click on a line at rest sets the start line; "Start at
// line" starts there and the bar counts the file's lines (it said "line 25 of 1": the one
// typed FG line's); while the file runs its playing line is highlighted and kept in view; after
// a stop the bar shows where the motion stopped, not 100 %, and no time remaining.
TEST_F(GuiWindow, TheListingSetsTheStartLineAndFollowsThePlayingLine) {
  // Line 19 leaves the tool at X 0, where it is: from line 20 on each line moves at once.
  std::string part = "SW, 0\nMS, 0.5\n";
  // 80 lines of 0.4 s from line 20: under way at the later dump even at a few frames a second.
  for (int i = 3; i <= 100; ++i) part += i % 2 ? "MX, 0\n" : "MX, 0.2\n";
  write("long.sbp", part);
  ASSERT_EQ(gui("wait idle\ndump loaded.json\nclick line 20\nwait frames 2\ndump picked.json\n"
                "click Start at line\nwait frames 30\ndump early.json\nwait frames 120\n"
                "dump later.json\nkey Escape\nwait idle\ndump stopped.json\n",
                "long.sbp --realtime"),
            0)
      << out_;
  const json loaded = state("loaded.json");
  EXPECT_EQ(loaded["listing"]["lines"], 100);
  EXPECT_EQ(loaded["listing"]["highlighted"], 0);
  EXPECT_EQ(loaded["listing"]["start_line"], 1);
  EXPECT_EQ(state("picked.json")["listing"]["start_line"], 20);
  auto in_view = [](const json& l) {
    return l["first_shown"] <= l["highlighted"] && l["highlighted"] <= l["last_shown"];
  };
  const json early = state("early.json");
  ASSERT_EQ(early["state"], "running") << early.dump();
  EXPECT_EQ(early["progress"]["lines"], 100) << early["progress"].dump();
  const int first = early["progress"]["line"].get<int>();
  EXPECT_GE(first, 20) << early["progress"].dump();
  EXPECT_EQ(
      early["progress"]["label"].get<std::string>().find(fmt::format("line {} of 100", first)), 0u)
      << early["progress"].dump();
  EXPECT_EQ(early["listing"]["highlighted"], first);
  EXPECT_TRUE(in_view(early["listing"])) << early["listing"].dump();
  const json later = state("later.json");
  ASSERT_EQ(later["state"], "running") << later.dump();
  EXPECT_GT(later["listing"]["highlighted"].get<int>(), first) << later["listing"].dump();
  EXPECT_EQ(later["listing"]["highlighted"], later["progress"]["line"]);
  EXPECT_TRUE(in_view(later["listing"])) << later["listing"].dump();
  const json stopped = state("stopped.json");
  EXPECT_EQ(stopped["state"], "stopped");
  const json& p = stopped["progress"];
  EXPECT_LT(p["line"].get<int>(), 100) << p.dump();
  EXPECT_LT(p["fraction"].get<double>(), 1) << p.dump();
  EXPECT_EQ(p["label"].get<std::string>().find("100 %"), std::string::npos) << p.dump();
  EXPECT_LT(p["remaining_s"].get<double>(), 0) << p.dump();
  EXPECT_NE(p["times"].get<std::string>().find("remaining -"), std::string::npos) << p.dump();
  EXPECT_EQ(stopped["listing"]["highlighted"], p["line"]);  // where it stopped
}

// Issue 25: the log showed ImGui's ids ("PAUSE###question: continue") and cut long lines off
// at its edge; it names the dialog, and a long line wraps onto more rows.
TEST_F(GuiWindow, TheLogShowsNoInternalIdsAndWrapsLongLines) {
  std::string words;
  for (int i = 0; i < 40; ++i) words += "a long line ";
  write("say.sbp", "PAUSE\nPRINT \"" + words + "end\"\n");
  ASSERT_EQ(gui("wait idle\nclick Start\nwait dialog\nclick Continue\nwait idle\n"
                "wait frames 2\ndump end.json\n",
                "say.sbp"),
            0)
      << out_;
  const json end = state("end.json");
  EXPECT_TRUE(has_line(end["log"], "  PAUSE: continue")) << end["log"].dump();
  EXPECT_FALSE(has_line(end["log"], "###")) << end["log"].dump();
  ASSERT_TRUE(has_line(end["log"], words + "end"));
  EXPECT_GE(end["log_last_rows"].get<int>(), 3) << end["log"].dump();  // 490 characters
}

// Issue 25: the window's preview stopped at the first INPUT; it goes on with the default the
// INPUT offers (the answer Enter at the dialog gives), as `gantry preview` does, and says so.
TEST_F(GuiWindow, ThePreviewGoesOnPastInputWithItsDefault) {
  write("ask.sbp", "&D = 2\nINPUT \"How far\" : &D\nMX, &D\nMY, 3\n");
  ASSERT_EQ(gui("wait idle\ndump s.json\n", "ask.sbp"), 0) << out_;
  const json s = state("s.json");
  EXPECT_EQ(s["preview"]["moves"], 2) << s["preview"].dump();
  ASSERT_TRUE(s["preview"].contains("bounds")) << s["preview"].dump();
  EXPECT_EQ(s["preview"]["bounds"][3], 2);  // X max: MX, &D with &D's default
  EXPECT_EQ(s["preview"]["bounds"][4], 3);
  EXPECT_TRUE(has_line(s["log"], "the preview answered INPUT &D with its default \"2\""))
      << s["log"].dump();
}

// Issue 25: no file-open dialog and no recent files. Ctrl+O opens the dialog in the working
// folder, listing its folders and part files only; a click goes into a folder or opens a file;
// a typed path and Enter open it too; the files opened are listed first in the next session.
TEST_F(GuiWindow, TheFileDialogOpensAPartFileAndTheNextSessionListsItAsRecent) {
  write("pick.sbp", "MX, 2\n");
  write("notes.txt", "not a part file\n");
  fs::create_directories(dir_ / "sub");
  write("sub/other.nc", "G0 X1 Y1\n");
  ASSERT_EQ(gui("wait idle\nkey ctrl+o\nwait frames 3\ndump open.json\nclick sub/\nwait frames 2\n"
                "dump sub.json\nclick Up\nwait frames 2\nclick pick.sbp\nwait idle\n"
                "wait frames 2\ndump loaded.json\n"),
            0)
      << out_;
  const json open = state("open.json");
  EXPECT_TRUE(open["file_dialog"]["showing"]) << open.dump();
  EXPECT_EQ(open["file_dialog"]["folder"], dir_.string());
  EXPECT_EQ(open["file_dialog"]["entries"], json({"config/", "sub/", "pick.sbp"}))
      << open["file_dialog"].dump();
  EXPECT_EQ(state("sub.json")["file_dialog"]["entries"], json({"other.nc"}));
  const json loaded = state("loaded.json");
  EXPECT_FALSE(loaded["file_dialog"]["showing"]);
  EXPECT_EQ(loaded["preview"]["file"], (dir_ / "pick.sbp").string());
  EXPECT_EQ(loaded["preview"]["moves"], 1);
  EXPECT_EQ(loaded["listing"]["lines"], 1);
  EXPECT_EQ(loaded["recent_files"], json({(dir_ / "pick.sbp").string()}));
  // The next session: the list was kept beside the machine's state; a typed path opens.
  EXPECT_TRUE(fs::exists(dir_ / "config/gantry/values/recent_files.txt"));
  ASSERT_EQ(gui("wait idle\nkey ctrl+o\nwait frames 3\ndump again.json\ntype sub/other.nc\n"
                "key Enter\nwait idle\nwait frames 2\ndump typed.json\n"),
            0)
      << out_;
  EXPECT_EQ(state("again.json")["recent_files"], json({(dir_ / "pick.sbp").string()}));
  const json typed = state("typed.json");
  EXPECT_EQ(typed["preview"]["file"], (dir_ / "sub/other.nc").string());
  EXPECT_EQ(typed["recent_files"],
            json({(dir_ / "sub/other.nc").string(), (dir_ / "pick.sbp").string()}));
}

// Issue 25: "SO, 1, 1" in a running file left the output lights dark (they showed the
// interpreter's state); they and the spindle line follow what the card plays.
TEST_F(GuiWindow, TheOutputLightsAndSpindleFollowTheRunningFile) {
  write("spin.sbp", "SW, 0\nMS, 2\nTR, 15000\nSO, 1, 1\nSO, 4, 1\nMX, 3\nSO, 4, 0\nMX, 0\n");
  ASSERT_EQ(gui("wait idle\nclick Start\nwait frames 40\nkey Space\nwait frames 40\n"
                "dump paused.json\nkey Space\nwait idle\ndump after.json\n",
                "spin.sbp --realtime"),
            0)
      << out_;
  const json paused = state("paused.json");
  ASSERT_EQ(paused["state"], "paused") << paused.dump();
  EXPECT_EQ(paused["outputs"], 0b1001) << paused.dump();  // switches 1 and 4, as played
  // No speed output in the default profile: TR's RPM is only recorded, and shown at rest.
  EXPECT_EQ(paused["spindle"], "spindle on");
  const json after = state("after.json");
  EXPECT_EQ(after["outputs"], 0);  // the file's end switched them off
  EXPECT_EQ(after["spindle"], "spindle off, 15000 RPM (set on the spindle; TR recorded it)");
}

// Issue 25: no live feed override in the window. + and - step it by 10 % while a file runs,
// within 10 % to 200 %, and the readout and the log say it. (What the planner has already
// planned keeps its speed: docs/controller.md.)
TEST_F(GuiWindow, PlusAndMinusStepTheFeedOverrideWhileAFileRuns) {
  write("long.sbp", "SW, 0\nMS, 1\nMX, 1\nMX, 2\nMX, 3\n");
  ASSERT_EQ(gui("wait idle\nclick Start\nwait frames 10\nkey Equal\nkey Equal\nkey Equal\n"
                "key Minus\nwait frames 2\ndump faster.json\nwait idle\ndump after.json\n",
                "long.sbp --realtime"),
            0)
      << out_;
  const json faster = state("faster.json");
  EXPECT_DOUBLE_EQ(faster["feed_override"].get<double>(), 1.2) << faster.dump();
  EXPECT_TRUE(has_line(faster["log"], "feed 120 % (moves already planned keep their speed)"))
      << faster.dump();
  const json after = state("after.json");
  EXPECT_EQ(after["state"], "idle");
  EXPECT_DOUBLE_EQ(after["feed_override"].get<double>(), 1.2);  // it stays for the next run
}

TEST_F(GuiWindow, KeypadButtonsAndKeysJogInFixedSteps) {
  ASSERT_EQ(gui("click X+\nwait idle\nclick X+\nwait idle\nclick Y+\nwait idle\n"
                "type K\nkey Enter\nwait frames 2\nkey Right\nwait idle\nkey PageUp\nwait idle\n"
                "dump keys.json\nkey Escape\nwait frames 2\ndump s.json\n"),
            0)
      << out_;
  const json keys = state("keys.json");
  EXPECT_TRUE(keys["keypad"]["keys"]);
  const json s = state("s.json");
  EXPECT_FALSE(s["keypad"]["keys"]);  // Esc gives the keys back to the command line
  EXPECT_NEAR(s["position"][0].get<double>(), 0.3, 1e-12);
  EXPECT_NEAR(s["position"][1].get<double>(), 0.1, 1e-12);
  EXPECT_NEAR(s["position"][2].get<double>(), 0.1, 1e-12);
}

// Issue 25: in continuous mode a tap of a key or of a button is one step of the keypad step
// (it jogged until the key came up, then ramped down: 0.42 in), as at the terminal; a key
// held past half a second jogs until it is let go (docs/console.md, "Taps and held keys").
TEST_F(GuiWindow, InContinuousModeATapIsOneStepAndAHoldJogsUntilLetGo) {
  // The simulated card in real time can run dry on a loaded machine (an underrun stops the
  // jog, and the status says so): the card is given 250 ms of lead (20 by default), and a
  // run that still ran dry is tried again, up to three times.
  std::ifstream in(fs::path(GANTRY_SOURCE_DIR) / "settings/default.toml");
  std::stringstream text;
  text << in.rdbuf();
  std::string profile = text.str();
  const std::size_t lead = profile.find("lead_ms = 20.0");
  ASSERT_NE(lead, std::string::npos);
  write("lead.toml", profile.replace(lead, 14, "lead_ms = 250.0"));
  for (int attempt = 0; attempt < 3; ++attempt) {
    fs::remove_all(dir_ / "config");  // the machine memory: each attempt starts at 0
    fs::create_directories(dir_ / "config");
    ASSERT_EQ(gui("wait idle\nclick Fixed step\ntype K\nkey Enter\nwait frames 2\ntap Right\n"
                  "wait idle\ndump tap.json\nclick X+\nwait idle\ndump click.json\n"
                  "hold Up 1.5\nwait idle\ndump hold.json\nscreenshot hold.png\n",
                  "--realtime --profile lead.toml"),
              0)
        << out_;
    bool dry = false;
    for (const char* dump : {"tap.json", "click.json", "hold.json"})
      dry = dry || state(dump)["message"].get<std::string>().find("underrun") != std::string::npos;
    if (!dry) break;
  }
  const json tap = state("tap.json");
  EXPECT_FALSE(tap["keypad"]["step"]);  // continuous mode
  EXPECT_NEAR(tap["position"][0].get<double>(), 0.1, 1e-12);
  EXPECT_NEAR(tap["position"][1].get<double>(), 0, 1e-12);
  const json click = state("click.json");
  EXPECT_NEAR(click["position"][0].get<double>(), 0.2, 1e-12);
  // Held 1.5 s: a step, then a continuous jog from 0.5 s at move speed (2 in/s) until let go,
  // far more than a step and short of the table's 18 in.
  const json hold = state("hold.json");
  EXPECT_EQ(hold["state"], "idle");
  EXPECT_NEAR(hold["position"][0].get<double>(), 0.2, 1e-3);  // the pulses played: a motor step
  EXPECT_GT(hold["position"][1].get<double>(), 0.6) << hold["message"];
  EXPECT_LT(hold["position"][1].get<double>(), 3.5);
  for (const json& l : hold["log"])
    EXPECT_EQ(l.get<std::string>().find("refused"), std::string::npos) << l;
}

// The profile's [pendant] keys in the window: F5 a step of 0.25 in X, Ctrl+G the feed + button
// (the same binding table as the terminal console's).
TEST_F(GuiWindow, KeysBoundInThePendantSectionActAsThePendantsButtons) {
  std::ifstream in(std::string(GANTRY_SOURCE_DIR) + "/settings/default.toml");
  std::stringstream profile;
  profile << in.rdbuf();
  write("profile.toml", profile.str() +
                            "\n[pendant]\nkeys = [\"F5 = step x+ 0.25\", \"Ctrl+G = feed +\"]\n");
  ASSERT_EQ(gui("wait idle\nkey F5\nwait frames 2\nwait idle\nkey ctrl+G\nwait frames 3\n"
                "dump s.json\n",
                "--profile profile.toml"),
            0)
      << out_;
  const json s = state("s.json");
  EXPECT_NEAR(s["position"][0].get<double>(), 0.25, 1e-12) << s.dump();
  EXPECT_EQ(s["position"][1], 0);
  EXPECT_DOUBLE_EQ(s["feed_override"].get<double>(), 1.1) << s.dump();
}

TEST_F(GuiWindow, PauseInputAndMsgboxAreDialogs) {
  write("ask.sbp",
        "INPUT \"How far\" &D\nMX, &D\nPAUSE\nMSGBOX(Go on?, YesNo, Check)\n"
        "IF &MSGANSWER = \"Yes\" THEN MY, 1\n");
  ASSERT_EQ(gui("wait idle\nclick Start\nwait dialog\ndump input.json\nscreenshot input.png\n"
                "type 2\nkey Enter\nwait dialog\ndump pause.json\nclick Continue\nwait dialog\n"
                "dump box.json\nclick Yes\nwait idle\ndump end.json\n",
                "ask.sbp"),
            0)
      << out_;
  const json input = state("input.json");
  EXPECT_EQ(input["dialog"]["kind"], "INPUT");
  EXPECT_EQ(input["dialog"]["text"], "How far");
  EXPECT_EQ(state("pause.json")["dialog"]["kind"], "PAUSE");
  const json box = state("box.json");
  EXPECT_EQ(box["dialog"]["kind"], "MSGBOX");
  EXPECT_EQ(box["dialog"]["buttons"], json({"Yes", "No"}));
  const json end = state("end.json");
  EXPECT_EQ(end["state"], "idle");
  EXPECT_EQ(end["position"], json({2, 1, 0, 0, 0, 0}));
}

TEST_F(GuiWindow, ALiveRunWarnsBeforeTheToolMoves) {
  ASSERT_EQ(gui("type MX, 1\nkey Enter\nwait frames 10\ndump warning.json\nwait idle\n"
                "dump done.json\n",
                "--realtime"),
            0)
      << out_;
  const json warning = state("warning.json");  // SW's 2 s: flashing, nothing moves yet
  EXPECT_EQ(warning["warning"], true);
  EXPECT_EQ(warning["position"][0], 0);
  const json done = state("done.json");
  EXPECT_EQ(done["warning"], false);
  EXPECT_NEAR(done["position"][0].get<double>(), 1, 1e-9);
}

TEST_F(GuiWindow, SpacePausesAndResumesAndF12IsTheEStop) {
  // SW, 0: no warning before the moves, so the pause comes while X moves.
  ASSERT_EQ(gui("type SW, 0\nkey Enter\nwait idle\n"
                "type MX, 3\nkey Enter\nwait frames 3\nkey Space\nwait frames 40\n"
                "dump paused.json\nscreenshot paused.png\nkey Space\nwait idle\ndump resumed.json\n"
                "type MX, 0\nkey Enter\nwait frames 3\nkey F12\nwait frames 3\ndump estop.json\n"
                "type ack\nkey Enter\nwait idle\ndump ack.json\n",
                "--realtime"),
            0)
      << out_;
  const json paused = state("paused.json");
  EXPECT_EQ(paused["state"], "paused");
  EXPECT_GT(paused["position"][0].get<double>(), 0);
  EXPECT_LT(paused["position"][0].get<double>(), 3);
  // Issue 25: paused has its own colour (magenta), not running's cyan, in the state word.
  const Image im = image("paused.png");
  const auto magenta = [](int r, int g, int b) { return r > 200 && g < 150 && b > 200; };
  const auto cyan = [](int r, int g, int b) { return r < 150 && g > 190 && b > 230; };
  EXPECT_GT(im.count(0, 40, 120, 62, magenta), 10);
  EXPECT_EQ(im.count(0, 40, 120, 62, cyan), 0);
  EXPECT_NEAR(state("resumed.json")["position"][0].get<double>(), 3, 1e-9);
  const json estop = state("estop.json");
  EXPECT_EQ(estop["state"], "estop");
  EXPECT_GT(estop["position"][0].get<double>(), 0);  // stopped on the way back
  const json ack = state("ack.json");
  EXPECT_EQ(ack["state"], "idle");
  EXPECT_TRUE(has_line(ack["log"], "E-stop acknowledged"));
}

// Issue 25: after F12 and ack, `MZ, 1` stayed "running" with no motion (the simulated card
// waited for the ticks played before the E-stop). The move plays at once and ends at Z 1.
TEST_F(GuiWindow, AfterAnAcknowledgedEStopTheNextMovePlays) {
  ASSERT_EQ(gui("type SW, 0\nkey Enter\nwait idle\ntype MX, 4\nkey Enter\nwait idle\n"
                "type MX, 0\nkey Enter\nwait frames 20\nkey F12\nwait frames 3\n"
                "type ack\nkey Enter\nwait idle\ntype MZ, 1\nkey Enter\nwait frames 30\n"
                "dump moving.json\nwait idle\ndump done.json\n",
                "--realtime"),
            0)
      << out_;
  const json moving = state("moving.json");  // half a second later: Z on its way, or there
  EXPECT_GT(moving["position"][2].get<double>(), 0.1) << moving.dump();
  const json done = state("done.json");
  EXPECT_EQ(done["state"], "idle");
  EXPECT_NEAR(done["position"][2].get<double>(), 1, 1e-9);
}

TEST_F(GuiWindow, ThePointerShowsTheLineUnderIt) {
  // A raster over the table, 0.1 in apart: in the top view some line is always within the
  // pick's few pixels. Line 2k+1 runs along Y = 0.1 k.
  std::string part = "M2, 24, 0\n";
  for (int k = 1; k <= 180; ++k)
    part += fmt::format("M2, {0}, {1:.1f}\nM2, {2}, {1:.1f}\n", k % 2 ? 24 : 0, 0.1 * k,
                        k % 2 ? 0 : 24);
  write("raster.sbp", part);
  ASSERT_EQ(gui("click Top\nwait idle\nhover 0.5 0.5\nwait frames 3\ndump h.json\n"
                "screenshot h.png\n",
                "raster.sbp"),
            0)
      << out_;
  const json h = state("h.json");
  const int line = h["preview"]["hover_line"].get<int>();
  ASSERT_GT(line, 0) << h["preview"].dump();
  // The middle of the view is the middle of the table, Y 9: a line near it.
  const double y = 0.1 * std::floor((line - 1) / 2.0);
  EXPECT_NEAR(y, 9.0, 0.5) << "line " << line;
}

TEST_F(GuiWindow, AScriptErrorNamesItsLine) {
  EXPECT_EQ(gui("wait idle\nclick Nothing Such\n"), 2);
  EXPECT_NE(out_.find("script line 2: no button named 'Nothing Such'"), std::string::npos) << out_;
  EXPECT_EQ(gui("fly\n"), 2);
  EXPECT_NE(out_.find("script.txt:1: unknown action 'fly'"), std::string::npos) << out_;
}

// Issue 25: the window restores the position the last session left (docs/machine_state.md)
// and says so; killed mid-move, it is unconfirmed, and stays so in the file saved at exit.
TEST_F(GuiWindow, ThePositionOfTheLastSessionIsRestoredAndSaid) {
  const fs::path state_file = dir_ / "config/gantry/values/Desktop_24x18__inches_.state.toml";
  fs::create_directories(state_file.parent_path());
  std::ofstream(state_file) << "motion = \"moving\"\nconfirmed = true\nunits = \"in\"\n"
                               "position = { x = 3.0, y = 2.0 }\nzero = { x = 1.0 }\n";
  ASSERT_EQ(gui("wait idle\ndump s.json\n"), 0) << out_;
  const json s = state("s.json");
  EXPECT_EQ(s["position"], json({2, 2, 0, 0, 0, 0}));  // working: table base less the zero
  EXPECT_TRUE(has_line(s["log"], "position restored from the last session: X 3.0000 Y 2.0000"))
      << s["log"].dump();
  EXPECT_TRUE(has_line(s["log"], "UNCONFIRMED: the last session ended mid-move"))
      << s["log"].dump();
  std::stringstream saved;
  saved << std::ifstream(state_file).rdbuf();
  EXPECT_NE(saved.str().find("\nmotion = \"at rest\""), std::string::npos) << saved.str();
  EXPECT_NE(saved.str().find("\nconfirmed = false"), std::string::npos) << saved.str();
}

// ---- layout, keypad, offsets, macros, theme (issue 25) ----------------------------------------

// Issue 25: at 1024 x 600 the Start/Pause/Stop/E-stop row was cut off. Every button drawn is
// wholly on the screen (a script's click on one that is not fails), and the run controls work.
TEST_F(GuiWindow, EveryControlFitsAt1024By600) {
  write("short.sbp", "MX, 1\nMY, 1\n");
  ASSERT_EQ(gui("wait idle\ndump s.json\nscreenshot s.png\nclick Start\nwait idle\n"
                "click X+\nwait idle\ndump after.json\nclick E-STOP\nwait frames 3\n"
                "dump estop.json\nclick Ack\nwait idle\ndump ack.json\n",
                "short.sbp --size 1024x600"),
            0)
      << out_;
  const json s = state("s.json");
  EXPECT_EQ(s["layout"]["display"], json({1024, 600}));
  for (const char* name : {"Start", "Pause", "Stop", "E-STOP", "Load", "X+", "Z-", "Stop jog"}) {
    ASSERT_TRUE(s["buttons"].contains(name)) << name << " was not drawn";
    EXPECT_TRUE(s["buttons"][name]["whole"]) << name << ": " << s["buttons"][name].dump();
    EXPECT_LE(s["buttons"][name]["rect"][3].get<double>(), 600) << name;
  }
  // The readout's digits are larger than the text even here.
  EXPECT_GT(s["layout"]["digits_px"].get<double>(), s["layout"]["font_px"].get<double>());
  const Image im = image("s.png");
  EXPECT_EQ(im.w, 1024);
  EXPECT_EQ(im.h, 600);
  const json after = state("after.json");  // the file ran, then X+ stepped
  EXPECT_NEAR(after["position"][0].get<double>(), 1.1, 1e-9);
  EXPECT_EQ(state("estop.json")["state"], "estop");
  EXPECT_EQ(state("ack.json")["state"], "idle");
}

// A width alone still works (16:10), and at 4K the fonts, the column and the digits grow.
TEST_F(GuiWindow, FontsAndTheReadoutScaleWithTheWindow) {
  ASSERT_EQ(gui("wait idle\ndump s.json\n", "--size 1024"), 0) << out_;
  EXPECT_EQ(state("s.json")["layout"]["display"], json({1024, 640}));
  ASSERT_EQ(gui("wait idle\ndump s.json\n"), 0) << out_;
  const json normal = state("s.json");
  ASSERT_EQ(gui("wait idle\ndump s.json\nscreenshot s.png\nclick Y+\nwait idle\n"
                "dump after.json\n",
                "--size 3840x2160"),
            0)
      << out_;
  const json big = state("s.json");
  EXPECT_EQ(normal["layout"]["scale"], 1);
  EXPECT_GT(big["layout"]["scale"].get<double>(), 2);
  EXPECT_GT(big["layout"]["font_px"].get<double>(), 2 * normal["layout"]["font_px"].get<double>());
  EXPECT_GT(big["layout"]["digits_px"].get<double>(),
            2 * normal["layout"]["digits_px"].get<double>());
  for (const auto& [name, b] : big["buttons"].items()) EXPECT_TRUE(b["whole"]) << name;
  // The keypad's buttons grow too.
  const json& y = big["buttons"]["Y+"]["rect"];
  EXPECT_GT(y[2].get<double>() - y[0].get<double>(), 100);
  const Image im = image("s.png");
  EXPECT_EQ(im.w, 3840);
  EXPECT_EQ(im.h, 2160);
  EXPECT_NEAR(state("after.json")["position"][1].get<double>(), 0.1, 1e-9);
}

// Issue 25: the first line typed in a new window did not run (what was typed before the
// command line had the keys was dropped); the script types from the very first frame.
TEST_F(GuiWindow, TheFirstLineTypedInANewWindowRuns) {
  ASSERT_EQ(gui("type MX, 1\nkey Enter\nwait idle\ndump s.json\n"), 0) << out_;
  const json s = state("s.json");
  EXPECT_EQ(s["history"], json({"MX, 1"}));
  EXPECT_EQ(s["position"][0], 1);
}

// Issue 25: a quick Enter tap (pressed and released between two frames) in a fill-in sheet
// was missed: the sheet looked at the key once a frame. Taps now count, in the sheet and at
// the command line.
TEST_F(GuiWindow, AQuickEnterTapCountsInAFillInSheet) {
  ASSERT_EQ(gui("wait idle\ntype MY\nkey Enter\nwait frames 3\ndump open.json\ntype 3\n"
                "tap Enter\nwait idle\ndump ran.json\ntype MZ, 0.5\ntap Enter\nwait idle\n"
                "dump line.json\n"),
            0)
      << out_;
  const json open = state("open.json");
  ASSERT_TRUE(open.contains("sheet")) << open.dump(2);
  const json ran = state("ran.json");
  EXPECT_FALSE(ran.contains("sheet")) << ran["sheet"].dump(2);
  EXPECT_EQ(ran["position"][1], 3);
  EXPECT_TRUE(has_line(ran["log"], "> MY, 3"));
  EXPECT_EQ(state("line.json")["position"][2], 0.5);
}

// Issue 25: jog step presets, 0.001 to 1 in (0.01 to 10 mm); a step jog goes the one chosen,
// VD's keypad step when none is.
TEST_F(GuiWindow, TheKeypadsStepPresetsSetTheStep) {
  ASSERT_EQ(gui("wait idle\nclick 0.01\nclick X+\nwait idle\nclick 1\nclick Y+\nwait idle\n"
                "dump in.json\nclick VD\nclick X+\nwait idle\ndump vd.json\n"
                "type VD, , , 1\nkey Enter\nwait idle\nclick 10\nwait frames 2\ndump mm.json\n"),
            0)
      << out_;
  const json in = state("in.json");
  EXPECT_NEAR(in["position"][0].get<double>(), 0.01, 1e-12);
  EXPECT_NEAR(in["position"][1].get<double>(), 1, 1e-12);
  EXPECT_EQ(in["keypad"]["step_size"], 1);
  const json vd = state("vd.json");  // VD's keypad step, 0.1 in
  EXPECT_NEAR(vd["position"][0].get<double>(), 0.11, 1e-12);
  const json mm = state("mm.json");
  EXPECT_EQ(mm["units"], "mm");
  EXPECT_EQ(mm["keypad"]["step_size"], 10);
  EXPECT_TRUE(mm["buttons"].contains("0.01"));
  EXPECT_FALSE(mm["buttons"].contains("0.001"));
}

// Issue 25: a work-offset view: machine (table base), offset and work position per axis, and a
// Zero button per axis that runs ZX, ZY ... as typed.
TEST_F(GuiWindow, TheOffsetsViewZeroesAnAxisAsTheConsoleDoes) {
  ASSERT_EQ(gui("wait idle\ntype MX, 3\nkey Enter\nwait idle\ntype MY, 2\nkey Enter\nwait idle\n"
                "click Offsets\nwait frames 2\ndump before.json\nclick Zero X\nwait idle\n"
                "wait frames 2\ndump after.json\nscreenshot after.png\n",
                "--size 1024x600"),
            0)
      << out_;
  const json before = state("before.json");
  EXPECT_TRUE(before["offsets_window"]);
  EXPECT_EQ(before["offsets"][0],
            json({{"axis", "X"}, {"machine", 3}, {"offset", 0}, {"work", 3}}));
  EXPECT_TRUE(before["buttons"]["Zero X"]["whole"]);
  const json after = state("after.json");
  EXPECT_TRUE(has_line(after["log"], "> ZX"));  // the console's command, run as typed
  EXPECT_EQ(after["offsets"][0],
            json({{"axis", "X"}, {"machine", 3}, {"offset", 3}, {"work", 0}}));
  EXPECT_EQ(after["offsets"][1],
            json({{"axis", "Y"}, {"machine", 2}, {"offset", 0}, {"work", 2}}));
  EXPECT_EQ(after["position"][0], 0);
}

// Issue 25: the readout marks a position the machine memory holds unconfirmed (a kill mid-move
// here), and Confirm vouches for it as `gantry state --confirm` does.
TEST_F(GuiWindow, AnUnconfirmedPositionIsMarkedUntilConfirmed) {
  const fs::path state_file = dir_ / "config/gantry/values/Desktop_24x18__inches_.state.toml";
  fs::create_directories(state_file.parent_path());
  std::ofstream(state_file) << "motion = \"moving\"\nconfirmed = true\nunits = \"in\"\n"
                               "position = { x = 3.0, y = 2.0 }\n";
  ASSERT_EQ(gui("wait idle\ndump before.json\nscreenshot before.png\nclick Confirm\n"
                "wait frames 2\ndump after.json\n"),
            0)
      << out_;
  const json before = state("before.json");
  EXPECT_FALSE(before["confirmed"]);
  EXPECT_TRUE(before["buttons"]["Confirm"]["whole"]);
  // The mark: yellow text on the state line.
  const Image im = image("before.png");
  const auto yellow = [](int r, int g, int b) { return r > 200 && g > 170 && b < 120; };
  EXPECT_GT(im.count(110, 40, 370, 62, yellow), 20);
  const json after = state("after.json");
  EXPECT_TRUE(after["confirmed"]);
  EXPECT_FALSE(after["buttons"].contains("Confirm"));
  EXPECT_TRUE(has_line(after["log"], "the position is confirmed"));
  std::stringstream saved;
  saved << std::ifstream(state_file).rdbuf();
  EXPECT_NE(saved.str().find("\nconfirmed = true"), std::string::npos) << saved.str();
}

// Issue 25: macro buttons. C2 runs the custom cut's file as typing C2 does (here the
// operator's own C2.sbp in --macros), and each part file there has a button running it (FP).
TEST_F(GuiWindow, MacroButtonsRunTheCustomCutsAndTheOperatorsFiles) {
  fs::create_directories(dir_ / "macros");
  std::ofstream(dir_ / "macros/C2.sbp") << "PRINT \"my C2\"\nMZ, 0.5\n";
  std::ofstream(dir_ / "macros/surface.sbp") << "MX, 2\n";
  ASSERT_EQ(gui("wait idle\nclick Macros\nwait frames 2\ndump open.json\nclick C2\nwait idle\n"
                "wait frames 2\ndump c2.json\nclick surface\nwait idle\nwait frames 2\n"
                "dump part.json\n",
                "--macros macros"),
            0)
      << out_;
  const json open = state("open.json");
  for (const char* name : {"C2", "C3", "C6", "C7", "C9", "surface"})
    EXPECT_TRUE(open["buttons"].contains(name)) << name;
  const json c2 = state("c2.json");
  EXPECT_TRUE(has_line(c2["log"], "> C2")) << c2["log"].dump();
  EXPECT_TRUE(has_line(c2["log"], "my C2")) << c2["log"].dump();
  EXPECT_EQ(c2["position"][2], 0.5);
  const json part = state("part.json");
  EXPECT_TRUE(has_line(part["log"], "> FP, \"")) << part["log"].dump();
  EXPECT_EQ(part["position"][0], 2);
}

// Issue 25: a light theme (View > Light theme) for a bright shop: light backgrounds, dark text.
TEST_F(GuiWindow, TheLightThemeHasLightBackgroundsAndDarkText) {
  ASSERT_EQ(gui("wait idle\ntype MX, 1\nkey Enter\nwait idle\nscreenshot dark.png\n"
                "click Light theme\nwait frames 3\nscreenshot light.png\ndump s.json\n"),
            0)
      << out_;
  EXPECT_EQ(state("s.json")["theme"], "light");
  const auto bright = [](int r, int g, int b) { return r > 200 && g > 200 && b > 200; };
  const auto dark = [](int r, int g, int b) { return r < 70 && g < 70 && b < 70; };
  // The console's log (right, bottom) and the readout (left, top): mostly background.
  const Image d = image("dark.png"), l = image("light.png");
  const int log_area = (1260 - 390) * (720 - 590);
  EXPECT_LT(d.count(390, 590, 1260, 720, bright), log_area / 20);
  EXPECT_GT(l.count(390, 590, 1260, 720, bright), log_area * 8 / 10);
  EXPECT_GT(l.count(0, 40, 370, 300, bright), 370 * 260 / 2);
  // Readable: the readout's digits are dark on it.
  EXPECT_GT(l.count(0, 60, 370, 200, dark), 1000);
}

// Issue 25: while a file FP called played, the listing highlighted that file's line number in
// the top file's text. It shows the file that plays, and says which it is.
TEST_F(GuiWindow, TheListingShowsTheCalledFileWhileItPlays) {
  write("main.sbp", "SW, 0\nMX, 0.5\nFP, sub.sbp\nMX, 0\n");
  write("sub.sbp", "' the called file\nMY, 0.5\nMY, 1\nPAUSE \"in the called file\"\nMY, 0\n");
  ASSERT_EQ(gui("wait idle\ndump loaded.json\nclick Start\nwait dialog\nwait frames 3\n"
                "dump called.json\nscreenshot called.png\nclick Continue\nwait idle\n"
                "wait frames 2\ndump done.json\n",
                "main.sbp"),
            0)
      << out_;
  const json loaded = state("loaded.json")["listing"];
  EXPECT_EQ(loaded["lines"], 4);
  EXPECT_EQ(fs::path(loaded["file"].get<std::string>()).filename(), "main.sbp");
  EXPECT_FALSE(loaded["called"]);
  const json called = state("called.json")["listing"];
  EXPECT_TRUE(called["called"]) << called.dump();
  EXPECT_EQ(fs::path(called["file"].get<std::string>()).filename(), "sub.sbp") << called.dump();
  EXPECT_EQ(called["lines"], 5);
  EXPECT_EQ(called["highlighted"], 3) << called.dump();  // MY, 1: the motion before the PAUSE
  const json done = state("done.json")["listing"];  // over: the top file again
  EXPECT_FALSE(done["called"]) << done.dump();
  EXPECT_EQ(fs::path(done["file"].get<std::string>()).filename(), "main.sbp");
}

// Issue 25: at rest after a stop inside a called file the listing keeps showing that file,
// with the line the run stopped at, and says so: its heading said "playing" at rest.
TEST_F(GuiWindow, AfterAStopInACalledFileTheListingShowsWhereItStopped) {
  write("main.sbp", "SW, 0\nMX, 0.5\nFP, sub.sbp\nMX, 0\n");
  write("sub.sbp", "' the called file\nMY, 0.5\nMY, 1\nPAUSE \"in the called file\"\nMY, 0\n");
  ASSERT_EQ(gui("wait idle\nclick Start\nwait dialog\nwait frames 3\ndump called.json\n"
                "key Escape\nwait idle\nwait frames 2\ndump s.json\nscreenshot s.png\n",
                "main.sbp"),
            0)
      << out_;
  EXPECT_EQ(state("called.json")["listing"]["heading"], "playing sub.sbp (called from main.sbp)");
  const json s = state("s.json");
  EXPECT_EQ(s["state"], "stopped");
  const json& l = s["listing"];
  EXPECT_TRUE(l["called"]) << l.dump();
  EXPECT_EQ(fs::path(l["file"].get<std::string>()).filename(), "sub.sbp") << l.dump();
  EXPECT_EQ(l["highlighted"], 4) << l.dump();  // the PAUSE the run stopped at, in sub.sbp
  EXPECT_EQ(l["heading"], "stopped in sub.sbp (called from main.sbp)");
  EXPECT_EQ(s["progress"]["line"], 3);  // the FP line, in main.sbp
}

// Issue 25: at 1280 x 800 the listing showed about 4 lines; it gets 8 before the readout's
// digits grow past twice the text.
TEST_F(GuiWindow, TheListingShowsEightLinesAt1280By800) {
  std::string part;
  for (int i = 1; i <= 60; ++i) part += i % 2 ? "MX, 1\n" : "MX, 0\n";
  write("many.sbp", part);
  ASSERT_EQ(gui("wait idle\nwait frames 2\ndump s.json\nscreenshot s.png\n", "many.sbp"), 0)
      << out_;
  const json s = state("s.json");
  EXPECT_EQ(s["layout"]["display"], json({1280, 800}));
  const json& l = s["listing"];
  EXPECT_GE(l["last_shown"].get<int>() - l["first_shown"].get<int>() + 1, 8) << l.dump();
  EXPECT_GT(s["layout"]["digits_px"].get<double>(), 2 * s["layout"]["font_px"].get<double>() - 1);
  for (const auto& [name, b] : s["buttons"].items()) EXPECT_TRUE(b["whole"]) << name;
}

// Issue 25: the file dialog walks with the keys: Down/Up mark an entry, Enter opens it (a
// folder: goes in), Backspace in an empty path goes to the parent with the folder left marked.
TEST_F(GuiWindow, TheFileDialogWalksWithTheArrowKeys) {
  write("a.sbp", "MX, 1\n");
  write("pick.sbp", "MX, 2\n");
  fs::create_directories(dir_ / "sub");
  write("sub/other.nc", "G0 X1 Y1\n");
  ASSERT_EQ(gui("wait idle\nkey ctrl+o\nwait frames 3\nkey Down\nkey Down\nwait frames 2\n"
                "dump marked.json\nscreenshot marked.png\nkey Enter\nwait frames 2\n"
                "dump sub.json\nkey Backspace\nwait frames 2\ndump up.json\nkey Down\nkey Down\n"
                "key Up\nwait frames 2\ndump a.json\nkey Enter\nwait idle\nwait frames 2\n"
                "dump loaded.json\n"),
            0)
      << out_;
  const json marked = state("marked.json")["file_dialog"];
  EXPECT_EQ(marked["entries"], json({"config/", "sub/", "a.sbp", "pick.sbp"})) << marked.dump();
  EXPECT_EQ(marked["marked"], "sub/") << marked.dump();
  const json sub = state("sub.json")["file_dialog"];
  EXPECT_EQ(sub["folder"], (dir_ / "sub").string()) << sub.dump();
  EXPECT_EQ(sub["entries"], json({"other.nc"}));
  const json up = state("up.json")["file_dialog"];
  EXPECT_EQ(up["folder"], dir_.string()) << up.dump();
  EXPECT_EQ(up["marked"], "sub/") << up.dump();
  EXPECT_EQ(state("a.json")["file_dialog"]["marked"], "a.sbp");
  const json loaded = state("loaded.json");
  EXPECT_FALSE(loaded["file_dialog"]["showing"]);
  EXPECT_EQ(loaded["preview"]["file"], (dir_ / "a.sbp").string());
}

// Issue 25: File > Open... opens the dialog Ctrl+O opens, in the loaded file's folder.
TEST_F(GuiWindow, FileOpenInTheMenuOpensTheFileDialog) {
  fs::create_directories(dir_ / "jobs");
  write("jobs/one.sbp", "MX, 1\n");
  ASSERT_EQ(gui("wait idle\nclick File > Open...\nwait frames 3\ndump s.json\n"
                "screenshot s.png\n",
                "jobs/one.sbp"),
            0)
      << out_;
  const json d = state("s.json")["file_dialog"];
  EXPECT_TRUE(d["showing"]) << d.dump();
  EXPECT_EQ(d["folder"], (dir_ / "jobs").string()) << d.dump();
  EXPECT_EQ(d["entries"], json({"one.sbp"}));
}

// Issue 25: E-STOP was black on dark red in the light theme; it is white on red in both.
TEST_F(GuiWindow, TheEStopReadsWhiteOnRedInBothThemes) {
  ASSERT_EQ(gui("wait idle\nwait frames 2\ndump dark.json\nscreenshot dark.png\n"
                "click Light theme\nwait frames 3\ndump light.json\nscreenshot light.png\n"),
            0)
      << out_;
  const auto white = [](int r, int g, int b) { return r > 220 && g > 220 && b > 220; };
  const auto red = [](int r, int g, int b) { return r > 140 && g < 60 && b < 60; };
  const auto black = [](int r, int g, int b) { return r < 60 && g < 60 && b < 60; };
  for (const char* theme : {"dark", "light"}) {
    const json dump = state(fmt::format("{}.json", theme));
    const json& b = dump["buttons"]["E-STOP"]["rect"];
    ASSERT_TRUE(b.is_array()) << theme;
    auto at = [&](int i, int inset) { return static_cast<int>(b[i].get<double>()) + inset; };
    const int x0 = at(0, 2), y0 = at(1, 2), x1 = at(2, -2), y1 = at(3, -2);
    const Image im = image(fmt::format("{}.png", theme));
    const int area = (x1 - x0) * (y1 - y0);
    EXPECT_GT(im.count(x0, y0, x1, y1, red), area / 2) << theme;
    EXPECT_GT(im.count(x0, y0, x1, y1, white), 20) << theme << ": the letters are not white";
    EXPECT_EQ(im.count(x0, y0, x1, y1, black), 0) << theme << ": dark letters on red";
  }
}

}  // namespace


// The window as the documentation shows it (docs/figures/console_window.png): the demo part
// run to its end, with the listing, the offsets and the macros open.
TEST_F(GuiWindow, TheDocumentationsPictureOfTheWindow) {
  fs::create_directories(dir_ / "macros");
  std::ofstream(dir_ / "macros/surface.sbp") << "MX, 2\n";
  ASSERT_EQ(gui("wait idle\nclick Offsets\nclick Macros\nclick Start\nwait idle\nwait frames 3\n"
                "dump s.json\nscreenshot window.png\n",
                fmt::format("'{}/parts/demo.sbp' --size 1280x800 --macros macros", GANTRY_SOURCE_DIR)),
            0)
      << out_;
  const json s = state("s.json");
  EXPECT_EQ(s["state"], "idle");
  EXPECT_TRUE(s["offsets_window"]);
  EXPECT_GT(s["listing"]["lines"].get<int>(), 30);
  EXPECT_EQ(s["progress"]["line"], s["progress"]["lines"]);
  EXPECT_GT(image("window.png").count(kPx0, kPy0, kPx1, kPy1, orange), 300);
  figure("window.png", "console_window.png");
}
