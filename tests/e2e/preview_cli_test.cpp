// End to end: `gantry preview` on parts/ files agrees with `gantry moves` and `gantry
// estimate`, writes pictures of the size asked for, and refuses bad files and options with
// located errors and exit status 1.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>  // getpid

#include <nlohmann/json.hpp>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "../support/run_gantry.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

using e2e::gantry;
using Result = e2e::GantryResult;

std::string read(const fs::path& p) {
  std::stringstream text;
  text << std::ifstream(p, std::ios::binary).rdbuf();
  return text.str();
}

// A PNG's width and height from its IHDR chunk (big-endian, bytes 16 to 23).
std::pair<int, int> png_size(const std::string& bytes) {
  auto be = [&](size_t at) {
    int v = 0;
    for (size_t i = 0; i < 4; ++i) v = v << 8 | static_cast<unsigned char>(bytes.at(at + i));
    return v;
  };
  EXPECT_EQ(bytes.substr(1, 3), "PNG");
  return {be(16), be(20)};
}

// A scratch folder per test.
class PreviewCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / fmt::format("gantry_preview_cli_{}", getpid());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path(name)) << text;
    return path(name);
  }
  fs::path dir_;
};

TEST_F(PreviewCli, DemoSummaryAgreesWithMovesAndEstimate) {
  const Result r = gantry("preview parts/demo.sbp --json -o " + path("demo.png"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(png_size(read(path("demo.png"))), std::make_pair(800, 600));
  EXPECT_TRUE(j["violations"].empty());

  // The moves `gantry moves` lists, and the box of their end points.
  const Result moves = gantry("moves parts/demo.sbp --format jsonl");
  ASSERT_EQ(moves.exit_code, 0) << moves.err;
  std::istringstream lines(moves.out);
  std::array<double, 3> lo{1e9, 1e9, 1e9}, hi{-1e9, -1e9, -1e9};
  int count = 0;
  for (std::string line; std::getline(lines, line);) {
    const json m = json::parse(line);
    ++count;
    if (m["kind"] != "line") continue;  // demo has no arcs
    for (const char* end : {"from", "to"})
      for (int a = 0; a < 3; ++a) {
        lo[a] = std::min(lo[a], m[end][a].get<double>());
        hi[a] = std::max(hi[a], m[end][a].get<double>());
      }
  }
  EXPECT_EQ(j["moves"], count);
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(j["bounds"]["min"][a].get<double>(), lo[a], 1e-6) << a;
    EXPECT_NEAR(j["bounds"]["max"][a].get<double>(), hi[a], 1e-6) << a;
  }
  const Result estimate = gantry("estimate parts/demo.sbp --json");
  ASSERT_EQ(estimate.exit_code, 0) << estimate.err;
  EXPECT_DOUBLE_EQ(j["estimated_time_s"].get<double>(),
                   json::parse(estimate.out)["estimated_time_s"].get<double>());

  // The text summary says the same.
  const Result text = gantry("preview parts/demo.sbp -o " + path("demo2.png"));
  EXPECT_NE(text.out.find(fmt::format("{} moves", count)), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("X 0.0000 to 12.0000, Y 0.0000 to 9.0000, Z -0.1250 to 1.0000"),
            std::string::npos)
      << text.out;
}

TEST_F(PreviewCli, EveryViewAndTheMaterialMapWriteTheSizeAsked) {
  for (const char* view : {"top", "iso", "front", "side"}) {
    const Result r = gantry(fmt::format(
        "preview parts/relative_steps.sbp --view {} --size 320x200 -o {}", view, path("v.png")));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(png_size(read(path("v.png"))), std::make_pair(320, 200)) << view;
  }
  const Result m =
      gantry("preview parts/demo.sbp --material --cutter ball --view iso --size 300x300 -o " +
             path("m.png"));
  ASSERT_EQ(m.exit_code, 0) << m.err;
  EXPECT_EQ(png_size(read(path("m.png"))), std::make_pair(300, 300));
  const Result svg =
      gantry("preview parts/speeds.sbp --view front --size 500x300 -o " + path("s.svg"));
  ASSERT_EQ(svg.exit_code, 0) << svg.err;
  const std::string text = read(path("s.svg"));
  EXPECT_EQ(text.rfind("<svg", 0), 0u);
  EXPECT_NE(text.find("width=\"500\" height=\"300\""), std::string::npos);
  EXPECT_NE(text.find("<path "), std::string::npos);
}

TEST_F(PreviewCli, SoftLimitViolationNamesItsLineAndFails) {
  const std::string file = write("limits.sbp", "J2, 1, 1\nM2, 2, 2\nMX, 30\n");
  const Result r = gantry(fmt::format("preview {} -o {}", file, path("l.png")));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("limits.sbp:3:1: error: move to X=30.0000 is outside the soft limits"),
            std::string::npos)
      << r.err;
  EXPECT_TRUE(fs::exists(path("l.png")));  // what the file would do up to there is drawn
}

