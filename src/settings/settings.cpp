// Loading and validating a machine profile from TOML; every problem is reported with its place.
#include "gantry/settings/settings.hpp"

#include <fmt/format.h>   // messages
#include <toml++/toml.h>  // the TOML parser

#include <algorithm>   // sort
#include <charconv>    // from_chars
#include <cmath>       // ceil for tick counts
#include <cstdlib>     // getenv: ~/ in subroutine folders
#include <filesystem>  // tool_table from the profile's folder
#include <set>         // keys seen, to reject unknown ones

#include "gantry/core/text_file.hpp"            // read_text_file
#include "gantry/settings/settings_schema.hpp"  // the numeric keys
#include "settings_private.hpp"       // parse_settings_table

namespace gantry {
namespace {

// Allowed values of one numeric key (the schema's rows carry theirs).
using Range = SettingRange;

// Reads one TOML table against its schema: each read marks a key as known; `finish`
// reports the keys nobody asked for. Errors accumulate so a load reports all of them.
class TableReader {
 public:
  TableReader(const toml::table& table, std::string path, const std::string& origin,
              std::vector<Diagnostic>& errors, bool absent = false)
      : table_(table), path_(std::move(path)), origin_(origin), errors_(errors), absent_(absent) {}

  double number(std::string_view key, Range range, double fallback) {
    const toml::node* node = find(key);
    if (!node) return fallback;
    std::optional<double> v = node->value<double>();  // accepts integers too
    if (!v || node->is_boolean()) {
      error(*node, fmt::format("{} must be a number", full(key)));
      return fallback;
    }
    if (!range.contains(*v)) {
      error(*node,
            fmt::format("{} = {} is out of range; allowed: {}", full(key), *v, range.describe()));
      return fallback;
    }
    return *v;
  }

  int integer(std::string_view key, int lo, int hi, int fallback) {
    const toml::node* node = find(key);
    if (!node) return fallback;
    if (!node->is_integer()) {
      error(*node, fmt::format("{} must be a whole number", full(key)));
      return fallback;
    }
    std::int64_t v = *node->value<std::int64_t>();
    if (v < lo || v > hi) {
      error(*node, fmt::format("{} = {} is out of range; allowed: {} to {}", full(key), v, lo, hi));
      return fallback;
    }
    return static_cast<int>(v);
  }

  bool boolean(std::string_view key, bool fallback) {
    const toml::node* node = find(key);
    if (!node) return fallback;
    if (!node->is_boolean()) {
      error(*node, fmt::format("{} must be true or false", full(key)));
      return fallback;
    }
    return *node->value<bool>();
  }

  // A string key holding a comma-separated list, e.g. "18, 19" or "0:17, 8:27": each item,
  // trimmed, goes to `item`, which returns false (and the reading stops) when it is bad; the
  // message is then "KEY: \"ITEM\" is not WHAT". A key that is not a string says `example`.
  template <class Item>
  void list(std::string_view key, std::string_view what, std::string_view example, Item item) {
    const toml::node* node = find(key);
    if (!node) return;
    const std::optional<std::string> text = node->value<std::string>();
    if (!text) {
      error(*node, fmt::format("{} must be a string such as \"{}\"", full(key), example));
      return;
    }
    std::string_view rest = *text;
    while (!rest.empty()) {
      const size_t comma = rest.find(',');
      std::string_view one = rest.substr(0, comma);
      rest = comma == std::string_view::npos ? std::string_view{} : rest.substr(comma + 1);
      while (!one.empty() && one.front() == ' ') one.remove_prefix(1);
      while (!one.empty() && one.back() == ' ') one.remove_suffix(1);
      if (!item(one)) {
        error(*node, fmt::format("{}: \"{}\" is not {}", full(key), one, what));
        return;
      }
    }
  }

  // "a, b, c": whole numbers in [lo, hi]; exactly `count` of them unless count is 0.
  std::vector<int> int_list(std::string_view key, int lo, int hi, size_t count = 0) {
    std::vector<int> out;
    bool ok = true;
    list(key, fmt::format("a whole number from {} to {}", lo, hi), "18, 19",
         [&](std::string_view one) {
           int v = 0;
           const auto r = std::from_chars(one.data(), one.data() + one.size(), v);
           ok = !one.empty() && r.ptr == one.data() + one.size() && v >= lo && v <= hi;
           if (ok) out.push_back(v);
           return ok;
         });
    if (ok && count && out.size() != count && find_quiet(key))
      fail(key, fmt::format("must list {} values, not {}", count, out.size()));
    return ok && (!count || out.size() == count) ? out : std::vector<int>(count, 0);
  }

