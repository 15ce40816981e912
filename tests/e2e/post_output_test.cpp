// End to end: part files in the exact shapes that real CAM post processors write
// (tests/data/posts/), through `gantry moves` and a run on the simulated card. Each file has
// a .expected file beside it, written by hand from the file's own numbers: every move's line,
// kind, speed class and end point (and an arc's centre). A post states every end point (a CG's
// is in its line), so the expectations do not come from Gantry. They pin the cut commands' Z
// rule (docs/cuts.md, D9): a CG with no plunge, at the depth the post's M3 set, leaves Z there;
// before issue 21 each CG lifted to Safe-Z, so the next M3 became a long diagonal plunge and
// the next CG was cut in the air.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "../support/run_gantry.hpp"

namespace {

namespace fs = std::filesystem;
using e2e::gantry;
using e2e::kAxes;
using e2e::kStepsPerUnit;
using nlohmann::json;

const fs::path kPosts = fs::path(GANTRY_SOURCE_DIR) / "tests/data/posts";

struct ExpectedMove {
  int line = 0;
  std::string kind, speed;
  std::array<double, 5> to{};  // X Y Z A B
  std::optional<std::array<double, 2>> centre;
};

// `line kind speed x y z a b [cx cy]` a row; `#` starts a comment line.
std::vector<ExpectedMove> read_expected(const fs::path& file) {
  std::vector<ExpectedMove> out;
  std::ifstream in(file);
  for (std::string text; std::getline(in, text);) {
    if (text.empty() || text[0] == '#') continue;
    std::istringstream row(text);
    ExpectedMove m;
    row >> m.line >> m.kind >> m.speed;
    for (double& v : m.to) row >> v;
    std::array<double, 2> c{};
    if (row >> c[0] >> c[1]) m.centre = c;
    out.push_back(m);
  }
  return out;
}

struct Post {
  const char* name;     // tests/data/posts/NAME.sbp and NAME.expected
  const char* options;  // for moves and run
};
void PrintTo(const Post& p, std::ostream* os) {
  *os << p.name;
}

class PostOutput : public ::testing::TestWithParam<Post> {
 protected:
  std::string file() const { return "tests/data/posts/" + std::string(GetParam().name) + ".sbp"; }
  std::string options() const { return GetParam().options; }
  std::vector<ExpectedMove> expected() const {
    return read_expected(kPosts / (std::string(GetParam().name) + ".expected"));
  }
};

TEST_P(PostOutput, EveryMoveEndsWhereTheFileSays) {
  const std::vector<ExpectedMove> want = expected();
  ASSERT_GT(want.size(), 10u);
  const e2e::GantryResult r = gantry("moves " + file() + " --format jsonl" + options());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::vector<json> got;
  std::istringstream lines(r.out);
  for (std::string text; std::getline(lines, text);) {
    const json m = json::parse(text);
    if (m["kind"] == "line" || m["kind"] == "arc") got.push_back(m);
  }
  ASSERT_EQ(got.size(), want.size()) << r.out;
  for (size_t i = 0; i < want.size(); ++i) {
    const ExpectedMove& w = want[i];
    const json& g = got[i];
    SCOPED_TRACE(::testing::Message() << "move " << i << " (line " << w.line << "): " << g.dump());
    EXPECT_EQ(g["line"], w.line);
    EXPECT_EQ(g["kind"], w.kind);
    EXPECT_EQ(g["speed_class"], w.speed);
    for (int a = 0; a < 5; ++a) EXPECT_NEAR(g["to"][a].get<double>(), w.to[a], 1e-9) << kAxes[a];
    EXPECT_NEAR(g["to"][5].get<double>(), 0, 1e-12);
    if (w.centre) {
      EXPECT_NEAR(g["center"][0].get<double>(), (*w.centre)[0], 1e-9);
      EXPECT_NEAR(g["center"][1].get<double>(), (*w.centre)[1], 1e-9);
    }
  }
}

TEST_P(PostOutput, RunsCleanOnTheSimulatedCardToItsLastPoint) {
  const ExpectedMove last = expected().back();
  const e2e::GantryResult r = gantry("run " + file() + " --yes --json" + options());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["status"], "done");
  EXPECT_TRUE(j["errors"].empty()) << j["errors"].dump();
  EXPECT_EQ(j["steps"], j["commanded_steps"]);  // every step the generator made was played
  for (int a = 0; a < 5; ++a) {
    const std::int64_t steps = std::llround(last.to[a] * kStepsPerUnit[a]);
    EXPECT_EQ(j["steps"][kAxes[a]].get<std::int64_t>(), steps) << kAxes[a];
    EXPECT_NEAR(j["position"][kAxes[a]].get<double>(), last.to[a], 0.5 / kStepsPerUnit[a] + 1e-12)
        << kAxes[a];
  }
  EXPECT_EQ(j["steps"]["c"], 0);
  EXPECT_EQ(j["timing_violations"], 0);
  EXPECT_LE(j["max_velocity_ratio"].get<double>(), 1.0);
  EXPECT_LE(j["max_accel_ratio"].get<double>(), 1.0);
}

// fusion_opensbp_inch (Fusion 360's shopbot.cps: CN, &Tool, C9, TR, C6, PAUSE 2, C7) runs
// with stand-ins for C6, C7, C9 and CN 90 that do not move, so that its moves are the post's
// own; CamPost.* in run_parts_test.cpp runs a Fusion-shaped job with the shipped macros.
INSTANTIATE_TEST_SUITE_P(Posts, PostOutput,
                         ::testing::Values(Post{"vcarve_profile_arcs_inch", ""},
                                           Post{"aspire_rotary_wrap_x_inch", ""},
                                           Post{"fusion_5axis_inch", ""},
                                           Post{"fusion_opensbp_inch",
                                                " --macros tests/data/posts/macros"}),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace
