// The %(n) table: every number maps to its own snapshot field, gaps are unknown, docs match.
#include <gtest/gtest.h>

#include <cstdio>
#include <ctime>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <variant>

#include "../support/recording_sink.hpp"
#include "gantry/interp/interpreter.hpp"
#include "gantry/interp/operator_io.hpp"
#include "gantry/interp/system_variables.hpp"
#include "gantry/lang/script.hpp"
#include "gantry/machine/controller.hpp"
#include "sim/sim_card.hpp"

namespace gantry {
namespace {

// A snapshot where every field the table reads holds a value no other field holds, so a
// number wired to the wrong field reads something unexpected.
MachineSnapshot distinct_snapshot() {
  MachineSnapshot m;
  m.location << 1.5, 2.5, 3.5, 4.5, 5.5, 6.5;
  m.table_base << 11.25, 12.25, 13.25, 14.25, 15.25, 16.25;
  m.limit_min << -21.5, -22.5, -23.5, -24.5, -25.5, -26.5;
  m.limit_max << 31.5, 32.5, 33.5, 34.5, 35.5, 36.5;
  m.limit_check_axes = 4;
  m.relative = true;
  m.preview = true;
  m.metric = true;
  m.axis_count = 5;
  m.cutter_diameter = 0.125;
  m.safe_z = 0.75;
  m.safe_a = 0.625;
  m.trigger_on_threshold = -0.3125;
  m.trigger_off_threshold = 0.4375;
  m.warning_delay = 3.25;
  m.tab_pull_up = 0.11;
  m.tab_spacing = 4.4;
  m.tab_size = 1.1;
  m.tab_lead = 0.55;
  m.move_speed = {41.0, 42.0, 43.0, 44.0, 45.0};
  m.jog_speed = {51.0, 52.0, 53.0, 54.0, 55.0};
  m.move_ramp = {0.61, 0.62, 0.63, 0.64, 0.65};
  m.jog_ramp = {0.71, 0.72, 0.73, 0.74, 0.75};
  m.steps_per_unit << 901.5, 902.5, 903.5, 904.5, 905.5, 906.5;
  m.resolution_multiplier = {2, 3, 4, 5, 6, 7};
  m.step_interval_divider = 17;
  m.driver_channel_axis = {'B', 'A', 'Z', 'Y', 'X', 'C'};
  // Inputs 1, 2, 4, 7, 11 and 12 closed: no run of four repeats elsewhere.
  for (int n : {1, 2, 4, 7, 11, 12}) m.inputs[n - 1] = true;
  m.input_mode = {0, 1, 2, 3, 4, 0, 1, 2, 3, 4, 1, 2};
  m.input3_mode = 1;
  m.input4_mode = 0;
  m.analog_inputs = {6.25, 7.75};
  // Outputs 1, 3, 8, 10 and 12 on.
  for (int n : {1, 3, 8, 10, 12}) m.outputs[n - 1] = true;
  m.output_mode = {5, 4, 3, 2, 1, 0, 1, 2, 3, 4, 5, 3};
  m.output4_auto_mode = -3;
  m.torch_height_control = true;
  m.indexer_on = true;
  m.spindle_rpm = 17999.6;
  m.software_version = "9.8.7";
  m.firmware_version = 312;
  m.controller_voltage = 4.8;
  m.controller_temperature = 38.5;
  m.file_path = "/parts/Sign.sbp";
  m.file_offset << 61.5, 62.5, 63.5, 0, 0, 0;
  m.file_proportion << 0.66, 0.67, 0.68, 1, 1, 1;
  m.elapsed_seconds = 130.9;
  m.now = {2024, 3, 7, 9, 5, 2};
  return m;
}

using Expected = std::variant<double, std::string>;

// What each %(n) must read from distinct_snapshot(), written out by hand from the handbook.
std::map<int, Expected> expected_values() {
  std::map<int, Expected> e;
  const double loc[] = {1.5, 2.5, 3.5, 4.5, 5.5};
  const double base[] = {11.25, 12.25, 13.25, 14.25, 15.25};
  for (int i = 0; i < 5; ++i) {
    e[1 + i] = loc[i];
    e[6 + i] = base[i];
  }
  const double lo[] = {-21.5, -22.5, -23.5, -24.5, -25.5};
  const double hi[] = {31.5, 32.5, 33.5, 34.5, 35.5};
  for (int i = 0; i < 5; ++i) {
    e[11 + 2 * i] = lo[i];
    e[12 + 2 * i] = hi[i];
  }
  e[21] = 1.0;
  e[22] = 1.0;
  e[23] = 0.125;
  e[24] = 3.25;
  e[25] = 1.0;
  e[27] = 5.0;
  e[28] = 0.75;
  e[29] = 0.625;
  e[30] = 4.0;
  const double wu[] = {901.5, 902.5, 903.5, 904.5, 905.5};
  for (int i = 0; i < 5; ++i) e[31 + i] = wu[i];
  const char* channels[] = {"B", "A", "Z", "Y", "X"};
  for (int i = 0; i < 5; ++i) e[36 + i] = std::string(channels[i]);
  e[41] = 0.11;
  e[42] = 4.4;
  e[43] = 1.1;
  e[44] = 0.55;
  e[46] = 1.0;
  e[47] = 0.0;
  e[48] = std::string("9.8.7");
  e[49] = 312.0;
  const double in_on[] = {1, 1, 0, 1, 0, 0, 1, 0, 0, 0, 1, 1};
  for (int i = 0; i < 8; ++i) e[51 + i] = in_on[i];
  e[60] = std::string("/parts/Sign.sbp");
  e[61] = 61.5;
  e[62] = 62.5;
  e[63] = 63.5;
  e[66] = 0.66;
  e[67] = 0.67;
  e[68] = 0.68;
  // X and Y share the XY group's value.
  const double move[] = {41, 41, 42, 43, 44};
  const double jog[] = {51, 51, 52, 53, 54};
  const double move_ramp[] = {0.61, 0.61, 0.62, 0.63, 0.64};
  const double jog_ramp[] = {0.71, 0.71, 0.72, 0.73, 0.74};
  for (int i = 0; i < 5; ++i) {
    e[71 + i] = move[i];
    e[76 + i] = jog[i];
    e[81 + i] = move_ramp[i];
    e[86 + i] = jog_ramp[i];
  }
  const double in_mode[] = {0, 1, 2, 3, 4, 0, 1, 2, 3, 4, 1, 2};
  for (int i = 0; i < 8; ++i) e[91 + i] = in_mode[i];
  e[99] = 1.0;
  e[100] = 1.0 + 4.0 + 128.0;  // outputs 1, 3, 8
  const double out_on[] = {1, 0, 1, 0, 0, 0, 0, 1, 0, 1, 0, 1};
  for (int i = 0; i < 8; ++i) e[101 + i] = out_on[i];
  e[109] = -3.0;
  const double out_mode[] = {5, 4, 3, 2, 1, 0, 1, 2, 3, 4, 5, 3};
  for (int i = 0; i < 12; ++i) e[111 + i] = out_mode[i];
  e[123] = 1.0;
  e[124] = 6.25;
  e[125] = 7.75;
  for (int i = 0; i < 4; ++i) e[126 + i] = in_on[8 + i];
  e[130] = 130.0;
  for (int i = 0; i < 4; ++i) e[131 + i] = in_mode[8 + i];
  e[135] = 2.0 + 8.0;  // outputs 10 and 12
  for (int i = 0; i < 4; ++i) e[136 + i] = out_on[8 + i];
  e[141] = -0.3125;
  e[142] = 0.4375;
  e[144] = 6.5;
  e[145] = 16.25;
  e[146] = std::string("03/07/2024");
  e[147] = std::string("09:05:02");
  e[150] = 17.0;
  const double multiplier[] = {2, 3, 4, 5, 6, 7};
  for (int i = 0; i < 6; ++i) e[151 + i] = multiplier[i];
  e[158] = 4.8;
  e[159] = 38.5;
  e[161] = std::string("18000");
  return e;
}

// The numbers the handbook lists, written out independently of the table.
std::set<int> handbook_numbers() {
  std::set<int> s;
  auto range = [&](int a, int b) {
    for (int n = a; n <= b; ++n) s.insert(n);
  };
  range(1, 25);
  range(27, 44);
  range(46, 49);
  range(51, 58);
  range(60, 63);
  range(66, 68);
  range(71, 109);
  range(111, 139);
  range(141, 142);
  range(144, 147);
  range(150, 156);
  range(158, 159);
  s.insert(161);
  return s;
}

TEST(SystemVariablesTest, TableListsExactlyTheHandbookNumbersInOrder) {
  std::set<int> in_table;
  int previous = 0;
  for (const SystemVariableInfo& v : system_variable_table()) {
    EXPECT_GT(v.number, previous) << "table unsorted or duplicated at %(" << v.number << ")";
    previous = v.number;
    in_table.insert(v.number);
    EXPECT_FALSE(v.name.empty()) << v.number;
    EXPECT_FALSE(v.unit.empty()) << v.number;
    EXPECT_FALSE(v.meaning.empty()) << v.number;
  }
  EXPECT_EQ(in_table, handbook_numbers());
  EXPECT_EQ(system_variable_table().size(), handbook_numbers().size());
}

TEST(SystemVariablesTest, EveryNumberReadsItsOwnField) {
  const MachineSnapshot m = distinct_snapshot();
  const std::map<int, Expected> expected = expected_values();
  std::set<int> expected_numbers;
  for (const auto& [n, value] : expected) expected_numbers.insert(n);
  ASSERT_EQ(expected_numbers, handbook_numbers()) << "test expectations incomplete";

  for (const auto& [n, want] : expected) {
    SCOPED_TRACE("%(" + std::to_string(n) + ")");
    const std::optional<Value> got = read_system_variable(n, m);
    ASSERT_TRUE(got.has_value());
    if (const double* d = std::get_if<double>(&want)) {
      ASSERT_TRUE(got->is_number());
      EXPECT_DOUBLE_EQ(got->num(), *d);
    } else {
      ASSERT_TRUE(got->is_string());
      EXPECT_EQ(got->str(), std::get<std::string>(want));
    }
  }
}

// The numbers whose value differs between two snapshots.
std::set<int> changed(const MachineSnapshot& a, const MachineSnapshot& b) {
  std::set<int> out;
  for (const SystemVariableInfo& v : system_variable_table()) {
    const Value x = *read_system_variable(v.number, a);
    const Value y = *read_system_variable(v.number, b);
    const bool same =
        x.is_number() ? y.is_number() && x.num() == y.num() : y.is_string() && x.str() == y.str();
    if (!same) out.insert(v.number);
  }
  return out;
}

// Flags and switches hold only 0 or 1, so distinct values cannot tell them apart: flip each
// alone and check that exactly its own numbers (and the output bytes) change.
TEST(SystemVariablesTest, EachFlagAndSwitchMovesOnlyItsOwnNumbers) {
  const MachineSnapshot base;
  struct Case {
    std::string what;
    void (*flip)(MachineSnapshot&);
    std::set<int> numbers;
  };
  const Case cases[] = {
      {"relative", [](MachineSnapshot& m) { m.relative = true; }, {21}},
      {"preview", [](MachineSnapshot& m) { m.preview = true; }, {22}},
      {"metric", [](MachineSnapshot& m) { m.metric = true; }, {25}},
      {"input3_mode", [](MachineSnapshot& m) { m.input3_mode = 1; }, {46}},
      {"input4_mode", [](MachineSnapshot& m) { m.input4_mode = 1; }, {47}},
      {"torch", [](MachineSnapshot& m) { m.torch_height_control = true; }, {99}},
      {"indexer", [](MachineSnapshot& m) { m.indexer_on = true; }, {123}},
  };
  for (const Case& c : cases) {
    MachineSnapshot m = base;
    c.flip(m);
    EXPECT_EQ(changed(base, m), c.numbers) << c.what;
  }
  for (int n = 1; n <= 12; ++n) {
    MachineSnapshot in = base;
    in.inputs[n - 1] = true;
    EXPECT_EQ(changed(base, in), std::set<int>{n <= 8 ? 50 + n : 117 + n}) << "input " << n;
    MachineSnapshot out = base;
    out.outputs[n - 1] = true;
    const std::set<int> want = n <= 8 ? std::set<int>{100, 100 + n} : std::set<int>{135, 127 + n};
    EXPECT_EQ(changed(base, out), want) << "output " << n;
    EXPECT_DOUBLE_EQ(read_system_variable(n <= 8 ? 100 : 135, out)->num(),
                     1 << (n <= 8 ? n - 1 : n - 9))
        << "output " << n;
  }
}

TEST(SystemVariablesTest, TypesFollowTheTable) {
  const MachineSnapshot m;
  for (const SystemVariableInfo& v : system_variable_table()) {
    SCOPED_TRACE("%(" + std::to_string(v.number) + ")");
    const std::optional<Value> got = read_system_variable(v.number, m);
    ASSERT_TRUE(got.has_value());
    EXPECT_EQ(got->is_string(), v.is_string);
  }
  for (int n : {36, 37, 38, 39, 40, 48, 60, 146, 147, 161}) {
    const SystemVariableInfo* info = find_system_variable(n);
    ASSERT_NE(info, nullptr) << n;
    EXPECT_TRUE(info->is_string) << n;
  }
}

TEST(SystemVariablesTest, UnknownNumbersReadNothing) {
  const MachineSnapshot m;
  for (int n : {0,   -1,  -23, 26,  45,  50,  59,  64,  65,  69,  70,
                110, 140, 143, 148, 149, 157, 160, 162, 169, 170, 1000}) {
    EXPECT_FALSE(read_system_variable(n, m).has_value()) << n;
    EXPECT_EQ(find_system_variable(n), nullptr) << n;
  }
  // Every number from well below to well above the table: defined exactly when listed.
  const std::set<int> listed = handbook_numbers();
  for (int n = -5; n <= 200; ++n) {
    EXPECT_EQ(read_system_variable(n, m).has_value(), listed.count(n) == 1) << n;
  }
}

TEST(SystemVariablesTest, FindReturnsTheRow) {
  const SystemVariableInfo* info = find_system_variable(23);
  ASSERT_NE(info, nullptr);
  EXPECT_EQ(info->number, 23);
  EXPECT_EQ(info->name, "Cutter Dia");
  // %(20) is the B high limit, not the cutter diameter the VC text claims.
  ASSERT_NE(find_system_variable(20), nullptr);
  EXPECT_EQ(find_system_variable(20)->name, "Max Table Limit B");
}

TEST(SystemVariablesTest, DefaultsAreTheShippedProfile) {
  const MachineSnapshot m;
  EXPECT_DOUBLE_EQ(read_system_variable(23, m)->num(), 0.25);  // VC cutter default
  EXPECT_DOUBLE_EQ(read_system_variable(21, m)->num(), 0.0);   // absolute
  EXPECT_DOUBLE_EQ(read_system_variable(25, m)->num(), 0.0);   // inches
  EXPECT_DOUBLE_EQ(read_system_variable(100, m)->num(), 0.0);  // all outputs off
  EXPECT_EQ(read_system_variable(36, m)->str(), "X");
  EXPECT_EQ(read_system_variable(146, m)->str(), "01/01/2000");
  EXPECT_EQ(read_system_variable(147, m)->str(), "00:00:00");
  EXPECT_EQ(read_system_variable(161, m)->str(), "0");
  EXPECT_EQ(read_system_variable(48, m)->str(), GANTRY_VERSION);
}

TEST(SystemVariablesTest, DocsPageMatchesTheTable) {
  const std::string path = std::string(GANTRY_SOURCE_DIR) + "/docs/system_variables.md";
  std::ifstream in(path, std::ios::binary);
  ASSERT_TRUE(in) << "cannot read " << path;
  std::ostringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), system_variables_markdown())
      << "docs/system_variables.md is stale: regenerate it from system_variables_markdown()";
}