  // "a, b, c": exactly `count` numbers within `range`.
  std::vector<double> number_list(std::string_view key, size_t count, Range range) {
    std::vector<double> out;
    bool ok = true;
    list(key, fmt::format("a number {}", range.describe()), "1, 1", [&](std::string_view one) {
      double v = 0;
      const auto r = std::from_chars(one.data(), one.data() + one.size(), v);
      ok = !one.empty() && r.ptr == one.data() + one.size() && range.contains(v);
      if (ok) out.push_back(v);
      return ok;
    });
    if (ok && out.size() != count && find_quiet(key))
      fail(key, fmt::format("must list {} values, not {}", count, out.size()));
    return ok && out.size() == count ? out : std::vector<double>(count, 1);
  }

  // Reports a rule the key's value breaks, at the key.
  void fail(std::string_view key, std::string_view why) {
    if (const toml::node* node = find_quiet(key))
      error(*node, fmt::format("{} {}", full(key), why));
  }

  // "a:b, c:d" pairs of whole numbers: bits 0-31 and GPIO line offsets. `form` names the
  // order ("BIT:LINE" or "LINE:BIT").
  std::vector<GpioLineBit> line_bits(std::string_view key, std::string_view form) {
    std::vector<GpioLineBit> out;
    const bool bit_first = form == "BIT:LINE";
    bool ok = true;
    list(key, fmt::format("{} (bits 0-31, line offsets from 0)", form), "0:17, 8:27",
         [&](std::string_view one) {
           const size_t colon = one.find(':');
           unsigned a = 0, b = 0;
           const char* end = one.data() + one.size();
           ok = colon != std::string_view::npos && colon > 0 && colon + 1 < one.size() &&
                std::from_chars(one.data(), one.data() + colon, a).ptr == one.data() + colon &&
                std::from_chars(one.data() + colon + 1, end, b).ptr == end &&
                (bit_first ? a : b) <= 31;
           if (ok) out.push_back({static_cast<int>(bit_first ? a : b), bit_first ? b : a});
           return ok;
         });
    return ok ? out : std::vector<GpioLineBit>{};
  }

  std::string choice(std::string_view key, std::initializer_list<std::string_view> allowed,
                     std::string fallback) {
    const toml::node* node = find(key);
    if (!node) return fallback;
    std::optional<std::string> v = node->value<std::string>();
    std::string list;
    for (auto a : allowed) list += fmt::format("{}\"{}\"", list.empty() ? "" : ", ", a);
    if (!v) {
      error(*node, allowed.size() == 0
                       ? fmt::format("{} must be a string", full(key))
                       : fmt::format("{} must be a string, one of {}", full(key), list));
      return fallback;
    }
    for (auto a : allowed)
      if (*v == a) return *v;
    if (allowed.size() == 0) return *v;
    error(*node, fmt::format("{} = \"{}\" is not allowed; use one of {}", full(key), *v, list));
    return fallback;
  }

  // A number key that may be left out (nullopt then); within `range` when given.
  std::optional<double> optional_number(std::string_view key, Range range) {
    seen_.insert(std::string(key));
    const toml::node* node = table_.get(key);
    if (!node) return std::nullopt;
    const std::optional<double> v = node->value<double>();
    if (!v || node->is_boolean()) {
      error(*node, fmt::format("{} must be a number", full(key)));
      return std::nullopt;
    }
    if (!range.contains(*v)) {
      error(*node,
            fmt::format("{} = {} is out of range; allowed: {}", full(key), *v, range.describe()));
      return std::nullopt;
    }
    return v;
  }

  // A sub-table that profiles may leave out; its keys are then not asked for.
  TableReader optional_table(std::string_view key) {
    static const toml::table empty;
    seen_.insert(std::string(key));
    const toml::node* node = table_.get(key);
    if (node && !node->is_table()) {
      error(*node, fmt::format("{} must be a table", full(key)));
      node = nullptr;
    }
    return TableReader(node ? *node->as_table() : empty, full(key), origin_, errors_, !node);
  }

  // A string key that profiles written before it existed may leave out.
  std::string optional_text(std::string_view key, std::string fallback) {
    seen_.insert(std::string(key));
    const toml::node* node = table_.get(key);
    if (!node) return fallback;
    if (!node->is_string()) {
      error(*node, fmt::format("{} must be a string", full(key)));
      return fallback;
    }
    return *node->value<std::string>();
  }

