// The testable facts of shared/spec/commands.md §8 about the non-cutting commands Gantry
// implements: §8.1 (inventory and syntax), §8.7 (FP), §8.8 (jog and move), §8.9 (ramping, as
// the look-ahead planner shows it), §8.11 (SA, SR, SO), and the VS and Z facts of §8.13 and
// §8.14. Each test names its fact by the spec's number; programs run through an Interpreter
// whose moves are recorded, or planned by a LookAheadPlanner for the ramping facts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "../support/interpreter_fixture.hpp"
#include "../support/memory_files.hpp"
#include "../support/recording_sink.hpp"
#include "../support/vec6_expect.hpp"
#include "../support/where.hpp"
#include "gantry/canon/canon_move.hpp"
#include "gantry/commands/command_table.hpp"
#include "gantry/core/diagnostic.hpp"
#include "gantry/interp/file_system.hpp"
#include "gantry/interp/interpreter.hpp"
#include "gantry/interp/operator_io.hpp"
#include "gantry/interp/persistent_store.hpp"
#include "gantry/lang/script.hpp"
#include "gantry/motion/corner_speed.hpp"
#include "gantry/motion/lookahead_planner.hpp"
#include "gantry/motion/planned_segment.hpp"
#include "gantry/settings/settings.hpp"