// Issue 25: the preview stopped at the first INPUT. It goes on with the default the INPUT
// offers (what Enter at the window's dialog gives), says so, and --input still answers first.
TEST_F(PreviewCli, ThePreviewGoesOnPastInputWithItsDefault) {
  const std::string file = write("ask.sbp", "&D = 2\nINPUT \"How far\" : &D\nMX, &D\nMY, 3\n");
  const Result r = gantry(fmt::format("preview {} --json -o {}", file, path("a.png")));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["moves"], 2) << r.out;
  EXPECT_NE(j["violations"].dump().find(
                "the preview answered INPUT &D with its default \\\"2\\\" (the run asks the "
                "operator)"),
            std::string::npos)
      << j["violations"].dump();
  const Result answered =
      gantry(fmt::format("preview {} --json --input D=5 -o {}", file, path("b.png")));
  EXPECT_EQ(nlohmann::json::parse(answered.out)["violations"].size(), 0u) << answered.out;
}

// Issue 25: `estimate` refused a file that `preview` estimated (FabMo's macro 211: 742 s),
// because a PAUSE waits for the operator. Both count the motion, not the waits, and an INPUT
// takes its default: the two give one figure.
TEST_F(PreviewCli, EstimateGoesOnPastPausesAndInputsAsThePreviewDoes) {
  const std::string file = write(
      "waits.sbp", "MX, 1\nPAUSE\n&D = 2\nINPUT \"How far\" : &D\nMX, &D\nMY, 3\n");
  const Result preview = gantry(fmt::format("preview {} --json -o {}", file, path("w.png")));
  ASSERT_EQ(preview.exit_code, 0) << preview.err;
  const double previewed = nlohmann::json::parse(preview.out)["estimated_time_s"].get<double>();
  EXPECT_GT(previewed, 1.0);
  const Result estimate = gantry(fmt::format("estimate {} --json", file));
  ASSERT_EQ(estimate.exit_code, 0) << estimate.err;
  EXPECT_DOUBLE_EQ(nlohmann::json::parse(estimate.out)["estimated_time_s"].get<double>(),
                   previewed);
}

TEST_F(PreviewCli, MissingAndBadFilesGiveLocatedErrors) {
  const Result missing = gantry("preview parts/nosuch.sbp -o " + path("n.png"));
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.err.find("parts/nosuch.sbp: error:"), std::string::npos) << missing.err;
  EXPECT_FALSE(fs::exists(path("n.png")));

  const std::string bad = write("bad.sbp", "J2, 1, 1\nM2, 2, (3\n");
  const Result r = gantry(fmt::format("preview {} -o {}", bad, path("b.png")));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("bad.sbp:2:8: error:"), std::string::npos) << r.err;
}

TEST_F(PreviewCli, BadOptionsAreRefusedBeforeAnythingIsWritten) {
  for (const char* opts : {"--size 10x10 -o {}/a.png", "--size 800 -o {}/a.png", "-o {}/a.jpg",
                           "--material -o {}/a.svg", "--cutter v200 --material -o {}/a.png",
                           "--view left -o {}/a.png", "--stock 10x8 -o {}/a.png",
                           "--stock 10x8x0@1,1,0 -o {}/a.png", "--stock 10x8x1@1,1 -o {}/a.png",
                           "--play 1 --play-line 3 -o {}/a.png", "--play -1 -o {}/a.png"}) {
    const Result r =
        gantry("preview parts/demo.sbp " + fmt::format(fmt::runtime(opts), dir_.string()));
    EXPECT_EQ(r.exit_code, 1) << opts;
    EXPECT_FALSE(r.err.empty()) << opts;
    EXPECT_TRUE(fs::is_empty(dir_)) << opts;
  }
}

