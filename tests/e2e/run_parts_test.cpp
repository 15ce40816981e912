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
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <thread>

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path kSource = GANTRY_SOURCE_DIR;

struct Result {
  int exit_code = -1;
  std::string out, err;
};

// Runs the gantry binary with `args`, capturing stdout and stderr.
// Runs gantry in the source folder. Each call gets a fresh config folder, so no run sees
// the values (or $variables) another test's run saved.
Result gantry(const std::string& args) {
  static int calls = 0;
  const fs::path err_file = fs::temp_directory_path() / fmt::format("gantry_e2e_{}.err", getpid());
  const fs::path config =
      fs::temp_directory_path() / fmt::format("gantry_e2e_config_{}_{}", getpid(), ++calls);
  const std::string cmd =
      fmt::format("cd '{}' && XDG_CONFIG_HOME='{}' '{}' {} 2>'{}'", kSource.string(),
                  config.string(), GANTRY_BIN, args, err_file.string());
  Result r;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf{};
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
  const int status = pclose(p);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream e(err_file);
  std::stringstream ss;
  ss << e.rdbuf();
  r.err = ss.str();
  fs::remove_all(config);
  fs::remove(err_file);
  return r;
}

// Steps per unit of the shipped profile, written out here so the test does not trust the code
// under test to convert positions.
constexpr std::array<double, 6> kStepsPerUnit{916.7324, 916.7324, 1018.5916,
                                              13.8889,  13.8889,  13.8889};
constexpr std::array<const char*, 6> kAxes{"x", "y", "z", "a", "b", "c"};

struct Expected {
  std::array<double, 6> last_point;  // the file's last commanded point, units
  int lines, moves;
};

// Every file in parts/ with its last commanded point, worked out by hand from the file.
const std::map<std::string, Expected> kParts = {
    {"demo.sbp", {{12, 9, 1, 0, 0, 0}, 46, 40}},
    {"relative_steps.sbp", {{5.125, 3.333333, 0.25, 0, 0, 0}, 16, 12}},
    {"rotary.sbp", {{3, 3, 1, 45, 0, 0}, 12, 8}},
    {"speeds.sbp", {{7.75, 3.5, 0.25, 0, 0, 0}, 12, 7}},
};

TEST(Parts, EveryPartFileHasExpectations) {
  for (const auto& entry : fs::directory_iterator(kSource / "parts")) {
    if (entry.path().extension() != ".sbp") continue;
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
  EXPECT_NEAR(card_s, j["planned_time_s"].get<double>(), 5e-6 * want.moves);
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
// 10 ticks throughout.
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
}

INSTANTIATE_TEST_SUITE_P(Golden, PinTrace,
                         ::testing::Values("trace_small", "trace_reversal", "trace_output"));

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
  EXPECT_EQ(all.size(), 128u);  // 125 codes, the M0 alias, and FabMo's CN and SU
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
                                           "speeds.sbp"),
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

// The real files in shared/corpus: every line must read. What Gantry deliberately does not
// offer is named in the message, never a plain syntax error.
TEST(Corpus, EveryLineOfEveryFileParses) {
  const fs::path corpus = kSource.parent_path() / "shared" / "corpus";
  if (!fs::exists(corpus)) GTEST_SKIP() << "no shared/corpus beside the repository";
  int files = 0;
  for (const auto& entry : fs::directory_iterator(corpus)) {
    if (entry.path().extension() != ".sbp") continue;
    ++files;
    const Result r = gantry(fmt::format("check '{}'", entry.path().string()));
    std::istringstream err(r.err);
    for (std::string line; std::getline(err, line);) {
      if (line.find(": error: ") == std::string::npos) continue;
      const bool named = line.find("unknown command '") != std::string::npos ||
                         line.find("is not implemented yet in Gantry") != std::string::npos ||
                         line.find("FabMo") != std::string::npos ||
                         line.find("custom cut") != std::string::npos ||
                         line.find("is out of range") != std::string::npos ||
                         // NIST files are in mm (VD): read as inches, they leave the table
                         line.find("outside the soft limits") != std::string::npos ||
                         line.find("empty index [] is not supported") != std::string::npos ||
                         line.find("'dz' is not a value") != std::string::npos;
      EXPECT_TRUE(named) << line;
    }
  }
  EXPECT_EQ(files, 28);
}

// A part file written for one test, in the temporary folder; its absolute path.
std::string part_file(const std::string& name, const std::string& text) {
  const fs::path p = fs::temp_directory_path() / fmt::format("gantry_e2e_{}_{}", getpid(), name);
  std::ofstream(p) << text;
  return p.string();
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

// A check that stopped short (here the budget) lets the run go on, and the report says the
// run went past that line unchecked: never plain "done".
TEST(Run, ReportSaysWhenTheCheckStoppedShort) {
  const std::string file =
      part_file("budget.sbp", "&i = 0\nLOOP:\n&i = &i + 1\nIF &i < 30 THEN GOTO LOOP\nMX, 1\n");
  const Result r = gantry(fmt::format("run '{}' --budget 20 --json", file));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["check"], "partial");
  EXPECT_EQ(j["check_stopped"]["line"], 3);  // the 21st statement
  const Result text = gantry(fmt::format("run '{}' --budget 20", file));
  EXPECT_NE(text.out.find("status     done, but the check before the run stopped at " + file +
                          ":3 and the lines after it ran unchecked\n"),
            std::string::npos)
      << text.out;
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

TEST(Cli, VersionAndHelp) {
  const Result v = gantry("--version");
  EXPECT_EQ(v.exit_code, 0);
  EXPECT_EQ(v.out, "gantry 0.1.0\n");
  const Result h = gantry("--help");
  EXPECT_EQ(h.exit_code, 0);
  for (const char* sub : {"run", "check", "moves"}) EXPECT_NE(h.out.find(sub), std::string::npos);
}

}  // namespace
