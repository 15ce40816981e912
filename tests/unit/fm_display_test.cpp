// G58's display line (and G25's): the manual's two worked examples, read from their verbatim
// command text, and the rules they show (upper case, one space, four decimals).
#include <gtest/gtest.h>

#include <array>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "gantry/interp/fm_display.hpp"

namespace gantry {
namespace {

// A G58 tail as the manual writes it ("text" elements, Vxx, Ay), read by this test alone (the
// parser is the FM front end's), its values looked up in `v` and `a`.
std::vector<FmDisplayItem> items_of(std::string_view tail, const std::map<int, double>& v,
                                    const std::map<int, std::string>& a) {
  std::vector<FmDisplayItem> out;
  std::size_t i = 0;
  while (i < tail.size()) {
    if (tail[i] == '"') {
      const std::size_t close = tail.find('"', i + 1);
      out.push_back(FmDisplayItem::quoted(tail.substr(i + 1, close - i - 1)));
      i = close + 1;
      continue;
    }
    const char letter = tail[i++];
    int n = 0;
    while (i < tail.size() && tail[i] >= '0' && tail[i] <= '9') n = n * 10 + (tail[i++] - '0');
    if (letter == 'V')
      out.push_back(FmDisplayItem::value(v.at(n)));
    else
      out.push_back(FmDisplayItem::string(a.at(n)));
  }
  return out;
}

// Seed 004, L580-587: `V1=3`, then the G58 displays THE VALUE OF V1 IS 3.0000.
TEST(FmDisplay, TheManualsVariableExample) {
  const auto items = items_of(R"("The""value""of""V1""is"V1)", {{1, 3.0}}, {});
  EXPECT_EQ(fm_display_line(items), "THE VALUE OF V1 IS 3.0000");
}

// Seed 004, L589-595: `A0=312A3`, then the G58 displays THE PART NUMBER IS 312A3.
TEST(FmDisplay, TheManualsStringExample) {
  const auto items = items_of(R"("The""Part""Number""is"A0)", {}, {{0, "312A3"}});
  EXPECT_EQ(fm_display_line(items), "THE PART NUMBER IS 312A3");
}

TEST(FmDisplay, ElementsInAnyOrderOneSpaceApartStringsInUpperCase) {
  const auto items = items_of(R"(A2V7"mm"V8A2)", {{7, -2.5}, {8, 12.0}}, {{2, "lot7b"}});
  EXPECT_EQ(fm_display_line(items), "LOT7B -2.5000 MM 12.0000 LOT7B");
  EXPECT_EQ(fm_display_line(std::vector<FmDisplayItem>{}), "");
  const std::array one{FmDisplayItem::quoted("done")};
  EXPECT_EQ(fm_display_line(one), "DONE");
}

TEST(FmDisplay, NumbersHaveFourDecimalsAndNoSignedZero) {
  EXPECT_EQ(fm_number_text(3), "3.0000");
  EXPECT_EQ(fm_number_text(1.23456), "1.2346");
  EXPECT_EQ(fm_number_text(-0.00004), "0.0000");
  EXPECT_EQ(fm_number_text(-0.0), "0.0000");
  EXPECT_EQ(fm_number_text(-0.00005001), "-0.0001");
  EXPECT_EQ(fm_number_text(123456.5), "123456.5000");
}

}  // namespace
}  // namespace gantry