  // An array of strings that profiles may leave out (empty then).
  std::vector<std::string> optional_texts(std::string_view key) {
    seen_.insert(std::string(key));
    std::vector<std::string> out;
    const toml::node* node = table_.get(key);
    if (!node) return out;
    const toml::array* items = node->as_array();
    if (!items) {
      error(*node, fmt::format("{} must be an array of strings, such as [\"~/jobs\"]", full(key)));
      return out;
    }
    for (const toml::node& item : *items) {
      if (!item.is_string()) {
        error(item, fmt::format("{} must hold only strings", full(key)));
        return {};
      }
      out.push_back(*item.value<std::string>());
    }
    return out;
  }

  // A sub-table; a missing or mistyped one is reported once, and its keys are not.
  TableReader table(std::string_view key) {
    static const toml::table empty;
    const toml::node* node = find(key);
    if (node && !node->is_table()) {
      error(*node, fmt::format("{} must be a table", full(key)));
      node = nullptr;
    }
    return TableReader(node ? *node->as_table() : empty, full(key), origin_, errors_, !node);
  }

  void finish() {
    for (auto&& [k, v] : table_)
      if (!seen_.count(std::string(k.str())))
        errors_.push_back({loc_of(k.source()), Severity::Error,
                           fmt::format("unknown key {}; check its spelling against "
                                       "docs/settings.md",
                                       full(k.str()))});
  }

 private:
  const toml::node* find_quiet(std::string_view key) const { return table_.get(key); }
  const toml::node* find(std::string_view key) {
    seen_.insert(std::string(key));
    const toml::node* node = table_.get(key);
    if (!node && !absent_) {
      errors_.push_back(
          {loc_of(table_), Severity::Error, fmt::format("missing key {}", full(key))});
    }
    return node;
  }
  std::string full(std::string_view key) const {
    return path_.empty() ? std::string(key) : fmt::format("{}.{}", path_, key);
  }
  // The key's own file: a values file laid over the profile keeps its nodes' sources.
  SourceLoc loc_of(const toml::source_region& r) const {
    return file_loc(r.path ? *r.path : origin_, static_cast<int>(r.begin.line),
                    static_cast<int>(r.begin.column));
  }
  SourceLoc loc_of(const toml::node& n) const { return loc_of(n.source()); }
  void error(const toml::node& n, std::string msg) {
    errors_.push_back({loc_of(n), Severity::Error, std::move(msg)});
  }