TEST(SystemVariablesTest, MarkdownHasOneRowPerVariable) {
  const std::string md = system_variables_markdown();
  for (const SystemVariableInfo& v : system_variable_table()) {
    EXPECT_NE(md.find("\n| " + std::to_string(v.number) + " | "), std::string::npos) << v.number;
  }
}

// ---- Live: what a running file has set reaches %(n) ---------------------------------------

// Runs part files through an interpreter whose motion goes nowhere, and reads &variables.
class LiveSystemVariables : public ::testing::Test {
 protected:
  void run(const std::string& text) {
    auto script = Script::from_text(text, "part.sbp");
    ASSERT_TRUE(script->ok()) << format(script->errors().front());
    interp().run(script);
  }
  std::vector<Diagnostic> check(const std::string& text) {
    return interp().check(Script::from_text(text, "part.sbp"));
  }
  Value var(const std::string& name) {
    const Value* v = interp().variable(name);
    EXPECT_NE(v, nullptr) << name;
    return v ? *v : Value();
  }
  Interpreter& interp() {
    if (!interp_) interp_.emplace(settings, sink, io, store, InterpreterOptions{});
    return *interp_;
  }
  Settings settings = default_settings();
  RecordingSink sink;
  ScriptedIO io{true, {}};
  PersistentStore store;
  std::optional<Interpreter> interp_;
};

