// The TOML form of a profile: every key, in the schema parse_settings_table reads.
#include <fmt/format.h>

#include "gantry/settings/settings_schema.hpp"  // the keys
#include "settings_private.hpp"

namespace gantry {
namespace {

template <class T>
std::string joined(const T* items, size_t count) {
  std::string out;
  for (size_t k = 0; k < count; ++k) out += fmt::format("{}{}", k ? ", " : "", items[k]);
  return out;
}

// The table at a dotted path under `root`, made when missing.
toml::table& table_at(toml::table& root, std::string_view path) {
  toml::table* t = &root;
  while (!path.empty()) {
    const size_t dot = path.find('.');
    const std::string_view part = path.substr(0, dot);
    path = dot == std::string_view::npos ? std::string_view{} : path.substr(dot + 1);
    t = t->emplace<toml::table>(part).first->second.as_table();
  }
  return *t;
}

void write_row(toml::table& root, const SettingRow& row, int i, const Settings& s) {
  Settings& m = const_cast<Settings&>(s);  // the fields are only read
  const void* field = row.field ? row.field(m, i) : nullptr;
  const std::string key = row.key_at(i);
  auto put = [&](auto&& value) { table_at(root, row.section_at(i)).insert(key, value); };
  switch (row.kind) {
    case SettingKind::Number:
      return put(*static_cast<const double*>(field));
    case SettingKind::OptionalNumber:
      if (const auto& v = *static_cast<const std::optional<double>*>(field)) put(*v);
      return;
    case SettingKind::Integer:
      return put(*static_cast<const int*>(field));
    case SettingKind::Bool:
      return put(*static_cast<const bool*>(field));
    case SettingKind::Choice:
      return put(std::string(row.names[static_cast<size_t>(row.choice_get(s, i))]));
    case SettingKind::Text: {
      const std::string& v = *static_cast<const std::string*>(field);
      if (!(row.omit_empty && v.empty())) put(v);
      return;
    }
    case SettingKind::Texts: {
      const auto& v = *static_cast<const std::vector<std::string>*>(field);
      if (row.omit_empty && v.empty()) return;
      toml::array items;
      for (const std::string& item : v) items.push_back(item);
      return put(std::move(items));
    }
    case SettingKind::IntList:
      if (row.count == 0) {
        const auto& v = *static_cast<const std::vector<int>*>(field);
        if (row.omit_empty && v.empty()) return;
        return put(joined(v.data(), v.size()));
      }
      return put(joined(static_cast<const int*>(field), static_cast<size_t>(row.count)));
    case SettingKind::NumberList:
      return put(joined(static_cast<const double*>(field), static_cast<size_t>(row.count)));
    case SettingKind::LineBits: {
      const bool bit_first = row.names[0] == "BIT:LINE";
      std::string out;
      for (const GpioLineBit& b : *static_cast<const std::vector<GpioLineBit>*>(field))
        out += bit_first ? fmt::format("{}{}:{}", out.empty() ? "" : ", ", b.bit, b.line)
                         : fmt::format("{}{}:{}", out.empty() ? "" : ", ", b.line, b.bit);
      return put(out);
    }
    case SettingKind::Coded: {
      const std::string v = row.encode(s);
      if (!(row.omit_empty && v.empty())) put(v);
      return;
    }
  }
}

}  // namespace

toml::table settings_table(const Settings& s) {
  toml::table root;
  for (const SettingRow& row : settings_schema())
    for (int i = 0; i < row.size(); ++i) write_row(root, row, i, s);
  return root;
}

}  // namespace gantry
