// End to end: real part files through `gantry` on the simulated card, checked to the step.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "../support/run_gantry.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path kSource = GANTRY_SOURCE_DIR;

using e2e::gantry;
using e2e::kAxes;
using e2e::kStepsPerUnit;
using Result = e2e::GantryResult;

struct Expected {
  std::array<double, 6> last_point;  // the file's last commanded point, units
  int lines, moves;
  // The arcs' chords beyond one per move: the card plays each chord as a segment, and each
  // may round by a tick as a move does.
  int chords = 0;
};

// Every file in parts/ with its last commanded point, worked out by hand from the file.
const std::map<std::string, Expected> kParts = {
    {"demo.sbp", {{12, 9, 1, 0, 0, 0}, 46, 40}},
    {"relative_steps.sbp", {{5.125, 3.333333, 0.25, 0, 0, 0}, 16, 12}},
    {"rotary.sbp", {{3, 3, 1, 45, 0, 0}, 12, 8}},
    {"speeds.sbp", {{7.75, 3.5, 0.25, 0, 0, 0}, 12, 7}},
    // Friendly Motion (docs/friendlymotion.md). Lines count statements run: a K's line runs
    // again (from the command after the K) at each return. trepan: 6 holes of 11 lines and
    // 6 moves (to the hole, out, 3 circles, back), 3 + 2 x 3 a row around them, 3 after, 6
    // returns; the last point is G90 X0.5Y0.5. scribe: the moves are the stroke font's (each
    // stroke's points, and where each G16 leaves the pen). taught_frame: user (0.5, 0.5) in
    // the frame from (2,1) towards (5,5) is table (2 + 0.6*0.5 - 0.8*0.5, 1 + 0.8*0.5 +
    // 0.6*0.5). subroutine: 3 passes of 2 calls (X0.5, Y0.5) and C30. trepan's 18 circles of
    // radius 0.05 are 23 chords each (22 beyond the move) at the default 0.0005 tolerance
    // (2 pi / (2 acos(1 - 0.0005 / 0.05)) = 22.2).
    {"trepan.fm", {{0.5, 0.5, 0, 0, 0, 0}, 86, 37, 18 * 22}},
    {"scribe.fm", {{0, 0, 0, 0, 0, 0}, 15, 92}},
    {"taught_frame.fm", {{1.9, 1.7, 0, 0, 0, 0}, 16, 8}},
    {"subroutine.fm", {{4, 3, 0, 0, 0, 0}, 38, 18}},
};

TEST(Parts, EveryPartFileHasExpectations) {
  for (const auto& entry : fs::directory_iterator(kSource / "parts")) {
    if (entry.path().extension() != ".sbp" && entry.path().extension() != ".fm") continue;
    EXPECT_TRUE(kParts.count(entry.path().filename().string()))
        << entry.path() << " has no expected result in run_parts_test.cpp";
  }
}

class PartRun : public ::testing::TestWithParam<std::string> {};

TEST_P(PartRun, EndsOnTheLastCommandedPointToTheStep) {
  const std::string name = GetParam();
  const Expected& want = kParts.at(name);
  const Result r = gantry(fmt::format("run parts/{} --json", name));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(r.out);  // exactly one JSON object on stdout
  EXPECT_EQ(j["status"], "done");
  EXPECT_EQ(j["lines"], want.lines);
  EXPECT_EQ(j["moves"], want.moves);
  for (int i = 0; i < 6; ++i) {
    const std::int64_t steps = std::llround(want.last_point[i] * kStepsPerUnit[i]);
    EXPECT_EQ(j["steps"][kAxes[i]].get<std::int64_t>(), steps) << "axis " << kAxes[i];
    EXPECT_EQ(j["commanded_steps"][kAxes[i]].get<std::int64_t>(), steps) << "axis " << kAxes[i];
    EXPECT_NEAR(j["position"][kAxes[i]].get<double>(), want.last_point[i],
                0.5 / kStepsPerUnit[i] + 1e-12)
        << "axis " << kAxes[i];
  }
  EXPECT_EQ(j["timing_violations"], 0);
  EXPECT_GT(j["max_velocity_ratio"].get<double>(), 0.0);
  EXPECT_LE(j["max_velocity_ratio"].get<double>(), 1.0);
  // Acceleration beyond the corner jumps (rotary.sbp's gentle ramps stay within one jump, so
  // its ratio is 0; the monitor's own tests show the check failing).
  EXPECT_LE(j["max_accel_ratio"].get<double>(), 1.0);
  // The card's clock and the planner agree to within one tick per move, and the estimate
  // made before the run to within 1 %.
  const double card_s = j["time_s"].get<double>();
  EXPECT_NEAR(card_s, j["planned_time_s"].get<double>(), 5e-6 * (want.moves + want.chords));
  EXPECT_NEAR(j["estimated_time_s"].get<double>(), card_s, 0.01 * card_s);
  // `gantry estimate` says the same without running.
  const Result e = gantry("estimate parts/" + name + " --json");
  ASSERT_EQ(e.exit_code, 0) << e.err;
  EXPECT_EQ(json::parse(e.out)["estimated_time_s"], j["estimated_time_s"]);
}