TEST_F(LiveSystemVariables, OutputSwitchesReadAsTheFileSetThem) {
  run("&before = %(101)\n"
      "SO, 1, 1\n&one = %(101)\n"
      "SO, 3, 1\nSO, 8, 1\nSO, 10, 1\nSO, 12, 1\n"
      "&byte = %(100)\n&upper = %(135)\n&three = %(103)\n&eight = %(108)\n&two = %(102)\n"
      "&ten = %(137)\n&eleven = %(138)\n&twelve = %(139)\n&nine = %(136)\n"
      "SO, 1, 0\n&off = %(101)\n&byte_after = %(100)\n");
  EXPECT_EQ(var("BEFORE").num(), 0);
  EXPECT_EQ(var("ONE").num(), 1);
  EXPECT_EQ(var("BYTE").num(), 1 + 4 + 128);  // outputs 1, 3 and 8: bits 0, 2 and 7
  EXPECT_EQ(var("UPPER").num(), 2 + 8);       // outputs 10 and 12: bits 1 and 3
  EXPECT_EQ(var("THREE").num(), 1);
  EXPECT_EQ(var("EIGHT").num(), 1);
  EXPECT_EQ(var("TWO").num(), 0);
  EXPECT_EQ(var("NINE").num(), 0);
  EXPECT_EQ(var("TEN").num(), 1);
  EXPECT_EQ(var("ELEVEN").num(), 0);
  EXPECT_EQ(var("TWELVE").num(), 1);
  EXPECT_EQ(var("OFF").num(), 0);
  EXPECT_EQ(var("BYTE_AFTER").num(), 4 + 128);
}

