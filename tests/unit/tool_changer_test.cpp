// The spindle and the tool changer on the simulated card (docs/hardware.md, "Spindle" and
// "Tool changer"): M3/M4/M5 on the profile's outputs, the spin-up and spin-down waits and the
// at-speed input seen on the pin trace; the speed as a frequency; the rack's change (M6, C9)
// with the drawbar switched over the slots, the tool measured on the sensor and its length in
// the tool table G43 reads; refused changes that move nothing.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include "pin_trace.hpp"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "gantry/interp/operator_io.hpp"
#include "gantry/lang/script.hpp"
#include "gantry/machine/controller.hpp"
#include "sim/sim_card.hpp"

namespace gantry {
namespace {

namespace fs = std::filesystem;
using test::channel_pulses;
using test::read_trace;
using Trace = std::vector<std::pair<std::int64_t, std::uint32_t>>;

constexpr int kX = 0, kY = 1, kZ = 2;
constexpr int kRunBit = 18, kReverseBit = 19, kDrawbarBit = 22;  // outputs 1, 2 and 5
constexpr int kAtSpeedBit = 9;                                   // input 5, wired below

std::string trace_path(const std::string& name) {
  return (fs::temp_directory_path() /
          ("gantry_tools_" + name + "_" + std::to_string(getpid()) + ".trace"))
      .string();
}

// A machine for one run: run() plays a file, keeps what the tests read, then closes the
// card so that its pin trace is all on disk.
struct Machine {
  Machine(Settings s, SimWorld world, const std::string& name)
      : settings(std::move(s)),
        path(trace_path(name)),
        card(std::make_unique<SimCard>(settings, false, std::move(world), path)),
        c(std::make_unique<Controller>(settings, *card, io, store)) {}
  ~Machine() { fs::remove(path); }
  Settings settings;
  std::string path;
  ScriptedIO io{true, {}};
  PersistentStore store;
  std::unique_ptr<SimCard> card;
  std::unique_ptr<Controller> c;
  ControllerStatus status;
  ModalState modal;
  std::optional<Diagnostic> stopped;  // why the run stopped short
  double time_s = 0;                  // the card's clock at the end