  const toml::table& table_;
  std::string path_;
  const std::string& origin_;
  std::vector<Diagnostic>& errors_;
  std::set<std::string> seen_;
  bool absent_;  // the table itself is missing (already reported)
};

GroupSpeeds read_speeds(TableReader t, Range range) {
  GroupSpeeds s;
  s.xy = t.number("xy", range, 1);
  s.z = t.number("z", range, 1);
  s.a = t.number("a", range, 1);
  s.b = t.number("b", range, 1);
  s.c = t.number("c", range, 1);
  t.finish();
  return s;
}

constexpr Range kSpeed{0, 1e5, true};

// "a, b, c": exactly `count` whole numbers in [lo, hi].
std::array<int, 12> twelve_ints(TableReader& t, std::string_view key, int lo, int hi) {
  std::array<int, 12> out{};
  const std::vector<int> v = t.int_list(key, lo, hi, 12);
  std::copy(v.begin(), v.end(), out.begin());
  return out;
}

// The operator's values: what the V commands set (docs/values.md).
void read_values(TableReader& root, Settings& s) {
  constexpr Range kAny{-1e9, 1e9};
  TableReader cutter = root.table("cutter");
  CutterSettings& c = s.cutter;
  c.diameter = cutter.number("diameter", {0, 1e4}, 0.25);
  c.safe_z = cutter.number("safe_z", kAny, 1);
  c.safe_a = cutter.number("safe_a", kAny, 1);
  c.plunge_negative = cutter.choice("plunge_direction", {"-", "+"}, "-") == "-";
  c.pocket_overlap = cutter.number("pocket_overlap", {0, 99}, 10);
  c.trigger_on = cutter.number("trigger_on", kAny, 0);
  c.trigger_off = cutter.number("trigger_off", kAny, 0);
  c.trigger_axis = cutter.choice("trigger_axis", {"z", "a"}, "z") == "a" ? 3 : 2;
  c.trigger_output = cutter.integer("trigger_output", 3, 12, 3);
  cutter.finish();

  TableReader tabs = root.table("tabs");
  for (const SettingRow& row : settings_schema("tabs"))
    row.member(s) = tabs.number(row.key, row.range, row.fallback());
  tabs.finish();

  TableReader display = root.table("display");
  DisplaySettings& d = s.display;
  d.axes = display.integer("axes", 3, 6, 3);
  for (int i = 0; i < 3; ++i) {
    const std::string u = display.choice(
        std::string("units_") + "abc" [i], { "in", "mm", "deg" }, "deg");
    d.rotary_units[i] = u == "in"   ? AxisUnit::Inches
                        : u == "mm" ? AxisUnit::Millimetres
                                    : AxisUnit::Degrees;
  }
  d.show_comments = display.boolean("show_comments", false);
  d.keypad_step = display.number("keypad_step", {0, 1e4, true}, 0.1);
  d.keypad_remote = display.integer("keypad_remote", 0, 2, 0);
  d.part_file_log = display.boolean("part_file_log", true);
  d.system_log = display.boolean("system_log", true);
  d.show_progress = display.boolean("show_progress", false);
  d.keypad_outputs_off = display.boolean("keypad_outputs_off", false);
  display.finish();

  TableReader preview = root.table("preview");
  PreviewSettings& p = s.preview;
  p.grid = preview.number("grid", {0, 1e6}, 6);
  p.table_x = preview.number("table_x", {0, 1e6, true}, 24);
  p.table_y = preview.number("table_y", {0, 1e6, true}, 18);
  p.table_z = preview.number("table_z", {0, 1e6, true}, 6);
  p.simulate_cutting = preview.boolean("simulate_cutting", false);
  p.draw_tool = preview.boolean("draw_tool", true);
  p.start_at_location = preview.boolean("start_at_location", true);
  p.show_jogs = preview.boolean("show_jogs", true);
  preview.finish();

  TableReader acc = root.table("accessories");
  AccessorySettings& a = s.accessories;
  a.mode = acc.integer("mode", 0, 1, 0);
  a.plasma_rate = acc.number("plasma_rate", {0, 10}, 0.25);
  a.pwm_low = acc.number("pwm_low", {0, 100}, 0);
  a.pwm_high = acc.number("pwm_high", {0, 100}, 0);
  a.pulse_khz = acc.number("pulse_khz", {0, 1e3}, 5.4);
  a.low_cycle = acc.number("low_cycle", {1, 10}, 3);
  a.temperature = acc.number("temperature", {0, 1e4}, 0);
  acc.finish();

  TableReader sw = root.table("switches");
  SwitchSettings& w = s.switches;
  w.limits = sw.boolean("limits", true);
  w.stop_normally_open = sw.boolean("stop_normally_open", false);
  w.accessory = sw.integer("accessory", 0, 3, 0);
  w.input_modes = twelve_ints(sw, "input_modes", 0, 4);
  w.output_modes = twelve_ints(sw, "output_modes", 0, 5);
  sw.finish();

  TableReader drivers = root.table("drivers");
  const std::string channels = drivers.choice("channels", {}, "XYZABC");
  s.drivers.channel_axis = {0, 1, 2, 3, 4, 5};
  bool channels_ok = channels.size() == kAxisCount;
  for (size_t k = 0; channels_ok && k < channels.size(); ++k) {
    const size_t axis =
        std::string_view("XYZABC").find(static_cast<char>(std::toupper(channels[k])));
    channels_ok = axis != std::string_view::npos;
    if (channels_ok) s.drivers.channel_axis[k] = static_cast<int>(axis);
  }
  if (!channels_ok)
    drivers.fail("channels", "must name six axes, one per driver channel, such as \"XYZABC\"");
  drivers.finish();

  TableReader cal = root.table("calibration");
  CalibrationSettings& k = s.calibration;
  k.circle_resolution = cal.number("circle_resolution", {0, 1e3, true}, 0.05);
  const std::vector<double> res = cal.number_list("resolution_multipliers", 5, {0, 10});
  std::copy(res.begin(), res.end(), k.resolution_multiplier.begin());
  k.step_divider = cal.integer("step_divider", 1, 100, 1);
  k.no_resolution_shift = cal.boolean("no_resolution_shift", false);
  cal.finish();

  TableReader machine = root.table("machine");
  s.machine.limit_checking = machine.boolean("limit_checking", true);
  s.machine.warning_s = machine.number("warning_s", {0, 3600}, 2);
  // A key added after profiles were written: a profile may leave it out (24 h).
  s.machine.max_dwell_s =
      machine.optional_number("max_dwell_s", {0, 2592000, true}).value_or(86400);
  s.machine.switch4_mode = machine.integer("switch4_mode", -4, -1, -1);
  s.machine.editor = machine.optional_text("editor", "");
  machine.finish();

  TableReader files = root.optional_table("files");  // profiles before it have none
  s.files.allow = files.optional_texts("allow");
  for (const std::string& folder : s.files.allow)
    if (!(folder.starts_with("/") || folder.starts_with("~/")))
      files.fail("allow",
                 fmt::format("must list folders as absolute paths or ~/..., not \"{}\"", folder));
  files.finish();
}

void read_profile(TableReader root, Settings& s) {
  s.name = root.choice("name", {}, "");
  s.units = root.choice("units", {"in", "mm"}, "in") == "mm" ? Units::Millimetres : Units::Inches;
  s.dialect =
      root.choice("dialect", {"sb3", "fabmo"}, "sb3") == "fabmo" ? Dialect::FabMo : Dialect::SB3;
  // A key added after profiles were written: a profile may leave it out.
  const std::string gcode = root.optional_text("gcode_dialect", "standard");
  if (gcode != "standard" && gcode != "wincnc")
    root.fail("gcode_dialect", "is not allowed; use one of \"standard\", \"wincnc\"");
  s.gcode_dialect = gcode == "wincnc" ? GcodeDialect::WinCNC : GcodeDialect::Standard;
  s.tool_table = root.optional_text("tool_table", "");
  s.subroutines = root.optional_texts("subroutines");

  TableReader axes = root.table("axes");
  for (int i = 0; i < kAxisCount; ++i) {
    TableReader ax = axes.table(std::string(1, kAxisLetters[i]));
    AxisSettings& a = s.axes[i];
    a.steps_per_unit = ax.number("steps_per_unit", {-1e6, 1e6}, 1);
    a.max_speed = ax.number("max_speed", kSpeed, 1);
    a.max_accel = ax.number("max_accel", {0, 1e7, true}, 1);
    a.min = ax.number("min", {-1e9, 1e9}, 0);
    a.max = ax.number("max", {-1e9, 1e9}, 0);
    ax.finish();
  }
  axes.finish();

  TableReader speeds = root.table("speeds");
  s.speeds.move = read_speeds(speeds.table("move"), kSpeed);
  s.speeds.jog = read_speeds(speeds.table("jog"), kSpeed);
  speeds.finish();

  TableReader ramps = root.table("ramps");
  RampSettings& r = s.ramps;
  for (const SettingRow& row : settings_schema("ramps"))
    row.member(s) = ramps.number(row.key, row.range, row.fallback());
  r.move_ramp_speed = read_speeds(ramps.table("move_speed"), kSpeed);
  r.jog_ramp_speed = read_speeds(ramps.table("jog_speed"), kSpeed);
  ramps.finish();

  TableReader planner = root.table("planner");
  PlannerSettings& pl = s.planner;
  const std::string mode = planner.choice("mode", {"sb3", "junction", "stop"}, "sb3");
  pl.mode = mode == "junction" ? PlannerMode::Junction
            : mode == "stop"   ? PlannerMode::Stop
                               : PlannerMode::SB3;
  pl.corner_jump = planner.number("corner_jump", {0, 1}, 0.11);
  pl.junction_deviation = planner.number("junction_deviation", {0, 1e3}, 0.002);
  pl.chord_tolerance = planner.number("chord_tolerance", {0, 1e3, true}, 0.0005);
  pl.jerk = planner.number("jerk", {0, 1e9}, 0);
  pl.lookahead = planner.integer("lookahead", 2, 1 << 20, 1024);
  planner.finish();

  TableReader card = root.table("card");
  CardSettings& c = s.card;
  c.type = card.choice("type", {"sim", "pci7200", "gpiod"}, "sim");
  c.clock_hz = card.number("clock_hz", {1e3, 1e9}, 4e6);
  c.pacer_divisor = card.integer("pacer_divisor", 2, 65535, 20);
  c.step_pulse_us = card.number("step_pulse_us", {0, 1e4, true}, 5);
  c.dir_setup_us = card.number("dir_setup_us", {0, 1e4}, 5);
  c.gpiod_chip = card.choice("gpiod_chip", {}, "/dev/gpiochip0");
  c.gpiod_outputs = card.line_bits("gpiod_outputs", "BIT:LINE");
  c.gpiod_inputs = card.line_bits("gpiod_inputs", "LINE:BIT");
  card.finish();

  TableReader pins = root.table("pins");
  for (int i = 0; i < kAxisCount; ++i) {
    TableReader p = pins.table(std::string(1, kAxisLetters[i]));
    PinSettings& pin = s.pins[i];
    pin.step_bit = p.integer("step_bit", 0, 31, i);
    pin.dir_bit = p.integer("dir_bit", 0, 31, 8 + i);
    pin.invert_dir = p.boolean("invert_dir", false);
    pin.step_active_low = p.boolean("step_active_low", false);
    p.finish();
  }
  pins.finish();

  read_values(root, s);

  TableReader outputs = root.table("outputs");
  OutputSettings& o = s.outputs;
  o.charge_pump_bit = outputs.integer("charge_pump_bit", -1, 31, 16);
  o.charge_pump_hz = outputs.number("charge_pump_hz", {0, 1e6, true}, 10000);
  o.spindle_bit = outputs.integer("spindle_bit", -1, 31, 17);
  o.aux_bits = outputs.int_list("aux_bits", -1, 31);
  outputs.finish();

  TableReader spindle = root.optional_table("spindle");  // profiles before TR have none
  SpindleSettings& sp = s.spindle;
  sp.pwm_bit = spindle.integer("pwm_bit", -1, 31, -1);
  sp.pwm_hz = spindle.number("pwm_hz", {0, 1e6, true}, 1000);
  sp.max_rpm = spindle.number("max_rpm", {0, 1e6, true}, 24000);
  spindle.finish();

  TableReader inputs = root.table("inputs");
  InputSettings& in = s.inputs;
  in.estop_bit = inputs.integer("estop_bit", -1, 31, 0);
  in.estop_active_low = inputs.boolean("estop_active_low", true);
  in.probe_bit = inputs.integer("probe_bit", -1, 31, 1);
  in.limits_active_low = inputs.boolean("limits_active_low", false);
  for (int i = 0; i < kAxisCount; ++i) {
    TableReader ax = inputs.table(std::string(1, kAxisLetters[i]));
    in.min_bit[i] = ax.integer("min_bit", -1, 31, -1);
    in.max_bit[i] = ax.integer("max_bit", -1, 31, -1);
    in.home_bit[i] = ax.integer("home_bit", -1, 31, -1);
    ax.finish();
  }
  const std::vector<int> switches = inputs.int_list("switch_bits", -1, 31, 12);
  if (switches.size() == 12) std::copy(switches.begin(), switches.end(), in.switch_bits.begin());
  inputs.finish();

  TableReader homing = root.table("homing");
  HomingSettings& h = s.homing;
  h.input = homing.integer("input", 1, 12, 3);
  h.order = homing.choice("order", {}, "zxy");
  if (h.order.empty() || h.order.find_first_not_of("xyzabc") != std::string::npos)
    homing.fail("order", "must list the axes to home, in order, as letters x y z a b c");
  h.fast_speed = homing.number("fast_speed", {0, 1e6, true}, 1);
  h.slow_speed = homing.number("slow_speed", {0, 1e6, true}, 0.1);
  h.back_off = homing.number("back_off", {0, 1e6, true}, 0.25);
  for (int i = 0; i < kAxisCount; ++i) {
    TableReader ax = homing.table(std::string(1, kAxisLetters[i]));
    h.direction[i] = ax.choice("direction", {"-", "+"}, i == 2 ? "+" : "-") == "+" ? 1 : -1;
    h.at[i] = ax.number("at", {-1e9, 1e9}, 0);
    ax.finish();
  }
  homing.finish();

  // The simulated card's switches (optional: a real card's profile has none).
  TableReader sim = root.optional_table("simulator");
  for (int i = 0; i < kAxisCount; ++i)
    s.simulator.home[i] = sim.optional_number(std::string("home_") + kAxisLetters[i], {-1e9, 1e9});
  s.simulator.plate_z = sim.optional_number("plate_z", {-1e9, 1e9});
  sim.finish();
  root.finish();
}

}  // namespace

// Rules that tie keys together; each is reported at the first key it names, in the file that
// key came from (a values file's key is in the values file), or at `origin`'s top when the
// table does not hold that key.
static void check_consistency(const Settings& s, const std::string& origin,
                              std::vector<Diagnostic>& errors, const toml::table* table = nullptr) {
  auto err_at = [&](std::string_view key, std::string msg) {
    const toml::node* node = table ? table->at_path(key).node() : nullptr;
    if (!node) return errors.push_back({file_loc(origin), Severity::Error, std::move(msg)});
    const toml::source_region& where = node->source();
    const std::string file = where.path ? std::string(*where.path) : origin;
    errors.push_back(
        {file_loc(file, static_cast<int>(where.begin.line), static_cast<int>(where.begin.column)),
         Severity::Error, std::move(msg)});
  };
  auto err = [&](std::string msg) { err_at(msg.substr(0, msg.find_first_of(" :")), msg); };
  const double pacer = s.card.pacer_hz();
  const double tick_us = 1e6 / pacer;
  const int pulse_ticks = static_cast<int>(std::ceil(s.card.step_pulse_us / tick_us - 1e-9));
  const double max_rate = pacer / (pulse_ticks + 1);  // one pulse plus at least one idle tick
  std::uint32_t used = 0;
  for (int i = 0; i < kAxisCount; ++i) {
    const char L = kAxisLetters[i];
    const AxisSettings& a = s.axes[i];
    if (a.min >= a.max)
      err(fmt::format("axes.{0}.min ({1}) must be below axes.{0}.max ({2})", L, a.min, a.max));
    if (a.steps_per_unit == 0) err(fmt::format("axes.{}.steps_per_unit must not be 0", L));
    const double rate = a.max_speed * std::fabs(a.steps_per_unit);
    if (rate > max_rate)
      err(fmt::format(
          "axes.{}.max_speed {} x steps_per_unit {} = {:.0f} steps/s exceeds the card's {:.0f} "
          "steps/s (pacer {:.0f} Hz, {}-tick pulse plus one idle tick); lower max_speed or "
          "raise the pacer",
          L, a.max_speed, a.steps_per_unit, rate, max_rate, pacer, pulse_ticks));
    for (const auto& [key, bit] :
         {std::pair{"step_bit", s.pins[i].step_bit}, std::pair{"dir_bit", s.pins[i].dir_bit}}) {
      if (used & (1u << bit))
        err(fmt::format("pins.{}.{}: output bit {} is already used by another pin", L, key, bit));
      used |= 1u << bit;
    }
  }
  std::vector<std::pair<std::string, int>> outputs = {
      {"outputs.charge_pump_bit", s.outputs.charge_pump_bit},
      {"outputs.spindle_bit", s.outputs.spindle_bit}};
  for (size_t k = 0; k < s.outputs.aux_bits.size(); ++k)
    outputs.emplace_back(fmt::format("outputs.aux_bits (output {})", k + 1), s.outputs.aux_bits[k]);
  outputs.emplace_back("spindle.pwm_bit", s.spindle.pwm_bit);
  for (const auto& [name, bit] : outputs) {
    if (bit < 0) continue;
    if (used & (1u << bit))
      err(fmt::format("{}: output bit {} is already used by another pin", name, bit));
    used |= 1u << bit;
  }
  // TR's duty is whole ticks of a period: 100 of them keep it within 1 % of the RPM asked.
  if (s.spindle.pwm_bit >= 0 && pacer / s.spindle.pwm_hz < 100)
    err(
        fmt::format("spindle.pwm_hz {} leaves {:.0f} ticks a period at the card's {:.0f} Hz "
                    "pacer; at most {:.0f} Hz keeps TR's duty within 1 %",
                    s.spindle.pwm_hz, pacer / s.spindle.pwm_hz, pacer, pacer / 100));
  // Each bit has one role, but the proximity switches of several axes may share one (wired
  // in parallel), and switch_bits only names bits for part files.
  std::uint32_t inputs_used = 0, home_bits = 0;
  auto input = [&](const std::string& name, int bit, bool home = false) {
    if (bit < 0) return;
    if ((inputs_used & (1u << bit)) && !(home && (home_bits & (1u << bit))))
      err(fmt::format("inputs.{}: input bit {} is already used by another input", name, bit));
    inputs_used |= 1u << bit;
    if (home) home_bits |= 1u << bit;
  };
  input("estop_bit", s.inputs.estop_bit);
  input("probe_bit", s.inputs.probe_bit);
  for (int i = 0; i < kAxisCount; ++i) {
    const std::string axis(1, kAxisLetters[i]);
    input(axis + ".min_bit", s.inputs.min_bit[i]);
    input(axis + ".max_bit", s.inputs.max_bit[i]);
  }
  for (int i = 0; i < kAxisCount; ++i)
    input(std::string(1, kAxisLetters[i]) + ".home_bit", s.inputs.home_bit[i], true);
  auto check_group = [&](const char* what, const GroupSpeeds& g) {
    const double xy_limit = std::min(s.axes[0].max_speed, s.axes[1].max_speed);
    const std::array<std::pair<const char*, std::pair<double, double>>, 5> items{{
        {"xy", {g.xy, xy_limit}},
        {"z", {g.z, s.axes[2].max_speed}},
        {"a", {g.a, s.axes[3].max_speed}},
        {"b", {g.b, s.axes[4].max_speed}},
        {"c", {g.c, s.axes[5].max_speed}},
    }};
    for (auto& [k, vl] : items)
      if (vl.first > vl.second)
        err(fmt::format("{}.{} = {} exceeds the axis max_speed {}", what, k, vl.first, vl.second));
  };
  check_group("speeds.move", s.speeds.move);
  check_group("speeds.jog", s.speeds.jog);
  std::array<int, kAxisCount> channels = s.drivers.channel_axis;
  std::sort(channels.begin(), channels.end());
  if (channels != std::array<int, kAxisCount>{0, 1, 2, 3, 4, 5})
    err("drivers.channels must name each axis once (one driver channel per axis)");
}

std::vector<std::string> settings_problems(const Settings& s) {
  std::vector<Diagnostic> errors;
  check_consistency(s, "", errors);
  std::vector<std::string> out;
  for (const Diagnostic& d : errors) out.push_back(d.message);
  return out;
}

SettingsLoad parse_settings(const std::string& text, const std::string& origin) {
  SettingsLoad out;
  toml::table table;
  try {
    table = toml::parse(text, origin);
  } catch (const toml::parse_error& e) {
    const auto& b = e.source().begin;
    out.errors.push_back({file_loc(origin, static_cast<int>(b.line), static_cast<int>(b.column)),
                          Severity::Error, fmt::format("not valid TOML: {}", e.description())});
    return out;
  }
  return parse_settings_table(table, origin);
}

namespace {

// The profile's subroutine folders, relative ones from the profile's folder; a folder that is
// not there is an error at the key now, not a "not found" at the first call.
void resolve_subroutine_folders(const toml::table& table, const std::string& origin,
                                SettingsLoad& out) {
  std::vector<std::string>& paths = out.settings.subroutine_paths;
  paths.clear();
  for (const std::string& folder : out.settings.subroutines) {
    std::filesystem::path p(folder);
    if (folder.starts_with("~/"))
      if (const char* home = std::getenv("HOME"))
        p = std::filesystem::path(home) / folder.substr(2);
    if (p.is_relative()) p = std::filesystem::path(origin).parent_path() / p;
    std::error_code ec;
    if (!std::filesystem::is_directory(p, ec)) {
      TableReader(table, "", origin, out.errors)
          .fail("subroutines",
                fmt::format("names the folder \"{}\" ({}), which does not exist or is not a "
                            "folder; create it or correct the path",
                            folder, p.string()));
      continue;
    }
    paths.push_back(p.string());
  }
}

}  // namespace

SettingsLoad parse_settings_table(const toml::table& table, const std::string& origin) {
  SettingsLoad out;
  read_profile(TableReader(table, "", origin, out.errors), out.settings);
  if (const std::string& t = out.settings.tool_table; !t.empty())  // from the profile's folder
    out.settings.tool_table_path =
        (std::filesystem::path(origin).parent_path() / std::filesystem::path(t)).string();
  resolve_subroutine_folders(table, origin, out);
  if (out.errors.empty()) check_consistency(out.settings, origin, out.errors, &table);
  return out;
}

SettingsLoad load_settings_file(const std::string& path) {
  const std::optional<std::string> text = read_text_file(path);
  if (!text) {
    SettingsLoad out;
    out.errors.push_back({file_loc(path), Severity::Error,
                          "cannot open the settings file; check the path (--profile) and its "
                          "permissions"});
    return out;
  }
  return parse_settings(*text, path);
}

Settings default_settings() {
  SettingsLoad load = parse_settings(default_profile_text(), "settings/default.toml");
  if (!load.ok()) throw GantryError(load.errors.front());  // a build defect, caught by tests
  return load.settings;
}

const char* units_name(Units u) {
  return u == Units::Inches ? "in" : "mm";
}

const char* planner_mode_name(PlannerMode m) {
  return m == PlannerMode::SB3 ? "sb3" : m == PlannerMode::Junction ? "junction" : "stop";
}

}  // namespace gantry