TEST_F(LiveSystemVariables, EveryOutputSwitchReadsItsOwnNumber) {
  for (int n = 1; n <= 12; ++n) {
    interp_.reset();
    const int own = n <= 8 ? 100 + n : 127 + n;
    std::string text = "SO, " + std::to_string(n) + ", 1\n";
    for (int k : {101, 102, 103, 104, 105, 106, 107, 108, 136, 137, 138, 139, 100, 135})
      text += "&V" + std::to_string(k) + " = %(" + std::to_string(k) + ")\n";
    run(text);
    for (int k : {101, 102, 103, 104, 105, 106, 107, 108, 136, 137, 138, 139})
      EXPECT_EQ(var("V" + std::to_string(k)).num(), k == own ? 1 : 0)
          << "SO " << n << ", %(" << k << ")";
    EXPECT_EQ(var("V100").num(), n <= 8 ? 1 << (n - 1) : 0) << "SO " << n;
    EXPECT_EQ(var("V135").num(), n > 8 ? 1 << (n - 9) : 0) << "SO " << n;
  }
}

TEST_F(LiveSystemVariables, MotorsOffReadsEveryOutputOff) {
  run("SO, 2, 1\nSO, 9, 1\n&on = %(100) + %(135)\nMO\n&off = %(100) + %(135)\n");
  EXPECT_EQ(var("ON").num(), 2 + 1);
  EXPECT_EQ(var("OFF").num(), 0);
}