TEST_F(PreviewCli, MovesSvgDrawsTheFigureWithThePreview) {
  const Result r = gantry("moves docs/figures/tabs.sbp --svg " + path("tabs.svg"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string svg = read(path("tabs.svg"));
  EXPECT_NE(svg.find("width=\"440\""), std::string::npos);
  EXPECT_NE(svg.find("stroke=\"#e08020\""), std::string::npos);  // the tabs stand out
  EXPECT_EQ(svg.find("<polygon"), std::string::npos);            // no table in a figure
}

// Issue 25: the stock given, tools followed, units as the file sets them, play.
TEST_F(PreviewCli, StockToolsSpindleAndPlayAreInTheSummary) {
  const std::string file = write(
      "tools.sbp",
      "TR, 12000\nJZ, 0.5\nJ2, 1, 1\nMZ, -0.2\nMX, 5\nJZ, 0.5\nVC, 0.5\nTR, 18000\n"
      "J2, 6, 2\nMZ, -0.2\nMY, 6\nJZ, 0.5\n");
  const Result r = gantry(fmt::format("preview {} --json --stock 10x8x0.75@-1,-1,0 -o {}", file,
                                      path("t.svg")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["stock"]["min"], json::parse("[-1.0, -1.0, -0.75]"));
  EXPECT_EQ(j["stock"]["max"], json::parse("[9.0, 7.0, 0.0]"));
  ASSERT_GE(j["tools"].size(), 1u) << j.dump();  // VC's cutter from the first segment
  EXPECT_EQ(j["tools"][0]["first_segment"], 0);
  EXPECT_TRUE(j["spindle"].is_array());
  EXPECT_NE(read(path("t.svg")).find("<polygon class=\"stock\""), std::string::npos);

  // Without --stock: the profile's VP table size (24 x 18 x 6 by default) at the origin.
  const Result d = gantry(fmt::format("preview {} --json -o {}", file, path("d.png")));
  ASSERT_EQ(d.exit_code, 0) << d.err;
  EXPECT_EQ(json::parse(d.out)["stock"]["max"], json::parse("[24.0, 18.0, 0.0]"));

  // At half the cycle time fewer segments are drawn, and the summary says so.
  const double total = j["estimated_time_s"].get<double>();
  const Result half = gantry(fmt::format("preview {} --json --play {} -o {}", file, total / 2,
                                         path("h.png")));
  ASSERT_EQ(half.exit_code, 0) << half.err;
  const json h = json::parse(half.out);
  EXPECT_LT(h["played"]["segments"].get<int>(), j["segments"].get<int>());
  EXPECT_LE(h["played"]["time_s"].get<double>(), total / 2 + 1e-9);
  const Result text =
      gantry(fmt::format("preview {} --play-line 5 -o {}", file, path("l.png")));
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("played: "), std::string::npos) << text.out;
}

// Issue 25: the summary in the units the file sets (VD, G21); each VC a cutter in the legend.
TEST_F(PreviewCli, TheSummaryIsInTheFilesUnitsAndListsEachCutter) {
  const std::string sbp = write("mm.sbp", "VD, , , 1\nJZ, 10\nMZ, -3\nMX, 100\nMY, 50\nJZ, 10\n");
  Result r = gantry(fmt::format("preview {} -o {}", sbp, path("mm.svg")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("bounds (mm): X 0.0000 to 100.0000, Y 0.0000 to 50.0000, Z -3.0000 to "
                       "10.0000"),
            std::string::npos)
      << r.out;
  EXPECT_NE(read(path("mm.svg")).find("(100.0000 mm)"), std::string::npos);
  const std::string nc = write("mm.nc", "G21 G90\nG0 Z5\nG1 Z-2 F300\nG1 X100 F600\nG1 Y50\nM2\n");
  r = gantry(fmt::format("preview {} --json -o {}", nc, path("nc.png")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["units"], "mm");
  EXPECT_NEAR(j["bounds"]["max"][0].get<double>(), 100, 1e-3);
  const std::string vc = write("vc.sbp", "VC, 0.125\nJZ, 0.5\nMZ, -0.1\nMX, 2\nJZ, 0.5\n"
                                         "VC, 0.5\nJ2, 0, 1\nMZ, -0.1\nMX, 2\nJZ, 0.5\n");
  r = gantry(fmt::format("preview {} -o {}", vc, path("vc.svg")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("tool change at line 7 (segment "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("cutter diameter 0.5\n"), std::string::npos) << r.out;
  EXPECT_NE(read(path("vc.svg")).find(">cutters 0.125 in, 0.5 in from line 7</text>"),
            std::string::npos);
  r = gantry(fmt::format("preview {} --json -o {}", vc, path("vc.png")));
  const json t = json::parse(r.out);
  ASSERT_EQ(t["tools"].size(), 2u) << r.out;
  EXPECT_EQ(t["tools"][0]["diameter"], 0.125);
  EXPECT_EQ(t["tools"][1]["diameter"], 0.5);
}

// Issue 25: "&Tool = 3" then C9 (the shipped macro, which sets no VC) left the preview's
// cutter the old one. The preview follows the tool, with its diameter from the tool table.
TEST_F(PreviewCli, AToolChangeByC9TakesTheToolsDiameterFromTheToolTable) {
  write("tools.tbl", "T1 P1 D0.125\nT3 P3 D0.5\n");
  const std::string sbp = write("tc.sbp",
                                "&Tool = 1\nC9\nJZ, 0.5\nMZ, -0.1\nMX, 2\nJZ, 0.5\n"
                                "&Tool = 3\nC9\nJ2, 0, 1\nMZ, -0.1\nMX, 2\nJZ, 0.5\n");
  Result r = gantry(fmt::format("preview {} --tool-table {} -o {}", sbp, path("tools.tbl"),
                                path("tc.svg")));
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("tool change at line 8 (segment "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("tool 3, cutter diameter 0.5\n"), std::string::npos) << r.out;
  EXPECT_NE(read(path("tc.svg")).find(">cutters T1 0.125 in, T3 0.5 in from line 8</text>"),
            std::string::npos)
      << read(path("tc.svg"));
  r = gantry(fmt::format("preview {} --tool-table {} --json -o {}", sbp, path("tools.tbl"),
                         path("tc.png")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json t = json::parse(r.out)["tools"];
  ASSERT_EQ(t.size(), 2u) << r.out;
  EXPECT_EQ(t[0]["tool"], 1);
  EXPECT_EQ(t[0]["diameter"], 0.125);
  EXPECT_EQ(t[1]["tool"], 3);
  EXPECT_EQ(t[1]["diameter"], 0.5);
  EXPECT_EQ(t[1]["line"], 8);
}

}  // namespace
