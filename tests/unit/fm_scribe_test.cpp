// G10 / G16 / G19, Friendly Motion's character scribing. The golden polylines are worked out by
// hand from the glyph table in src/commands/stroke_font.cpp (H: width 4, strokes 0,0-0,6;
// 4,0-4,6; 0,3-4,3 ...), scaled as the manual says (1" high, 2:1 height to width): they check
// the font's data and the scaling, not a copy of the code. The insertion examples are the
// manual's (seed 004, L415-440), with the deviations the digest decides (§7.9).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "gantry/core/diagnostic.hpp"
#include "gantry/interp/fm_scribe.hpp"

namespace gantry {
namespace {

// Where G16's text starts: `G16"` is columns 5-8 of its line, so the text's first character is
// at column 9.
const SourceLoc kText = file_loc("scribe.fm", 4, 9);

using Strokes = std::vector<std::vector<FmPoint>>;

void expect_strokes(const Strokes& got, const Strokes& want) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t s = 0; s < want.size(); ++s) {
    ASSERT_EQ(got[s].size(), want[s].size()) << "stroke " << s;
    for (std::size_t p = 0; p < want[s].size(); ++p) {
      EXPECT_NEAR(got[s][p][0], want[s][p][0], 1e-12) << "stroke " << s << " point " << p;
      EXPECT_NEAR(got[s][p][1], want[s][p][1], 1e-12) << "stroke " << s << " point " << p;
    }
  }
}

// The error `f` throws: at line 4, `column`, its message holding every one of `words`.
template <typename F>
void expect_error(F&& f, int column, const std::vector<std::string>& words) {
  try {
    f();
    ADD_FAILURE() << "no error";
  } catch (const GantryError& e) {
    const Diagnostic& d = e.diagnostic();
    EXPECT_EQ(d.loc.line, 4);
    EXPECT_EQ(d.loc.column, column) << d.message;
    for (const std::string& w : words)
      EXPECT_NE(d.message.find(w), std::string::npos) << d.message << " lacks " << w;
  }
}

FmScribePath scribe(const std::string& text, double height = 1) {
  return fm_scribe(text, 0, "", {height, 0.5}, kText);
}

// At 1": a font unit across is 0.5/4 = 0.125 (the H is half as wide as high), up 1/6.
// H (width 4, advance 5 = 0.625), then I (width 2: 0,6-2,6; 1,6-1,0; 0,0-2,0) from x 0.625;
// the table ends where a third character would start, 0.625 + 3 x 0.125 = 1.0.
TEST(FmScribe, TheWordHiAtOneInch) {
  const FmScribePath p = scribe("HI");
  expect_strokes(p.strokes, {{{0, 0}, {0, 1}},
                             {{0.5, 0}, {0.5, 1}},
                             {{0, 0.5}, {0.5, 0.5}},
                             {{0.625, 1}, {0.875, 1}},
                             {{0.75, 1}, {0.75, 0}},
                             {{0.625, 0}, {0.875, 0}}});
  EXPECT_DOUBLE_EQ(p.end[0], 1.0);
  EXPECT_DOUBLE_EQ(p.end[1], 0.0);
  // The start is the lower left corner of the first character.
  double min_x = 1e9, min_y = 1e9;
  for (const auto& s : p.strokes)
    for (const FmPoint& q : s) {
      min_x = std::min(min_x, q[0]);
      min_y = std::min(min_y, q[1]);
    }
  EXPECT_EQ(min_x, 0);
  EXPECT_EQ(min_y, 0);
}

