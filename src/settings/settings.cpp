// Loading and validating a machine profile from TOML; every problem is reported with its place.
#include "gantry/settings/settings.hpp"

#include <fmt/format.h>   // messages
#include <toml++/toml.h>  // the TOML parser

#include <algorithm>   // sort
#include <charconv>    // from_chars
#include <cmath>       // ceil for tick counts
#include <cstdlib>     // getenv: ~/ in subroutine folders
#include <filesystem>  // tool_table from the profile's folder
#include <functional>  // the table finder
#include <map>         // the tables read
#include <set>         // keys seen, to reject unknown ones
#include <span>

#include "gantry/core/text_file.hpp"            // read_text_file
#include "gantry/settings/settings_schema.hpp"  // the keys
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

  std::string choice(std::string_view key, std::span<const std::string_view> allowed,
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

  // Whether a key that may be left out is there (asked for either way).
  bool has(std::string_view key) {
    seen_.insert(std::string(key));
    return table_.get(key) != nullptr;
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

// Reads one row's key (`i`: the family's index) from its table into `s`.
void read_row(TableReader& t, const SettingRow& row, int i, Settings& s) {
  const std::string key = row.key_at(i);
  void* field = row.field ? row.field(s, i) : nullptr;
  switch (row.kind) {
    case SettingKind::Number: {
      double& v = *static_cast<double*>(field);
      if (!row.optional) {
        v = t.number(key, row.range, v);
      } else if (const std::optional<double> got = t.optional_number(key, row.range)) {
        v = *got;
      }
      return;
    }
    case SettingKind::OptionalNumber:
      *static_cast<std::optional<double>*>(field) = t.optional_number(key, row.range);
      return;
    case SettingKind::Integer: {
      int& v = *static_cast<int*>(field);
      if (row.optional && !t.has(key)) return;  // a key added after profiles were written
      v = t.integer(key, static_cast<int>(row.range.lo), static_cast<int>(row.range.hi), v);
      return;
    }
    case SettingKind::Bool: {
      bool& v = *static_cast<bool*>(field);
      if (row.optional && !t.has(key)) return;
      v = t.boolean(key, v);
      return;
    }
    case SettingKind::Choice: {
      const std::string fallback(row.names[static_cast<size_t>(row.choice_get(s, i))]);
      std::string v;
      if (row.optional) {  // a key added after profiles were written
        v = t.optional_text(key, fallback);
        std::string list;
        for (std::string_view n : row.names) list += fmt::format("{}\"{}\"", list.empty() ? "" : ", ", n);
        if (std::find(row.names.begin(), row.names.end(), v) == row.names.end())
          t.fail(key, fmt::format("is not allowed; use one of {}", list));
      } else {
        v = t.choice(key, row.names, fallback);
      }
      const auto at = std::find(row.names.begin(), row.names.end(), v);
      if (at != row.names.end()) row.choice_set(s, i, static_cast<int>(at - row.names.begin()));
      return;
    }
    case SettingKind::Text: {
      std::string& v = *static_cast<std::string*>(field);
      v = row.optional ? t.optional_text(key, v) : t.choice(key, row.names, v);
      if (row.check)
        if (const std::string why = row.check(v); !why.empty()) t.fail(key, why);
      return;
    }
    case SettingKind::Texts: {
      auto& v = *static_cast<std::vector<std::string>*>(field);
      v = t.optional_texts(key);
      if (row.check)
        for (const std::string& item : v)
          if (const std::string why = row.check(item); !why.empty()) t.fail(key, why);
      return;
    }
    case SettingKind::IntList: {
      if (row.optional && !t.has(key)) return;  // a key added after profiles were written
      const std::vector<int> v = t.int_list(key, static_cast<int>(row.range.lo),
                                            static_cast<int>(row.range.hi), row.count);
      if (row.count == 0)
        *static_cast<std::vector<int>*>(field) = v;
      else if (v.size() == static_cast<size_t>(row.count))
        std::copy(v.begin(), v.end(), static_cast<int*>(field));
      return;
    }
    case SettingKind::NumberList: {
      const std::vector<double> v = t.number_list(key, row.count, row.range);
      std::copy(v.begin(), v.end(), static_cast<double*>(field));
      return;
    }
    case SettingKind::LineBits:
      *static_cast<std::vector<GpioLineBit>*>(field) = t.line_bits(key, row.names[0]);
      return;
    case SettingKind::Coded:
      if (row.optional && !t.has(key)) return;  // a key added after profiles were written
      if (!row.decode(s, t.choice(key, {}, row.encode(s)))) t.fail(key, row.rule);
      return;
  }
}

// Reads every row of the schema, in its order; a family's consecutive rows in one table are
// read axis by axis (axes.x's keys, then axes.y's), as the tables are written.
void read_profile(TableReader& root, Settings& s) {
  std::map<std::string, TableReader> tables;  // by path; nodes do not move
  std::vector<std::string> order;             // to finish each table once, inner ones first
  // `optional`: the schema's row says the table may be left out (a table holding one holds
  // no other).
  std::function<TableReader&(const std::string&, bool)> table =
      [&](const std::string& path, bool optional) -> TableReader& {
    if (path.empty()) return root;
    if (auto it = tables.find(path); it != tables.end()) return it->second;
    const size_t dot = path.rfind('.');
    TableReader& parent = table(dot == std::string::npos ? "" : path.substr(0, dot), false);
    const std::string key = dot == std::string::npos ? path : path.substr(dot + 1);
    TableReader child = optional ? parent.optional_table(key) : parent.table(key);
    order.push_back(path);
    return tables.emplace(path, std::move(child)).first->second;
  };
  for_each_setting([&](const SettingRow& row, int i) {
    read_row(table(row.section_at(i), row.optional_table), row, i, s);
    return true;
  });
  for (auto it = order.rbegin(); it != order.rend(); ++it) tables.at(*it).finish();
  root.finish();
}

}  // namespace

// [friendly_motion]'s outputs (docs/friendlymotion.md): the beam's gate and every relay an
// output switch that is wired, no switch two relays' (a probe on bus A and on bus B at once
// would join the buses), none the beam's; the feed range in order.
static void friendly_motion_rules(const Settings& s, const std::function<void(std::string)>& err) {
  const FriendlyMotionSettings& fm = s.friendly_motion;
  auto wired = [&](int n) {
    return n >= 1 && n <= static_cast<int>(s.outputs.aux_bits.size()) &&
           s.outputs.aux_bits[n - 1] >= 0;
  };
  // Output 1 is the default, named whether or not the profile is a laser table's: an unwired
  // one leaves M100 refused and G16 tracing with the beam off, as before the setting.
  if (fm.laser_output > 1 && !wired(fm.laser_output))
    err(fmt::format(
        "friendly_motion.laser_output: output switch {} is not wired (outputs.aux_bits)",
        fm.laser_output));
  std::map<int, std::string> used;
  for (const auto& [bus, relays] : {std::pair{'a', &fm.relay_a}, std::pair{'b', &fm.relay_b}})
    for (size_t k = 0; k < relays->size(); ++k) {
      const int n = (*relays)[k];
      if (n == 0) continue;
      const std::string name = fmt::format("friendly_motion.relay_{} (probe {})", bus, k + 1);
      if (!wired(n))
        err(fmt::format("{}: output switch {} is not wired (outputs.aux_bits)", name, n));
      else if (n == fm.laser_output)
        err(fmt::format("{}: output switch {} gates the laser (friendly_motion.laser_output)", name,
                        n));
      else if (const auto [at, fresh] = used.emplace(n, name); !fresh)
        err(fmt::format("{}: output switch {} is already {}'s relay", name, n, at->second));
    }
  if (fm.feed_min && fm.feed_max && *fm.feed_min > *fm.feed_max)
    err(fmt::format("friendly_motion.feed_min ({}) is above friendly_motion.feed_max ({})",
                    *fm.feed_min, *fm.feed_max));
}

// [spindle]'s outputs and inputs and [toolchanger]'s places (docs/hardware.md, "Spindle",
// "Tool changer"): switches that are wired, heights in order, places within the soft limits.
static void spindle_and_tool_changer_rules(const Settings& s, double pacer,
                                           const std::function<void(std::string)>& err) {
  auto output_wired = [&](int n) {
    return n >= 1 && n <= static_cast<int>(s.outputs.aux_bits.size()) && s.outputs.aux_bits[n - 1] >= 0;
  };
  auto input_wired = [&](int n) { return n >= 1 && n <= 12 && s.inputs.switch_bits[n - 1] >= 0; };
  const SpindleSettings& sp = s.spindle;
  if (sp.pwm_bit >= 0 && sp.speed_mode == SpindleSettings::SpeedMode::Frequency &&
      sp.max_hz > pacer / 2)
    err(fmt::format("spindle.max_hz {} is faster than the card's {:.0f} Hz pacer can carry (at "
                    "most {:.0f} Hz, two ticks a period)",
                    sp.max_hz, pacer, pacer / 2));
  if (!sp.dac_bits.empty() && sp.pwm_bit >= 0)
    err("spindle.dac_bits and spindle.pwm_bit are both speed outputs: give one of them");
  if (sp.dac_bits.size() > 16)
    err(fmt::format("spindle.dac_bits lists {} bits: a D/A word has at most 16",
                    sp.dac_bits.size()));
  if (sp.speed_output() && sp.initial_rpm > sp.max_rpm)
    err(fmt::format("spindle.initial_rpm {} is faster than spindle.max_rpm {}", sp.initial_rpm,
                    sp.max_rpm));
  if (sp.reverse_output == 1)
    err("spindle.reverse_output cannot be output switch 1, which runs the spindle");
  else if (sp.reverse_output != 0 && !output_wired(sp.reverse_output))
    err(fmt::format("spindle.reverse_output: output switch {} is not wired (outputs.aux_bits)",
                    sp.reverse_output));
  if (sp.at_speed_input != 0 && !input_wired(sp.at_speed_input))
    err(fmt::format("spindle.at_speed_input: input switch {} is not wired (inputs.switch_bits)",
                    sp.at_speed_input));
  const ToolChangerSettings& tc = s.toolchanger;
  const AxisSettings &x = s.axes[0], &y = s.axes[1], &z = s.axes[2];
  auto outside = [](const AxisSettings& a, double v) { return v < a.min || v > a.max; };
  if (tc.rack() || tc.sensor_input != 0) {
    if (outside(z, tc.clear_z))
      err(fmt::format("toolchanger.clear_z {} is outside Z's soft limits {} to {}", tc.clear_z,
                      z.min, z.max));
  }
  if (tc.rack()) {
    if (tc.release_output == 0)
      err("toolchanger.release_output is needed with a rack: the output switch that opens the "
          "drawbar");
    else if (tc.release_output == 1 || tc.release_output == sp.reverse_output)
      err(fmt::format("toolchanger.release_output: output switch {} drives the spindle",
                      tc.release_output));
    else if (!output_wired(tc.release_output))
      err(fmt::format("toolchanger.release_output: output switch {} is not wired "
                      "(outputs.aux_bits)",
                      tc.release_output));
    if (tc.slot_z >= tc.clear_z)
      err(fmt::format("toolchanger.slot_z ({}) must be below toolchanger.clear_z ({})", tc.slot_z,
                      tc.clear_z));
    if (outside(z, tc.slot_z))
      err(fmt::format("toolchanger.slot_z {} is outside Z's soft limits {} to {}", tc.slot_z,
                      z.min, z.max));
    for (size_t k = 0; k < tc.slots.size(); ++k)
      if (outside(x, tc.slots[k][0]) || outside(y, tc.slots[k][1]))
        err(fmt::format("toolchanger.slots: slot {} (X {}, Y {}) is outside the soft limits", k + 1,
                        tc.slots[k][0], tc.slots[k][1]));
  }
  if (tc.sensor_input != 0) {
    if (!input_wired(tc.sensor_input))
      err(fmt::format("toolchanger.sensor_input: input switch {} is not wired "
                      "(inputs.switch_bits)",
                      tc.sensor_input));
    if (tc.sensor_min_z >= tc.sensor_start_z)
      err(fmt::format("toolchanger.sensor_min_z ({}) must be below toolchanger.sensor_start_z ({})",
                      tc.sensor_min_z, tc.sensor_start_z));
    if (tc.sensor_start_z > tc.clear_z)
      err(fmt::format("toolchanger.sensor_start_z ({}) must be at most toolchanger.clear_z ({})",
                      tc.sensor_start_z, tc.clear_z));
    if (outside(z, tc.sensor_min_z))
      err(fmt::format("toolchanger.sensor_min_z {} is outside Z's soft limits {} to {}",
                      tc.sensor_min_z, z.min, z.max));
    if (outside(x, tc.sensor_x) || outside(y, tc.sensor_y))
      err(fmt::format("toolchanger.sensor_x: the sensor (X {}, Y {}) is outside the soft limits",
                      tc.sensor_x, tc.sensor_y));
  }
}

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
  for (size_t k = 0; k < s.spindle.dac_bits.size(); ++k)
    outputs.emplace_back(fmt::format("spindle.dac_bits (bit {})", k), s.spindle.dac_bits[k]);
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
  spindle_and_tool_changer_rules(s, pacer, err);
  friendly_motion_rules(s, err);
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
  // A bound other keys set (the speeds' axis max_speed) is the row's, as VS checks it.
  for (const SettingRow& row : settings_schema())
    if (row.most)
      for (int i = 0; i < row.size(); ++i)
        if (const double v = row.get(s, i), limit = row.most(s, i); v > limit)
          err(fmt::format("{} = {} exceeds the axis max_speed {}", row.path(i), v, limit));
  if (s.feed_override.min >= s.feed_override.max)
    err(fmt::format("feed_override.min ({} %) must be below feed_override.max ({} %)",
                    s.feed_override.min, s.feed_override.max));
  // A slaved axis (docs/hardware.md) takes a second channel from an axis not in use.
  std::array<int, kAxisCount> channels_of{};
  for (int axis : s.drivers.channel_axis) ++channels_of[axis];
  for (int i = 0; i < kAxisCount; ++i) {
    const char L = static_cast<char>(kAxisLetters[i] - 'a' + 'A');
    if (channels_of[i] > 2)
      err(fmt::format("drivers.channels names {} {} times: an axis has one driver channel, or two "
                      "(a slaved axis)",
                      L, channels_of[i]));
    else if (channels_of[i] == 0 && i < s.display.axes)
      err(fmt::format("drivers.channels names no driver channel for {}, an axis in use "
                      "(display.axes = {})",
                      L, s.display.axes));
    if (i == s.display.w_axis) {
      // W is a second vertical head: a length, on an axis the machine uses.
      if (i >= s.display.axes)
        err(fmt::format("display.w_axis names {} as W, an axis display.axes = {} does not use", L,
                        s.display.axes));
      else if (s.display.rotary_units[static_cast<size_t>(i - 3)] == AxisUnit::Degrees)
        err(
            fmt::format("display.w_axis names {} as W, a vertical head, but display.units_{} is "
                        "degrees; give it \"{}\"",
                        L, kAxisLetters[i], units_name(s.units)));
    }
    if (s.homing.square_input[i] != 0 && channels_of[i] != 2)
      err(fmt::format("homing.{}.square_input needs {} on two driver channels (drivers.channels), "
                      "a slaved axis",
                      kAxisLetters[i], L));
    if (const std::optional<double>& p = s.homing.park[i];
        p && (*p < s.axes[i].min || *p > s.axes[i].max))
      err(fmt::format("homing.{}.park {} is outside {}'s soft limits {} to {} (axes.{}.min/max)",
                      kAxisLetters[i], *p, L, s.axes[i].min, s.axes[i].max, kAxisLetters[i]));
  }
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
  TableReader root(table, "", origin, out.errors);
  read_profile(root, out.settings);
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