TEST(Run, MiMovesAnAxisBesideTheCutAndEachEndsWhereItsPulsesLeftIt) {
  const Result r = gantry("run tests/data/mi_oscillate.sbp --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["status"], "done");
  EXPECT_EQ(j["steps"]["x"], 0);
  EXPECT_EQ(j["steps"]["y"], 0);
  EXPECT_EQ(j["steps"]["z"], std::llround(1.0 * kStepsPerUnit[2]));  // back from each swing
  // B turned 45 deg/s for the 1.5 s of MY, 0 and ramped down: the steps it played, which the
  // generator counted too.
  const std::int64_t b = j["steps"]["b"].get<std::int64_t>();
  EXPECT_GT(b, std::llround(60 * kStepsPerUnit[4]));
  EXPECT_EQ(j["commanded_steps"]["b"].get<std::int64_t>(), b);
  EXPECT_EQ(j["timing_violations"], 0);
  EXPECT_LE(j["max_velocity_ratio"].get<double>(), 1.0);
  EXPECT_LE(j["max_accel_ratio"].get<double>(), 1.0);
  // The card runs past the planned path by the rests: at most a cycle of Z (0.4 s) and B's
  // ramp down (0.125 s).
  const double extra = j["time_s"].get<double>() - j["planned_time_s"].get<double>();
  EXPECT_GT(extra, 0.0);
  EXPECT_LT(extra, 0.4 + 0.125 + 1e-3);
}

TEST(FeedOverride, FasterAndSlowerRunsStayWithinTheLimitsAndMatchTheirEstimates) {
  double previous = 1e9;
  for (int percent : {50, 100, 200}) {
    SCOPED_TRACE(percent);
    const std::string opt = fmt::format(" --feed-override {}", percent);
    const Result r = gantry("run parts/demo.sbp --json" + opt);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const json j = json::parse(r.out);
    const double card_s = j["time_s"].get<double>();
    EXPECT_LT(card_s, previous);  // a higher override is quicker
    previous = card_s;
    // At 200 % the moves run at the axes' max_speed: tick rounding of the step times reads
    // as up to 0.01 % over it.
    EXPECT_LE(j["max_velocity_ratio"].get<double>(), 1.0001);
    EXPECT_LE(j["max_accel_ratio"].get<double>(), 1.001);
    EXPECT_NEAR(j["estimated_time_s"].get<double>(), card_s, 0.01 * card_s);
    const Result e = gantry("estimate parts/demo.sbp --json" + opt);
    EXPECT_EQ(json::parse(e.out)["estimated_time_s"], j["estimated_time_s"]);
  }
  EXPECT_NE(gantry("run parts/demo.sbp --feed-override 5").exit_code, 0);  // below 10 %
}

// The simulated card's pin trace of tiny files, word change by word change, against golden
// traces checked by hand: trace_small (3 X steps out, then 1 back with 2 Y steps),
// trace_reversal (3 X steps out, 2 back: the direction bit 8 rises between the pulses, at
// least the setup time before the first step back), trace_output (output 1, bit 18, on from
// the first word, off one word after X's two steps). The charge pump toggles bit 16 every
// 10 ticks throughout. Every trace ends at the idle word (all zero): as the process ends the
// controller switches the card's outputs off, every time (it once raced its own quit).
class PinTrace : public ::testing::TestWithParam<std::string> {};

TEST_P(PinTrace, MatchesTheGoldenTrace) {
  const std::string name = GetParam();
  const fs::path out =
      fs::temp_directory_path() / fmt::format("gantry_{}_{}.trace", name, getpid());
  const Result r = gantry("run tests/data/" + name + ".sbp --json --trace '" + out.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream got(out), want(kSource / "tests/data" / (name + ".trace"));
  std::stringstream g, w;
  g << got.rdbuf();
  w << want.rdbuf();
  fs::remove(out);
  EXPECT_EQ(g.str(), w.str());
  EXPECT_GT(w.str().size(), 1000u);
  EXPECT_TRUE(w.str().ends_with(" 00000000\n"));
}

INSTANTIATE_TEST_SUITE_P(Golden, PinTrace,
                         ::testing::Values("trace_small", "trace_reversal", "trace_output"));

// Issue 21: a stop followed at once by a start the other way. A PAUSE (answered by --yes),
// a probe that touches nothing and the sync before a probe each play the motion out: the
// machine stops from the ramp speed and the next move starts on the card's next tick. Z
// reverses in each; the card measured 2.8 times Z's acceleration limit and still said "done".
struct ReversalCase {
  const char* name;
  const char* text;
  double last_z;  // where the file leaves Z
};

class ReversalAtRest : public ::testing::TestWithParam<ReversalCase> {};

TEST_P(ReversalAtRest, StaysWithinTheAxisLimitsAndIsDone) {
  const ReversalCase c = GetParam();
  const fs::path file =
      fs::temp_directory_path() / fmt::format("gantry_{}_{}.sbp", c.name, getpid());
  std::ofstream(file) << c.text;
  const Result r = gantry("run '" + file.string() + "' --yes --json");
  fs::remove(file);
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["status"], "done");
  EXPECT_EQ(j["timing_violations"], 0);
  EXPECT_EQ(j["kinematic_violations"], 0);
  EXPECT_LE(j["max_velocity_ratio"].get<double>(), 1.001);
  EXPECT_LE(j["max_accel_ratio"].get<double>(), 1.001);
  EXPECT_EQ(j["steps"]["z"].get<std::int64_t>(), std::llround(c.last_z * kStepsPerUnit[2]));
}

INSTANTIATE_TEST_SUITE_P(
    HoldBoundaries, ReversalAtRest,
    ::testing::Values(ReversalCase{"pause", "MZ, 1\nPAUSE\nMZ, 0.5\n", 0.5},
                      ReversalCase{"probe_miss", "PZ, -1, 0.5, 1\nJZ, 0.5\n", 0.5},
                      ReversalCase{"probe_start", "MZ, 1\nPZ, -1, 0.5, 1\n", -1},
                      // Issue 22 again: the probe touches the profile's plate (Z -2), stops,
                      // and the move after it reverses from rest.
                      ReversalCase{"probe_touch", "MZ, 1\nPZ, -3, 0.5, 1\nMZ, 1\n", 1}),
    [](const auto& info) { return std::string(info.param.name); });

// A job in the shape of Fusion 360's OpenSBP post (tests/data/fusion_post.sbp: &Tool, C9,
// TR, C6, PAUSE 2 at each of two tools, C7 and END) with Gantry's shipped macros and no
// --macros. Expected values worked out by hand from the file and parts/macros/C6, C7, C9.
struct TraceWord {
  std::int64_t tick;
  std::uint32_t word;
};

std::vector<TraceWord> read_trace(const fs::path& path) {
  std::vector<TraceWord> out;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream l(line);
    TraceWord w{};
    l >> w.tick >> std::hex >> w.word;
    out.push_back(w);
  }
  return out;
}

// The ticks at which `bit` rises (or falls).
std::vector<std::int64_t> edges(const std::vector<TraceWord>& t, int bit, bool rising) {
  std::vector<std::int64_t> out;
  for (size_t i = 1; i < t.size(); ++i) {
    const bool was = t[i - 1].word >> bit & 1u, is = t[i].word >> bit & 1u;
    if (is != was && is == rising) out.push_back(t[i].tick);
  }
  return out;
}

// The fraction of [from, to) during which `bit` is high.
double duty(const std::vector<TraceWord>& t, int bit, std::int64_t from, std::int64_t to) {
  std::int64_t high = 0;
  for (size_t i = 0; i < t.size(); ++i) {
    const std::int64_t a = std::max(from, t[i].tick);
    const std::int64_t b = std::min(to, i + 1 < t.size() ? t[i + 1].tick : to);
    if (b > a && (t[i].word >> bit & 1u)) high += b - a;
  }
  return static_cast<double>(high) / static_cast<double>(to - from);
}