// G19 2 in millimetres: 50.8 mm high, everything twice 25.4 times the inch figures.
TEST(FmScribe, G19ScalesHeightAndWidthTogether) {
  const double h = fm_character_height(2, true, kText);
  EXPECT_DOUBLE_EQ(h, 50.8);
  EXPECT_DOUBLE_EQ(fm_character_height(2, false, kText), 2.0);
  EXPECT_DOUBLE_EQ(fm_character_height(0.25, false, kText), 0.25);  // absolute, not cumulative
  const FmScribePath p = scribe("HI", h);
  const FmScribePath one = scribe("HI");
  ASSERT_EQ(p.strokes.size(), one.strokes.size());
  for (std::size_t s = 0; s < p.strokes.size(); ++s)
    for (std::size_t k = 0; k < p.strokes[s].size(); ++k) {
      EXPECT_NEAR(p.strokes[s][k][0], one.strokes[s][k][0] * 50.8, 1e-9);
      EXPECT_NEAR(p.strokes[s][k][1], one.strokes[s][k][1] * 50.8, 1e-9);
    }
  EXPECT_NEAR(p.end[0], 50.8, 1e-9);
  for (double bad : {0.0, -1.0, std::nan("")})
    expect_error([&] { fm_character_height(bad, false, kText); }, 9, {"G19", "above 0"});
}

// `)` is a new line 1.5 heights down, back at the start's X: 1 (width 4: 1,5 2,6 2,0; 1,0 3,0),
// then 2 (0,5 1,6 3,6 4,5 4,4 0,0 4,0) on the line below. A `.` is a dot: one point.
TEST(FmScribe, NewLineAndDot) {
  const FmScribePath p = scribe("1)2.");
  const double y = -1.5, s = 1.0 / 6;
  expect_strokes(p.strokes, {{{0.125, 5 * s}, {0.25, 1}, {0.25, 0}},
                             {{0.125, 0}, {0.375, 0}},
                             {{0, y + 5 * s},
                              {0.125, y + 1},
                              {0.375, y + 1},
                              {0.5, y + 5 * s},
                              {0.5, y + 4 * s},
                              {0, y},
                              {0.5, y}},
                             {{0.625 + 0.0625, y}}});
  // 2 (advance 0.625) and . (width 1, advance 0.25) on the second line.
  EXPECT_DOUBLE_EQ(p.end[0], 0.875);
  EXPECT_DOUBLE_EQ(p.end[1], -1.5);
  EXPECT_DOUBLE_EQ(scribe("AB)").end[0], 0);
  EXPECT_DOUBLE_EQ(scribe("AB)").end[1], -1.5);
}

// The manual's first example, G16"HELLO,_MARY: advances from the font table (letters 4 + 1,
// the comma 1 + 1, the space 2 + 1), so M starts at font unit 30, and 16 strokes in all.
TEST(FmScribe, HelloMary) {
  const FmScribePath p = scribe("HELLO,_MARY");
  EXPECT_EQ(p.strokes.size(), 16u);
  EXPECT_DOUBLE_EQ(p.end[0], 50 * 0.125);
  // M (0,0 0,6 2,3 4,6 4,0) is stroke 10 (index 9): after H 3, E 2, L 1, L 1, O 1, the comma 1.
  expect_strokes({p.strokes[9]}, {{{3.75, 0}, {3.75, 1}, {4.0, 0.5}, {4.25, 1}, {4.25, 0}}});
  // The comma (0.5,0.5 0.5,0 0,-1) reaches below the baseline, from x 25 units.
  expect_strokes({p.strokes[8]}, {{{3.1875, 0.5 / 6}, {3.1875, 0}, {3.125, -1.0 / 6}}});
  // `_` prints as a space: the same as H_H with a blank.
  EXPECT_DOUBLE_EQ(scribe("H_H").strokes[3][0][0], (5 + 3) * 0.125);
}

