// Reading and storing values at `.field` / `[index]` paths inside persistent variables.
#include "persistent_path.hpp"

#include <fmt/format.h>  // messages

#include <cctype>   // toupper
#include <cmath>    // trunc, fabs
#include <cstdint>  // int64_t

#include "gantry/lang/expr_node.hpp"  // index expressions' own locations

namespace gantry {

namespace {

using nlohmann::json;

// Assigning far past the end fills the gap with nulls; a typo such as `$t[1e9]` must not
// try to allocate billions of them.
constexpr double kMaxIndex = 100000;

std::string root_name(std::string_view name) {
  std::string out = (!name.empty() && name[0] == '$') ? "" : "$";
  out += name;
  return out;
}

size_t evaluate_index(const Expr& index, EvalEnv& env) {
  const SourceLoc at = index.root()->start_loc();
  const double d = evaluate_number(index, env);
  if (d != std::trunc(d) || d < 0)
    fail(at,
         fmt::format("an index must be a whole number of at least 0, not {}", format_number(d)));
  if (d > kMaxIndex)
    fail(at, fmt::format("index {} is too large; the largest is {}", format_number(d),
                         format_number(kMaxIndex)));
  return static_cast<size_t>(d);
}

// Finds `field` in `obj`: fields are stored upper case, but a file edited by hand may
// spell them otherwise.
const json* find_field(const json& obj, const std::string& field) {
  auto it = obj.find(field);
  if (it != obj.end()) return &*it;
  for (auto i = obj.begin(); i != obj.end(); ++i) {
    const std::string& k = i.key();
    if (k.size() != field.size()) continue;
    bool same = true;
    for (size_t c = 0; c < k.size() && same; ++c)
      same = std::toupper(static_cast<unsigned char>(k[c])) == static_cast<unsigned char>(field[c]);
    if (same) return &*i;
  }
  return nullptr;
}

json to_json(const Value& v) {
  if (v.is_string()) return v.str();
  const double d = v.num();
  // Whole numbers are stored as integers so the persisted file reads `3`, not `3.0`.
  if (d == std::trunc(d) && std::fabs(d) < 9007199254740992.0)  // 2^53: exact in a double
    return static_cast<std::int64_t>(d);
  return d;
}

}  // namespace

std::string describe_path(std::string_view name, const std::vector<Accessor>& path, EvalEnv& env) {
  std::string out = root_name(name);
  for (const Accessor& a : path) {
    if (a.is_field) {
      out += "." + a.field;
    } else if (!a.index) {
      out += "[]";
    } else {
      try {
        out += fmt::format("[{}]", evaluate_index(*a.index, env));
      } catch (const GantryError&) {
        out += "[?]";
      }
    }
  }
  return out;
}

Value read_path(const json& root, const std::vector<Accessor>& path, EvalEnv& env,
                const SourceLoc& loc, std::string_view name, std::optional<size_t> placeholder) {
  std::string shown = root_name(name);
  const json* cur = &root;
  for (const Accessor& a : path) {
    const std::string parent = shown;
    if (a.is_field) {
      shown += "." + a.field;
      if (cur->is_array())
        fail(loc, fmt::format("{} is a list, so {} does not exist; read an element, as in {}[0]",
                              parent, shown, parent));
      if (!cur->is_object()) {
        if (cur->is_null()) fail(loc, fmt::format("{} is not set", shown));
        fail(loc, fmt::format("{} holds a single value, so {} does not exist", parent, shown));
      }
      cur = find_field(*cur, a.field);
      if (!cur) fail(loc, fmt::format("{} is not set", shown));
    } else {
      if (!a.index && !placeholder)
        fail(loc,
             fmt::format("empty index [] cannot be read; give the index, as in {}[%(25)]", parent));
      const size_t i = a.index ? evaluate_index(*a.index, env) : *placeholder;
      shown += fmt::format("[{}]", i);
      if (cur->is_object())
        fail(loc, fmt::format("{} has named fields, not a list; read a field, as in {}.NAME",
                              parent, parent));
      if (!cur->is_array()) {
        if (cur->is_null()) fail(loc, fmt::format("{} is not set", shown));
        fail(loc, fmt::format("{} holds a single value, so {} does not exist", parent, shown));
      }
      if (i >= cur->size()) fail(loc, fmt::format("{} is not set", shown));
      cur = &(*cur)[i];
    }
  }
  switch (cur->type()) {
    case json::value_t::null:
      fail(loc, fmt::format("{} is not set", shown));
    case json::value_t::string:
      return Value::string(cur->get<std::string>());
    case json::value_t::boolean:  // stored by another tool: the language's truth values
      return Value::number(cur->get<bool>() ? -1.0 : 0.0);
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
    case json::value_t::number_float:
      return Value::number(cur->get<double>());
    case json::value_t::array:
      fail(loc, fmt::format("{} is a list of values; read one element, as in {}[0]", shown, shown));
    default:
      fail(loc,
           fmt::format("{} is a group of fields; read one of them, as in {}.NAME", shown, shown));
  }
}

void assign_path(json& root, const std::vector<Accessor>& path, const Value& v, EvalEnv& env,
                 const SourceLoc& loc, std::optional<size_t> placeholder) {
  // Indices are evaluated before anything changes, so a failing index leaves the variable
  // as it was.
  std::vector<size_t> indices;
  for (const Accessor& a : path) {
    if (a.is_field) continue;
    if (!a.index && !placeholder) fail(loc, "empty index [] is not supported; give the index");
    indices.push_back(a.index ? evaluate_index(*a.index, env) : *placeholder);
  }
  // Null and single values along the way become the object or array the path needs (a
  // persistent variable outlives the program, so a program must be able to reshape it); a
  // list is never turned into fields or the other way round, which would lose its contents.
  json* cur = &root;
  size_t next_index = 0;
  for (const Accessor& a : path) {
    if (a.is_field) {
      if (cur->is_array())
        fail(loc, fmt::format("cannot set field .{}: that part of the variable is a list; use an "
                              "index such as [0]",
                              a.field));
      if (!cur->is_object()) *cur = json::object();
      cur = &(*cur)[a.field];
    } else {
      const size_t i = indices[next_index++];
      if (cur->is_object())
        fail(loc, fmt::format("cannot set index [{}]: that part of the variable has named "
                              "fields; use .NAME",
                              i));
      if (!cur->is_array()) *cur = json::array();
      if (cur->size() <= i) cur->get_ref<json::array_t&>().resize(i + 1);
      cur = &(*cur)[i];
    }
  }
  *cur = to_json(v);
}

}  // namespace gantry
