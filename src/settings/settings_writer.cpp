// The TOML form of a profile: every key, in the schema parse_settings_table reads.
#include <fmt/format.h>

#include "gantry/settings/settings_schema.hpp"  // the numeric keys
#include "settings_private.hpp"

namespace gantry {
namespace {

toml::table groups(const GroupSpeeds& g) {
  return toml::table{{"xy", g.xy}, {"z", g.z}, {"a", g.a}, {"b", g.b}, {"c", g.c}};
}

template <class T>
std::string joined(const T& items, auto&& format_one) {
  std::string out;
  for (const auto& v : items) out += fmt::format("{}{}", out.empty() ? "" : ", ", format_one(v));
  return out;
}

const char* axis_unit_name(AxisUnit u) {
  return u == AxisUnit::Inches ? "in" : u == AxisUnit::Millimetres ? "mm" : "deg";
}

}  // namespace

toml::table settings_table(const Settings& s) {
  toml::table root{
      {"name", s.name},
      {"units", units_name(s.units)},
      {"dialect", s.dialect == Dialect::FabMo ? "fabmo" : "sb3"},
      {"gcode_dialect", s.gcode_dialect == GcodeDialect::WinCNC ? "wincnc" : "standard"}};
  if (!s.tool_table.empty()) root.insert("tool_table", s.tool_table);  // optional
  if (!s.subroutines.empty()) {                                        // optional
    toml::array dirs;
    for (const std::string& d : s.subroutines) dirs.push_back(d);
    root.insert("subroutines", dirs);
  }
  toml::table axes, pins, inputs, homing;
  for (int i = 0; i < kAxisCount; ++i) {
    const std::string L(1, kAxisLetters[i]);
    const AxisSettings& a = s.axes[i];
    axes.insert(L, toml::table{{"steps_per_unit", a.steps_per_unit},
                               {"max_speed", a.max_speed},
                               {"max_accel", a.max_accel},
                               {"min", a.min},
                               {"max", a.max}});
    const PinSettings& p = s.pins[i];
    pins.insert(L, toml::table{{"step_bit", p.step_bit},
                               {"dir_bit", p.dir_bit},
                               {"invert_dir", p.invert_dir},
                               {"step_active_low", p.step_active_low}});
    inputs.insert(L, toml::table{{"min_bit", s.inputs.min_bit[i]},
                                 {"max_bit", s.inputs.max_bit[i]},
                                 {"home_bit", s.inputs.home_bit[i]}});
    homing.insert(L, toml::table{{"direction", s.homing.direction[i] > 0 ? "+" : "-"},
                                 {"at", s.homing.at[i]}});
  }
  root.insert("axes", std::move(axes));
  root.insert("speeds",
              toml::table{{"move", groups(s.speeds.move)}, {"jog", groups(s.speeds.jog)}});
  const RampSettings& r = s.ramps;
  toml::table ramps;
  for (const SettingRow& row : settings_schema("ramps")) ramps.insert(row.key, row.get(s));
  ramps.insert("move_speed", groups(r.move_ramp_speed));
  ramps.insert("jog_speed", groups(r.jog_ramp_speed));
  root.insert("ramps", std::move(ramps));
  const PlannerSettings& pl = s.planner;
  root.insert("planner", toml::table{{"mode", planner_mode_name(pl.mode)},
                                     {"corner_jump", pl.corner_jump},
                                     {"junction_deviation", pl.junction_deviation},
                                     {"chord_tolerance", pl.chord_tolerance},
                                     {"jerk", pl.jerk},
                                     {"lookahead", pl.lookahead}});
  const CardSettings& c = s.card;
  auto pairs = [](const std::vector<GpioLineBit>& v, bool bit_first) {
    return joined(v, [&](const GpioLineBit& b) {
      return bit_first ? fmt::format("{}:{}", b.bit, b.line) : fmt::format("{}:{}", b.line, b.bit);
    });
  };
  root.insert("card", toml::table{{"type", c.type},
                                  {"clock_hz", c.clock_hz},
                                  {"pacer_divisor", c.pacer_divisor},
                                  {"step_pulse_us", c.step_pulse_us},
                                  {"dir_setup_us", c.dir_setup_us},
                                  {"gpiod_chip", c.gpiod_chip},
                                  {"gpiod_outputs", pairs(c.gpiod_outputs, true)},
                                  {"gpiod_inputs", pairs(c.gpiod_inputs, false)}});
  root.insert("pins", std::move(pins));
  const auto number = [](auto v) { return fmt::format("{}", v); };
  const OutputSettings& o = s.outputs;
  root.insert("outputs", toml::table{{"charge_pump_bit", o.charge_pump_bit},
                                     {"charge_pump_hz", o.charge_pump_hz},
                                     {"spindle_bit", o.spindle_bit},
                                     {"aux_bits", joined(o.aux_bits, number)}});
  root.insert("spindle", toml::table{{"pwm_bit", s.spindle.pwm_bit},
                                     {"pwm_hz", s.spindle.pwm_hz},
                                     {"max_rpm", s.spindle.max_rpm}});
  inputs.insert("estop_bit", s.inputs.estop_bit);
  inputs.insert("estop_active_low", s.inputs.estop_active_low);
  inputs.insert("probe_bit", s.inputs.probe_bit);
  inputs.insert("limits_active_low", s.inputs.limits_active_low);
  inputs.insert("switch_bits", joined(s.inputs.switch_bits, number));
  root.insert("inputs", std::move(inputs));
  homing.insert("input", s.homing.input);
  homing.insert("order", s.homing.order);
  homing.insert("fast_speed", s.homing.fast_speed);
  homing.insert("slow_speed", s.homing.slow_speed);
  homing.insert("back_off", s.homing.back_off);
  root.insert("homing", std::move(homing));
  toml::table simulator;
  for (int i = 0; i < kAxisCount; ++i)
    if (s.simulator.home[i])
      simulator.insert(std::string("home_") + kAxisLetters[i], *s.simulator.home[i]);
  if (s.simulator.plate_z) simulator.insert("plate_z", *s.simulator.plate_z);
  if (!simulator.empty()) root.insert("simulator", std::move(simulator));

  const CutterSettings& k = s.cutter;
  root.insert("cutter", toml::table{{"diameter", k.diameter},
                                    {"safe_z", k.safe_z},
                                    {"safe_a", k.safe_a},
                                    {"plunge_direction", k.plunge_negative ? "-" : "+"},
                                    {"pocket_overlap", k.pocket_overlap},
                                    {"trigger_on", k.trigger_on},
                                    {"trigger_off", k.trigger_off},
                                    {"trigger_axis", k.trigger_axis == 3 ? "a" : "z"},
                                    {"trigger_output", k.trigger_output}});
  toml::table tabs;
  for (const SettingRow& row : settings_schema("tabs")) tabs.insert(row.key, row.get(s));
  root.insert("tabs", std::move(tabs));
  const DisplaySettings& d = s.display;
  root.insert("display", toml::table{{"axes", d.axes},
                                     {"units_a", axis_unit_name(d.rotary_units[0])},
                                     {"units_b", axis_unit_name(d.rotary_units[1])},
                                     {"units_c", axis_unit_name(d.rotary_units[2])},
                                     {"show_comments", d.show_comments},
                                     {"keypad_step", d.keypad_step},
                                     {"keypad_remote", d.keypad_remote},
                                     {"part_file_log", d.part_file_log},
                                     {"system_log", d.system_log},
                                     {"show_progress", d.show_progress},
                                     {"keypad_outputs_off", d.keypad_outputs_off}});
  const PreviewSettings& p = s.preview;
  root.insert("preview", toml::table{{"grid", p.grid},
                                     {"table_x", p.table_x},
                                     {"table_y", p.table_y},
                                     {"table_z", p.table_z},
                                     {"simulate_cutting", p.simulate_cutting},
                                     {"draw_tool", p.draw_tool},
                                     {"start_at_location", p.start_at_location},
                                     {"show_jogs", p.show_jogs}});
  const AccessorySettings& a = s.accessories;
  root.insert("accessories", toml::table{{"mode", a.mode},
                                         {"plasma_rate", a.plasma_rate},
                                         {"pwm_low", a.pwm_low},
                                         {"pwm_high", a.pwm_high},
                                         {"pulse_khz", a.pulse_khz},
                                         {"low_cycle", a.low_cycle},
                                         {"temperature", a.temperature}});
  const SwitchSettings& w = s.switches;
  root.insert("switches", toml::table{{"limits", w.limits},
                                      {"stop_normally_open", w.stop_normally_open},
                                      {"accessory", w.accessory},
                                      {"input_modes", joined(w.input_modes, number)},
                                      {"output_modes", joined(w.output_modes, number)}});
  std::string channels;
  for (int axis : s.drivers.channel_axis) channels += "XYZABC"[axis];
  root.insert("drivers", toml::table{{"channels", channels}});
  const CalibrationSettings& cal = s.calibration;
  root.insert("calibration",
              toml::table{{"circle_resolution", cal.circle_resolution},
                          {"resolution_multipliers", joined(cal.resolution_multiplier, number)},
                          {"step_divider", cal.step_divider},
                          {"no_resolution_shift", cal.no_resolution_shift}});
  root.insert("machine", toml::table{{"limit_checking", s.machine.limit_checking},
                                     {"warning_s", s.machine.warning_s},
                                     {"max_dwell_s", s.machine.max_dwell_s},
                                     {"switch4_mode", s.machine.switch4_mode},
                                     {"editor", s.machine.editor}});
  toml::array allow;
  for (const std::string& folder : s.files.allow) allow.push_back(folder);
  root.insert("files", toml::table{{"allow", allow}});
  return root;
}

}  // namespace gantry