TEST(CamPost, FusionShapedJobChangesToolsAndSwitchesTheSpindleWithTheShippedMacros) {
  const std::string file = "tests/data/fusion_post.sbp";
  const Result c = gantry("check " + file + " --yes");
  EXPECT_EQ(c.exit_code, 0) << c.out << c.err;

  // The moves: C9 lifts to Safe-Z (1), goes to the change position (table base 0, 0), the
  // spindle goes off (C7: output 1 off, 5 s spin-down), and it comes back over where it was.
  const Result m = gantry("moves " + file + " --format jsonl --yes");
  ASSERT_EQ(m.exit_code, 0) << m.err;
  std::vector<std::string> seen;  // "file:line kind to" of every move with an effect
  std::istringstream lines(m.out);
  std::string line;
  while (std::getline(lines, line)) {
    const json j = json::parse(line);
    const std::string kind = j["kind"];
    if (kind == "stop" || (kind == "line" && j["from"] == j["to"])) continue;  // MS; no motion
    std::string what = fs::path(j["file"].get<std::string>()).filename().string() + ":" +
                       std::to_string(j["line"].get<int>()) + " " + kind;
    if (kind == "line")
      what += fmt::format(" {:g},{:g},{:g}", j["to"][0].get<double>(), j["to"][1].get<double>(),
                          j["to"][2].get<double>());
    if (kind == "output")
      what += fmt::format(" {} {}", j["output"].get<int>(), j["on"] ? "on" : "off");
    if (kind == "dwell") what += fmt::format(" {:g}", j["dwell_s"].get<double>());
    seen.push_back(what);
  }
  const std::vector<std::string> want = {
      // tool 1 (at 0, 0, 0): C9 lifts; the change position is where the tool is
      "C9.sbp:26 line 0,0,1", "C7.sbp:15 output 1 off", "C7.sbp:16 dwell 5",
      "C6.sbp:14 output 1 on", "C6.sbp:15 dwell 3", "fusion_post.sbp:11 dwell 2",
      "fusion_post.sbp:13 line 0,0,0.6", "fusion_post.sbp:14 line 2,2,0.6",
      "fusion_post.sbp:15 line 2,2,0.2", "fusion_post.sbp:16 line 2,2,-0.25",
      "fusion_post.sbp:17 line 6,2,-0.25", "fusion_post.sbp:18 line 6,5,-0.25",
      "fusion_post.sbp:19 line 2,5,-0.25", "fusion_post.sbp:20 line 2,2,-0.25",
      "fusion_post.sbp:21 line 2,2,0.6",
      // tool 2: up, over to the change position, spindle off, back over 2, 2
      "C9.sbp:26 line 2,2,1", "C9.sbp:28 line 0,0,1", "C7.sbp:15 output 1 off", "C7.sbp:16 dwell 5",
      "C9.sbp:33 line 2,2,1", "C6.sbp:14 output 1 on", "C6.sbp:15 dwell 3",
      "fusion_post.sbp:27 dwell 2", "fusion_post.sbp:29 line 8,3,1",
      "fusion_post.sbp:30 line 8,3,0.2", "fusion_post.sbp:31 line 8,3,-0.125",
      "fusion_post.sbp:32 line 10,3,-0.125", "fusion_post.sbp:33 line 10,4,-0.125",
      "fusion_post.sbp:34 line 10,4,0.6", "C7.sbp:15 output 1 off", "C7.sbp:16 dwell 5"};
  EXPECT_EQ(seen, want);

  // On the card with the shipped profile: TR has no speed output, so one warning for both.
  const Result r = gantry("run " + file + " --yes --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["status"], "done");
  EXPECT_EQ(j["timing_violations"], 0);
  const std::array<double, 3> end{10, 4, 0.6};
  for (int i = 0; i < 3; ++i)
    EXPECT_EQ(j["steps"][kAxes[i]].get<std::int64_t>(), std::llround(end[i] * kStepsPerUnit[i]));
  size_t tr_warnings = 0;
  for (size_t at = r.err.find("TR: "); at != std::string::npos; at = r.err.find("TR: ", at + 1))
    ++tr_warnings;
  EXPECT_EQ(tr_warnings, 1u) << r.err;
}

TEST(CamPost, WithAPwmSpeedOutputTheTraceCarriesEachToolsDuty) {
  // The shipped profile with the spindle's speed on bit 30: 1 kHz (200 ticks), 24000 RPM.
  std::ifstream in(kSource / "settings/default.toml");
  std::stringstream text;
  text << in.rdbuf();
  std::string profile = text.str();
  profile.replace(profile.find("pwm_bit = -1"), 12, "pwm_bit = 30");
  const fs::path settings = fs::temp_directory_path() / fmt::format("gantry_pwm_{}.toml", getpid());
  const fs::path trace = fs::temp_directory_path() / fmt::format("gantry_pwm_{}.trace", getpid());
  std::ofstream(settings) << profile;
  const Result r =
      gantry(fmt::format("run tests/data/fusion_post.sbp --yes --json --settings '{}' "
                         "--trace '{}'",
                         settings.string(), trace.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("TR: "), std::string::npos) << r.err;  // no warning: it is wired
  const std::vector<TraceWord> t = read_trace(trace);
  fs::remove(trace);
  fs::remove(settings);
  ASSERT_GT(t.size(), 100u);
  // Output 1 (bit 18), the spindle: on at each C6, off at tool 2's C9 and at the end.
  const std::vector<std::int64_t> on = edges(t, 18, true), off = edges(t, 18, false);
  ASSERT_EQ(on.size(), 2u);
  ASSERT_EQ(off.size(), 2u);
  EXPECT_LT(on[0], off[0]);
  EXPECT_LT(off[0], on[1]);
  EXPECT_LT(on[1], off[1]);
  // C6 waits 3 s and the post 2 s more before the tool moves: 5 s at 200 kHz.
  EXPECT_GE(off[0] - on[0], 5 * 200000);
  // While the spindle runs, bit 30's duty is TR's RPM over 24000, to within the 1 % the
  // profile's pwm_hz allows.
  EXPECT_NEAR(duty(t, 30, on[0], off[0]), 18000.0 / 24000, 0.005);
  EXPECT_NEAR(duty(t, 30, on[1], off[1]), 16000.0 / 24000, 0.005);
  EXPECT_EQ(duty(t, 30, 0, on[0] - 200000 * 3), 0.0);  // before TR: C9's lift, C7's wait
  EXPECT_EQ(t.back().word >> 30 & 1u, 0u);             // 0 once the job has ended
}

// Faults on the simulated card: the run stops, says why and where, and the position it
// reports is exactly the pulses the card played (the card's own count and the generator's).
struct FaultCase {
  const char* options;
  const char* fault;
};

class CardFaultRun : public ::testing::TestWithParam<FaultCase> {};

TEST_P(CardFaultRun, MotionStopsAndThePositionIsThePulsesPlayed) {
  const FaultCase c = GetParam();
  const Result r = gantry(std::string("run parts/demo.sbp --json ") + c.options);
  EXPECT_EQ(r.exit_code, 1);
  const json j = json::parse(r.out);
  EXPECT_EQ(j["status"], "error");
  EXPECT_EQ(j["fault"], c.fault);
  ASSERT_EQ(j["errors"].size(), 1u);
  const std::string message = j["errors"][0]["message"];
  EXPECT_NE(message.find(std::string(c.fault) + ": the card stopped at"), std::string::npos)
      << message;
  if (std::string(c.fault) == "limit switch") {  // which switch, by name
    EXPECT_EQ(message.rfind("X high limit switch (input bit 3): ", 0), 0u) << message;
  }
  EXPECT_EQ(j["steps"], j["played_steps"]);
  EXPECT_NE(j["steps"], j["commanded_steps"]);  // it stopped short of the file's end
  EXPECT_EQ(j["timing_violations"], 0);
  for (int i = 0; i < 6; ++i)
    EXPECT_NEAR(j["position"][kAxes[i]].get<double>(),
                j["steps"][kAxes[i]].get<double>() / kStepsPerUnit[i], 1e-12);
}

INSTANTIATE_TEST_SUITE_P(Faults, CardFaultRun,
                         ::testing::Values(FaultCase{"--sim-estop-at 3.2", "E-stop"},
                                           FaultCase{"--sim-stall-at 1.5", "underrun"},
                                           FaultCase{"--sim-limit x+=5", "limit switch"}));

TEST(CardFaultRun, EStopStopsAtItsTickAndALimitAtTheStepThatTripsIt) {
  const json e = json::parse(gantry("run parts/demo.sbp --json --sim-estop-at 3.2").out);
  EXPECT_NEAR(e["time_s"].get<double>(), 3.2, 1e-9);
  const json l = json::parse(gantry("run parts/demo.sbp --json --sim-limit x+=5").out);
  EXPECT_EQ(l["steps"]["x"], std::llround(std::ceil(5 * kStepsPerUnit[0])));
  EXPECT_NE(gantry("run parts/demo.sbp --sim-limit q+=5").err.find("--sim-limit q+=5 must be"),
            std::string::npos);
}

TEST(Cards, AGpioCardThatCannotKeepThePacerIsRefusedBeforeAnythingRuns) {
  const Result r = gantry("run parts/demo.sbp --card gpiod");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("error: cannot open the gpiod card: gpiod: pacer rate 200000 Hz is above"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.out, "");  // no report: nothing ran
}

TEST(Cards, AMissingPci7200IsNamedBeforeAnythingRuns) {
  const Result r = gantry("run parts/demo.sbp --card pci7200");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("error: cannot open the pci7200 card: no PCI-7200 found"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("is the card fitted?"), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");
}

TEST(Commands, TheTableAsJsonHasEveryCodeWithItsParametersAndCoverage) {
  const Result r = gantry("commands --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json all = json::parse(r.out);
  EXPECT_EQ(all.size(), 129u);  // 126 codes (TR the newest), the M0 alias, FabMo's CN and SU
  const auto mx =
      std::find_if(all.begin(), all.end(), [](const json& c) { return c["code"] == "MX"; });
  ASSERT_NE(mx, all.end());
  EXPECT_EQ((*mx)["group"], "Move");
  EXPECT_EQ((*mx)["coverage"], "complete");
  EXPECT_EQ((*mx)["parameters"][0]["name"], "X location");
  const json zero = json::parse(gantry("commands --json --group zero").out);
  EXPECT_EQ(zero.size(), 12u);
  for (const json& c : zero) EXPECT_EQ(c["group"], "Zero");
  const Result bad = gantry("commands --group bogus");
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("no command group 'bogus'; the groups are Cuts, File"), std::string::npos);
}

TEST(Estimate, BadFileGetsItsErrorsAndNoEstimate) {
  const Result r = gantry("estimate tests/data/unknown_command.sbp");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("unknown command"), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");
}

TEST(Estimate, TextGivesHoursMinutesSecondsAndThePlannerMode) {
  const Result r = gantry("estimate parts/demo.sbp");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("parts/demo.sbp: 0:00:"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("with the sb3 planner"), std::string::npos) << r.out;
}

INSTANTIATE_TEST_SUITE_P(AllParts, PartRun,
                         ::testing::Values("demo.sbp", "relative_steps.sbp", "rotary.sbp",
                                           "speeds.sbp", "trepan.fm", "scribe.fm",
                                           "taught_frame.fm", "subroutine.fm"),
                         [](const auto& info) {
                           std::string n = info.param;
                           for (char& c : n)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return n;
                         });

TEST(Run, TextReportNamesTheOutcome) {
  const Result r = gantry("run parts/speeds.sbp");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("status     done"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("equal to the planner's commanded steps"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("0 violations"), std::string::npos) << r.out;
}

// Bad input: a located message, exit status 1, and not one pulse on the card.
void expect_rejected(const Result& r, const std::string& located_message) {
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find(located_message), std::string::npos) << "stderr was:\n"
                                                            << r.err << "\nexpected to contain:\n"
                                                            << located_message;
}

void expect_no_motion(const std::string& out) {
  const json j = json::parse(out);
  EXPECT_EQ(j["status"], "error");
  EXPECT_EQ(j["time_s"].get<double>(), 0.0);
  for (const char* a : kAxes) EXPECT_EQ(j["steps"][a].get<std::int64_t>(), 0) << a;
}

TEST(BadInput, UnknownCommand) {
  const Result r = gantry("run tests/data/unknown_command.sbp --json");
  expect_rejected(r, "tests/data/unknown_command.sbp:3:1: error: unknown command 'QQ'");
  expect_no_motion(r.out);
}

TEST(BadInput, NonNumericParameter) {
  const Result r = gantry("run tests/data/non_numeric.sbp --json");
  expect_rejected(r,
                  "tests/data/non_numeric.sbp:3:5: error: expected a number for Y location "
                  "(MY), found 'one'");
  expect_no_motion(r.out);
}

TEST(BadInput, MoveBeyondTheSoftLimitStopsBeforeAnyMotion) {
  // Line 2 is a legal move, but the file is refused whole: nothing moves at all.
  const Result r = gantry("run tests/data/soft_limit.sbp --json");
  expect_rejected(r,
                  "tests/data/soft_limit.sbp:3:1: error: move to X=30.0000 is outside the "
                  "soft limits");
  expect_no_motion(r.out);
}

TEST(BadInput, MissingPartFile) {
  const Result r = gantry("run parts/no_such_file.sbp --json");
  expect_rejected(r, "parts/no_such_file.sbp: error: cannot open the part file");
  expect_no_motion(r.out);
}

TEST(BadInput, SettingsWithAWrongValue) {
  const Result r = gantry("run parts/demo.sbp --settings tests/data/bad_value.toml --json");
  expect_rejected(r,
                  "tests/data/bad_value.toml:13:13: error: axes.x.max_speed = -8 is out of "
                  "range; allowed: > 0 and <= 100000");
  EXPECT_EQ(r.out, "");  // no card was started, so there is no report
}

TEST(BadInput, MissingSettingsFile) {
  const Result r = gantry("run parts/demo.sbp --settings tests/data/none.toml");
  expect_rejected(r, "tests/data/none.toml: error: cannot open the settings file");
}

TEST(Check, ValidFileExitsZero) {
  const Result r = gantry("check parts/demo.sbp");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
}

TEST(Check, ReportsEveryErrorInOrder) {
  const Result r = gantry("check tests/data/many_errors.sbp");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err,
            "tests/data/many_errors.sbp:3:1: error: unknown command 'QQ'; see docs/commands.md "
            "for the commands Gantry knows\n"
            "tests/data/many_errors.sbp:4:5: error: expected a number for Y location (MY), "
            "found 'abc'\n"
            "tests/data/many_errors.sbp:5:5: error: XY speed 0 is out of range; allowed: above 0 "
            "and up to 8 in/s (the axis max_speed in the profile)\n"
            "tests/data/many_errors.sbp:6:8: error: MZ takes 1 parameter; this is parameter 2\n");
}

// ShopBot's own spellings (issue 21): `\`, a name starting with a digit, ON INP, a '(' in a
// MSGBOX's text, an unquoted answer in an IF test, CR with 10 parameters and C#, &n. Each was
// an error before; now the file reads, CR's extra parameter is the one warning, and C#, &whole
// runs C7.sbp beside the file.
TEST(Check, ShopBotsOwnSpellingsRead) {
  const Result r = gantry("check tests/data/spellings/shopbot_spellings.sbp");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err,
            "tests/data/spellings/shopbot_spellings.sbp:8:36: warning: CR takes 9 parameters; "
            "parameter 10 "
            "and those after it are ignored, as SB3 ignores them\n");
  const Result moves =
      gantry("moves tests/data/spellings/shopbot_spellings.sbp --format jsonl --yes");
  ASSERT_EQ(moves.exit_code, 0) << moves.err;
  std::istringstream in(moves.out);
  std::string line, last;
  while (std::getline(in, line)) last = line;
  ASSERT_FALSE(last.empty());
  const json m = json::parse(last);
  EXPECT_EQ(m["file"], "tests/data/spellings/C7.sbp");
  EXPECT_EQ(m["to"][0], 1);
}

TEST(Moves, JsonlGivesEveryCanonicalMove) {
  const Result r = gantry("moves parts/relative_steps.sbp --format jsonl");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream in(r.out);
  std::string line;
  std::vector<json> moves;
  while (std::getline(in, line)) moves.push_back(json::parse(line));
  ASSERT_EQ(moves.size(), 12u);
  const json& first = moves[0];
  EXPECT_EQ(first["file"], "parts/relative_steps.sbp");
  EXPECT_EQ(first["line"], 4);
  EXPECT_EQ(first["kind"], "line");
  EXPECT_EQ(first["speed_class"], "jog");
  EXPECT_EQ(first["from"], json::array({0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(first["to"], json::array({2, 2, 0.25, 0, 0, 0}));
  // Jog XY 6 in/s is the binding limit: Z moves 0.25 at 6 * 0.25 / hypot(2, 2) < 3 in/s.
  EXPECT_NEAR(first["speed"].get<double>(), 6.0 * std::sqrt(8 + 0.0625) / std::sqrt(8), 1e-12);
  const json& plunge = moves[1];  // SR; MZ, -0.35
  EXPECT_EQ(plunge["speed_class"], "move");
  EXPECT_NEAR(plunge["to"][2].get<double>(), -0.1, 1e-12);
  EXPECT_DOUBLE_EQ(plunge["speed"].get<double>(), 0.5);
  const json& last = moves.back();
  EXPECT_EQ(last["line"], 17);
  EXPECT_EQ(last["to"][0], 5.125);
}

TEST(Help, DocsCommandsPageIsGeneratedFromTheTable) {
  const Result r = gantry("help --markdown");
  ASSERT_EQ(r.exit_code, 0);
  std::ifstream in(kSource / "docs" / "commands.md");
  std::stringstream page;
  page << in.rdbuf();
  EXPECT_EQ(r.out, page.str())
      << "regenerate with: build/gantry help --markdown > docs/commands.md";
}

TEST(Help, OneCommandListsItsParametersInOrder) {
  const Result r = gantry("help vs");
  ASSERT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("Usage: VS, XY move speed, Z move speed, A move speed, B move speed, "
                       "XY jog speed, Z jog speed, A jog speed, B jog speed"),
            std::string::npos)
      << r.out;
  const Result bad = gantry("help qq");
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("unknown command 'qq'"), std::string::npos);
}

// The real files in shared/corpus (its README names their sources), run as an operator
// would: --yes for their questions, on the simulated card. FabMo's machine macros run on the
// machine they were written for (the Handibot profile, FabMo's dialect, soft limits off) with
// the $variables FabMo's own standard-variables macro (201) sets. Every file that is not
// broken by itself checks clean and runs to its end with no violation; each that cannot is
// listed with the words of its first error.
struct CorpusFile {
  const char* name;
  bool fabmo_machine;   // needs the FabMo machine above
  const char* refused;  // "" runs clean; else why not, as the first error says it
};

const std::vector<CorpusFile> kCorpus = {
    {"fabmo_macro_201.sbp", false, ""},
    {"fabmo_macro_211.sbp", false, ""},  // PartWorks V-carve: CN 90, C9, TR, C6, C7, 13,811 M3
    {"fabmo_test1.sbp", false, ""},
    {"fabmo_test2.sbp", false, ""},
    {"fabmo_macro_2.sbp", true, ""},
    {"fabmo_macro_79.sbp", true, ""},
    {"fabmo_macro_9.sbp", true, ""},
    {"fabmo_handibot2_macro_77.sbp", true, ""},
    // Broken by themselves, or FabMo-only: each names what it lacks.
    {"fabmo_dtatc_macro_71.sbp", true, "C75 runs custom cut 75, but there is no C75.sbp"},
    {"fabmo_macro_3.sbp", true, "reads FabMo's configuration tree, which Gantry does not offer"},
    {"fabmo_probe_digitize_example.sbp", false,
     "DATA_SEND is a FabMo statement that sends data to its web dashboard"},
    {"nist_singleLinesPics3.sbp", false, "'dz' is not a value"},  // the source's own bug
    {"nist_cameratest.sbp", false, ""},
    {"nist_crossDoubleHoriz.sbp", false, ""},
    {"nist_crossDoubleHorizPics2.sbp", false, ""},
    {"nist_crossUnderPics.sbp", false, ""},
    {"nist_disturbHoriz3_2_0.500.sbp", false, ""},
    {"nist_disturbUnder_1_0.500_VF_10.00_VS_10.00.sbp", false, ""},
    {"nist_metatest.sbp", false, ""},
    {"nist_retract.sbp", false, ""},
    {"nist_singleLines.sbp", false, ""},
    {"nist_singleLinesNoZig_2.5.sbp", false, ""},
    {"nist_singleLinesPics9.sbp", false, ""},
    {"nist_singleLinesPics_program.sbp", false, ""},
    {"nist_speed_test.sbp", false, ""},
    {"nist_timing_calibration.sbp", false, ""},
    {"nist_timing_calibration_4.sbp", false, ""},
    {"nist_tripleLinesXS.sbp", false, ""},
};

TEST(Corpus, EveryFileRunsCleanOrNamesWhyNot) {
  const fs::path corpus = kSource.parent_path() / "shared" / "corpus";
  ASSERT_TRUE(fs::exists(corpus)) << "no shared/corpus beside the repository (CI lays it there)";
  std::set<std::string> listed;
  for (const CorpusFile& f : kCorpus) listed.insert(f.name);
  for (const auto& entry : fs::directory_iterator(corpus)) {
    if (entry.path().extension() != ".sbp" && entry.path().extension() != ".fm") continue;
    EXPECT_TRUE(listed.count(entry.path().filename().string())) << entry.path();
  }
  EXPECT_EQ(listed.size(), 28u);

  // FabMo's standard variables, as its macro 201 sets them.
  const fs::path tmp = fs::temp_directory_path();
  const fs::path standard = tmp / fmt::format("gantry_corpus_201_{}.json", getpid());
  fs::remove(standard);
  ASSERT_EQ(gantry(fmt::format("run '{}' --yes --persistent '{}'",
                               (corpus / "fabmo_macro_201.sbp").string(), standard.string()))
                .exit_code,
            0);
  int clean = 0;
  for (const CorpusFile& f : kCorpus) {
    SCOPED_TRACE(f.name);
    std::string options = " --yes";
    if (f.fabmo_machine) {
      const fs::path store = tmp / fmt::format("gantry_corpus_{}.json", getpid());
      const fs::path values = tmp / fmt::format("gantry_corpus_{}.toml", getpid());
      fs::copy_file(standard, store, fs::copy_options::overwrite_existing);
      fs::copy_file(kSource / "tests/data/fabmo/fabmo_machine.toml", values,
                    fs::copy_options::overwrite_existing);
      options += fmt::format(" --profile handibot --persistent '{}' --values '{}'", store.string(),
                             values.string());
    }
    const std::string file = (corpus / f.name).string();
    const Result check = gantry(fmt::format("check '{}'{}", file, options));
    const Result run = gantry(fmt::format("run '{}'{} --json", file, options));
    if (*f.refused) {
      EXPECT_EQ(check.exit_code, 1);
      EXPECT_NE(check.err.find(f.refused), std::string::npos) << check.err;
      EXPECT_EQ(run.exit_code, 1);
      continue;
    }
    EXPECT_EQ(check.exit_code, 0) << check.err;
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const json j = json::parse(run.out);
    EXPECT_EQ(j["status"], "done");
    EXPECT_EQ(j["check"], "complete");
    EXPECT_EQ(j["fault"], "none");
    EXPECT_EQ(j["steps"], j["commanded_steps"]);
    EXPECT_EQ(j["timing_violations"], 0);
    EXPECT_EQ(j["kinematic_violations"], 0);
    clean += 1;
  }
  EXPECT_EQ(clean, 24);
  fs::remove(standard);
}

// ---- Homing and zeroing on the simulated machine (issue 21) ----------------------------
// The default profile's [simulator], written out here: X's proximity switch closes at or below
// X -1.5, Y's at or below -1.0, Z's at or above 0.75 (input 3, bit 8), the plate's top at
// Z -2.0 (input 1), all in the card's coordinates (0 where the tool starts). A switch closes at
// the first step at or beyond its place.

// Writes `text` to a part file of its own and gives its path.
std::string part_file(const std::string& name, const std::string& text) {
  const fs::path p = fs::temp_directory_path() / fmt::format("gantry_{}_{}.sbp", name, getpid());
  std::ofstream(p) << text;
  return p.string();
}

std::int64_t steps_of(const json& j, int axis) {
  return j["steps"][kAxes[axis]].get<std::int64_t>();
}

// Where homing leaves each axis: the step where its switch closed, then backed off 0.25 in.
struct Homed {
  std::int64_t x =
      std::llround(std::floor(-1.5 * kStepsPerUnit[0]) + std::llround(0.25 * kStepsPerUnit[0]));
  std::int64_t y =
      std::llround(std::floor(-1.0 * kStepsPerUnit[1]) + std::llround(0.25 * kStepsPerUnit[1]));
  std::int64_t z =
      std::llround(std::ceil(0.75 * kStepsPerUnit[2]) - std::llround(0.25 * kStepsPerUnit[2]));
};

// The least time homing can take: each axis searches its switch's distance at 1 in/s and
// comes back the last 0.25 in at 0.1 in/s; the back-offs (at 1 in/s, or jog speed in C3.sbp),
// the ramps and each probe's return to the latch come on top, less than 3 s in all.
constexpr double kLeastHomingTime = (0.75 + 1.5 + 1.0) + 3 * 2.5;

class Homing : public ::testing::TestWithParam<const char*> {};

// C3 without a C3.sbp is the built-in homing; with --macros parts/macros, the shipped C3.sbp.
TEST_P(Homing, C3EndsBackedOffEachSwitchToTheStepInABoundedTime) {
  const std::string file = part_file("home", "C3\n");
  const Result r = gantry(fmt::format("run '{}' --json {}", file, GetParam()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(r.out);
  const Homed want;
  EXPECT_EQ(steps_of(j, 0), want.x);
  EXPECT_EQ(steps_of(j, 1), want.y);
  EXPECT_EQ(steps_of(j, 2), want.z);
  const double t = j["time_s"].get<double>();
  EXPECT_GT(t, kLeastHomingTime);
  EXPECT_LT(t, kLeastHomingTime + 3.0) << "homing ran further than its switches";
  EXPECT_EQ(j["timing_violations"], 0);
  fs::remove(file);
}

INSTANTIATE_TEST_SUITE_P(BuiltInAndShipped, Homing, ::testing::Values("", "--macros parts/macros"));

// C2 makes the plate's top read its thickness: a move to Z 0.118 afterwards lands on the step
// where the cutter touched it. Homed first, the plate is where it was on the table.
TEST(Zeroing, C2MakesThePlateTopReadItsThickness) {
  for (const char* before : {"", "C3\n"}) {
    const std::string file = part_file("zero", std::string(before) + "C2\nJZ, 0.118\n");
    const Result r = gantry(fmt::format("run '{}' --json --macros parts/macros", file));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const json j = json::parse(r.out);
    EXPECT_EQ(steps_of(j, 2), std::llround(std::floor(-2.0 * kStepsPerUnit[2]))) << before;
    fs::remove(file);
  }
}

TEST(Zeroing, C2EndsLiftedClearOfThePlate) {
  const std::string file = part_file("zero_lift", "C2\n");
  const json j =
      json::parse(gantry(fmt::format("run '{}' --json --macros parts/macros", file)).out);
  EXPECT_EQ(steps_of(j, 2), std::llround(std::floor(-2.0 * kStepsPerUnit[2])) +
                                std::llround(1.0 * kStepsPerUnit[2]));
  fs::remove(file);
}

// ON INPUT fires on a proximity switch: the card stops at the step that closes it.
TEST(SimulatedSwitches, OnInputStopsAtTheStepWhereTheZSwitchCloses) {
  const std::string file =
      part_file("on_input", "ON INPUT(3, 1) GOTO HIT\nMZ, 3\nMX, 5\nEND\nHIT:\nMX, 1\n");
  const Result r = gantry(fmt::format("run '{}' --json", file));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(steps_of(j, 2), std::llround(std::ceil(0.75 * kStepsPerUnit[2])));
  EXPECT_EQ(steps_of(j, 0), std::llround(kStepsPerUnit[0]));
  fs::remove(file);
}

TEST(PauseUntil, NothingToCloseTheInputIsRefusedAtItsLineBeforeAnythingMoves) {
  const std::string file = part_file("pause_until", "MX, 1\nPAUSE UNTIL 3, 1\nMX, 2\n");
  for (const char* how : {"run '{}' --json --yes", "check '{}'"}) {
    const Result r = gantry(fmt::format(fmt::runtime(how), file));
    EXPECT_EQ(r.exit_code, 1);
    const std::string text = r.err + r.out;
    EXPECT_NE(text.find(":2:1: error: PAUSE UNTIL waits for input 3 to close, and nothing will "
                        "close it: nobody is at the machine"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("--sim-input 3=1@SECONDS"), std::string::npos) << text;
    if (std::string(how).find("run") == 0) {
      EXPECT_EQ(steps_of(json::parse(r.out), 0), 0);
    }
  }
  fs::remove(file);
}

TEST(PauseUntil, AnInputEventEndsTheWaitAtItsTime) {
  const std::string file = part_file("pause_event", "MX, 1\nPAUSE UNTIL 3, 1\nMX, 2\n");
  const Result r = gantry(fmt::format("run '{}' --json --yes --sim-input 3=1@6.5", file));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(steps_of(j, 0), std::llround(2 * kStepsPerUnit[0]));
  const double t = j["time_s"].get<double>();
  EXPECT_GT(t, 6.5 + 0.5);  // the wait, then 1 in at 2 in/s
  EXPECT_LT(t, 6.5 + 0.5 + 0.2);
  fs::remove(file);
}

TEST(PauseUntil, ASwitchWhereTheToolRestsAnswersIt) {
  const std::string file = part_file("pause_switch", "MZ, 1\nPAUSE UNTIL 3, 1\nMZ, 0\n");
  const Result r = gantry(fmt::format("run '{}' --json --yes", file));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  fs::remove(file);
}

TEST(PauseUntil, AMalformedSimInputSaysTheForm) {
  for (const char* bad : {"3=1", "13=1@2", "3=2@1", "2=1@1", "3=1@q>=2", "3=1@x=2"}) {
    const Result r = gantry(fmt::format("run parts/demo.sbp --sim-input '{}'", bad));
    EXPECT_EQ(r.exit_code, 1) << bad;
    EXPECT_NE(r.err.find(fmt::format("error: --sim-input {}: ", bad)), std::string::npos) << r.err;
  }
}

// ---- Shipped profiles --------------------------------------------------------------------

TEST(Profiles, AShippedProfileIsFoundByNameFromAnyDirectory) {
  const std::string file = part_file("profile", "MX, 30\n");
  const Result r = gantry(fmt::format("check '{}' --profile shopbot-desktop", file));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("outside the table of profile 'shopbot-desktop' (24 x 18 x 5.5 in); it "
                       "fits: prsalpha-48x96, prsalpha-60x120, prsstandard-48x96, "
                       "prsstandard-60x120, shopbot-desktop-max (--profile NAME)"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(gantry(fmt::format("check '{}' --profile prsalpha-48x96", file)).exit_code, 0);
  // From another directory too: the shipped folder's path is compiled in.
  EXPECT_EQ(std::system(fmt::format("cd / && '{}' check '{}' --profile prsalpha-48x96 "
                                    ">/dev/null 2>&1",
                                    GANTRY_BIN, file)
                            .c_str()),
            0);
  const Result missing = gantry(fmt::format("check '{}' --profile no-such-table", file));
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.err.find("no-such-table: error: no such profile file, and no shipped profile "
                             "of that name"),
            std::string::npos);
  EXPECT_NE(missing.err.find("  prsalpha-60x120"), std::string::npos);
  fs::remove(file);
}

// FabMo's Handibot plate macro (C77) on the shipped Handibot profile runs to its end: it drives
// Z to its top, touches the plate twice and records the second touch (working Z, zeroed at the
// first) as the plate's height, on the FabMo machine (tests/data/fabmo/fabmo_machine.toml:
// FabMo's dialect, soft limits off). With the plate's top at Z 2.0 both touches are at the first
// step at or below it, so the height reads 0 and Z ends 0.5 above that step.
TEST(Corpus, FabmoPlateMacroTouchesThePlateOnTheHandibot) {
  const fs::path corpus = kSource.parent_path() / "shared" / "corpus";
  ASSERT_TRUE(fs::exists(corpus)) << "no shared/corpus beside the repository (CI lays it there)";
  const fs::path store = fs::temp_directory_path() / fmt::format("gantry_c77_{}.json", getpid());
  const fs::path values = fs::temp_directory_path() / fmt::format("gantry_c77_{}.toml", getpid());
  fs::copy_file(kSource / "tests/data/fabmo/macro_201_variables.json", store,
                fs::copy_options::overwrite_existing);
  fs::copy_file(kSource / "tests/data/fabmo/fabmo_machine.toml", values,
                fs::copy_options::overwrite_existing);
  const Result r = gantry(fmt::format(
      "run '{}' --profile handibot --yes --json --persistent '{}' --values '{}' --sim-probe-z 2",
      (corpus / "fabmo_handibot2_macro_77.sbp").string(), store.string(), values.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(r.out);
  const std::int64_t touch = std::llround(std::floor(2.0 * kStepsPerUnit[2]));
  EXPECT_EQ(steps_of(j, 2), touch + std::llround(0.5 * kStepsPerUnit[2]));
  // The Handibot profile has the Desktop's unit values. M2, 6, 0 takes it to the plate's place.
  EXPECT_EQ(steps_of(j, 0), std::llround(6 * kStepsPerUnit[0]));
  std::ifstream in(store);
  EXPECT_EQ(json::parse(in)["variables"]["ZZEROPLATETHICKNESS"], 0);
  fs::remove(store);
}

int count_lines(const std::string& text) {
  return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}

// Many errors: at most --max-errors of them (100 by default) and one line for the rest.
TEST(Check, StopsAfterTheErrorCapAndSummarisesTheRestInOneLine) {
  std::string text = "MX, 1\n";
  for (int i = 0; i < 300; ++i) text += "QQ, 1\n";
  const std::string file = part_file("many.sbp", text);
  const Result r = gantry(fmt::format("check '{}'", file));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(count_lines(r.err), 101) << r.err.substr(0, 2000);
  EXPECT_NE(r.err.find(file + ":2:1: error: unknown command 'QQ'"), std::string::npos);
  EXPECT_NE(
      r.err.find("\ngantry: stopped after 100 errors; 200 more not shown: 200 'unknown command'\n"),
      std::string::npos)
      << r.err.substr(r.err.size() - 300);
  const Result five = gantry(fmt::format("check '{}' --max-errors 5", file));
  EXPECT_EQ(count_lines(five.err), 6) << five.err;
  const Result all = gantry(fmt::format("check '{}' --max-errors 0", file));
  EXPECT_EQ(count_lines(all.err), 300);
  fs::remove(file);
}

// The load pass reads every line: an unknown command is an error even where no run goes.
TEST(Check, AnUnknownCommandOnALineNeverReachedIsAnError) {
  const std::string file = part_file("unreached.sbp", "MX, 1\nEND\nQQ, 1\n");
  const Result r = gantry(fmt::format("check '{}'", file));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, file +
                       ":3:1: error: unknown command 'QQ'; see docs/commands.md for the "
                       "commands Gantry knows\n");
  EXPECT_EQ(r.out, "");
  fs::remove(file);
}

// An INPUT the check cannot answer: not "ok"; where it stopped, and how to answer.
TEST(Check, AnUnansweredInputIsNotCalledClean) {
  const std::string file = part_file("input.sbp", "MX, 1\nINPUT \"Depth?\" &depth\nMZ, -&depth\n");
  const Result r = gantry(fmt::format("check '{}'", file));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out.find("ok"), std::string::npos) << r.out;
  EXPECT_EQ(r.out, file +
                       ": NOT fully checked: the check stopped at line 2 of 3 (see above); the "
                       "lines after it were not checked\n");
  EXPECT_NE(r.err.find(file + ":2:1: warning: checking stopped here: the file asks the operator "
                              "for &DEPTH; run from a terminal, or give it with --input "
                              "'&DEPTH=VALUE'"),
            std::string::npos)
      << r.err;
  const Result answered = gantry(fmt::format("check '{}' --input depth=0.25", file));
  EXPECT_EQ(answered.exit_code, 0) << answered.err;
  EXPECT_EQ(answered.out, file + ": ok, 3 lines\n");
  fs::remove(file);
}

// --json: stdout is one JSON object; what the file PRINTs goes to stderr.
TEST(Run, JsonStdoutIsOneObjectWhenTheFilePrints) {
  const std::string file = part_file("prints.sbp", "PRINT \"hello from the part\"\nMX, 1\n");
  const Result r = gantry(fmt::format("run '{}' --json", file));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(json::accept(r.out)) << r.out;
  EXPECT_NE(r.err.find("hello from the part"), std::string::npos) << r.err;
  const Result text = gantry(fmt::format("run '{}'", file));  // without --json, on stdout
  EXPECT_NE(text.out.find("hello from the part"), std::string::npos) << text.out;
  fs::remove(file);
}

// A spent statement budget is an error, located in the loop: the run is refused and nothing
// moves (a warning let `gantry run` loop for ever, deaf to Ctrl-C).
TEST(Run, ASpentStatementBudgetRefusesTheRun) {
  const std::string file =
      part_file("budget.sbp", "&i = 0\nLOOP:\n&i = &i + 1\nIF &i < 30 THEN GOTO LOOP\nMX, 1\n");
  const Result r = gantry(fmt::format("run '{}' --budget 20 --json", file));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["status"], "error");
  EXPECT_EQ(j["steps"]["x"], 0);
  EXPECT_NE(r.err.find(file + ":4:1: error: the check ran 25 statements and the file had not "
                              "ended: it loops here"),
            std::string::npos)
      << r.err;
  const Result check = gantry(fmt::format("check '{}' --budget 20", file));
  EXPECT_EQ(check.exit_code, 1);
  const Result full = gantry(fmt::format("run '{}' --json", file));
  EXPECT_EQ(json::parse(full.out)["check"], "complete");
  fs::remove(file);
}

// SIGTERM while the file is checked (before any motion): gantry stops promptly, says why and
// exits non-zero. The 2 s bound only keeps a broken build from hanging the test.
TEST(Signals, SigtermStopsACheckThatLoops) {
  const std::string file = part_file("forever.sbp", "LOOP:\nMX, 1\nMX, 2\nGOTO LOOP\n");
  for (const char* sub : {"check", "run"}) {
    const fs::path err = fs::temp_directory_path() / fmt::format("gantry_e2e_sig_{}.err", getpid());
    const std::string cmd = fmt::format("exec '{}' {} '{}' --budget 0 2>'{}' >/dev/null",
                                        GANTRY_BIN, sub, file, err.string());
    pid_t pid = 0;
    const char* argv[] = {"/bin/sh", "-c", cmd.c_str(), nullptr};
    ASSERT_EQ(posix_spawn(&pid, "/bin/sh", nullptr, nullptr, const_cast<char**>(argv), environ), 0);
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    kill(pid, SIGTERM);
    int status = 0;
    bool ended = false;
    for (int i = 0; i < 200 && !ended; ++i) {
      ended = waitpid(pid, &status, WNOHANG) == pid;
      if (!ended) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    if (!ended) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
    }
    std::ifstream in(err);
    std::stringstream e;
    e << in.rdbuf();
    EXPECT_TRUE(ended) << sub << " did not stop within 2 s of SIGTERM";
    ASSERT_TRUE(WIFEXITED(status)) << sub << ": killed, not stopped";
    EXPECT_NE(WEXITSTATUS(status), 0) << sub;
    EXPECT_NE(e.str().find("gantry: signal 15: stopping the"), std::string::npos) << e.str();
    EXPECT_NE(e.str().find("error: the check was stopped here (a signal)"), std::string::npos)
        << e.str();
    fs::remove(err);
  }
  fs::remove(file);
}

// Issue 22: a double Ctrl-C (an E-stop) reported fault "none", and a stopped run said it had
// executed the whole file. Each signal count is reported by name, with what ran.
TEST(Signals, AStopAndADoubleSigintAreReportedByNameWithWhatRan) {
  const std::string file = part_file("long_x", "MS, 2\nMX, 10\nMY, 5\n");
  for (const int signals : {1, 2}) {
    const fs::path out = fs::temp_directory_path() / fmt::format("gantry_e2e_int_{}.out", getpid());
    // A live run keeps the machine's state next to its values file: this test's own.
    const std::string cmd = fmt::format(
        "exec '{}' run '{}' --realtime --json --values '{}.values.toml' 2>/dev/null >'{}'",
        GANTRY_BIN, file, out.string(), out.string());
    pid_t pid = 0;
    const char* argv[] = {"/bin/sh", "-c", cmd.c_str(), nullptr};
    ASSERT_EQ(posix_spawn(&pid, "/bin/sh", nullptr, nullptr, const_cast<char**>(argv), environ), 0);
    // After SW's 2 s warning X moves at 2 in/s for 5 s.
    std::this_thread::sleep_for(std::chrono::milliseconds(3000));
    for (int i = 0; i < signals; ++i) {
      kill(pid, SIGINT);
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    int status = 0;
    bool ended = false;
    for (int i = 0; i < 1000 && !ended; ++i) {
      ended = waitpid(pid, &status, WNOHANG) == pid;
      if (!ended) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    if (!ended) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
    }
    EXPECT_TRUE(ended) << signals << " SIGINT: the run did not end within 10 s";
    std::stringstream text;
    text << std::ifstream(out).rdbuf();
    fs::remove(out);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 1);
    const json j = json::parse(text.str());
    EXPECT_EQ(j["status"], "error");
    EXPECT_EQ(j["stopped_by"], signals == 1 ? "stop" : "E-stop") << text.str();
    EXPECT_EQ(j["fault"], signals == 1 ? "none" : "E-stop") << text.str();
    EXPECT_EQ(j["cut"], true);
    EXPECT_EQ(j["lines"], 2);  // in MX, 10: MY never ran
    EXPECT_EQ(j["moves"], 1);
    EXPECT_GT(steps_of(j, 0), 0);
    EXPECT_EQ(steps_of(j, 1), 0);
  }
  fs::remove(file);
}

// Issue 22: PAUSE 1e20 garbled the steps and said "done"; PAUSE 1e12 ran for ever; PAUSE -1
// was skipped. `check` and `run` refuse each, located, and nothing moves.
TEST(BadInput, HugeWaitsAreRefusedBeforeAnythingMoves) {
  struct Case {
    const char* name;
    const char* text;
    const char* says;
  };
  const Case cases[] = {
      {"pause_1e20.sbp", "MX, 0.5\nPAUSE 1e20\nMX, 1\n", ":2:1: error: a wait of 1e+20 s"},
      {"pause_1e12.sbp", "MX, 0.5\nPAUSE 1e12\n", ":2:1: error: a wait of 1000000000000 s"},
      {"pause_minus.sbp", "MX, 0.5\nPAUSE -1\n", ":2:1: error: a wait of -1 s"},
      {"g4.nc", "G20 G1 X0.5 F60\nG4 P100000000000000\nG1 X1\n",
       ":2:1: error: a wait of 100000000000000 s"},
  };
  for (const Case& c : cases) {
    const fs::path p = fs::temp_directory_path() / fmt::format("{}_{}", getpid(), c.name);
    std::ofstream(p) << c.text;
    const Result checked = gantry("check '" + p.string() + "'");
    expect_rejected(checked, p.string() + c.says);
    const Result ran = gantry("run '" + p.string() + "' --json");
    expect_rejected(ran, p.string() + c.says);
    expect_no_motion(ran.out);
    fs::remove(p);
  }
}

// --realtime: an underrun is reported with how late the producer was, never hidden by a
// clock shift (issue 22: the simulated card moved its clock forward instead; 2,749 late
// blocks, the worst 56 ms, ran as "done"). The first file starves the card on purpose: a loop
// with no motion while the moves the planner released play out under a moving tool (a
// profile with a short look-ahead, so some are released). Since issue 26 the feeder holds the
// planner and releases the tail of the path to rest when the job thread is late, so that file
// runs "done" (the tool slows to rest and goes on after the loop). An ordinary file under load
// runs "done" or reports its underrun with its lateness, never a silent clock shift.
TEST(Realtime, ALateProducerIsAReportedUnderrunNeverASilentClockShift) {
  std::stringstream profile;
  profile << std::ifstream(fs::path(GANTRY_SOURCE_DIR) / "settings/default.toml").rdbuf();
  std::string toml = profile.str();
  for (auto [from, to] : {std::pair<std::string, std::string>{"lookahead = 1024", "lookahead = 4"},
                          {"warning_s = 2.0", "warning_s = 0.0"}}) {
    const std::size_t at = toml.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    toml.replace(at, from.size(), to);
  }
  const fs::path settings = fs::temp_directory_path() / fmt::format("gantry_rt_{}.toml", getpid());
  std::ofstream(settings) << toml;
  std::string starving = "MS, 2\n";
  // The planner releases 4 of the 15 moves (0.1 s of motion); the loop takes far longer.
  for (int k = 1; k <= 15; ++k) starving += fmt::format("MX, {}\n", 0.05 * k);
  starving += "&i = 0\nL:\n&i = &i + 1\nIF &i < 5000000 THEN GOTO L\nMX, 3\n";
  const std::string starve = part_file("starve", starving);
  const std::string plain = part_file("plain", "MS, 2\nMX, 0.5\nMY, 0.5\nMX, 0\nMY, 0\n");
  for (const std::string& file : {starve, plain}) {
    const Result r = gantry(fmt::format(  // a live run: its machine state in its own values file
        "run '{}' --realtime --budget 0 --settings '{}' --values '{}.values.toml' --json", file,
        settings.string(), settings.string()));
    const json j = json::parse(r.out);
    if (j["fault"] == "underrun") {  // under load: reported, with its lateness
      EXPECT_EQ(r.exit_code, 1) << file;
      EXPECT_EQ(j["status"], "error") << r.out;
      EXPECT_EQ(j["fault"], "underrun") << r.out;
      ASSERT_FALSE(j["errors"].empty()) << r.out;
      const std::string m = j["errors"][0]["message"];
      EXPECT_NE(m.find("underrun (the producer was "), std::string::npos) << m;
      EXPECT_NE(m.find(" ms late: the card's queue ran dry at "), std::string::npos) << m;
    } else {
      EXPECT_EQ(r.exit_code, 0) << r.err;
      EXPECT_EQ(j["status"], "done") << r.out;
      EXPECT_EQ(j["fault"], "none") << r.out;
    }
  }
  fs::remove(starve);
  fs::remove(plain);
  fs::remove(settings);
}

TEST(Cli, VersionAndHelp) {
  const Result v = gantry("--version");
  EXPECT_EQ(v.exit_code, 0);
  EXPECT_EQ(v.out, "gantry 0.1.0\n");
  const Result h = gantry("--help");
  EXPECT_EQ(h.exit_code, 0);
  for (const char* sub : {"run", "check", "moves"}) EXPECT_NE(h.out.find(sub), std::string::npos);
}

}  // namespace
