// The label index: every label of a long file found at its line, names past a page, and the
// jumps to labels that never come reported where they are, in the file's order.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <optional>
#include <string>
#include <vector>

#include "gantry/core/diagnostic.hpp"  // format
#include "gantry/lang/script.hpp"
#include "lang/label_index.hpp"

namespace gantry {
namespace {

TEST(LabelIndex, ANameIsOneNumberAndTheFirstDefinitionStays) {
  LabelIndex labels;
  const LabelIndex::Id a = labels.intern("A");
  EXPECT_EQ(labels.intern("B"), a + 1);
  EXPECT_EQ(labels.intern("A"), a);
  EXPECT_FALSE(labels.at(a));  // named by a jump, not defined yet
  EXPECT_FALSE(labels.find("A"));
  EXPECT_FALSE(labels.find("C"));  // never named
  EXPECT_TRUE(labels.define(a, Cursor{40, 3}));
  EXPECT_FALSE(labels.define(a, Cursor{90, 7}));
  ASSERT_TRUE(labels.find("A"));
  EXPECT_EQ(labels.find("A")->offset, 40u);
  EXPECT_EQ(labels.find("A")->line, 3);
}

TEST(LabelIndex, NamesLongerThanAPageAndManyOfThemKeepTheirText) {
  LabelIndex labels;
  const std::string long_name(100000, 'L');  // more than a 64 KiB page of names
  for (int i = 0; i < 50000; ++i) {
    const std::string name = i == 777 ? long_name : fmt::format("N{}", i);
    ASSERT_EQ(labels.intern(name), static_cast<LabelIndex::Id>(i));
    labels.define(i, Cursor{static_cast<size_t>(i) * 10, i + 2});
  }
  EXPECT_EQ(labels.name(777), long_name);
  for (int i = 0; i < 50000; ++i) {
    const std::string name = i == 777 ? long_name : fmt::format("N{}", i);
    ASSERT_EQ(labels.name(i), name);
    const std::optional<Cursor> at = labels.find(name);
    ASSERT_TRUE(at) << name;
    EXPECT_EQ(at->line, i + 2);
    EXPECT_EQ(at->offset, static_cast<size_t>(i) * 10);
  }
}

// 20,000 labels, each jumped to from before it (forward) and after it (backward), and two
// labels that never come, jumped to from several lines: every label is at the line after
// it, and each jump to a missing label is one error at its line and column, in file order.
TEST(LabelIndex, ALongFilesLabelsAndItsJumpsToMissingOnes) {
  std::string text = "&x = 0\n";
  int line = 1;
  std::vector<int> label_line(20000);
  std::vector<std::string> expected;
  for (int k = 0; k < 20000; ++k) {
    text += fmt::format("IF &x > 1 THEN GOTO L{}\n", k);  // forward
    ++line;
    text += fmt::format("L{}:\n", k);
    label_line[k] = ++line;
    if (k % 5000 == 17) {
      text += fmt::format("GOSUB NEVER{}\n", k % 2);
      expected.push_back(fmt::format("part.sbp:{}:7: error: no label NEVER{}", ++line, k % 2));
    }
    text += fmt::format("IF &x > 2 THEN GOTO L{}\n", k / 2);  // backward
    ++line;
  }
  const auto script = Script::from_text(text, "part.sbp");
  ASSERT_EQ(script->errors().size(), expected.size());
  for (size_t i = 0; i < expected.size(); ++i)
    EXPECT_EQ(format(script->errors()[i]).substr(0, expected[i].size()), expected[i]);
  for (int k = 0; k < 20000; ++k) {
    const std::optional<Cursor> at = script->label(fmt::format("L{}", k));
    ASSERT_TRUE(at) << k;
    EXPECT_EQ(at->line, label_line[k] + 1);
  }
  EXPECT_FALSE(script->label("NEVER0"));
}

}  // namespace
}  // namespace gantry
