// The settings schema: its rows drive the readers, the writer, the unit change, VR and the docs.
#include "gantry/settings/settings_schema.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "gantry/settings/settings.hpp"

namespace gantry {
namespace {

std::string settings_doc() {
  std::ifstream in(std::string(GANTRY_SOURCE_DIR) + "/docs/settings.md");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Each schema row is a line of docs/settings.md's key table, with the schema's range and help.
TEST(SettingsSchemaDocs, EveryRowIsInTheKeyTable) {
  const std::string doc = settings_doc();
  ASSERT_FALSE(doc.empty());
  for (const SettingRow& row : settings_schema()) {
    const std::string line = "| `" + row.path() + "` | " + row.type_name() + " | " + row.allowed() +
                             " | " + std::string(row.help) + " |\n";
    EXPECT_NE(doc.find(line), std::string::npos) << "docs/settings.md lacks the line\n" << line;
    if (row.unit == SettingUnit::Length) {
      EXPECT_NE(row.help.find("(a length)"), std::string::npos) << row.path();
    }
  }
}

// The key table lists no key the schema lacks: each of its rows is a schema row.
TEST(SettingsSchemaDocs, TheKeyTableListsOnlySchemaRows) {
  const std::string doc = settings_doc();
  const size_t table = doc.find("| key | type | allowed | meaning |");
  ASSERT_NE(table, std::string::npos);
  const size_t end = doc.find("\n\n", table);
  std::istringstream lines(doc.substr(table, end - table));
  std::string line;
  int keys = 0;
  while (std::getline(lines, line)) {
    if (!line.starts_with("| `")) continue;
    const std::string path = line.substr(3, line.find('`', 3) - 3);
    EXPECT_NO_THROW(setting_row(path)) << "docs/settings.md lists " << path;
    ++keys;
  }
  EXPECT_EQ(keys, static_cast<int>(settings_schema().size()));
}

TEST(SettingsSchema, PathsAreUniqueAndFound) {
  for (const SettingRow& row : settings_schema()) {
    EXPECT_EQ(&setting_row(row.path()), &row);
    if (row.kind == SettingKind::Number &&
        row.family != SettingFamily::Groups) {  // speeds: 0 until a profile sets them
      for (int i = 0; i < row.size(); ++i)
        EXPECT_TRUE(row.range.contains(row.get(Settings{}, i))) << row.path(i);
    }
  }
  EXPECT_THROW(setting_row("ramps.no_such_key"), std::out_of_range);
  EXPECT_EQ(settings_schema("ramps").size(), 7u);
  EXPECT_EQ(settings_schema("tabs").size(), 4u);
}

// The ramp rates have one range in the profile and in VR (issue 24: they had drifted).
TEST(SettingsSchema, RampRateRangeIsOne) {
  for (const char* key :
       {"ramps.move_ramp_rate", "ramps.jog_ramp_rate", "ramps.keypad_ramp_rate"}) {
    const SettingRow& row = setting_row(key);
    EXPECT_EQ(row.range.docs(), "1e-06 to 1000000") << key;
    Settings s;
    EXPECT_FALSE(set_setting(s, row, 0));
    EXPECT_FALSE(set_setting(s, row, 5e-7));
    EXPECT_DOUBLE_EQ(row.get(s), 0.2);
    EXPECT_TRUE(set_setting(s, row, 1e-6));
    EXPECT_DOUBLE_EQ(row.get(s), 1e-6);
  }
}

TEST(SettingsSchema, ProfileRejectsARampRateBelowTheRange) {
  std::string text = default_profile_text();
  const size_t at = text.find("move_ramp_rate");
  ASSERT_NE(at, std::string::npos);
  const size_t eol = text.find('\n', at);
  text.replace(at, eol - at, "move_ramp_rate = 1e-7");
  const SettingsLoad l = parse_settings(text, "p.toml");
  ASSERT_EQ(l.errors.size(), 1u);
  EXPECT_EQ(l.errors[0].message,
            "ramps.move_ramp_rate = 1e-07 is out of range; allowed: >= 1e-06 and <= 1000000");
}

TEST(SettingsSchema, LengthRowsFollowTheUnits) {
  Settings s;
  s.ramps.move_ramp_rate = 1;
  s.ramps.threshold_3d = 50;
  convert_units(s, Units::Millimetres);
  EXPECT_DOUBLE_EQ(s.ramps.move_ramp_rate, 25.4);
  EXPECT_DOUBLE_EQ(s.ramps.threshold_3d, 50);  // a percent: unchanged
}

// The tables a profile may leave out are the schema's: every row of such a table says so.
TEST(SettingsSchema, OptionalTablesAreTheRows) {
  std::set<std::string> optional;
  for (const SettingRow& row : settings_schema())
    if (row.optional_table) optional.insert(std::string(row.section));
  EXPECT_EQ(optional, (std::set<std::string>{"feed_override", "files", "friendly_motion", "limits",
                                             "pendant", "simulator", "spindle", "toolchanger"}));
  for (const SettingRow& row : settings_schema())
    EXPECT_EQ(row.optional_table, optional.count(std::string(row.section)) == 1) << row.path();
}

// The speeds' bound is their row's: (0, the axis max_speed], XY's the lower of X's and Y's.
TEST(SettingsSchema, SpeedRowsAreBoundedByTheAxisMaxSpeed) {
  Settings s;
  s.axes[0].max_speed = 4;
  s.axes[1].max_speed = 3;
  s.axes[2].max_speed = 2;
  for (const char* table : {"speeds.move", "speeds.jog"}) {
    const SettingRow& row = settings_schema(table).front();
    EXPECT_EQ(row.range_in(s, 0).hi, 3) << table;
    EXPECT_EQ(row.range_in(s, 1).hi, 2) << table;
    EXPECT_FALSE(row.range_in(s, 1).contains(0)) << table;
  }
  EXPECT_EQ(settings_schema("ramps.move_speed").front().range_in(s, 0).hi, 1e5);
}

}  // namespace
}  // namespace gantry