TEST_F(LiveSystemVariables, SwitchFourModeIsTheLastSoFourMinusN) {
  run("&first = %(109)\nSO, 4, -4\n&plain = %(109)\nSO, 4, -2\n&auto = %(109)\n");
  EXPECT_EQ(var("FIRST").num(), -1);  // the shipped profile: on while a run moves the tool
  EXPECT_EQ(var("PLAIN").num(), -4);
  EXPECT_EQ(var("AUTO").num(), -2);
}

TEST_F(LiveSystemVariables, OutputModesFollowVn) {
  // VN's fields 15-26 are the modes of outputs 1-12.
  run("&before = %(111)\nVN, , , , , , , , , , , , , , , 5, 4, , , , , , , , , , 3\n"
      "&one = %(111)\n&two = %(112)\n&three = %(113)\n&twelve = %(122)\n");
  EXPECT_EQ(var("BEFORE").num(), 0);
  EXPECT_EQ(var("ONE").num(), 5);
  EXPECT_EQ(var("TWO").num(), 4);
  EXPECT_EQ(var("THREE").num(), 0);
  EXPECT_EQ(var("TWELVE").num(), 3);
}

// The system clock's local date and time, as %(146) and %(147) print them.
std::pair<std::string, std::string> clock_text() {
  const std::time_t now = std::time(nullptr);
  std::tm t{};
  localtime_r(&now, &t);
  char date[16], time[16];
  std::strftime(date, sizeof date, "%m/%d/%Y", &t);
  std::strftime(time, sizeof time, "%H:%M:%S", &t);
  return {date, time};
}