  // Runs `text` as `name` (part.nc: G-code) to its end, however it ends; the outcome of its
  // check.
  Outcome play(const std::string& text, const std::string& name = "part.nc") {
    const Outcome o = c->run(Script::from_text(text, name));
    c->wait();
    status = c->status();
    modal = c->modal();
    stopped = c->summary().error;
    time_s = card->time_s();
    c.reset();
    card.reset();  // the trace file closes
    return o;
  }
  void run(const std::string& text, const std::string& name = "part.nc") {
    const Outcome o = play(text, name);
    ASSERT_TRUE(o) << o.reason << (o.errors.empty() ? "" : " " + o.errors[0].message);
  }
  std::string error() const { return stopped ? format(*stopped) : ""; }
  Trace trace() const { return read_trace(path); }
  double pacer() const { return settings.card.pacer_hz(); }
  // Whole steps of `units` on `axis`.
  std::int64_t steps(double units, int axis) const {
    return std::llround(units * settings.axes[axis].steps_per_unit);
  }
};

// The ticks at which bit `bit` of the output word goes high (rise) or low.
std::vector<std::int64_t> edges(const Trace& t, int bit, bool rise) {
  std::vector<std::int64_t> out;
  bool level = false;
  for (const auto& [tick, w] : t) {
    const bool now = (w >> bit & 1u) != 0;
    if (now != level && now == rise) out.push_back(tick);
    level = now;
  }
  return out;
}

// The axis's position, in steps, after the pulses before `tick`.
std::int64_t steps_at(const Trace& t, const Settings& s, int axis, std::int64_t tick) {
  std::int64_t n = 0;
  for (const test::TracePulse& p :
       channel_pulses(t, s.pins[axis].step_bit, s.pins[axis].dir_bit, s.pins[axis].invert_dir))
    if (p.tick < tick) n += p.positive ? 1 : -1;
  return n;
}

// The first step pulse of `axis` at or after `tick` (-1: none).
std::int64_t first_step_after(const Trace& t, const Settings& s, int axis, std::int64_t tick) {
  for (const test::TracePulse& p :
       channel_pulses(t, s.pins[axis].step_bit, s.pins[axis].dir_bit, s.pins[axis].invert_dir))
    if (p.tick >= tick) return p.tick;
  return -1;
}

Settings spindle_profile() {
  Settings s = default_settings();
  s.outputs.charge_pump_bit = -1;  // a quieter trace
  s.machine.warning_s = 0;
  s.spindle.reverse_output = 2;
  s.spindle.spin_up_s = 1.5;
  s.spindle.spin_down_s = 2.5;
  return s;
}

// ---- the spindle

// M4 sets the direction line before the spindle runs; M3 after it stops the spindle, waits its
// spin-down, clears the direction and starts again; each start waits spin_up_s before X moves.
TEST(Spindle, DirectionWiringReversesThroughAStopWithTheWaitsOnThePinTrace) {
  Machine m(spindle_profile(), {}, "direction");
  m.run("G20\nM4\nG1 X0.5 F60\nM3\nG1 X1\nM5\nG1 X0\n");
  ASSERT_EQ(m.error(), "");
  const Trace t = m.trace();
  const auto run_on = edges(t, kRunBit, true), run_off = edges(t, kRunBit, false);
  const auto rev_on = edges(t, kReverseBit, true), rev_off = edges(t, kReverseBit, false);
  ASSERT_EQ(run_on.size(), 2u);
  ASSERT_EQ(run_off.size(), 2u);
  ASSERT_EQ(rev_on.size(), 1u);
  ASSERT_EQ(rev_off.size(), 1u);
  const auto up = static_cast<std::int64_t>(1.5 * m.pacer());
  const auto down = static_cast<std::int64_t>(2.5 * m.pacer());
  EXPECT_LE(rev_on[0], run_on[0]);  // counter-clockwise selected before it runs
  // M4: no X step within the spin-up.
  EXPECT_GE(first_step_after(t, m.settings, kX, run_on[0]), run_on[0] + up);
  // M3: it stops, spins down, the direction clears, then it starts and spins up.
  EXPECT_GE(rev_off[0], run_off[0] + down);
  EXPECT_LE(rev_off[0], run_on[1]);
  EXPECT_GE(run_on[1], run_off[0] + down);
  EXPECT_GE(first_step_after(t, m.settings, kX, run_on[1]), run_on[1] + up);
  EXPECT_EQ(steps_at(t, m.settings, kX, run_on[1]), m.steps(0.5, kX));  // the first cut ended
  // M5: X waits for the spin-down.
  EXPECT_GE(first_step_after(t, m.settings, kX, run_off[1]), run_off[1] + down);
  EXPECT_EQ(m.status.steps[kX], 0);
}

// Run wiring (a VFD's FWD and REV terminals): M4 drives the reverse output alone.
TEST(Spindle, RunWiringNeverDrivesBothOutputs) {
  Settings s = spindle_profile();
  s.spindle.reverse_wiring = SpindleSettings::ReverseWiring::Run;
  Machine m(s, {}, "run");
  m.run("G20\nM3\nG1 X0.2 F60\nM4\nG1 X0.4\nM5\n");
  ASSERT_EQ(m.error(), "");
  const Trace t = m.trace();
  for (const auto& [tick, w] : t)
    EXPECT_FALSE((w >> kRunBit & 1u) && (w >> kReverseBit & 1u)) << "both on at tick " << tick;
  EXPECT_EQ(edges(t, kRunBit, true).size(), 1u);
  EXPECT_EQ(edges(t, kReverseBit, true).size(), 1u);
  EXPECT_GE(edges(t, kReverseBit, true)[0],
            edges(t, kRunBit, false)[0] + static_cast<std::int64_t>(2.5 * m.pacer()));
}

TEST(Spindle, M4WithoutAReverseOutputIsRefusedBeforeAnythingMoves) {
  Settings s = spindle_profile();
  s.spindle.reverse_output = 0;
  Machine m(s, {}, "no_reverse");
  const Outcome o = m.play("G20\nG1 X1 F60\nM4\n");
  ASSERT_FALSE(o);
  ASSERT_FALSE(o.errors.empty());
  EXPECT_EQ(format(o.errors[0]),
            "part.nc:3:1: error: M4 (spindle counter-clockwise) is not available: this "
            "machine's profile names no output for it (spindle.reverse_output), so output switch "
            "1 runs the spindle one way only; use M3");
  EXPECT_EQ(m.status.steps[kX], 0);
}

// The at-speed input: the machine waits for it after the start; SO 1 (C6's way) too.
TEST(Spindle, AtSpeedInputHoldsTheMotionUntilItCloses) {
  Settings s = spindle_profile();
  s.spindle.spin_up_s = 0;
  s.spindle.at_speed_input = 5;
  s.inputs.switch_bits[4] = kAtSpeedBit;
  SimWorld w;
  w.input_events.push_back({3.0, kAtSpeedBit, true});  // the drive is at speed at 3 s
  Machine m(s, w, "at_speed");
  m.run("SO, 1, 1\nMX, 0.5\n", "part.sbp");
  ASSERT_EQ(m.error(), "");
  const Trace t = m.trace();
  const std::int64_t first = first_step_after(t, m.settings, kX, 0);
  EXPECT_GE(first, static_cast<std::int64_t>(3.0 * m.pacer()));
  EXPECT_LE(first, static_cast<std::int64_t>(3.05 * m.pacer()));  // within a 10 ms wait step
  EXPECT_EQ(m.status.steps[kX], m.steps(0.5, kX));
}

TEST(Spindle, AtSpeedTimeoutStopsTheJobWithAMessageBeforeTheCut) {
  Settings s = spindle_profile();
  s.spindle.spin_up_s = 0;
  s.spindle.at_speed_input = 5;
  s.spindle.at_speed_timeout_s = 2;
  s.inputs.switch_bits[4] = kAtSpeedBit;
  Machine m(s, {}, "timeout");  // the input never closes
  m.run("G20\nM3 S12000\nG1 X1 F60\n");
  EXPECT_EQ(m.error(),
            "part.nc:2:1: error: the spindle did not reach its speed: input switch 5 "
            "(spindle.at_speed_input) did not close within 2 s (spindle.at_speed_timeout_s); "
            "the job stops here. Check the drive (a fault, a speed it cannot reach) and its "
            "wiring");
  EXPECT_EQ(m.status.steps[kX], 0);
  EXPECT_GE(m.time_s, 2.0);
  const Trace t = m.trace();
  EXPECT_EQ(edges(t, kRunBit, false).size(), 1u);  // the spindle is off again
}

// Frequency mode: S (and TR) as a square wave of rpm / max_rpm x max_hz.
TEST(Spindle, FrequencyModeCarriesTheSpeedAsAPulseRate) {
  Settings s = spindle_profile();
  s.spindle.spin_up_s = 0;
  s.spindle.spin_down_s = 0;
  s.spindle.pwm_bit = 30;
  s.spindle.speed_mode = SpindleSettings::SpeedMode::Frequency;
  s.spindle.max_hz = 2000;
  s.spindle.max_rpm = 24000;
  Machine m(s, {}, "frequency");
  m.run("G20\nS6000 M3\nG4 P1\nS18000\nG4 P1\nM5\n");
  ASSERT_EQ(m.error(), "");
  const auto rises = edges(m.trace(), 30, true);
  // 6000 RPM: 500 Hz for a second, then 18000: 1500 Hz for a second.
  const auto one_s = static_cast<std::int64_t>(m.pacer());
  ASSERT_FALSE(rises.empty());
  const std::int64_t t0 = rises.front();
  std::vector<std::int64_t> first, second;
  for (std::int64_t r : rises) (r < t0 + one_s ? first : second).push_back(r);
  ASSERT_GE(first.size(), 2u);
  ASSERT_GE(second.size(), 2u);
  EXPECT_EQ(first[1] - first[0], std::llround(m.pacer() / 500));
  EXPECT_EQ(second.back() - second[second.size() - 2], std::llround(m.pacer() / 1500));
  EXPECT_NEAR(static_cast<double>(first.size()), 500, 2);
  // The rate is whole ticks a period: 133 at 1500 Hz, 1503.8 periods a second.
  EXPECT_NEAR(static_cast<double>(second.size()),
              m.pacer() / static_cast<double>(std::llround(m.pacer() / 1500)), 3);
}

// The D/A word (spindle.dac_bits, 4 bits here: 0 to 15 for 0 to max_rpm) on the pin trace:
// initial_rpm's word before the spindle first runs, then S's, and 0 after the run.
TEST(Spindle, DacBitsCarryTheSpeedAsAWordFromTheInitialRpmOn) {
  Settings s = spindle_profile();
  s.spindle.spin_up_s = 0;
  s.spindle.spin_down_s = 0;
  s.spindle.max_rpm = 24000;
  s.spindle.dac_bits = {6, 7, 14, 15};
  s.spindle.initial_rpm = 12000;
  Machine m(s, {}, "dac");
  m.run("G20\nM3\nG4 P0.5\nS6000\nG4 P0.5\nS18000\nG4 P0.5\nM5\n");
  ASSERT_EQ(m.error(), "");
  auto word = [](std::uint32_t w) {
    return static_cast<int>((w >> 6 & 1u) | (w >> 7 & 1u) << 1 | (w >> 14 & 1u) << 2 |
                            (w >> 15 & 1u) << 3);
  };
  const Trace t = m.trace();
  std::vector<int> words;  // each new word, in order
  for (const auto& [tick, w] : t)
    if (words.empty() || words.back() != word(w)) words.push_back(word(w));
  // 12000 -> 7.5 -> 8; 6000 -> 3.75 -> 4; 18000 -> 11.25 -> 11; the run's end: 0.
  EXPECT_EQ(words, (std::vector<int>{0, 8, 4, 11, 0}));
  const auto run_on = edges(t, kRunBit, true);
  ASSERT_EQ(run_on.size(), 1u);
  for (const auto& [tick, w] : t) {  // the speed stood before the spindle started
    if (tick == run_on[0]) {
      EXPECT_EQ(word(w), 8);
    }
  }
}

// ---- the tool changer

constexpr double kSensorX = 10, kSensorY = 16, kSensorTop = -1.25, kSensorZero = -2.0;

Settings rack_profile() {
  Settings s = spindle_profile();
  s.spindle.spin_up_s = 0;
  s.spindle.spin_down_s = 1;
  ToolChangerSettings& tc = s.toolchanger;
  tc.slots = {{2, 16}, {4, 16}, {6, 16}};
  tc.slot_z = -1;
  tc.clear_z = 2;
  tc.release_output = 5;
  tc.release_s = 0.5;
  tc.sensor_input = 1;  // the probe's input
  tc.sensor_x = kSensorX;
  tc.sensor_y = kSensorY;
  tc.sensor_start_z = 0.5;
  tc.sensor_min_z = -3;
  tc.sensor_zero_z = kSensorZero;
  tc.sensor_speed = 0.5;
  return s;
}

// The sensor: closed at or below its top over its place, nowhere else.
SimWorld rack_world(double top = kSensorTop) {
  SimWorld w;
  w.probe_surface = [top](double x, double y) {
    return std::hypot(x - kSensorX, y - kSensorY) < 0.05 ? top : -1e9;
  };
  return w;
}

// Where the axes were (steps) at each rise and fall of the drawbar output.
std::vector<std::array<std::int64_t, 3>> drawbar_places(const Machine& m, bool rise) {
  const Trace t = m.trace();
  std::vector<std::array<std::int64_t, 3>> out;
  for (std::int64_t tick : edges(t, kDrawbarBit, rise))
    out.push_back({steps_at(t, m.settings, kX, tick), steps_at(t, m.settings, kY, tick),
                   steps_at(t, m.settings, kZ, tick)});
  return out;
}

// Tool 1 let go at its slot's Z over slot 1, then tool 3 picked over slot 3: the drawbar
// opens down in slot 1, and up over slot 3 before going down; it closes up over slot 1 and
// down in slot 3.
void expect_drawbar_swapped_tool_1_for_3(const Machine& m) {
  auto at = [&](double x, double y, double z) {
    return std::array<std::int64_t, 3>{m.steps(x, kX), m.steps(y, kY), m.steps(z, kZ)};
  };
  EXPECT_EQ(drawbar_places(m, true),
            (std::vector<std::array<std::int64_t, 3>>{at(2, 16, -1), at(6, 16, 2)}));
  EXPECT_EQ(drawbar_places(m, false),
            (std::vector<std::array<std::int64_t, 3>>{at(2, 16, 2), at(6, 16, -1)}));
}

TEST(ToolChanger, M6SwapsToolsOnTheRackMeasuresTheNewOneAndG43UsesIt) {
  Machine m(rack_profile(), rack_world(), "m6");
  m.run("G20\nG0 X1 Y1\nM61 Q1\nS12000 M3\nT3 M6\nG43\nG0 Z0\n");
  ASSERT_EQ(m.error(), "");
  expect_drawbar_swapped_tool_1_for_3(m);
  // The spindle was stopped, and spun down, before the drawbar first opened.
  const Trace t = m.trace();
  ASSERT_EQ(edges(t, kRunBit, false).size(), 1u);
  EXPECT_GE(edges(t, kDrawbarBit, true)[0],
            edges(t, kRunBit, false)[0] + static_cast<std::int64_t>(m.pacer()));
  // Measured: the first step at or below the sensor's top, less sensor_zero_z.
  const ModalState st = m.modal;
  EXPECT_EQ(st.gcode.tool, 3);
  const ToolEntry* e = st.gcode.tools.find(3);
  ASSERT_NE(e, nullptr);
  const double spu = m.settings.axes[kZ].steps_per_unit;
  const double trip = std::floor(kSensorTop * spu) / spu;
  EXPECT_NEAR(e->length(), trip - kSensorZero, 1e-9);
  // Back over X1 Y1, then G43's Z0 puts the tip (the length below the spindle) at working 0.
  const ControllerStatus s = m.status;
  EXPECT_EQ(s.steps[kX], m.steps(1, kX));
  EXPECT_EQ(s.steps[kY], m.steps(1, kY));
  EXPECT_EQ(s.steps[kZ], std::llround((trip - kSensorZero) * spu));
}

TEST(ToolChanger, TheMeasuredLengthIsWrittenToTheToolTableFile) {
  const fs::path table =
      fs::temp_directory_path() / ("gantry_tools_table_" + std::to_string(getpid()) + ".tbl");
  {
    std::ofstream out(table);
    out << "T1 P1 D0.25 Z+0.5 ;quarter inch\nT2 P2 D0.125 ;eighth\n";
  }
  Settings s = rack_profile();
  s.tool_table_path = table.string();
  Machine m(s, rack_world(), "table");
  m.run("G20\nT2 M6\n");
  ASSERT_EQ(m.error(), "");
  std::stringstream text;
  text << std::ifstream(table).rdbuf();
  fs::remove(table);
  const double spu = s.axes[kZ].steps_per_unit;
  const double length = std::floor(kSensorTop * spu) / spu - kSensorZero;
  EXPECT_EQ(text.str().substr(0, 26), "T1 P1 D0.25 Z+0.5 ;quarter");  // the other line as it was
  EXPECT_NE(text.str().find("T2 P2 D+0.125 Z+" + fmt::format("{}", length)), std::string::npos)
      << text.str();
}

// C9, OpenSBP's change, on the rack: &Tool's tool, and Z's zero follows the new length less
// the old one's (tool 1's set to 0.25 by G10 L1 between the changes; the simulated sensor
// measures every tool alike), so that working Z stays the tip's height.
TEST(ToolChanger, C9ChangesOnTheRackAndWorkingZFollowsTheNewLength) {
  Machine m(rack_profile(), rack_world(), "c9");
  m.run("&Tool = 1\nC9\nG10 L1 P1 Z0.25\n&Tool = 2\nC9\nJZ, 0\n", "part.sbp");
  ASSERT_EQ(m.error(), "");
  const ModalState st = m.modal;
  EXPECT_EQ(st.gcode.tool, 2);
  EXPECT_EQ(drawbar_places(m, true).size(), 3u);  // pick 1, put 1 back, pick 2
  const double spu = m.settings.axes[kZ].steps_per_unit;
  const double length = std::floor(kSensorTop * spu) / spu - kSensorZero;
  EXPECT_NEAR(st.zero[kZ], length - 0.25, 1e-9);
  EXPECT_EQ(m.status.steps[kZ], std::llround((length - 0.25) * spu));  // working Z 0
  const ControllerStatus s = m.status;
  EXPECT_EQ(s.steps[kX], 0);  // back where the changes began
  EXPECT_EQ(s.steps[kY], 0);
}

TEST(ToolChanger, AToolWithNoSlotIsRefusedAndNothingMoves) {
  Machine m(rack_profile(), rack_world(), "no_slot");
  const Outcome o = m.play("G20\nG0 X1\nT4 M6\n");
  ASSERT_FALSE(o);
  ASSERT_FALSE(o.errors.empty());
  EXPECT_EQ(format(o.errors[0]),
            "part.nc:3:4: error: tool 4 has no slot in the tool rack (toolchanger.slots lists 3 "
            "slots: tools 1 to 3); nothing moved");
  EXPECT_EQ(m.status.steps[kX], 0);
}

TEST(ToolChanger, ASensorThatNeverClosesStopsTheJobAndTheLengthIsKept) {
  Machine m(rack_profile(), rack_world(-10), "no_trip");  // below the probe's travel
  m.run("G20\nT2 M6\nG0 X5\n");
  EXPECT_EQ(m.error(),
            "part.nc:2:4: error: tool 2 did not close the tool-length sensor (input switch 1) "
            "between Z 0.5 and Z -3 (toolchanger.sensor_start_z, sensor_min_z): is the tool in "
            "the spindle, and the sensor wired? The job stops with the tool at the sensor's "
            "lowest point; its length was not changed");
  const ControllerStatus s = m.status;
  EXPECT_EQ(s.steps[kX], m.steps(kSensorX, kX));  // G0 X5 never ran
  EXPECT_EQ(s.steps[kZ], m.steps(-3, kZ));
  EXPECT_EQ(m.modal.gcode.tools.find(2)->length(), 0);
}

// Without a rack the change stays manual (the operator is asked), and a sensor still measures.
TEST(ToolChanger, WithoutARackTheOperatorChangesAndTheSensorMeasures) {
  Settings s = rack_profile();
  s.toolchanger.slots.clear();
  Machine m(s, rack_world(), "manual");
  m.run("G20\nT2 M6\n");
  ASSERT_EQ(m.error(), "");
  EXPECT_TRUE(edges(m.trace(), kDrawbarBit, true).empty());
  const double spu = s.axes[kZ].steps_per_unit;
  EXPECT_NEAR(m.modal.gcode.tools.find(2)->length(),
              std::floor(kSensorTop * spu) / spu - kSensorZero, 1e-9);
}

// ---- measuring without a change: G37, WinCNC's M37 and M37.1

// The lowest Z the trace reaches (steps), and X and Y (steps) at that moment.
std::array<std::int64_t, 3> lowest_z(const Trace& t, const Settings& s) {
  std::int64_t z = 0, low = 0, tick = 0;
  for (const test::TracePulse& p :
       channel_pulses(t, s.pins[kZ].step_bit, s.pins[kZ].dir_bit, s.pins[kZ].invert_dir)) {
    z += p.positive ? 1 : -1;
    if (z < low) {
      low = z;
      tick = p.tick + 1;
    }
  }
  return {steps_at(t, s, kX, tick), steps_at(t, s, kY, tick), low};
}

// G37 probes the tool in the spindle on the sensor (no drawbar, no change), writes its length
// to the tool table and comes back over where it began; G43 in the next block applies it.
TEST(ToolMeasure, G37MeasuresTheToolInTheSpindleAndG43AfterItAppliesTheLength) {
  Machine m(rack_profile(), rack_world(), "g37");
  m.run("G20\nG0 X1 Y1\nM61 Q2\nG37\nG43\nG0 Z0\n");
  ASSERT_EQ(m.error(), "");
  const Trace t = m.trace();
  EXPECT_TRUE(edges(t, kDrawbarBit, true).empty());
  const double spu = m.settings.axes[kZ].steps_per_unit;
  const double trip = std::floor(kSensorTop * spu) / spu;
  // The probe went down over the sensor, past its top only by its ramp down after the trip.
  const std::array<std::int64_t, 3> low = lowest_z(t, m.settings);
  EXPECT_EQ(low[0], m.steps(kSensorX, kX));
  EXPECT_EQ(low[1], m.steps(kSensorY, kY));
  EXPECT_LE(low[2], std::llround(trip * spu));
  EXPECT_GT(low[2], std::llround(trip * spu) - m.steps(0.05, kZ));
  const ToolEntry* e = m.modal.gcode.tools.find(2);
  ASSERT_NE(e, nullptr);
  EXPECT_NEAR(e->length(), trip - kSensorZero, 1e-9);
  EXPECT_EQ(m.modal.gcode.tool, 2);
  // Back over X1 Y1; G0 Z0 with G43 on puts the spindle the length above working 0.
  EXPECT_EQ(m.status.steps[kX], m.steps(1, kX));
  EXPECT_EQ(m.status.steps[kY], m.steps(1, kY));
  EXPECT_EQ(m.status.steps[kZ], std::llround((trip - kSensorZero) * spu));
}

// Without G43 the length measured is in the table only: Z0 is the spindle's own Z 0.
TEST(ToolMeasure, G37WithoutG43LeavesTheOffsetOff) {
  Machine m(rack_profile(), rack_world(), "g37_no_g43");
  m.run("G20\nM61 Q2\nG37\nG0 Z0\n");
  ASSERT_EQ(m.error(), "");
  EXPECT_EQ(m.status.steps[kZ], 0);
  EXPECT_NE(m.modal.gcode.tools.find(2)->length(), 0);
}

TEST(ToolMeasure, G37IsRefusedWithoutASensorOrAToolAndNothingMoves) {
  Settings s = rack_profile();
  s.toolchanger = ToolChangerSettings{};
  Machine m(s, rack_world(), "g37_none");
  Outcome o = m.play("G20\nG0 X1\nM61 Q1\nG37\n");
  ASSERT_FALSE(o);
  ASSERT_FALSE(o.errors.empty());
  EXPECT_EQ(format(o.errors[0]),
            "part.nc:4:1: error: G37 measures the tool in the spindle on the tool-length sensor, "
            "and this machine's profile has none (toolchanger.sensor_input); give its length "
            "with G10 L1 (or M37 Z in the WinCNC dialect)");
  EXPECT_EQ(m.status.steps[kX], 0);
  Machine empty(rack_profile(), rack_world(), "g37_empty");
  o = empty.play("G20\nG0 X1\nG37\n");
  ASSERT_FALSE(o);
  ASSERT_FALSE(o.errors.empty());
  EXPECT_EQ(format(o.errors[0]),
            "part.nc:3:1: error: G37: the spindle holds no tool (tool 0); load one with M6 T, or "
            "say which it holds with M61 Q; nothing moved");
  EXPECT_EQ(empty.status.steps[kX], 0);
  Machine axes(rack_profile(), rack_world(), "g37_axes");
  o = axes.play("G20\nM61 Q1\nG37 Z1\n");
  ASSERT_FALSE(o);
  EXPECT_EQ(format(o.errors[0]),
            "part.nc:3:5: error: G37 takes no axis words (Z): the sensor's place and its descent "
            "are the profile's [toolchanger]; put a move on a line of its own");
}

Settings wincnc_rack() {
  Settings s = rack_profile();
  s.gcode_dialect = GcodeDialect::WinCNC;
  return s;
}

// WinCNC's M37 T on a rack: M6's sequence (the drawbar at the same places), the sensor's
// measure, and G43 on at once (M37 turns it on).
TEST(ToolMeasure, WincncM37TOnARackRunsTheChangeMeasuresAndTurnsG43On) {
  Machine m(wincnc_rack(), rack_world(), "m37_rack");
  m.run("G20\nG0 X1 Y1\nL110 T1\nM37 T3\nG0 Z0\n");
  ASSERT_EQ(m.error(), "");
  expect_drawbar_swapped_tool_1_for_3(m);
  const double spu = m.settings.axes[kZ].steps_per_unit;
  const double length = std::floor(kSensorTop * spu) / spu - kSensorZero;
  EXPECT_EQ(m.modal.gcode.tool, 3);
  EXPECT_NEAR(m.modal.gcode.tools.find(3)->length(), length, 1e-9);
  EXPECT_NEAR(m.modal.gcode.tool_length, length, 1e-9);
  EXPECT_EQ(m.status.steps[kX], m.steps(1, kX));
  EXPECT_EQ(m.status.steps[kY], m.steps(1, kY));
  EXPECT_EQ(m.status.steps[kZ], std::llround(length * spu));
}

TEST(ToolMeasure, WincncM37TZOnARackIsRefusedAndNothingMoves) {
  Machine m(wincnc_rack(), rack_world(), "m37_z");
  const Outcome o = m.play("G20\nG0 X1\nL110 T1\nM37 T3 Z0\n");
  ASSERT_FALSE(o);
  ASSERT_FALSE(o.errors.empty());
  EXPECT_EQ(format(o.errors[0]),
            "part.nc:4:8: error: M37 T3 Z: the rack changes the tool first, and its tip is then "
            "at no known point; give O (its length), or neither (the sensor measures it), or "
            "change with M6 T3, bring the tip to a known point and M37 Z there");
  EXPECT_EQ(m.status.steps[kX], 0);
}

// M37.1 calibrates the sensor: with a tool M37 Z0 measured at the table, probed on the
// sensor, the sensor's zero becomes the one that measures that same length; G37 then gives
// it. M37.1 Z states the sensor's height instead.
TEST(ToolMeasure, WincncM37Point1CalibratesTheSensorForG37) {
  Machine m(wincnc_rack(), rack_world(), "m37_1");
  m.run("G20\nL110 T2\nG0 Z-0.75\nM37 Z0\nM37.1\nG49\nG37\nG0 X3\n");
  ASSERT_EQ(m.error(), "");
  EXPECT_NEAR(m.modal.gcode.tools.find(2)->length(), -0.75, 1e-9);
  EXPECT_NEAR(m.modal.gcode.tool_length, -0.75, 1e-9);  // G37 turned it on again
  Machine z(wincnc_rack(), rack_world(), "m37_1z");
  z.run("G20\nL110 T2\nM37.1 Z-0.5\nG37\n");
  ASSERT_EQ(z.error(), "");
  const double spu = z.settings.axes[kZ].steps_per_unit;
  EXPECT_NEAR(z.modal.gcode.tools.find(2)->length(), std::floor(kSensorTop * spu) / spu + 0.5,
              1e-9);
}

TEST(ToolMeasure, WincncM37Point2AndTheSecondSwitchAreRefusedByName) {
  Machine m(wincnc_rack(), rack_world(), "m37_2");
  Outcome o = m.play("G20\nM37.2 Z0\n");
  ASSERT_FALSE(o);
  EXPECT_EQ(format(o.errors[0]),
            "part.nc:2:1: error: M37.2 (the second tool measure switch's height, TM2) is not "
            "supported: Gantry has one tool-length sensor (the profile's [toolchanger]); "
            "calibrate it with M37.1");
  Machine t(wincnc_rack(), rack_world(), "tm2");
  o = t.play("G20\nG0 X{TMX+0} Y{TMY+0}\nG0 Z{TM2+0}\n");
  ASSERT_FALSE(o);
  EXPECT_EQ(format(o.errors[0]),
            "part.nc:3:6: error: {TM2} is the second tool measure switch's (g37 I J, M37.2): "
            "Gantry has one tool-length sensor");
}

// ---- the profile's keys

std::string messages(const SettingsLoad& l) {
  std::string out;
  for (const Diagnostic& d : l.errors) out += d.message + "\n";
  return out;
}

SettingsLoad with_tables(const std::string& tables) {
  return parse_settings(default_profile_text() + tables, "p.toml");
}

TEST(ToolChangerSettings, ARackLoadsWithItsSlots) {
  const SettingsLoad l = with_tables(
      "\n[toolchanger]\nslots = \"2 16; 4.5 16\"\nslot_z = -1.0\nclear_z = 2.0\n"
      "release_output = 5\n");
  ASSERT_TRUE(l.ok()) << messages(l);
  ASSERT_EQ(l.settings.toolchanger.slots.size(), 2u);
  EXPECT_EQ(l.settings.toolchanger.slots[1][0], 4.5);
  EXPECT_EQ(l.settings.toolchanger.release_s, 0.5);
}

TEST(ToolChangerSettings, BadRacksAreRefusedAtTheirKeys) {
  EXPECT_EQ(messages(with_tables("\n[toolchanger]\nslots = \"2 16; 4\"\n")),
            "toolchanger.slots must list each slot's X and Y, slots apart with `;` (\"2 40; 6 "
            "40\")\n");
  EXPECT_EQ(messages(with_tables("\n[toolchanger]\nslots = \"2 16; 40 16\"\nslot_z = -1.0\n"
                                 "clear_z = 2.0\nrelease_output = 5\n")),
            "toolchanger.slots: slot 2 (X 40, Y 16) is outside the soft limits\n");
  EXPECT_EQ(messages(with_tables("\n[toolchanger]\nslots = \"2 16\"\nslot_z = 2.0\n"
                                 "clear_z = 1.0\n")),
            "toolchanger.release_output is needed with a rack: the output switch that opens the "
            "drawbar\ntoolchanger.slot_z (2) must be below toolchanger.clear_z (1)\n");
  EXPECT_EQ(messages(with_tables("\n[toolchanger]\nsensor_input = 2\nclear_z = 1.0\n"
                                 "sensor_start_z = 0.5\nsensor_min_z = -1.0\n")),
            "toolchanger.sensor_input: input switch 2 is not wired (inputs.switch_bits)\n");
}

TEST(SpindleSettings, NewKeysLoadAndAreChecked) {
  const SettingsLoad l = parse_settings(default_profile_text() + "", "p.toml");
  ASSERT_TRUE(l.ok()) << messages(l);
  EXPECT_EQ(l.settings.spindle.reverse_output, 0);
  EXPECT_EQ(l.settings.spindle.speed_mode, SpindleSettings::SpeedMode::Pwm);
  std::string text = default_profile_text();
  const std::string from = "max_rpm = 24000.0";
  const size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos);
  text.insert(at + from.size(),
              "\nreverse_output = 1\nat_speed_input = 6\nspeed_mode = \"frequency\"\n"
              "reverse_wiring = \"run\"\nspin_up_s = 3.0\n");
  EXPECT_EQ(messages(parse_settings(text, "p.toml")),
            "spindle.reverse_output cannot be output switch 1, which runs the spindle\n"
            "spindle.at_speed_input: input switch 6 is not wired (inputs.switch_bits)\n");
}

TEST(SpindleSettings, DacBitsAndInitialRpmLoadAndAreChecked) {
  std::string text = default_profile_text();
  const std::string from = "max_rpm = 24000.0";
  const size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos);
  std::string good = text;
  good.insert(at + from.size(), "\ndac_bits = \"6, 7, 14, 15\"\ninitial_rpm = 12000.0\n");
  const SettingsLoad l = parse_settings(good, "p.toml");
  ASSERT_TRUE(l.ok()) << messages(l);
  EXPECT_EQ(l.settings.spindle.dac_bits, (std::vector<int>{6, 7, 14, 15}));
  EXPECT_EQ(l.settings.spindle.initial_rpm, 12000);
  EXPECT_TRUE(l.settings.spindle.speed_output());
  std::string bad = text;
  bad.insert(at + from.size(), "\ndac_bits = \"6, 16\"\ninitial_rpm = 30000.0\n");
  EXPECT_EQ(messages(parse_settings(bad, "p.toml")),
            "spindle.dac_bits (bit 1): output bit 16 is already used by another pin\n"
            "spindle.initial_rpm 30000 is faster than spindle.max_rpm 24000\n");
}

}  // namespace
}  // namespace gantry