namespace gantry {
namespace {

// ---- helpers ----------------------------------------------------------------------------

// A number written in full precision, for program text.
std::string num(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

double deg(double d) {
  return d * M_PI / 180;
}

class CommandFacts : public KeptInterpreterFixture {
 protected:
  CommandFacts() { options.files = &files; }

  // The straight moves only (no Stop, Output or Dwell items).
  std::vector<CanonMove> lines() const {
    std::vector<CanonMove> out;
    for (const CanonMove& m : sink.moves)
      if (m.kind == MoveKind::Line) out.push_back(m);
    return out;
  }
  std::vector<MoveKind> kinds() const {
    std::vector<MoveKind> out;
    for (const CanonMove& m : sink.moves) out.push_back(m.kind);
    return out;
  }
  double variable(std::string_view name) {
    const Value* v = interp().variable(name);
    EXPECT_NE(v, nullptr) << name;
    return v ? v->num() : std::nan("");
  }

  MemoryFiles files;
};

// ---- through the planner (§8.9 and the speed facts of §8.8) -------------------------------

class Collect : public SegmentSink {
 public:
  void segment(const PlannedSegment& s) override {
    if (s.profile.length > 0) segs.push_back(s);  // motion only: no outputs or dwells
  }
  void flush() override {}
  std::vector<PlannedSegment> segs;
};

// Runs `text` through an Interpreter into a LookAheadPlanner; returns the planned motion.
std::vector<PlannedSegment> plan(std::string_view text, const Settings& s) {
  Collect out;
  LookAheadPlanner planner(s, out);
  std::string printed;
  ScriptedIO io(true, {}, &printed);
  PersistentStore store;
  Interpreter interp(s, planner, io, store);
  const std::shared_ptr<const Script> script = Script::from_text(std::string(text), "part.sbp");
  EXPECT_TRUE(script->ok()) << format(script->errors().front());
  try {
    interp.run(script);
  } catch (const GantryError& e) {
    ADD_FAILURE() << format(e.diagnostic());
  }
  return out.segs;
}

// The speed at the junction after segment k (the exit of k is the entry of k + 1).
double junction(const std::vector<PlannedSegment>& segs, size_t k) {
  EXPECT_LT(k + 1, segs.size());
  if (k + 1 >= segs.size()) return std::nan("");
  EXPECT_DOUBLE_EQ(segs[k].profile.v_exit, segs[k + 1].profile.v_entry);
  return segs[k].profile.v_exit;
}

// XY may run at 10 in/s, as in the reference's ramping statements.
Settings fast_xy() {
  Settings s = default_settings();
  s.axes[0].max_speed = s.axes[1].max_speed = 12;
  return s;
}

// MS, v then a 10 in move along X and an 8 in move turning left by `turn_deg`.
std::string corner_program(double v, double turn_deg) {
  return "MS, " + num(v) + "\nM2, 10, 0\nM2, " + num(10 + 8 * std::cos(deg(turn_deg))) + ", " +
         num(8 * std::sin(deg(turn_deg))) + "\n";
}

// ===========================================================================================
// §8.1 Command inventory and syntax
// ===========================================================================================

constexpr std::string_view kSb3QuickIndex[] = {
    "CA", "CC", "CG", "CP", "CR", "FC", "FE", "FG", "FP", "FS", "HA", "HB", "HC", "HE", "HN",
    "HQ", "HR", "HT", "HU", "HW", "J2", "J3", "J4", "J5", "JA", "JB", "JH", "JS", "JX", "JY",
    "JZ", "M2", "M3", "M4", "M5", "MA", "MB", "MD", "MH", "MI", "MN", "MO", "MS", "MX", "MY",
    "MZ", "RA", "RI", "RP", "RR", "RS", "RZ", "SA", "SF", "SI", "SK", "SL", "SM", "SO", "SP",
    "SR", "ST", "SV", "SW", "TC", "TD", "TF", "TH", "TS", "TT", "TU", "UD", "UL", "UN", "UR",
    "UU", "UV", "UZ", "VA", "VB", "VC", "VD", "VI", "VL", "VN", "VO", "VP", "VR", "VS", "VU",
    "Z2", "Z3", "Z4", "Z5", "ZA", "ZB", "ZT", "ZX", "ZY", "ZZ"};

// Fact 1: the SB3 quick index's 100 codes are all known: each has a table entry, and a line
// using one is never an unknown command.
TEST(CommandFactsInventory, Fact1_EveryCodeOfTheSb3QuickIndexIsKnown) {
  ASSERT_EQ(std::size(kSb3QuickIndex), 100u);
  ASSERT_EQ(std::set<std::string_view>(std::begin(kSb3QuickIndex), std::end(kSb3QuickIndex)).size(),
            100u);
  const CommandTable& table = CommandTable::standard();
  for (std::string_view code : kSb3QuickIndex) {
    SCOPED_TRACE(std::string(code));
    const CommandSpec* spec = table.find(code);
    ASSERT_NE(spec, nullptr);
    EXPECT_EQ(spec->code, code);
    const Settings s = default_settings();
    RecordingSink sink;
    std::string printed;  // the help codes print their sheets
    ScriptedIO io(true, {}, &printed);
    PersistentStore store;
    InterpreterOptions options;
    options.dry_run = true;
    options.operator_present = false;
    Interpreter interp(s, sink, io, store, options);
    for (const Diagnostic& d :
         interp.check(Script::from_text(std::string(code) + "\n", "part.sbp")))
      EXPECT_NE(d.message.rfind("unknown command", 0), 0u) << d.message;
  }
}

// Fact 2: SB3's menu groups are Cuts, File, Help, Jog, Move, Record, Settings, Tools,
// Utilities, Values and Zero; each code of the quick index is in the group of its first letter.
TEST(CommandFactsInventory, Fact2_Sb3MenuGroups) {
  const std::map<char, std::string> group_of = {
      {'C', "Cuts"},      {'F', "File"},   {'H', "Help"},     {'J', "Jog"},
      {'M', "Move"},      {'R', "Record"}, {'S', "Settings"}, {'T', "Tools"},
      {'U', "Utilities"}, {'V', "Values"}, {'Z', "Zero"}};
  const CommandTable& table = CommandTable::standard();
  std::set<std::string> groups;
  for (std::string_view code : kSb3QuickIndex) {
    const CommandSpec* spec = table.find(code);
    ASSERT_NE(spec, nullptr) << code;
    EXPECT_EQ(group_name(spec->group), group_of.at(code[0])) << code;
    groups.insert(group_name(spec->group));
  }
  EXPECT_EQ(groups, (std::set<std::string>{"Cuts", "File", "Help", "Jog", "Move", "Record",
                                           "Settings", "Tools", "Utilities", "Values", "Zero"}));
}

// Fact 3: SB3 also documents TI, UI, US and VH.
TEST(CommandFactsInventory, Fact3_Sb3DocumentsTiUiUsVh) {
  const CommandTable& table = CommandTable::standard();
  const std::pair<std::string_view, std::string> codes[] = {
      {"TI", "Tools"}, {"UI", "Utilities"}, {"US", "Utilities"}, {"VH", "Values"}};
  for (const auto& [code, group] : codes) {
    const CommandSpec* spec = table.find(code);
    ASSERT_NE(spec, nullptr) << code;
    EXPECT_EQ(group_name(spec->group), group) << code;
  }
}

// Fact 4: every code of FabMo's index is known.
TEST(CommandFactsInventory, Fact4_EveryCodeOfTheFabMoIndexIsKnown) {
  constexpr std::string_view codes[] = {
      "CA", "CC", "CG", "CP", "CR", "JX", "JY", "JZ", "JA", "JB", "J2", "J3", "J4", "J5",
      "JH", "JS", "MX", "MY", "MZ", "MA", "MB", "MC", "M2", "M3", "M4", "M5", "M6", "MH",
      "MS", "PX", "PY", "PZ", "PA", "PB", "PC", "P2", "P3", "P4", "P5", "P6", "RA", "RI",
      "RP", "RR", "RS", "RZ", "SA", "SO", "SR", "ST", "SV", "VA", "VC", "VD", "VI", "VL",
      "VR", "VS", "ZX", "ZY", "ZZ", "ZA", "ZB", "ZC", "Z2", "Z3", "Z4", "Z5", "Z6", "ZT"};
  EXPECT_EQ(std::set<std::string_view>(std::begin(codes), std::end(codes)).size(), 70u);
  for (std::string_view code : codes) {
    const CommandSpec* spec = CommandTable::standard().find(code);
    ASSERT_NE(spec, nullptr) << code;
    EXPECT_EQ(spec->code, code);
  }
}

// Fact 5: FabMo documents J6, JC, SC and SK in its body.
TEST(CommandFactsInventory, Fact5_FabMoDocumentsJ6JcScSk) {
  const std::pair<std::string_view, std::string> codes[] = {
      {"J6", "Jog"}, {"JC", "Jog"}, {"SC", "Settings"}, {"SK", "Settings"}};
  for (const auto& [code, group] : codes) {
    const CommandSpec* spec = CommandTable::standard().find(code);
    ASSERT_NE(spec, nullptr) << code;
    EXPECT_EQ(group_name(spec->group), group) << code;
  }
}

// Fact 6: parameters are separated by commas, in the order of the abbreviated header.
TEST_F(CommandFacts, Fact6_CommaSeparatedParametersInHeaderOrder) {
  run("M3, 1, 2, 3\nM3 4,5,1\nMS, 3, 1, 20, 30, 40\n");
  const auto m = lines();
  ASSERT_EQ(m.size(), 2u);
  expect_vec(m[0].to, at(1, 2, 3));                      // x, y, z
  expect_vec(m[1].to, at(4, 5, 1));                      // the SB3 form: code, space, parameters
  expect_speeds(state().speeds.move, 3, 1, 20, 30, 40);  // xy, z, a, b, c
}

// Fact 7: `MX, 5.3` moves X to 5.3 (SA), or by 5.3 (SR).
TEST_F(CommandFacts, Fact7_MxWithOneNumberIsAValidLine) {
  run("MX, 5.3\nSR\nMX, 5.3\n");
  const auto m = lines();
  ASSERT_EQ(m.size(), 2u);
  expect_vec(m[0].to, at(5.3));
  expect_vec(m[1].to, at(10.6));
}

// Fact 8: the text after an apostrophe is a comment.
TEST_F(CommandFacts, Fact8_TextAfterAnApostropheIsAComment) {
  run("MX, 1 'to X 1, then MY, 5\n' MX, 2\n'MY, 3\nMY, 2   ' comment, with, commas\n");
  const auto m = lines();
  ASSERT_EQ(m.size(), 2u);
  expect_vec(m[0].to, at(1));
  expect_vec(m[1].to, at(1, 2));
}

// Fact 9: for M2-M5 and J2-J5 a blank coordinate keeps that axis where it is.
TEST_F(CommandFacts, Fact9_BlankCoordinateKeepsTheAxis) {
  const char* codes[] = {"M2", "M3", "M4", "M5", "J2", "J3", "J4", "J5"};
  for (const char* code : codes) {
    SCOPED_TRACE(code);
    const int n = code[1] - '0';
    // From (1, 2, 0.5, 3, 4): every axis but the last given blank, the last moved to 2.5
    // (SA) and then by 1 (SR).
    run("SA\nM5, 1, 2, 0.5, 3, 4\n");
    std::string blanks;
    for (int i = 1; i < n; ++i) blanks += ", ";
    sink.moves.clear();
    run(std::string(code) + blanks + ", 2.5\nSR\n" + code + blanks + ", 1\nSA\n");
    Vec6 expected = at(1, 2, 0.5, 3, 4);
    const auto m = lines();
    ASSERT_EQ(m.size(), 2u);
    expected[n - 1] = 2.5;
    expect_vec(m[0].to, expected);
    expected[n - 1] = 3.5;
    expect_vec(m[1].to, expected);
  }
}

// Fact 10: a parameter may be an expression such as 1.5 * SQR(4.2)/(23-12.23).
TEST_F(CommandFacts, Fact10_ParameterLineAcceptsExpressions) {
  run("MX, 1.5 * SQR(4.2)/(23-12.23)\n");
  ASSERT_EQ(lines().size(), 1u);
  EXPECT_NEAR(lines()[0].to[0], 1.5 * std::sqrt(4.2) / (23 - 12.23), 1e-15);
}

// Fact 11: trigonometric functions take radians (degrees x .017453 = radians).
TEST_F(CommandFacts, Fact11_TrigonometryTakesRadians) {
  run("MX, 2 * SIN(0.5235987755982988)\nMY, 4 * COS(60 * .017453)\nMZ, ATN(1) * 57.2958 / 45\n");
  const auto m = lines();
  ASSERT_EQ(m.size(), 3u);
  EXPECT_NEAR(m[0].to[0], 1.0, 1e-12);                          // sin(30 degrees) = 0.5
  EXPECT_NEAR(m[1].to[1], 4 * std::cos(60 * 0.017453), 1e-12);  // about 2
  EXPECT_NEAR(m[1].to[1], 2.0, 1e-4);
  EXPECT_NEAR(m[2].to[2], 1.0, 1e-6);  // atan(1) = 45 degrees
}

// Fact 12: `12+11/16` as a distance moves to 12.6875.
TEST_F(CommandFacts, Fact12_FractionalDistance) {
  run("MX, 12+11/16\n");
  ASSERT_EQ(lines().size(), 1u);
  EXPECT_DOUBLE_EQ(lines()[0].to[0], 12.6875);
}

// Fact 13: negative fractional values are written -2-7/32 or -(2+7/32).
TEST_F(CommandFacts, Fact13_NegativeFractions) {
  run("MZ, -2-7/32\nMZ, 0\nMZ, -(2+7/32)\nMX, 5\nSR\nMX, -2-7/32\n");
  const auto m = lines();
  ASSERT_EQ(m.size(), 5u);
  EXPECT_DOUBLE_EQ(m[0].to[2], -2.21875);
  EXPECT_DOUBLE_EQ(m[2].to[2], -2.21875);
  EXPECT_DOUBLE_EQ(m[4].to[0], 5 - 2.21875);  // a negative relative move
}

// Fact 14: variables of the session may be used in the parameter line.
TEST_F(CommandFacts, Fact14_VariablesInTheParameterLine) {
  run("&w = 2.5\nMX, &w * 2\nMY, &w\n&w = 1\nMY, &w + 10\n");
  const auto m = lines();
  ASSERT_EQ(m.size(), 3u);
  expect_vec(m[0].to, at(5));
  expect_vec(m[1].to, at(5, 2.5));
  expect_vec(m[2].to, at(5, 11));
}

// Fact 15: variables begin with & and are set as `&var = value`.
TEST_F(CommandFacts, Fact15_VariablesBeginWithAmpersand) {
  run("&Depth = 0.75\nMZ, -&depth\n");
  EXPECT_EQ(variable("DEPTH"), 0.75);
  ASSERT_EQ(lines().size(), 1u);
  EXPECT_DOUBLE_EQ(lines()[0].to[2], -0.75);
}

// Fact 18: MH and JH take no parameters: the line alone starts the move.
TEST_F(CommandFacts, Fact18_MhAndJhTakeNoParameters) {
  EXPECT_TRUE(CommandTable::standard().find("MH")->params.empty());
  EXPECT_TRUE(CommandTable::standard().find("JH")->params.empty());
  run("M2, 3, 4\nMH\n");
  ASSERT_FALSE(lines().empty());
  expect_vec(lines().back().to, at(0, 0, 1));
  const Diagnostic d = run_error("JH, 1\n");
  EXPECT_EQ(where(d.loc), "part.sbp:1:5");
  EXPECT_EQ(d.message, "JH takes 0 parameters; this is parameter 1");
}

// Fact 19: part files may use Windows/DOS (CR LF) or Unix (LF) line endings.
TEST_F(CommandFacts, Fact19_WindowsDosAndUnixLineEndings) {
  run("M2, 1, 0\r\nM2, 1, 2\r\n'note\r\nM2, 3, 4\r\n");
  run("M2, 1, 0\nM2, 1, 2\n'note\nM2, 3, 4\n");
  const auto m = lines();
  ASSERT_EQ(m.size(), 6u);
  for (size_t i = 0; i < 3; ++i) {
    expect_vec(m[i].to, m[i + 3].to);
    EXPECT_EQ(m[i].loc.line, m[i + 3].loc.line);
  }
  expect_vec(m[2].to, at(3, 4));
  EXPECT_EQ(m[2].loc.line, 4);
  EXPECT_EQ(where(run_error("MX, 1\r\nMZ, abc\r\n").loc), "part.sbp:2:5");
  EXPECT_EQ(where(run_error("MX, 1\nMZ, abc\n").loc), "part.sbp:2:5");
}

// ===========================================================================================
// §8.7 File commands: FP
// ===========================================================================================

// Fact 95: FP's parameters are filename, proportion X, Y, Z, repetitions, offset, plunge,
// tab feature, plunge from Z 0.
TEST_F(CommandFacts, Fact95_FpParameterOrder) {
  const CommandSpec* fp = CommandTable::standard().find("FP");
  ASSERT_NE(fp, nullptr);
  std::vector<std::string> names;
  for (const ParamSpec& p : fp->params) names.emplace_back(p.name);
  EXPECT_EQ(names, (std::vector<std::string>{"file name", "proportion X", "proportion Y",
                                             "proportion Z", "repetitions", "offset", "plunge",
                                             "tab feature", "plunge from Z 0"}));
  // Positions 2-6 at work: X x2, Y x3, Z x0.5, twice, 2D offset from (1, 1, 1).
  files.texts["child.sbp"] = "M3, 1, 1, -1\nM3, 0, 0, 0\n";
  run("M3, 1, 1, 1\nFP, child.sbp, 2, 3, 0.5, 2, 2\n");
  const auto m = lines();
  ASSERT_EQ(m.size(), 5u);
  for (size_t pass = 0; pass < 2; ++pass) {
    expect_vec(m[1 + 2 * pass].to, at(3, 4, -0.5));
    expect_vec(m[2 + 2 * pass].to, at(1, 1, 0));
  }
}

// Fact 96: FP's proportions default to 1, 1, 1 and scale the file's cuts.
TEST_F(CommandFacts, Fact96_FpProportionsDefaultToOneAndScale) {
  files.texts["child.sbp"] = "M3, 1, 2, -1\n";
  run("FP, child.sbp\nM3, 0, 0, 0\nFP, child.sbp, 2, 3, 0.5\n");
  const auto m = lines();
  ASSERT_EQ(m.size(), 3u);
  expect_vec(m[0].to, at(1, 2, -1));
  expect_vec(m[2].to, at(2, 6, -0.5));
}

// Fact 97: repetitions (default 1) is how many times the whole file runs, from the current
// location.
TEST_F(CommandFacts, Fact97_FpRepetitionsRunTheWholeFileAgain) {
  files.texts["step.sbp"] = "SR\nMX, 1\nMY, 1\nSA\n";
  run("M2, 2, 2\nFP, step.sbp\n");
  ASSERT_EQ(lines().size(), 3u);
  expect_vec(lines().back().to, at(3, 3));
  sink.moves.clear();
  run("M2, 2, 2\nFP, step.sbp, , , , 3\n");
  const auto m = lines();
  ASSERT_EQ(m.size(), 7u);
  for (int k = 0; k < 3; ++k) {
    expect_vec(m[1 + 2 * k].to, at(3 + k, 2 + k));
    expect_vec(m[2 + 2 * k].to, at(3 + k, 3 + k));
  }
}

// Fact 98: offset 1 runs the file as if the current X, Y, Z were a temporary 0, 0, 0.
TEST_F(CommandFacts, Fact98_FpOffset1IsA3dOffset) {
  files.texts["child.sbp"] = "M3, 1, 1, -0.5\nM3, 0, 0, 0\n";
  run("M3, 5, 5, 1\nFP, child.sbp, , , , , 1\n");
  const auto m = lines();
  ASSERT_EQ(m.size(), 3u);
  expect_vec(m[1].to, at(6, 6, 0.5));
  expect_vec(m[2].to, at(5, 5, 1));
}

// Fact 99: offset 2 offsets X and Y from the current location; Z goes to the file's values.
TEST_F(CommandFacts, Fact99_FpOffset2IsA2dOffset) {
  files.texts["child.sbp"] = "M3, 1, 1, -0.5\nM3, 0, 0, 0\n";
  run("M3, 5, 5, 1\nFP, child.sbp, , , , , 2\n");
  const auto m = lines();
  ASSERT_EQ(m.size(), 3u);
  expect_vec(m[1].to, at(6, 6, -0.5));
  expect_vec(m[2].to, at(5, 5, 0));
}

// Fact 100: offset 0 or blank (the default) runs the file at its own locations.
TEST_F(CommandFacts, Fact100_FpWithoutOffsetUsesTheFilesLocations) {
  files.texts["child.sbp"] = "M3, 1, 1, -0.5\n";
  run("M3, 5, 5, 1\nFP, child.sbp\nM3, 5, 5, 1\nFP, child.sbp, , , , , 0\n");
  const auto m = lines();
  ASSERT_EQ(m.size(), 4u);
  expect_vec(m[1].to, at(1, 1, -0.5));
  expect_vec(m[3].to, at(1, 1, -0.5));
}

// Fact 101: plunge (default 0) is the depth added for each repetition, for template files
// without Z moves: pass k is cut k x plunge below the start (spec §3.2's pass model).
TEST_F(CommandFacts, Fact101_FpPlungeCutsEachRepetitionDeeper) {
  files.texts["square.sbp"] = "M2, 2, 1\nM2, 2, 2\nM2, 1, 2\nM2, 1, 1\n";
  run("M2, 1, 1\nFP, square.sbp, , , , 3\n");  // no plunge: every pass at Z 0
  for (const CanonMove& m : lines()) EXPECT_EQ(m.to[2], 0);
  sink.moves.clear();
  run("FP, square.sbp, , , , 3, , -0.25\n");
  std::vector<double> depths;  // the Z of each XY cut
  for (const CanonMove& m : lines())
    if (m.from[0] != m.to[0] || m.from[1] != m.to[1]) {
      EXPECT_EQ(m.from[2], m.to[2]);
      depths.push_back(m.to[2]);
    }
  ASSERT_EQ(depths.size(), 12u);
  for (size_t i = 0; i < depths.size(); ++i)
    EXPECT_DOUBLE_EQ(depths[i], -0.25 * static_cast<double>(i / 4 + 1)) << "cut " << i;
}

// ===========================================================================================
// §8.8 Jog / Move commands
// ===========================================================================================

// Fact 110: J2-J5 move at the jog speed, M2-M5 at the move speed, in a straight line.
TEST_F(CommandFacts, Fact110_MultiAxisJogsAtJogSpeedMovesAtMoveSpeed) {
  run("M2, 1, 1\nJ2, 2, 2\nM3, 3, 3, 1\nJ3, 4, 4, 0\nM4, 1, 1, 1, 5\nJ4, 2, 2, 0, 6\n"
      "M5, 3, 3, 1, 7, 8\nJ5, 4, 4, 0, 9, 10\n");
  const auto m = lines();
  ASSERT_EQ(m.size(), 8u);
  for (size_t i = 0; i < m.size(); ++i) {
    SCOPED_TRACE(i);
    const bool jog = i % 2 == 1;
    EXPECT_EQ(m[i].speed_class, jog ? SpeedClass::Jog : SpeedClass::Move);
    if (jog)
      expect_speeds(m[i].speeds, 6.0, 3.0, 45, 45, 45);
    else
      expect_speeds(m[i].speeds, 2.0, 0.5, 10, 10, 10);
  }
  // Planned: one straight segment each, cruising at 2 (M2) or 6 (J2) in/s.
  const auto move = plan("M2, 6, 8\n", default_settings());
  ASSERT_EQ(move.size(), 1u);
  expect_vec(move[0].from, at(0, 0));
  expect_vec(move[0].to, at(6, 8));
  EXPECT_DOUBLE_EQ(move[0].profile.length, 10);
  EXPECT_NEAR(move[0].profile.v_cruise, 2.0, 1e-12);
  const auto jog = plan("J2, 6, 8\n", default_settings());
  ASSERT_EQ(jog.size(), 1u);
  EXPECT_NEAR(jog[0].profile.v_cruise, 6.0, 1e-12);
}

// Fact 111: JX-JB move one axis at jog speed, MX-MB at move speed; the target is a location
// (SA) or a distance (SR).
TEST_F(CommandFacts, Fact111_SingleAxisCommandsAbsoluteOrRelative) {
  const std::pair<const char*, int> codes[] = {{"MX", 0}, {"MY", 1}, {"MZ", 2}, {"MA", 3},
                                               {"MB", 4}, {"JX", 0}, {"JY", 1}, {"JZ", 2},
                                               {"JA", 3}, {"JB", 4}};
  for (const auto& [code, axis] : codes) {
    SCOPED_TRACE(code);
    sink.moves.clear();
    run(std::string("SA\n") + code + ", 2\n" + code + ", 1.5\nSR\n" + code + ", 1.5\n" + code +
        ", -0.5\nSA\n");
    const auto m = lines();
    ASSERT_EQ(m.size(), 4u);
    const double expected[] = {2, 1.5, 3, 2.5};
    for (size_t i = 0; i < 4; ++i) {
      Vec6 v = Vec6::Zero();
      v[axis] = expected[i];
      expect_vec(m[i].to, v);
      EXPECT_EQ(m[i].speed_class, code[0] == 'J' ? SpeedClass::Jog : SpeedClass::Move);
    }
    run(std::string(code) + ", 0\n");
  }
}

// Fact 113: JS's parameters are the XY, Z, A and B jog speeds (units/s).
TEST_F(CommandFacts, Fact113_JsSetsXyZABJogSpeeds) {
  run("JS, 5, 2, 30, 40\nJY, 1\nMY, 2\n");
  expect_speeds(state().speeds.jog, 5, 2, 30, 40, 45);
  expect_speeds(state().speeds.move, 2.0, 0.5, 10, 10, 10);
  const auto m = lines();
  ASSERT_EQ(m.size(), 2u);
  expect_speeds(m[0].speeds, 5, 2, 30, 40, 45);
  const auto planned = plan("JS, 5, 2, 30, 40\nJY, 10\n", default_settings());
  ASSERT_EQ(planned.size(), 1u);
  EXPECT_NEAR(planned[0].profile.v_cruise, 5, 1e-12);
}

// Fact 114: FabMo's JS adds the C jog speed as parameter 5.
TEST_F(CommandFacts, Fact114_JsFifthParameterIsTheCJogSpeed) {
  const CommandSpec* js = CommandTable::standard().find("JS");
  ASSERT_EQ(js->params.size(), 5u);
  run("JS, , , , , 60\n");
  expect_speeds(state().speeds.jog, 6.0, 3.0, 45, 45, 60);
}

// Fact 115: MS's parameters are the XY, Z, A and B move speeds; FabMo adds C.
TEST_F(CommandFacts, Fact115_MsSetsXyZABCMoveSpeeds) {
  run("MS, 3, 1, 20, 30\nMX, 1\nJX, 2\n");
  expect_speeds(state().speeds.move, 3, 1, 20, 30, 10);
  expect_speeds(state().speeds.jog, 6.0, 3.0, 45, 45, 45);
  run("MS, , , , , 40\n");
  expect_speeds(state().speeds.move, 3, 1, 20, 30, 40);
  const auto m = lines();
  ASSERT_EQ(m.size(), 2u);
  expect_speeds(m[0].speeds, 3, 1, 20, 30, 10);
  const auto planned = plan("MS, 3\nMX, 10\n", default_settings());
  ASSERT_EQ(planned.size(), 1u);
  EXPECT_NEAR(planned[0].profile.v_cruise, 3, 1e-12);
}

// Fact 116: MS and JS in a file stop the run of moves (the tool ramps down and up again at
// them); VS changes speed without stopping.
TEST_F(CommandFacts, Fact116_MsAndJsPunctuateTheMovesVsDoesNot) {
  run("MX, 5\nMS, 2\nMX, 10\nJS, 6\nVS, 2\nMX, 15\n");
  EXPECT_EQ(kinds(), (std::vector<MoveKind>{MoveKind::Line, MoveKind::Stop, MoveKind::Line,
                                            MoveKind::Stop, MoveKind::Line}));
  // Planned: the same speed before and after; only MS and JS bring the tool down to 0.4.
  const Settings s = default_settings();
  EXPECT_NEAR(junction(plan("MX, 5\nMX, 10\n", s), 0), 2.0, 1e-12);
  EXPECT_NEAR(junction(plan("MX, 5\nVS, 2\nMX, 10\n", s), 0), 2.0, 1e-12);
  EXPECT_NEAR(junction(plan("MX, 5\nMS, 2\nMX, 10\n", s), 0), 0.4, 1e-12);
  EXPECT_NEAR(junction(plan("MX, 5\nJS, 6\nMX, 10\n", s), 0), 0.4, 1e-12);
}

// Fact 117: the speed is the vector speed of the cutter tip.
TEST(CommandFactsRamps, Fact117_SpeedIsTheVectorSpeedOfTheTip) {
  const auto segs = plan("M2, 6, 8\n", default_settings());
  ASSERT_EQ(segs.size(), 1u);
  const Vec6 u = (segs[0].to - segs[0].from) / segs[0].profile.length;
  EXPECT_NEAR(segs[0].profile.v_cruise, 2.0, 1e-12);  // along the path, not per axis
  EXPECT_NEAR(segs[0].profile.v_cruise * u[0], 1.2, 1e-12);
  EXPECT_NEAR(segs[0].profile.v_cruise * u[1], 1.6, 1e-12);
}

// Fact 118: MH / JH raise Z to Safe-Z first when it is below (the profile's 1.0, VC's
// default: AMB-4), leave it when above, then go to X 0, Y 0 at move (MH) or jog (JH) speed.
TEST_F(CommandFacts, Fact118_HomeRaisesZToSafeZOnlyWhenBelow) {
  run("M3, 5, 4, 0.25\nMH\n");
  auto m = lines();
  ASSERT_EQ(m.size(), 3u);
  expect_vec(m[1].to, at(5, 4, 1));
  expect_vec(m[2].to, at(0, 0, 1));
  EXPECT_EQ(m[1].speed_class, SpeedClass::Move);
  EXPECT_EQ(m[2].speed_class, SpeedClass::Move);
  sink.moves.clear();
  run("M3, 5, 4, 2\nJH\n");
  m = lines();
  ASSERT_EQ(m.size(), 2u);
  expect_vec(m[1].to, at(0, 0, 2));
  EXPECT_EQ(m[1].speed_class, SpeedClass::Jog);
  sink.moves.clear();
  run("M3, 5, 4, 0.25\nJH\n");
  m = lines();
  ASSERT_EQ(m.size(), 3u);
  expect_vec(m[1].to, at(5, 4, 1));
  EXPECT_EQ(m[1].speed_class, SpeedClass::Jog);
  expect_vec(m[2].to, at(0, 0, 1));
  EXPECT_EQ(m[2].speed_class, SpeedClass::Jog);
}

// Fact 119: MH / JH ignore relative mode: always to absolute 0, 0.
TEST_F(CommandFacts, Fact119_HomeIgnoresRelativeMode) {
  run("SR\nM3, 3, 2, 1.5\nMH\nM2, 4, 4\nJH\n");
  const auto m = lines();
  ASSERT_EQ(m.size(), 4u);
  expect_vec(m[1].to, at(0, 0, 1.5));
  expect_vec(m[3].to, at(0, 0, 1.5));
  EXPECT_FALSE(state().absolute);  // still relative afterwards
}

// Fact 121: MD's parameters are the length, the angle, then an optional Z change.
TEST_F(CommandFacts, Fact121_MdParameterOrder) {
  run("M2, 5, 5\nMD, 2, 90, 0.5\nMD, 1, 0\n");
  const auto m = lines();
  ASSERT_EQ(m.size(), 3u);
  expect_vec(m[1].to, at(7, 5, 0.5), 1e-12);
  expect_vec(m[2].to, at(7, 6, 0.5), 1e-12);
}

// Fact 122: MD's length starts at the end of the last move, at move speed.
TEST_F(CommandFacts, Fact122_MdStartsAtTheLastMovesEndAtMoveSpeed) {
  run("J3, 3, 4, 0.5\nMD, 1.5, 90\n");
  const auto m = lines();
  ASSERT_EQ(m.size(), 2u);
  expect_vec(m[1].from, at(3, 4, 0.5));
  expect_vec(m[1].to, at(4.5, 4, 0.5), 1e-12);
  EXPECT_EQ(m[1].speed_class, SpeedClass::Move);
  expect_speeds(m[1].speeds, 2.0, 0.5, 10, 10, 10);
}

// Fact 123: MD's absolute angle is ShopBot's: 0 degrees at the top (+Y), clockwise.
TEST_F(CommandFacts, Fact123_MdZeroDegreesIsUp) {
  run("M2, 5, 5\nMD, 1, 0\nMD, 1, 90\nMD, 1, 180\nMD, 1, 270\n");
  const auto m = lines();
  ASSERT_EQ(m.size(), 5u);
  expect_vec(m[1].to, at(5, 6), 1e-12);
  expect_vec(m[2].to, at(6, 6), 1e-12);
  expect_vec(m[3].to, at(6, 5), 1e-12);
  expect_vec(m[4].to, at(5, 5), 1e-12);
}

// Fact 124: `90R` is 90 degrees clockwise of the last move's direction, `L` counter-clockwise;
// with no previous move the R or L is ignored.
TEST_F(CommandFacts, Fact124_MdRelativeAngles) {
  run("MD, 1, 90R\n");  // the first move: 90 from +Y, +X
  expect_vec(lines().back().to, at(1, 0), 1e-12);
  sink.moves.clear();
  run("M2, 5, 5\nMX, 7\nMD, 1, 90R\nMD, 1, 90L\nMD, 2, 45L\n");
  const auto m = lines();
  ASSERT_EQ(m.size(), 5u);
  expect_vec(m[2].to, at(7, 4), 1e-12);  // the last move was +X: 90R is -Y
  expect_vec(m[3].to, at(8, 4), 1e-12);  // the last move was -Y: 90L is +X
  expect_vec(m[4].to, at(8 + std::sqrt(2.0), 4 + std::sqrt(2.0)), 1e-12);  // 45L of +X
}

// Fact 125: MD's clock notation: 3:00 is 90 degrees (+X), 1:30 is 45.
TEST_F(CommandFacts, Fact125_MdClockNotation) {
  run("M2, 5, 5\nMD, 1, 3:00\nMD, 2, 1:30\nMD, 1, 6:00\n");
  const auto m = lines();
  ASSERT_EQ(m.size(), 4u);
  expect_vec(m[1].to, at(6, 5), 1e-12);
  expect_vec(m[2].to, at(6 + std::sqrt(2.0), 5 + std::sqrt(2.0)), 1e-12);
  expect_vec(m[3].to, at(6 + std::sqrt(2.0), 4 + std::sqrt(2.0)), 1e-12);
}

// Fact 126: MD's compass notation: E is +X, SSW is 202.5 degrees, up to three letters.
TEST_F(CommandFacts, Fact126_MdCompassNotation) {
  run("M2, 5, 5\nMD, 1, E\nMD, 2, SSW\nMD, 1, N\n");
  const auto m = lines();
  ASSERT_EQ(m.size(), 4u);
  expect_vec(m[1].to, at(6, 5), 1e-12);
  expect_vec(m[2].to, at(6 + 2 * std::sin(deg(202.5)), 5 + 2 * std::cos(deg(202.5))), 1e-12);
  expect_vec(m[3].to, at(6 + 2 * std::sin(deg(202.5)), 6 + 2 * std::cos(deg(202.5))), 1e-12);
}

// Fact 127: MD's Z change: a plain number is a Z location; U moves up by it, D down by it.
TEST_F(CommandFacts, Fact127_MdZChange) {
  run("M3, 5, 5, 0.5\nMD, 1, 90, 0.25\nMD, 1, 90, 0.5U\nMD, 1, 90, 0.25D\n");
  const auto m = lines();
  ASSERT_EQ(m.size(), 4u);
  EXPECT_NEAR(m[1].to[2], 0.25, 1e-12);
  EXPECT_NEAR(m[2].to[2], 0.75, 1e-12);
  EXPECT_NEAR(m[3].to[2], 0.5, 1e-12);
  expect_vec(m[3].to, at(8, 5, 0.5), 1e-12);
}

// ===========================================================================================
// §8.9 Ramping (SB3), as planned by the look-ahead planner
// ===========================================================================================

// Fact 133: a simple move is a symmetrical trapezoid in time, with linear ramps from the ramp
// speed up to the move speed and back down to the ramp speed.
TEST(CommandFactsRamps, Fact133_ASimpleMoveIsASymmetricalTrapezoid) {
  const auto segs = plan("MX, 10\n", default_settings());
  ASSERT_EQ(segs.size(), 1u);
  const Trapezoid& t = segs[0].profile;
  EXPECT_DOUBLE_EQ(t.v_entry, 0.4);
  EXPECT_DOUBLE_EQ(t.v_cruise, 2.0);
  EXPECT_DOUBLE_EQ(t.v_exit, 0.4);
  EXPECT_EQ(t.jerk, 0);  // linear ramps
  EXPECT_GT(t.t_cruise, 0);
  EXPECT_NEAR(t.t_accel, t.t_decel, 1e-12);
  EXPECT_NEAR(t.s_accel, t.length - t.s_accel - t.s_cruise, 1e-12);
  EXPECT_NEAR(t.speed_at(t.t_accel / 2), 1.2, 1e-9);  // linear: halfway in time, halfway in speed
}

// Fact 135: moves too short to reach speed (a run of short back-and-forth cuts) go at a
// steady ramp speed, without speeding up and slowing down within each.
TEST(CommandFactsRamps, Fact135_ShortBackAndForthMovesRunAtTheRampSpeed) {
  // Led in along Y, so that every reversal is a plain full ramp.
  std::string text = "MY, 1\nSR\n";
  for (int i = 0; i < 10; ++i) text += "MX, 0.1\nMX, -0.1\n";
  const auto segs = plan(text, default_settings());
  ASSERT_EQ(segs.size(), 21u);
  for (size_t k = 1; k < segs.size(); ++k) {
    SCOPED_TRACE(k);
    EXPECT_NEAR(segs[k].profile.v_entry, 0.4, 1e-12);
    EXPECT_NEAR(segs[k].profile.v_cruise, 0.4, 1e-12);
    EXPECT_NEAR(segs[k].profile.v_exit, 0.4, 1e-12);
  }
}

// Fact 136: the ramp rate is the distance over which the speed changes by 2 units/s; a
// smaller rate accelerates faster.
TEST(CommandFactsRamps, Fact136_RampRateIsTheDistanceForTwoUnitsPerSecond) {
  Settings s = default_settings();  // ramp speed 0.4: MS 2.4 is 2 in/s above it
  const auto rate_02 = plan("MS, 2.4\nMX, 10\n", s);
  ASSERT_EQ(rate_02.size(), 1u);
  EXPECT_NEAR(rate_02[0].profile.s_accel, 0.2, 1e-12);
  s.ramps.move_ramp_rate = 0.4;
  const auto rate_04 = plan("MS, 2.4\nMX, 10\n", s);
  ASSERT_EQ(rate_04.size(), 1u);
  EXPECT_NEAR(rate_04[0].profile.s_accel, 0.4, 1e-12);
  EXPECT_GT(rate_02[0].profile.accel, rate_04[0].profile.accel);
  EXPECT_NEAR(rate_02[0].profile.accel, 2 * rate_04[0].profile.accel, 1e-12);
}

// Fact 137: every isolated move ramps at both ends when the move speed is above the ramp
// speed; every jog ramps, also between two jogs in a line.
TEST(CommandFactsRamps, Fact137_IsolatedMovesAndEveryJogRamp) {
  const Settings s = default_settings();
  const auto ramped = plan("MX, 10\n", s);
  ASSERT_EQ(ramped.size(), 1u);
  EXPECT_GT(ramped[0].profile.t_accel, 0);
  EXPECT_GT(ramped[0].profile.t_decel, 0);
  // Move speed 0.3, below the 0.4 ramp speed: no ramp, the whole move at 0.3.
  const auto slow = plan("MS, 0.3\nMX, 10\n", s);
  ASSERT_EQ(slow.size(), 1u);
  EXPECT_DOUBLE_EQ(slow[0].profile.v_entry, 0.3);
  EXPECT_DOUBLE_EQ(slow[0].profile.v_cruise, 0.3);
  EXPECT_DOUBLE_EQ(slow[0].profile.v_exit, 0.3);
  EXPECT_EQ(slow[0].profile.t_accel, 0);
  EXPECT_EQ(slow[0].profile.t_decel, 0);
  // Jogs: ramped at both ends, even straight on from a jog or a move.
  const auto jogs = plan("JX, 5\nJX, 10\nMX, 15\n", s);
  ASSERT_EQ(jogs.size(), 3u);
  EXPECT_DOUBLE_EQ(jogs[0].profile.v_entry, 0.4);
  EXPECT_DOUBLE_EQ(jogs[0].profile.v_cruise, 6.0);
  EXPECT_NEAR(junction(jogs, 0), 0.4, 1e-12);
  EXPECT_NEAR(junction(jogs, 1), 0.4, 1e-12);
  EXPECT_NEAR(junction(plan("MX, 5\nMX, 10\n", s), 0), 2.0, 1e-12);  // moves run straight on
}

// Fact 138: a corner sharper than 43 degrees (0.75 rad) ramps fully down to the ramp speed,
// whatever the speed (here between two long moves).
TEST(CommandFactsRamps, Fact138_CornersOver43DegreesRampFully) {
  for (double v : {1.0, 2.0, 10.0}) {
    SCOPED_TRACE(v);
    EXPECT_NEAR(junction(plan(corner_program(v, 44), fast_xy()), 0), 0.4, 1e-12);
    EXPECT_NEAR(junction(plan(corner_program(v, 90), fast_xy()), 0), 0.4, 1e-12);
  }
}

// Fact 139: at 10 in/s any corner over about 5 degrees slows the tool; at 1 in/s only the
// 43-degree criterion does.
TEST(CommandFactsRamps, Fact139_TheCriterionAngleDependsOnSpeed) {
  const Settings s = fast_xy();
  EXPECT_NEAR(junction(plan(corner_program(10, 4), s), 0), 10, 1e-9);
  const double six = junction(plan(corner_program(10, 6), s), 0);
  EXPECT_LT(six, 10 * 0.65 + 1e-9);
  EXPECT_GT(six, 0.4);
  EXPECT_NEAR(junction(plan(corner_program(1, 6), s), 0), 1, 1e-9);
  EXPECT_NEAR(junction(plan(corner_program(1, 42), s), 0), 1, 1e-9);
  EXPECT_NEAR(junction(plan(corner_program(1, 44), s), 0), 0.4, 1e-12);
}

// Fact 140: the slow corner speed defaults to 65 %: once the slight-ramp criterion is reached
// the tool keeps 65 % of its speed (AMB-23).
TEST(CommandFactsRamps, Fact140_SlowCornerSpeedDefaultsTo65Percent) {
  EXPECT_EQ(default_settings().ramps.slow_corner, 65);
  const double v = junction(plan(corner_program(10, 5.001), fast_xy()), 0);
  EXPECT_NEAR(v, 6.5, 1e-3);
}

// Fact 141: a larger slow corner speed slows the tool less on gentle corners.
TEST(CommandFactsRamps, Fact141_LargerSlowCornerSpeedRampsLess) {
  Settings s = fast_xy();
  const double at65 = junction(plan(corner_program(10, 6), s), 0);
  s.ramps.slow_corner = 80;
  const double at80 = junction(plan(corner_program(10, 6), s), 0);
  EXPECT_GT(at80, at65);
  EXPECT_NEAR(junction(plan(corner_program(10, 5.001), s), 0), 8.0, 1e-3);
}

// Fact 142: the minimum distance to check defaults to 0.15 in; a larger one makes ramping
// more frequent (a turn spread over short moves is seen whole).
TEST(CommandFactsRamps, Fact142_LargerMinimumDistanceRampsMoreOften) {
  EXPECT_EQ(default_settings().ramps.min_distance, 0.15);
  // At 10 in/s (criterion 5 degrees): 10 in along X, 0.4 in at 3 degrees, 5 in at 6 degrees.
  // Each corner turns 3 degrees; over the last inch of path the second turns about 5.9.
  const Vec6 p2 = at(10 + 0.4 * std::cos(deg(3)), 0.4 * std::sin(deg(3)));
  const std::string text = "MS, 10\nM2, 10, 0\nM2, " + num(p2[0]) + ", " + num(p2[1]) + "\nM2, " +
                           num(p2[0] + 5 * std::cos(deg(6))) + ", " +
                           num(p2[1] + 5 * std::sin(deg(6))) + "\n";
  Settings s = fast_xy();
  const auto near = plan(text, s);
  ASSERT_EQ(near.size(), 3u);
  EXPECT_NEAR(junction(near, 1), 10, 1e-9);
  s.ramps.min_distance = 1.0;
  const auto far = plan(text, s);
  ASSERT_EQ(far.size(), 3u);
  EXPECT_LT(junction(far, 1), 6.5 + 1e-9);
  EXPECT_GT(junction(far, 1), 0.4);
}

// Fact 143: XY ramps are decided by the change of direction, Z (A, B) ramps by the change in
// the motor's speed: the same straight XY path ramps fully when Z's speed changes by more
// than the Z ramp speed (0.4), and not when it changes by less.
TEST(CommandFactsRamps, Fact143_ZRampsAreDecidedByZSpeedChange) {
  const Settings s = default_settings();
  // Z from 0 to 0.3 in/s (XY at 2 in/s throughout): no ramp.
  EXPECT_NEAR(junction(plan("M2, 2, 0\nM3, 4, 0, -0.3\n", s), 0), 2.0, 1e-12);
  // Z from 0 to 0.5 in/s: a full ramp to the ramp speed.
  const auto ramped = plan("M2, 2, 0\nM3, 4, 0, -0.5\n", s);
  ASSERT_EQ(ramped.size(), 2u);
  const Vec6 u = (ramped[1].to - ramped[1].from).normalized();
  EXPECT_NEAR(ramped[1].profile.v_cruise * u[2], -0.5, 1e-12);
  EXPECT_NEAR(junction(ramped, 0), 0.4, 1e-12);
}

// Fact 144: when Z (or A, B) would have to move faster than its move speed, the XY speed is
// reduced.
TEST(CommandFactsRamps, Fact144_XySlowsSoThatZAndAKeepTheirSpeeds) {
  const auto segs = plan("M3, 2, 0, -1\nM4, 3, 0, -1, 20\n", default_settings());
  ASSERT_EQ(segs.size(), 2u);
  Vec6 u = (segs[0].to - segs[0].from) / segs[0].profile.length;
  EXPECT_NEAR(segs[0].profile.v_cruise * u[0], 1.0, 1e-12);   // XY 1 in/s instead of 2
  EXPECT_NEAR(segs[0].profile.v_cruise * u[2], -0.5, 1e-12);  // Z at its 0.5 in/s
  u = (segs[1].to - segs[1].from) / segs[1].profile.length;
  EXPECT_NEAR(segs[1].profile.v_cruise * u[0], 0.5, 1e-12);  // XY 0.5 in/s
  EXPECT_NEAR(segs[1].profile.v_cruise * u[3], 10, 1e-12);   // A at its 10 deg/s
}

// Fact 145: with Z ramp speed 0.4, a change of Z speed from 2 to 1.3 in/s (0.7 > 0.4) ramps
// into and out of the move.
TEST(CommandFactsRamps, Fact145_AZSpeedChangeOf07Ramps) {
  const Settings s = default_settings();
  const auto segs = plan("MS, , 2\nM3, 2, 0, 2\nM3, 4, 0, 3.3\n", s);
  ASSERT_EQ(segs.size(), 2u);
  const Vec6 u0 = (segs[0].to - segs[0].from).normalized();
  const Vec6 u1 = (segs[1].to - segs[1].from).normalized();
  EXPECT_NEAR(segs[0].profile.v_cruise * u0[2], 2.0, 1e-12);
  EXPECT_NEAR(segs[1].profile.v_cruise * u1[2], 1.3, 1e-12);
  EXPECT_NEAR(junction(segs, 0), rest_speed(u1, false, s), 1e-12);
  // A change of 0.3 (2 to 1.7 in/s) does not ramp.
  EXPECT_GT(junction(plan("MS, , 2\nM3, 2, 0, 2\nM3, 4, 0, 3.7\n", s), 0), 2.0);
}

// Fact 146: a larger 3D threshold makes 3D ramping less likely (a smaller one, more likely).
TEST(CommandFactsRamps, Fact146_The3dThresholdScalesTheZCriterion) {
  Settings s = default_settings();
  const std::string change_07 = "MS, , 2\nM3, 2, 0, 2\nM3, 4, 0, 3.3\n";
  const std::string change_03 = "MS, , 2\nM3, 2, 0, 2\nM3, 4, 0, 3.7\n";
  const double ramped = junction(plan(change_07, s), 0);
  s.ramps.threshold_3d = 200;  // 0.8 in/s: the 0.7 change passes
  EXPECT_GT(junction(plan(change_07, s), 0), 3 * ramped);
  s.ramps.threshold_3d = 50;  // 0.2 in/s: the 0.3 change ramps
  const auto segs = plan(change_03, s);
  ASSERT_EQ(segs.size(), 2u);
  EXPECT_NEAR(junction(segs, 0), rest_speed((segs[1].to - segs[1].from).normalized(), false, s),
              1e-12);
}

// Fact 147: circles below the small-circle size run at the ramp speed.
TEST(CommandFactsRamps, Fact147_SmallCirclesRunAtTheRampSpeed) {
  const Settings s = default_settings();
  auto top_speed = [&](double diameter) {
    CanonMove c;
    c.kind = MoveKind::Arc;
    c.from = c.to = at(5, 5);
    c.speeds = s.speeds.move;
    c.center_x = 5 + diameter / 2;
    c.center_y = 5;
    c.sweep = 2 * M_PI;
    Collect out;
    LookAheadPlanner p(s, out);
    p.move(c);
    p.flush();
    double top = 0;
    for (const PlannedSegment& seg : out.segs) top = std::max(top, seg.profile.v_cruise);
    return top;
  };
  EXPECT_LE(top_speed(0.2), 0.4 + 1e-12);  // radius 0.1, diameter 0.2: small either way
  EXPECT_GT(top_speed(1.0), 0.4);          // radius 0.5, diameter 1: large either way
}

// ===========================================================================================
// §8.11 Settings commands
// ===========================================================================================

// Fact 155: in absolute mode, going to 3, 7 twice moves only the first time.
TEST_F(CommandFacts, Fact155_SaGoingTwiceToALocationMovesOnce) {
  run("SA\nM2, 3, 7\nM2, 3, 7\n");
  ASSERT_EQ(lines().size(), 1u);
  expect_vec(lines()[0].to, at(3, 7));
  EXPECT_TRUE(state().absolute);
}

// Fact 156: in relative mode, going to 3, 7 twice moves +3, +7 each time.
TEST_F(CommandFacts, Fact156_SrMovesByTheDistanceEachTime) {
  run("SR\nM2, 3, 7\nM2, 3, 7\n");
  const auto m = lines();
  ASSERT_EQ(m.size(), 2u);
  expect_vec(m[0].to, at(3, 7));
  expect_vec(m[1].from, at(3, 7));
  expect_vec(m[1].to, at(6, 14));
  EXPECT_FALSE(state().absolute);
}

// Fact 157: in SR from Z .2, `MZ -.45` reaches Z -.25 and `JZ .45` returns to .2.
TEST_F(CommandFacts, Fact157_SrPlungeAndReturn) {
  run("SA\nM3 1,1,.2\nSR\nMZ -.45\nJZ .45\n");
  const auto m = lines();
  ASSERT_EQ(m.size(), 3u);
  EXPECT_NEAR(m[1].to[2], -0.25, 1e-12);
  EXPECT_EQ(m[1].speed_class, SpeedClass::Move);
  EXPECT_NEAR(m[2].to[2], 0.2, 1e-12);
  EXPECT_EQ(m[2].speed_class, SpeedClass::Jog);
}

// Fact 169: SO's parameters are the switch number and 0 (off) or 1 (on); a blank state turns
// the switch off.
TEST_F(CommandFacts, Fact169_SoSwitchAndStateBlankIsOff) {
  run("SO, 2, 1\nMX, 1\nSO, 2, 0\nSO, 3, 1\nSO, 3\n");
  ASSERT_EQ(sink.moves.size(), 5u);
  const std::pair<int, bool> expected[] = {{2, true}, {2, false}, {3, true}, {3, false}};
  const size_t at_index[] = {0, 2, 3, 4};
  for (size_t i = 0; i < 4; ++i) {
    const CanonMove& m = sink.moves[at_index[i]];
    EXPECT_EQ(m.kind, MoveKind::Output) << i;
    EXPECT_EQ(m.output, expected[i].first) << i;
    EXPECT_EQ(m.output_on, expected[i].second) << i;
  }
  EXPECT_EQ(state().outputs, 0u);
  EXPECT_EQ(where(sink.moves[4].loc), "part.sbp:5:1");
}

// Fact 170: switches are numbered 1-8 (SB3) or 1-12 (FabMo): Gantry takes 1 to 12 (AMB-27).
TEST_F(CommandFacts, Fact170_SoSwitchesOneToTwelve) {
  std::string text;
  for (int n = 1; n <= 12; ++n) text += "SO, " + std::to_string(n) + ", 1\n";
  run(text);
  EXPECT_EQ(state().outputs, 0u);  // all off again at the end of the job
  ASSERT_EQ(sink.moves.size(), 24u);
  for (int n = 1; n <= 12; ++n) {
    EXPECT_EQ(sink.moves[n - 1].output, n);
    EXPECT_TRUE(sink.moves[n - 1].output_on);
  }
  Diagnostic d = run_error("MX, 1\nSO, 13, 1\n");
  EXPECT_EQ(where(d.loc), "part.sbp:2:5");
  EXPECT_EQ(d.message, "output switch 13 does not exist; switches are 1 to 12");
  d = run_error("SO, 0, 1\n");
  EXPECT_EQ(where(d.loc), "part.sbp:1:5");
  EXPECT_EQ(d.message, "output switch 0 does not exist; switches are 1 to 12");
}

// Fact 172: every output switch is off when the control program ends; the state is not kept.
TEST_F(CommandFacts, Fact172_OutputsAreOffWhenTheJobEnds) {
  run("SO, 5, 1\nSO, 7, 1\nMX, 1\n");
  ASSERT_EQ(sink.moves.size(), 5u);
  for (size_t k : {3u, 4u}) {
    EXPECT_EQ(sink.moves[k].kind, MoveKind::Output);
    EXPECT_FALSE(sink.moves[k].output_on);
  }
  EXPECT_EQ(sink.moves[3].output + sink.moves[4].output, 12);
  EXPECT_EQ(state().outputs, 0u);
  // Also when the job ends with an error.
  sink.moves.clear();
  EXPECT_EQ(where(run_error("SO, 1, 1\nQQ\n").loc), "part.sbp:2:1");
  ASSERT_EQ(sink.moves.size(), 2u);
  EXPECT_EQ(sink.moves[1].output, 1);
  EXPECT_FALSE(sink.moves[1].output_on);
  EXPECT_EQ(state().outputs, 0u);
}

// ===========================================================================================
// VS (§8.13) and the Zero commands (§8.14), which the settings commands rely on
// ===========================================================================================

// Fact 228: SB3's VS takes the XY, Z, A, B move speeds, then the XY, Z, A, B jog speeds.
TEST_F(CommandFacts, Fact228_VsTakesMoveThenJogSpeeds) {
  run("VS, 1, .2, 3, 4, 5, 1.5, 30, 40\nMX, 1\nJX, 2\n");
  const auto m = lines();
  ASSERT_EQ(m.size(), 2u);
  expect_speeds(m[0].speeds, 1, 0.2, 3, 4, 10);
  expect_speeds(m[1].speeds, 5, 1.5, 30, 40, 45);
  run("VS, 1, 1, 1, 1, 1, 1, 1, 1, 1\n");  // a ninth is ignored, as SB3 does, with a warning
  ASSERT_EQ(io.warnings().size(), 1u);
  EXPECT_EQ(where(io.warnings()[0].loc), "part.sbp:1:29");
}

// Fact 230: VS changes made in a part file are undone when that file ends.
TEST_F(CommandFacts, Fact230_VsInAFileRevertsWhenTheFileEnds) {
  files.texts["child.sbp"] = "VS, 3, 0.25, , , 7\nMX, 1\nJX, 2\n";
  run("FP, child.sbp\nMX, 3\nJX, 4\n");
  const auto m = lines();
  ASSERT_EQ(m.size(), 4u);
  expect_speeds(m[0].speeds, 3, 0.25, 10, 10, 10);
  expect_speeds(m[1].speeds, 7, 3.0, 45, 45, 45);
  expect_speeds(m[2].speeds, 2.0, 0.5, 10, 10, 10);
  expect_speeds(m[3].speeds, 6.0, 3.0, 45, 45, 45);
}

// Fact 237: Z commands take no parameters.
TEST_F(CommandFacts, Fact237_ZeroCommandsTakeNoParameters) {
  for (const char* code : {"ZX", "ZY", "ZZ", "ZA", "ZB", "ZC", "Z2", "Z3", "Z4", "Z5", "Z6"}) {
    SCOPED_TRACE(code);
    EXPECT_TRUE(CommandTable::standard().find(code)->params.empty());
    const Diagnostic d = run_error(std::string("SA\n") + code + ", 1\n");
    EXPECT_EQ(where(d.loc), "part.sbp:2:5");
    EXPECT_EQ(d.message, std::string(code) + " takes 0 parameters; this is parameter 1");
  }
}

// A Z command zeroes exactly its axes: their working locations (and %(1)-%(5)) read 0, the
// others keep theirs, and the machine does not move.
struct ZeroCase {
  const char* code;
  unsigned axes;  // bit 0 X .. bit 5 C
};

class CommandFactsZero : public CommandFacts {
 protected:
  void expect_zeroes(const ZeroCase& c) {
    SCOPED_TRACE(c.code);
    run("M5, 2, 3, 0.5, 4, 5\n");
    const Vec6 before = state().position;
    const Vec6 table = state().position + state().zero;
    const size_t moves = sink.moves.size();
    run(std::string(c.code) + "\n&x = %(1)\n&y = %(2)\n&z = %(3)\n&a = %(4)\n&b = %(5)\n");
    EXPECT_EQ(sink.moves.size(), moves);  // nothing moved
    for (int i = 0; i < kAxisCount; ++i)
      EXPECT_EQ(state().position[i], (c.axes >> i) & 1 ? 0.0 : before[i]) << kAxisLetters[i];
    expect_vec(state().position + state().zero, table);
    const char* names[] = {"X", "Y", "Z", "A", "B"};
    for (int i = 0; i < 5; ++i)
      EXPECT_DOUBLE_EQ(variable(names[i]), (c.axes >> i) & 1 ? 0.0 : before[i]) << names[i];
  }
};

// Fact 238: Z2 zeroes X, Y; Z3 X, Y, Z; Z4 X, Y, Z, A; Z5 X, Y, Z, A, B; ZX-ZB one axis each.
TEST_F(CommandFactsZero, Fact238_Sb3ZeroCommands) {
  const ZeroCase cases[] = {{"Z2", 0b11},    {"Z3", 0b111},  {"Z4", 0b1111},
                            {"Z5", 0b11111}, {"ZX", 0b1},    {"ZY", 0b10},
                            {"ZZ", 0b100},   {"ZA", 0b1000}, {"ZB", 0b10000}};
  for (const ZeroCase& c : cases) expect_zeroes(c);
}

// Fact 239: FabMo adds ZC (C) and Z6 (all six axes).
TEST_F(CommandFactsZero, Fact239_FabMoZcAndZ6) {
  // No command moves C yet, so C is 0 already: ZC must leave X-B alone, Z6 zero them.
  expect_zeroes({"ZC", 0b100000});
  expect_zeroes({"Z6", 0b111111});
}

// Fact 241: limit checking uses table base coordinates, not working coordinates.
TEST_F(CommandFacts, Fact241_SoftLimitsAreInTableBaseCoordinates) {
  const Diagnostic d = run_error("MX, 20\nZX\nMX, 5\n");  // working 5 is table base 25
  EXPECT_EQ(where(d.loc), "part.sbp:3:1");
  EXPECT_EQ(d.message.rfind("move to X=5.0000 (table base X=25.0000) is outside the soft limits "
                            "0.0000 to 24.0000 in",
                            0),
            0u)
      << d.message;
  ASSERT_EQ(lines().size(), 1u);
  run("MX, -19\n");  // working -19 is table base 1: inside
  expect_vec(lines().back().to, at(1));
  expect_vec(state().position, at(-19));
}

// Fact 244: zeroing changes the working offsets; table base coordinates are never lost.
TEST_F(CommandFacts, Fact244_ZeroingKeepsTableBaseCoordinates) {
  run("M3, 5, 4, 1\nZ3\n&wx = %(1)\n&wz = %(3)\n&bx = %(6)\n&by = %(7)\n&bz = %(8)\n"
      "M3, 1, 1, -0.5\n&bx2 = %(6)\n&bz2 = %(8)\n");
  EXPECT_EQ(variable("WX"), 0);
  EXPECT_EQ(variable("WZ"), 0);
  EXPECT_EQ(variable("BX"), 5);
  EXPECT_EQ(variable("BY"), 4);
  EXPECT_EQ(variable("BZ"), 1);
  EXPECT_EQ(variable("BX2"), 6);
  EXPECT_EQ(variable("BZ2"), 0.5);
  expect_vec(lines().back().to, at(6, 5, 0.5));  // the machine moves in table base coordinates
}

// Fact 258: FabMo's SR example: SA; M3 1,1,.2; SR; MZ -.45; JZ .45; JX 1.5.
TEST_F(CommandFacts, Fact258_FabMoSrExample) {
  run("SA\nM3 1,1,.2\nSR\nMZ -.45\nJZ .45\nJX 1.5\n");
  const auto m = lines();
  ASSERT_EQ(m.size(), 4u);
  expect_vec(m[0].to, at(1, 1, 0.2));
  expect_vec(m[1].to, at(1, 1, -0.25), 1e-12);
  expect_vec(m[2].to, at(1, 1, 0.2), 1e-12);
  expect_vec(m[3].to, at(2.5, 1, 0.2), 1e-12);
  const SpeedClass cls[] = {SpeedClass::Move, SpeedClass::Move, SpeedClass::Jog, SpeedClass::Jog};
  for (size_t i = 0; i < 4; ++i) EXPECT_EQ(m[i].speed_class, cls[i]) << i;
}

}  // namespace
}  // namespace gantry
