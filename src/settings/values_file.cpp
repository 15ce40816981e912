// The values file: reading it over a profile, and writing the keys that differ.
#include "gantry/settings/values_file.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>  // all_of, equal
#include <cctype>     // isalnum
#include <sstream>  // the formatter writes to a stream

#include "gantry/core/text_file.hpp"  // user_config_dir
#include "gantry/settings/settings_schema.hpp"  // the machine's keys
#include "settings_private.hpp"       // settings_table, parse_settings_table

namespace gantry {

namespace {

// Moves every key of `from` into `into`; tables merge key by key. Moving (not copying)
// keeps each node's source position, so errors point into the values file.
void lay_over(toml::table& into, toml::table& from) {
  for (auto&& [key, node] : from) {
    toml::node* mine = into.get(key);
    if (mine && mine->is_table() && node.is_table()) {
      lay_over(*mine->as_table(), *node.as_table());
      continue;
    }
    const toml::key& k = key;  // a structured binding cannot be captured (C++20, clang)
    node.visit([&](auto& n) { into.insert_or_assign(k, std::move(n)); });
  }
}

bool same_leaf(const toml::node& a, const toml::node& b) {
  if (a.type() != b.type()) return false;
  if (a.is_floating_point()) return *a.value<double>() == *b.value<double>();
  if (a.is_integer()) return *a.value<std::int64_t>() == *b.value<std::int64_t>();
  if (a.is_boolean()) return *a.value<bool>() == *b.value<bool>();
  if (a.is_string()) return *a.value<std::string>() == *b.value<std::string>();
  if (const toml::array* x = a.as_array(), *y = b.as_array(); x && y)  // [files] allow
    return x->size() == y->size() &&
           std::equal(x->begin(), x->end(), y->begin(),
                      [](const toml::node& i, const toml::node& j) { return same_leaf(i, j); });
  return false;
}

// The keys of `now` that differ from `was` (both complete profiles).
toml::table difference(const toml::table& was, const toml::table& now) {
  toml::table out;
  for (auto&& [key, node] : now) {
    const toml::node* old = was.get(key);
    if (node.is_table()) {
      toml::table sub = old && old->is_table() ? difference(*old->as_table(), *node.as_table())
                                               : *node.as_table();
      if (!sub.empty()) out.insert(key, std::move(sub));
    } else if (!old || !same_leaf(*old, node)) {
      const toml::key& k = key;
      node.visit([&](const auto& n) { out.insert(k, n); });
    }
  }
  return out;
}

// A number as the shortest text that reads back as the same double (0.3, not
// 0.29999999999999999 as toml++'s own formatter writes it), always with a point or exponent.
std::string toml_number(double d) {
  std::string s = fmt::format("{}", d);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";  // n: inf, nan
  return s;
}

std::string toml_key(const std::string& k) {
  const bool bare = !k.empty() && std::all_of(k.begin(), k.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
  });
  if (bare) return k;
  std::ostringstream quoted;
  quoted << toml::toml_formatter(toml::value<std::string>(k));
  return quoted.str();
}

// `t` as TOML: its own keys, then each table under a [dotted.header] (a table with only
// tables in it gets none), as toml++'s formatter lays them out, numbers by toml_number.
void format_table(const toml::table& t, const std::string& header, std::string& out) {
  bool leaves = false;
  for (auto&& [key, node] : t) {
    if (node.is_table()) continue;
    if (!leaves && !header.empty()) out += fmt::format("{}[{}]\n", out.empty() ? "" : "\n", header);
    leaves = true;
    std::ostringstream value;
    if (node.is_floating_point())
      value << toml_number(*node.value<double>());
    else
      node.visit([&](const auto& n) { value << toml::toml_formatter(n); });
    out += fmt::format("{} = {}\n", toml_key(std::string(key.str())), value.str());
  }
  for (auto&& [key, node] : t)
    if (const toml::table* sub = node.as_table()) {
      const std::string k = toml_key(std::string(key.str()));
      format_table(*sub, header.empty() ? k : header + "." + k, out);
    }
}

std::string format_table(const toml::table& t) {
  std::string out;
  format_table(t, "", out);
  return out;
}

}  // namespace

SettingsLoad parse_settings(const std::string& profile_text, const std::string& profile_origin,
                            const std::optional<std::string>& values_text,
                            const std::string& values_origin) {
  if (!values_text) return parse_settings(profile_text, profile_origin);
  SettingsLoad out;
  toml::table profile, values;
  for (auto [text, origin, table] : {std::tuple{&profile_text, &profile_origin, &profile},
                                     std::tuple{&*values_text, &values_origin, &values}}) {
    try {
      *table = toml::parse(*text, *origin);
    } catch (const toml::parse_error& e) {
      const auto& b = e.source().begin;
      out.errors.push_back({file_loc(*origin, static_cast<int>(b.line), static_cast<int>(b.column)),
                            Severity::Error, fmt::format("not valid TOML: {}", e.description())});
    }
  }
  if (!out.errors.empty()) return out;
  lay_over(profile, values);
  return parse_settings_table(profile, profile_origin);
}

std::string settings_text(const Settings& s) {
  return format_table(settings_table(s)) + "\n";
}

std::string values_text(const Settings& current, const Settings& profile) {
  const toml::table diff = difference(settings_table(profile), settings_table(current));
  return fmt::format(
      "# Gantry values for the profile \"{}\": the V commands' changes (docs/values.md).\n"
      "# Each key overrides the profile's; delete a key (or this file) to return to the "
      "profile.\n\n{}\n",
      profile.name, format_table(diff));
}

std::string default_values_path(const std::string& profile_name) {
  std::string file;
  for (char c : profile_name) file += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return fmt::format("{}/values/{}.toml", user_config_dir(), file.empty() ? "profile" : file);
}

// The first key describing the machine itself (not an operator's value) that differs: the
// schema's machine rows, the tables whose every key is the machine's (card, pins, outputs,
// inputs: named by the table) before the single keys (axes' limits, the planner); "" when
// none does.
std::string machine_key_changed(const Settings& now, const Settings& next) {
  const toml::table a = settings_table(now), b = settings_table(next);
  std::string changed;
  for (const SettingOwner owner : {SettingOwner::MachineTable, SettingOwner::MachineKey}) {
    // A family's consecutive rows in one table are compared axis by axis.
    for_each_setting([&](const SettingRow& row, int i) {
      if (row.owner != owner) return true;
      const std::string path = row.path(i);
      const toml::node* x = a.at_path(path).node();
      const toml::node* y = b.at_path(path).node();
      if (x && y ? same_leaf(*x, *y) : x == y) return true;
      changed = owner == SettingOwner::MachineKey ? path : path.substr(0, path.find('.'));
      return false;
    });
    if (!changed.empty()) return changed;
  }
  return "";
}

}  // namespace gantry