// The glyph table as src/commands/stroke_font.cpp writes it, read from the source text here
// (`{4, "0,0 2,6 4,0; 0.67,2 3.33,2"},  // A`): width and strokes by character.
struct SourceGlyph {
  double width = 0;
  std::vector<std::vector<FmPoint>> strokes;
};
std::map<char, SourceGlyph> glyph_table_source() {
  std::ifstream in(GANTRY_SOURCE_DIR "/src/commands/stroke_font.cpp");
  const std::regex entry(R"re(^\s*\{([0-9.]+), "([^"]*)"\},\s*// (\S+)\s*$)re");
  std::map<char, SourceGlyph> out;
  for (std::string line; std::getline(in, line);) {
    std::smatch m;
    if (!std::regex_match(line, m, entry)) continue;
    const std::string name = m[3];
    const char c = name == "backslash" ? '\\' : name == "space" ? ' ' : name[0];
    SourceGlyph g;
    g.width = std::stod(m[1]);
    std::vector<FmPoint> stroke;
    std::istringstream points(std::regex_replace(std::string(m[2]), std::regex(";"), " ; "));
    for (std::string p; points >> p;) {
      if (p == ";") {
        g.strokes.push_back(stroke);
        stroke.clear();
        continue;
      }
      const std::size_t comma = p.find(',');
      stroke.push_back({std::stod(p.substr(0, comma)), std::stod(p.substr(comma + 1))});
    }
    if (!stroke.empty()) g.strokes.push_back(stroke);
    out[c] = g;
  }
  return out;
}

// Every character of the manual's set, a new line among them, at G19 0.25: each stroke where
// the font's source puts it, scaled 0.25/8 across and 0.25/6 up from its pen position.
TEST(FmScribe, TheWholeCharacterSetFollowsTheFontSource) {
  const std::map<char, SourceGlyph> table = glyph_table_source();
  ASSERT_GE(table.size(), 60u) << "the glyph table's layout changed";
  const std::string text = "ABCDEFGHIJKLMNOPQRSTUVWXYZ)0123456789_!#'*+,-./:;<=>[\\]^";
  const double h = 0.25, kx = h / 8, ky = h / 6;
  Strokes want;
  double pen = 0, base = 0;
  for (char c : text) {
    if (c == ')') {
      pen = 0;
      base -= 1.5 * h;
      continue;
    }
    const SourceGlyph& g = table.at(c == '_' ? ' ' : c);
    for (const auto& s : g.strokes) {
      std::vector<FmPoint>& out = want.emplace_back();
      for (const FmPoint& p : s) out.push_back({(pen + p[0]) * kx, base + p[1] * ky});
    }
    pen += g.width + 1;
  }
  const FmScribePath got = fm_scribe(text, 0, "", {h, 0.5}, kText);
  expect_strokes(got.strokes, want);
  EXPECT_NEAR(got.end[0], pen * kx, 1e-12);
  EXPECT_NEAR(got.end[1], -1.5 * h, 1e-12);
}

TEST(FmScribe, LowerCaseIsScribedAsCapitals) {
  const FmScribePath a = scribe("serial9"), b = scribe("SERIAL9");
  expect_strokes(a.strokes, b.strokes);
}

TEST(FmScribe, TheCharacterSetIsTheManuals) {
  for (char c : std::string("ABCXYZ0189!#'*+,-./:;<=>[\\]^ ")) EXPECT_TRUE(fm_scribable(c)) << c;
  for (char c : std::string("\"$&(?@`{|}~a%_)\t")) EXPECT_FALSE(fm_scribable(c)) << c;
  // Each refused character named, at its own column (the text starts at column 9).
  expect_error([] { scribe("AB?C"); }, 11, {"cannot scribe '?'", "A-Z, 0-9"});
  expect_error([] { scribe("X&"); }, 10, {"'&'"});
  expect_error([] { scribe("(1"); }, 9, {"'('"});
  expect_error([] { scribe("A\tB"); }, 10, {"the byte 9"});
  expect_error([] { scribe(""); }, 9, {"no text"});
}

// Seed 004, L415-440, with @0 = ABCD and V73 = 66.55.
TEST(FmScribeInsert, TheManualsExamples) {
  auto in = [](const char* t) { return fm_scribe_insert(t, 66.55, "ABCD", kText); };
  EXPECT_EQ(in("HELLO,_MARY"), "HELLO,_MARY");
  EXPECT_EQ(in("%f"), "66.55");  // the manual's bare %f: shortest, not C's 66.550000
  EXPECT_EQ(in("%I"), "66");     // truncated, in either case
  EXPECT_EQ(in("%i"), "66");
  EXPECT_EQ(in("%c"), "B");
  EXPECT_EQ(in("%s"), "ABCD");
  EXPECT_EQ(in("%sEFGH"), "ABCDEFGH");  // the manual prints "%EFGH": its s was lost
  // printf's width: the manual shows V73=66.55 and COUNT=066; C gives a blank (digest §7.9).
  EXPECT_EQ(in("V73=%6.2f"), "V73= 66.55");
  EXPECT_EQ(in("COUNT=_%3i"), "COUNT=_ 66");
  EXPECT_EQ(in("COUNT=_%03i"), "COUNT=_066");
}

TEST(FmScribeInsert, PrintfFlagsWidthAndPrecision) {
  auto in = [](const char* t, double v, const char* s = "") {
    return fm_scribe_insert(t, v, s, kText);
  };
  EXPECT_EQ(in("%-5i|", 42), "42   |");
  EXPECT_EQ(in("%+i", 42), "+42");
  EXPECT_EQ(in("%i", -3.7), "-3");  // toward zero
  EXPECT_EQ(in("%.3f", 2.5), "2.500");
  EXPECT_EQ(in("%08.2f", -2.5), "-0002.50");
  EXPECT_EQ(in("%.2s", 0, "ABCD"), "AB");
  EXPECT_EQ(in("%6s", 0, "AB"), "    AB");
  EXPECT_EQ(in("%-3c|", 65), "A  |");
  EXPECT_EQ(in("%f", 3), "3");
}

TEST(FmScribeInsert, ErrorsPointAtTheirColumn) {
  auto in = [](const char* t, double v = 66.55) { fm_scribe_insert(t, v, "ABCD", kText); };
  expect_error([&] { in("%EFGH"); }, 10, {"%E puts in nothing"});
  expect_error([&] { in("A%s%i"); }, 12, {"one variable"});
  expect_error([&] { in("AB%"); }, 11, {"followed by s"});
  expect_error([&] { in("%5.2"); }, 9, {"followed by s"});
  expect_error([&] { in("%+s"); }, 9, {"flag '+'", "%s"});
  expect_error([&] { in("%.2c"); }, 9, {"%c takes no precision"});
  expect_error([&] { in("%123i"); }, 9, {"two digits"});
  expect_error([&] { in("%c", 10); }, 9, {"%c", "10", "printable"});
  expect_error([&] { in("%i", 1e300); }, 9, {"too large"});
  expect_error([&] { in("%f", std::nan("")); }, 9, {"not a number"});
}

// What the variable puts in is scribed by the same rules, and an error there points at the %.
TEST(FmScribe, InsertedTextIsScribedByTheSameRules) {
  const FmScribePath p = fm_scribe("N%s", 0, "a_b", {1, 0.5}, kText);
  expect_strokes(p.strokes, scribe("NA_B").strokes);
  expect_error([] { fm_scribe("N%s", 0, "a&b", {1, 0.5}, kText); }, 10, {"'&'", "(put in by %s)"});
  expect_error([] { fm_scribe("=%c", 63, "", {1, 0.5}, kText); }, 10, {"'?'", "(put in by %c)"});
}

TEST(FmScribe, BadStyleIsRefused) {
  expect_error([] { fm_scribe("A", 0, "", {0, 0.5}, kText); }, 9, {"above 0"});
  expect_error([] { fm_scribe("A", 0, "", {1, -1}, kText); }, 9, {"above 0"});
}

TEST(FmFontFile, OnlyTheDefaultFontFileIsAccepted) {
  fm_select_font("fontfile.txt", kText);
  fm_select_font("FONTFILE.TXT", kText);
  fm_select_font("C:\\USL\\fontfile.txt", kText);
  expect_error([] { fm_select_font("script.fnt", kText); }, 9,
               {"G10\"script.fnt\"", "format", "stroke font"});
}

}  // namespace
}  // namespace gantry
