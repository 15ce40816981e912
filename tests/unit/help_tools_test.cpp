// The Help (H) and Tools (T) families: what each prints or writes, the moves of the part
// files the tool generators write, and their errors (located, nothing moved, nothing written).
#include <gtest/gtest.h>
#include <unistd.h>  // getpid

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "../support/recording_sink.hpp"
#include "gantry/commands/command_docs.hpp"
#include "gantry/commands/command_table.hpp"
#include "gantry/core/diagnostic.hpp"
#include "gantry/interp/interpreter.hpp"
#include "gantry/lang/script.hpp"
#include "gantry/settings/settings.hpp"

namespace gantry {
namespace {

namespace fs = std::filesystem;

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Each test gets its own folder; the part file runs from there, so relative names land in it.
class HelpToolsTest : public ::testing::Test {
 protected:
  HelpToolsTest() {
    static int counter = 0;
    dir_ = fs::temp_directory_path() / ("gantry_help_tools_test_" + std::to_string(::getpid()) +
                                        "_" + std::to_string(counter++));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  ~HelpToolsTest() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  void write(const std::string& name, const std::string& text) const {
    std::ofstream(path(name), std::ios::binary) << text;
  }

  // Runs `text` as part.sbp in the test's folder; errors fail the test.
  void run(const std::string& text, InterpreterOptions options = {}) {
    auto script = Script::from_text(text, path("part.sbp"));
    ASSERT_TRUE(script->ok()) << format(script->errors().front());
    Interpreter interp(settings, sink, io, store, options);
    try {
      interp.run(script);
    } catch (const GantryError& e) {
      FAIL() << format(e.diagnostic());
    }
  }

  // Runs `text` expecting an error; returns it.
  Diagnostic run_error(const std::string& text) {
    auto script = Script::from_text(text, path("part.sbp"));
    Interpreter interp(settings, sink, io, store);
    try {
      interp.run(script);
    } catch (const GantryError& e) {
      return e.diagnostic();
    }
    ADD_FAILURE() << "no error from:\n" << text;
    return {};
  }

  std::vector<Diagnostic> check(const std::string& text) {
    auto script = Script::from_text(text, path("part.sbp"));
    InterpreterOptions options;
    options.dry_run = true;
    Interpreter interp(settings, sink, io, store, options);
    return interp.check(script);
  }

  // The moves that `file` (in the test's folder) makes when run from working 0.
  std::vector<CanonMove> moves_of(const std::string& file) {
    sink.moves.clear();
    run("FP, " + file + "\n");
    return sink.moves;
  }

  Settings settings = default_settings();
  RecordingSink sink;
  std::string printed;
  ScriptedIO io{true, {}, &printed};
  PersistentStore store;

 private:
  fs::path dir_;
};

// ---- Help ---------------------------------------------------------------------------------

TEST_F(HelpToolsTest, HaPrintsTheVersionAndTheProfile) {
  run("HA\n");
  EXPECT_NE(printed.find(std::string("Gantry ") + GANTRY_VERSION + "\n"), std::string::npos)
      << printed;
  EXPECT_NE(printed.find("Machine profile: " + settings.name + " (units: in, card: sim)"),
            std::string::npos)
      << printed;
  EXPECT_TRUE(sink.moves.empty());
}

TEST_F(HelpToolsTest, WebCommandsPrintShopBotsAddress) {
  for (const char* code : {"HB", "HW", "HN"}) {
    printed.clear();
    run(std::string(code) + "\n");
    EXPECT_NE(printed.find("https://www.shopbottools.com"), std::string::npos) << code;
  }
  printed.clear();
  run("HN\n");
  EXPECT_NE(printed.find("gantry --version"), std::string::npos) << printed;
  EXPECT_NE(printed.find("gantry check FILE"), std::string::npos) << printed;
}

TEST_F(HelpToolsTest, HcListsEveryCodeByGroup) {
  run("HC\n");
  EXPECT_NE(printed.find("docs/commands.md"), std::string::npos);
  EXPECT_NE(printed.find("  Tools      TR TC TD TF TH TI TS TT TU\n"), std::string::npos) << printed;
  for (const CommandSpec& s : CommandTable::standard().all())
    EXPECT_NE(printed.find(" " + std::string(s.code)), std::string::npos) << s.code;
}

TEST_F(HelpToolsTest, HeGivesEachCommandsParametersInPartFileOrder) {
  run("HE\n");
  EXPECT_TRUE(std::regex_search(printed, std::regex("\n  MX  Move X axis +X location\n")))
      << printed;
  EXPECT_TRUE(std::regex_search(printed, std::regex("\n  M2  [^\n]+  X location, Y location\n")));
  EXPECT_TRUE(std::regex_search(printed, std::regex("\n  ZX  Zero X axis\n")));  // no parameters
  EXPECT_TRUE(std::regex_search(printed, std::regex("\n  UI  [^\n]+\\[cannot run here\\]\n")));
  // One line per command, under its group.
  size_t lines = 0;
  for (const CommandSpec& s : CommandTable::standard().all())
    lines += printed.find("\n  " + std::string(s.code) + "  ") != std::string::npos;
  EXPECT_EQ(lines, CommandTable::standard().all().size());
}

TEST_F(HelpToolsTest, HrIsTheCommandList) {
  run("HR\n");
  EXPECT_EQ(printed, command_list(CommandTable::standard()));
}

TEST_F(HelpToolsTest, EveryPageTheHelpNamesExists) {
  for (const char* code : {"HA", "HB", "HC", "HE", "HN", "HQ", "HR", "HT", "HU", "HW"}) {
    printed.clear();
    run(std::string(code) + "\n");
    EXPECT_FALSE(printed.empty()) << code;
    const std::regex page("(README\\.md|docs/[a-z_]+\\.md)");
    for (auto it = std::sregex_iterator(printed.begin(), printed.end(), page);
         it != std::sregex_iterator(); ++it)
      EXPECT_TRUE(fs::exists(fs::path(GANTRY_SOURCE_DIR) / it->str()))
          << code << " names " << it->str();
  }
  printed.clear();
  run("HU\n");
  for (const char* p : {"README.md", "docs/language.md", "docs/commands.md", "docs/settings.md",
                        "docs/hardware.md", "docs/system_variables.md"})
    EXPECT_NE(printed.find(p), std::string::npos) << p;
  EXPECT_TRUE(sink.moves.empty());
}

TEST_F(HelpToolsTest, TheHelpSheetsAreComplete) {
  for (const char* code : {"HA", "HC", "HE", "HQ", "HR", "HU", "HW"})
    EXPECT_EQ(CommandTable::standard().find(code)->coverage, "") << code;
  for (const char* code : {"HB", "HN", "HT"})
    EXPECT_NE(CommandTable::standard().find(code)->coverage, "") << code;
}

// ---- TD: drill press --------------------------------------------------------------------------

// The XY of each point where a move ends at Z `z`, in order.
std::vector<std::pair<double, double>> ends_at_z(const std::vector<CanonMove>& moves, double z) {
  std::vector<std::pair<double, double>> out;
  for (const CanonMove& m : moves)
    if (m.kind == MoveKind::Line && std::abs(m.to[2] - z) < 1e-9)
      out.emplace_back(m.to[0], m.to[1]);
  return out;
}

TEST_F(HelpToolsTest, TdWritesAFileThatDrillsEachHoleOfThePattern) {
  run("TD, holes.sbp, 1, 2, 2, 2, 3, 1.5, 0.5, 2, 0.4\n");
  EXPECT_TRUE(sink.moves.empty());  // TD itself moves nothing
  EXPECT_NE(printed.find("TD wrote 4 holes to " + path("holes.sbp")), std::string::npos) << printed;
  const std::string text = slurp(path("holes.sbp"));
  EXPECT_NE(text.find("' Units: in."), std::string::npos) << text;
  EXPECT_NE(text.find("\nSA\n"), std::string::npos);

  const std::vector<CanonMove> moves = moves_of("holes.sbp");
  // Every plunge to the bottom: exactly the four holes, back and forth along the rows.
  const auto bottoms = ends_at_z(moves, -0.5);
  const std::vector<std::pair<double, double>> holes = {{1, 2}, {4, 2}, {4, 3.5}, {1, 3.5}};
  EXPECT_EQ(bottoms, holes);
  // Half way down first (two passes), and nothing else goes below the surface.
  EXPECT_EQ(ends_at_z(moves, -0.25), holes);
  for (const CanonMove& m : moves) {
    EXPECT_GE(m.to[2], -0.5 - 1e-12);
    if (m.to[2] < 0) {  // below the surface only straight down over a hole
      EXPECT_EQ(m.from[0], m.to[0]);
      EXPECT_EQ(m.from[1], m.to[1]);
    }
    if (m.from[0] != m.to[0] || m.from[1] != m.to[1]) {
      EXPECT_DOUBLE_EQ(m.from[2], 0.4);  // XY travel at the safe Z only
      EXPECT_EQ(m.speed_class, SpeedClass::Jog);
    }
  }
  EXPECT_DOUBLE_EQ(moves.back().to[2], 0.4);
}

TEST_F(HelpToolsTest, TdWithTheTableTopAsZeroDrillsFromTheSurface) {
  run("TD, holes.sbp, 5, 5, , , , , 0.75, 1, , , , , , 1, 0.75\n");
  const auto moves = moves_of("holes.sbp");
  const std::vector<std::pair<double, double>> hole = {{5, 5}};
  EXPECT_EQ(ends_at_z(moves, 0), hole);  // the bottom: the table top
  // The profile's safe Z (1) above the surface (0.75).
  EXPECT_DOUBLE_EQ(moves.front().to[2], 1.75);
}

TEST_F(HelpToolsTest, TdCutsALargeHoleAroundItsOutlineOrPocketsIt) {
  const double bit = 0.25, hole = 1.25, r = (hole - bit) / 2, x = 6, y = 4;
  for (int pocket : {0, 1}) {
    run("TD, big.sbp, 6, 4, , , , , 0.3, 1, , 1.25, 0.25, " + std::to_string(pocket) + ", 20\n");
    const auto moves = moves_of("big.sbp");
    double far = 0, near = 1e9;
    std::set<long> radii;  // the rings, in 1e-4
    for (const CanonMove& m : moves) {
      if (m.to[2] > -0.3 + 1e-9) continue;
      const double d = std::hypot(m.to[0] - x, m.to[1] - y);
      far = std::max(far, d);
      near = std::min(near, d);
      radii.insert(std::lround(d * 1e4));
    }
    EXPECT_NEAR(far, r, 1e-4) << pocket;  // the bit's edge reaches the hole's edge, no further
    if (pocket) {
      EXPECT_NEAR(near, 0, 1e-9);  // plunged at the centre
      // Rings out from the centre no more than 80 % of the bit apart: 0.2 -> 3 rings of 1/3.
      std::vector<long> rings(radii.begin(), radii.end());
      ASSERT_GE(rings.size(), 2u);
      for (size_t i = 1; i < rings.size(); ++i)
        EXPECT_LE(rings[i] - rings[i - 1], std::lround(bit * 0.8 * 1e4) + 1);
    } else {
      EXPECT_NEAR(near, r, 1e-4);  // the outline only: the middle comes free
    }
  }
}

TEST_F(HelpToolsTest, TdErrorsAreLocatedAndWriteNothing) {
  struct Case {
    std::string line;
    int column;
    std::string message;
  };
  const Case cases[] = {
      {"TD, h.sbp, 1, 1, 2, 1, , , 0.5", 23, "2 holes in a row need a X spacing other than 0 (TD)"},
      {"TD, h.sbp, 1, 1, 1.5, 1, , , 0.5", 18,
       "holes in X (TD) is 1.5; it must be a whole number from 1 to 1000"},
      {"TD, h.sbp, 1, 1, , , , , -0.5", 26, "depth (TD) is -0.5; it must be above 0"},
      {"TD, h.sbp, 1, 1, , , , , 0.5, , , 0.125, 0.25", 35,
       "a hole of diameter 0.125 is smaller than the bit (0.25); use a bit no wider than the "
       "hole"},
      {"TD, h.sbp, 1, 1, , , , , 0.5, , -0.1", 33,
       "safe Z (TD) is -0.1, not above the material surface (Z 0); the tool would travel "
       "through the material"},
      {"TD, h.sbp, 1, 1, , , , , 0.5, , , , , , , 1", 1,
       "TD needs the material thickness (parameter 16) when Z 0 is the table top"},
      {"TD, h.sbp, 1, 1, , , , , 0.5, , , , , 2", 39,
       "pocket (TD) is 2; it is 0 (cut the outline) or 1 (pocket from the centre out)"},
      {"TD, h.sbp, 1, 1, , , , , 0.5, , , 1, , 1, 100", 43,
       "overlap (TD) is 100 %; it must be from 0 up to (not including) 100"},
  };
  for (const Case& c : cases) {
    const Diagnostic d = run_error("MX, 1\n" + c.line + "\n");
    EXPECT_EQ(d.message, c.message) << c.line;
    EXPECT_EQ(d.loc.line, 2) << c.line;
    EXPECT_EQ(d.loc.column, c.column) << c.line;
  }
  EXPECT_FALSE(fs::exists(path("h.sbp")));
  EXPECT_EQ(sink.moves.size(), std::size(cases));  // each run's MX, nothing more
}

TEST_F(HelpToolsTest, TdNeedsItsFileAndDepth) {
  EXPECT_EQ(run_error("TD\n").message, "TD needs its parameter 1 (file name)");
  EXPECT_EQ(run_error("TD, h.sbp\n").message, "TD needs its parameter 8 (depth)");
}

TEST_F(HelpToolsTest, ACheckWritesNothingButSeesWhatItWrote) {
  const auto found = check("TD, holes.sbp, 1, 1, 2, 2, 1, 1, 0.25\nFP, holes.sbp\n");
  EXPECT_TRUE(found.empty()) << format(found.front());
  EXPECT_FALSE(fs::exists(path("holes.sbp")));
  EXPECT_EQ(ends_at_z(sink.moves, -0.25).size(), 4u);  // the check ran the file it wrote
}

TEST_F(HelpToolsTest, AToolCannotRewriteTheRunningFile) {
  write("part.sbp", "TD, part.sbp, 1, 1, , , , , 0.5\n");
  const Diagnostic d = run_error("TD, part.sbp, 1, 1, , , , , 0.5\n");
  EXPECT_EQ(d.message,
            path("part.sbp") + " is running; a command cannot rewrite a running part file");
  EXPECT_EQ(slurp(path("part.sbp")), "TD, part.sbp, 1, 1, , , , , 0.5\n");
}

// ---- TU: tabletop surfacer ----------------------------------------------------------------

// Rows along X at depth: every point of the area is within half a bit of one of them.
TEST_F(HelpToolsTest, TuCoversTheWholeAreaWithTheOverlap) {
  const double x0 = 1, y0 = 2, w = 10, h = 7.3, bit = 1, depth = 0.05;
  run("TU, surface.sbp, 1, 2, 10, 7.3, 0.05, 2, 1, 25\n");
  EXPECT_TRUE(sink.moves.empty());
  const auto moves = moves_of("surface.sbp");
  std::vector<CanonMove> cuts;  // at the final depth
  std::set<long> rows;          // their Y, in 1e-4
  for (const CanonMove& m : moves) {
    EXPECT_GE(m.to[2], -depth - 1e-12);
    if (std::abs(m.from[2] + depth) < 1e-9 && std::abs(m.to[2] + depth) < 1e-9) {
      cuts.push_back(m);
      if (m.from[1] == m.to[1]) {
        rows.insert(std::lround(m.to[1] * 1e4));
        EXPECT_NEAR(std::min(m.from[0], m.to[0]), x0 + bit / 2, 1e-9);
        EXPECT_NEAR(std::max(m.from[0], m.to[0]), x0 + w - bit / 2, 1e-9);
      }
    }
    if (m.to[2] < 0) {  // in the material, the bit never leaves the area
      EXPECT_GE(m.to[0], x0 + bit / 2 - 1e-9);
      EXPECT_LE(m.to[0], x0 + w - bit / 2 + 1e-9);
      EXPECT_GE(m.to[1], y0 + bit / 2 - 1e-9);
      EXPECT_LE(m.to[1], y0 + h - bit / 2 + 1e-9);
    }
  }
  // (7.3 - 1) / 0.75 = 8.4: 9 steps, 10 rows, evenly 0.7 apart.
  ASSERT_EQ(rows.size(), 10u);
  EXPECT_EQ(*rows.begin(), std::lround((y0 + bit / 2) * 1e4));
  EXPECT_EQ(*rows.rbegin(), std::lround((y0 + h - bit / 2) * 1e4));
  for (auto a = rows.begin(), b = std::next(a); b != rows.end(); ++a, ++b)
    EXPECT_LE(*b - *a, std::lround(bit * 0.75 * 1e4));
  // Every point of the area (a 0.1 grid) is under the bit on some cut, but for the corners
  // a round bit cannot reach without leaving the area.
  auto distance = [](double px, double py, const CanonMove& m) {
    const double ax = m.from[0], ay = m.from[1], dx = m.to[0] - ax, dy = m.to[1] - ay;
    const double len2 = dx * dx + dy * dy;
    const double t = len2 > 0 ? std::clamp(((px - ax) * dx + (py - ay) * dy) / len2, 0.0, 1.0) : 0;
    return std::hypot(px - ax - t * dx, py - ay - t * dy);
  };
  for (double px = x0; px <= x0 + w + 1e-9; px += 0.1)
    for (double py = y0; py <= y0 + h + 1e-9; py += 0.1) {
      const double cx = std::clamp(px, x0 + bit / 2, x0 + w - bit / 2);
      const double cy = std::clamp(py, y0 + bit / 2, y0 + h - bit / 2);
      if (std::hypot(px - cx, py - cy) > bit / 2) continue;  // a corner
      double best = 1e9;
      for (const CanonMove& m : cuts) best = std::min(best, distance(px, py, m));
      ASSERT_LE(best, bit / 2 + 1e-9) << px << ", " << py;
    }
}

TEST_F(HelpToolsTest, TuRowsAlongYSwapTheAxes) {
  run("TU, s.sbp, 0, 0, 2, 3, 0.1, 1, 0.5, 0, 1\n");
  const auto moves = moves_of("s.sbp");
  std::set<long> columns;
  for (const CanonMove& m : moves)
    if (std::abs(m.to[2] + 0.1) < 1e-9 && std::abs(m.from[2] + 0.1) < 1e-9 && m.from[0] == m.to[0])
      columns.insert(std::lround(m.to[0] * 1e4));
  // (2 - 0.5) / 0.5 = 3 steps: 4 columns at X 0.25, 0.75, 1.25, 1.75.
  EXPECT_EQ(columns, (std::set<long>{2500, 7500, 12500, 17500}));
}

TEST_F(HelpToolsTest, TuRefusesAnAreaSmallerThanTheBit) {
  const Diagnostic d = run_error("TU, s.sbp, 0, 0, 0.5, 3, 0.1, 1, 1\n");
  EXPECT_EQ(d.message,
            "X size (TU) is 0.5, less than the bit (1): the bit cannot stay inside the area");
  EXPECT_EQ(d.loc.column, 18);
  EXPECT_FALSE(fs::exists(path("s.sbp")));
}

// ---- TF: fluter ---------------------------------------------------------------------------

TEST_F(HelpToolsTest, TfCutsEachFluteToDepthBackAndForth) {
  run("TF, flutes.sbp, 2, 1, 3, 0.75, 10, 0.2, 2\n");
  const auto moves = moves_of("flutes.sbp");
  std::map<long, std::vector<double>> by_flute;  // X (1e-4) -> the Z of each cutting move
  for (const CanonMove& m : moves)
    if (m.to[2] < 0 && m.from[2] == m.to[2]) {
      EXPECT_EQ(m.from[0], m.to[0]);  // along Y
      EXPECT_DOUBLE_EQ(std::abs(m.to[1] - m.from[1]), 10);
      by_flute[std::lround(m.to[0] * 1e4)].push_back(m.to[2]);
    }
  const std::map<long, std::vector<double>> expected = {
      {20000, {-0.1, -0.2}}, {27500, {-0.1, -0.2}}, {35000, {-0.1, -0.2}}};
  EXPECT_EQ(by_flute, expected);
}

// ---- TH: header writer --------------------------------------------------------------------

TEST_F(HelpToolsTest, ThAddsAHeaderAndReplacesItsOwn) {
  write("job.sbp", "MX, 1\nMY, 2\n");
  run("TH, job.sbp, Sign, Ann, Oak, 24, 18, 0.75, 1/4 end mill, 0, Tabs by hand, , last.sbp\n");
  const std::string once = slurp(path("job.sbp"));
  EXPECT_TRUE(
      once.starts_with("'---- Header (Gantry TH) ----\n' Title: Sign\n' Contact: Ann\n"
                       "' Material: Oak\n' Blank: X 24, Y 18, thickness 0.75 in\n"
                       "' Bit: 1/4 end mill\n' Z zero: the material surface\n"
                       "' Notes: Tabs by hand\n' Units: in; machine profile \""))
      << once;
  EXPECT_TRUE(std::regex_search(
      once, std::regex("\n' Header written \\d{4}-\\d\\d-\\d\\d by Gantry [^\n]+ \\(TH\\)\n"
                       "'---- End of header ----\nMX, 1\nMY, 2\n"
                       "'---- Run last \\(Gantry TH\\) ----\nFP, \"last.sbp\"\n$")))
      << once;
  EXPECT_NE(printed.find("TH wrote a header of 11 lines to " + path("job.sbp")), std::string::npos);
  // Again, with other values: one header, one closing FP.
  run("TH, job.sbp, Sign 2, , , , , , , , , first.sbp\n");
  const std::string twice = slurp(path("job.sbp"));
  EXPECT_TRUE(std::regex_match(twice, std::regex("'---- Header \\(Gantry TH\\) ----\n"
                                                 "' Title: Sign 2\n' Units: [^\n]+\n"
                                                 "' Header written [^\n]+\nFP, \"first.sbp\"\n"
                                                 "'---- End of header ----\nMX, 1\nMY, 2\n")))
      << twice;
  // The file still runs: the header is comments, then the FP lines.
  write("first.sbp", "MZ, -0.1\n");
  EXPECT_EQ(moves_of("job.sbp").size(), 3u);
}

TEST_F(HelpToolsTest, ThKeepsWindowsLineEndings) {
  write("job.sbp", "MX, 1\r\nMY, 2\r\n");
  run("TH, job.sbp, Box\n");
  const std::string text = slurp(path("job.sbp"));
  EXPECT_TRUE(text.starts_with("'---- Header (Gantry TH) ----\r\n' Title: Box\r\n")) << text;
  EXPECT_TRUE(text.ends_with("'---- End of header ----\r\nMX, 1\r\nMY, 2\r\n")) << text;
}

TEST_F(HelpToolsTest, ThKeepsAByteOrderMarkFirst) {
  write("job.sbp", "\xEF\xBB\xBFMX, 1\n");
  run("TH, job.sbp, Box\n");
  run("TH, job.sbp, Box 2\n");
  const std::string text = slurp(path("job.sbp"));
  EXPECT_TRUE(text.starts_with("\xEF\xBB\xBF'---- Header (Gantry TH) ----\n' Title: Box 2\n"))
      << text;
  EXPECT_TRUE(text.ends_with("'---- End of header ----\nMX, 1\n")) << text;
  EXPECT_EQ(moves_of("job.sbp").size(), 1u);
}

TEST_F(HelpToolsTest, ThNeedsAnExistingFile) {
  const Diagnostic d = run_error("TH, nothing.sbp, Box\n");
  EXPECT_EQ(d.message,
            "cannot read " + path("nothing.sbp") + "; TH adds a header to an existing part file");
  EXPECT_EQ(d.loc.column, 5);
  EXPECT_FALSE(fs::exists(path("nothing.sbp")));
}

// ---- TS and the tools not offered -----------------------------------------------------------

TEST_F(HelpToolsTest, TsPrintsTheSetup) {
  run("MS, 1.5, 0.25\nTS\n");
  EXPECT_NE(printed.find("Machine profile: " + settings.name + "\nUnits: in\nCard: sim"),
            std::string::npos)
      << printed;
  EXPECT_TRUE(std::regex_search(printed, std::regex("\nX +916.7324 +8 +20 +0 to 24\n"))) << printed;
  EXPECT_NE(printed.find("Move speeds (in/s): XY 1.5, Z 0.25,"), std::string::npos) << printed;
}

TEST_F(HelpToolsTest, TiRunsAPartFileAtEachEqualTurnOfTheAxis) {
  write("flute.sbp", "MX, 1\nMX, 0\n");
  run("TI, index.sbp, flute.sbp, , 3, 30, 0.5\n");
  EXPECT_TRUE(sink.moves.empty());
  const std::string text = slurp(path("index.sbp"));
  EXPECT_NE(text.find("JZ, 0.5\nJB, 30\nFP, flute.sbp\n"), std::string::npos) << text;
  EXPECT_NE(text.find("JB, 150\nFP, flute.sbp\n"), std::string::npos) << text;
  EXPECT_NE(text.find("JB, 270\nFP, flute.sbp\n"), std::string::npos) << text;
  // Run: the flute's moves three times, each after a turn of B at safe Z.
  const std::vector<CanonMove> moves = moves_of("index.sbp");
  std::vector<double> turns;
  int flutes = 0;
  for (const CanonMove& m : moves) {
    if (m.to[4] != m.from[4]) {
      EXPECT_DOUBLE_EQ(m.from[2], 0.5);  // turned up at safe Z only
      turns.push_back(m.to[4]);
    }
    flutes += m.to[0] == 1 && m.from[0] == 0;
  }
  EXPECT_EQ(turns, (std::vector<double>{30, 150, 270}));
  EXPECT_EQ(flutes, 3);
}

TEST_F(HelpToolsTest, TiErrorsAreLocated) {
  Diagnostic d = run_error("TI, index.sbp, flute.sbp, X\n");
  EXPECT_EQ(d.loc.line, 1);
  EXPECT_EQ(d.loc.column, 27) << d.message;  // the axis
  d = run_error("TI, index.sbp\n");
  EXPECT_NE(d.message.find("part file"), std::string::npos) << d.message;
  EXPECT_FALSE(fs::exists(path("index.sbp")));
}

TEST_F(HelpToolsTest, TcChecksTheWholeGridBeforeTheFirstProbe) {
  const Diagnostic d = run_error("TC, copy.sbp, 20, 1, 10, 2, 0.5, -1\n");  // X to 30: off
  EXPECT_EQ(d.loc.line, 1);
  EXPECT_NE(d.message.find("soft limits"), std::string::npos) << d.message;
  EXPECT_TRUE(sink.moves.empty());
  EXPECT_FALSE(fs::exists(path("copy.sbp")));
}

TEST_F(HelpToolsTest, TcWithoutAMachineWritesTheGridAtTheBottom) {
  // No live machine (a check, a preview): every probe reaches the bottom, quietly.
  run("TC, points.csv, 1, 1, 1, 0.5, 0.5, -0.25, 0.5\n");
  EXPECT_EQ(slurp(path("points.csv")),
            "x,y,z\n1,1,-0.25\n1.5,1,-0.25\n2,1,-0.25\n2,1.5,-0.25\n1.5,1.5,-0.25\n1,1.5,-0.25\n");
  EXPECT_TRUE(io.warnings().empty());
}

}  // namespace
}  // namespace gantry