TEST_F(LiveSystemVariables, DateAndTimeAreTheLocalClockNow) {
  const auto before = clock_text();
  run("&d = %(146)\n&t = %(147)\n");
  const auto after = clock_text();
  const std::string d = var("D").str(), t = var("T").str();
  EXPECT_TRUE(d == before.first || d == after.first) << d;
  // Between the two readings (a run over midnight reads either side of it).
  EXPECT_TRUE((before.second <= t && t <= after.second) || after.second < before.second) << t;
  EXPECT_NE(d, "01/01/2000");
}

TEST_F(LiveSystemVariables, ElapsedTimeIsZeroInACheckWithNoMachine) {
  const std::vector<Diagnostic> found =
      check("MZ, 1\n&t = %(130)\nIF &t <> 0 THEN GOTO wrong\nEND\nwrong:\nMX, 99\n");
  EXPECT_TRUE(found.empty()) << format(found.front());  // MX 99 would leave the table
}

// On the simulated card the machine's clock is virtual time: MZ, 1.5 at the move speed of
// 0.5 in/s lasts 3 s and a little (its ramps start at 0.4 in/s), so %(130) reads 3 after it.
TEST(LiveElapsedTime, IsTheMachineTimeOfTheMotionPlayedBeforeTheLine) {
  const Settings settings = default_settings();
  SimCard card(settings, false, {});
  ScriptedIO io{true, {}};
  PersistentStore store;
  Controller c{settings, card, io, store};
  const Outcome o = c.run(
      Script::from_text("&start = %(130)\nMZ, 1.5\n&t = %(130)\nJX, &t\nJY, &start\n", "part.sbp"));
  ASSERT_TRUE(o) << o.reason;
  c.wait();
  EXPECT_EQ(c.state(), MachineState::Idle) << c.status().message;
  EXPECT_DOUBLE_EQ(c.modal().position[0], 3);
  EXPECT_DOUBLE_EQ(c.modal().position[1], 0);
}

}  // namespace
}  // namespace gantry
