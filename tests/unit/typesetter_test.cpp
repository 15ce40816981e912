// TT and Gantry's single-stroke font: every printable ASCII character has a glyph inside its
// box, and the part file TT writes engraves the letters where and how deep it was asked.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "../support/interpreter_fixture.hpp"
#include "../support/temp_dir.hpp"
#include "gantry/commands/command_table.hpp"
#include "gantry/commands/stroke_font.hpp"
#include "gantry/core/diagnostic.hpp"
#include "gantry/interp/interpreter.hpp"
#include "gantry/lang/script.hpp"
#include "gantry/settings/settings.hpp"

namespace gantry {
namespace {

namespace fs = std::filesystem;

// ---- the font -------------------------------------------------------------------------------

TEST(StrokeFont, EveryPrintableAsciiCharacterHasAGlyphInsideItsBox) {
  for (int c = ' '; c <= '~'; ++c) {
    const StrokeGlyph* g = StrokeFont::glyph(static_cast<char>(c));
    ASSERT_NE(g, nullptr) << c;
    EXPECT_GT(g->width, 0) << static_cast<char>(c);
    EXPECT_EQ(g->strokes.empty(), c == ' ') << static_cast<char>(c);
    for (const auto& stroke : g->strokes)
      for (const auto& p : stroke) {
        EXPECT_GE(p[0], 0) << static_cast<char>(c);
        EXPECT_LE(p[0], g->width) << static_cast<char>(c);
        EXPECT_GE(p[1], StrokeFont::kDescent) << static_cast<char>(c);
        EXPECT_LE(p[1], StrokeFont::kCapHeight + 0.5) << static_cast<char>(c);
      }
  }
  for (char c : {'\t', '\n', '\x7f', '\x1f', static_cast<char>(0xc3)})
    EXPECT_EQ(StrokeFont::glyph(c), nullptr) << static_cast<int>(c);
}

TEST(StrokeFont, NoTwoCharactersLookAlike) {
  std::set<std::string> seen;
  for (int c = '!'; c <= '~'; ++c) {
    const StrokeGlyph* g = StrokeFont::glyph(static_cast<char>(c));
    std::string key = fmt::format("{}|", g->width);
    for (const auto& stroke : g->strokes) {
      for (const auto& p : stroke) key += fmt::format("{},{} ", p[0], p[1]);
      key += ";";
    }
    EXPECT_TRUE(seen.insert(key).second) << static_cast<char>(c);
  }
}

TEST(StrokeFont, LettersSitOnTheirLines) {
  // Capitals reach the cap height, lower case the x-height, descenders go below the baseline.
  auto top = [](char c) {
    double y = -1e9;
    for (const auto& s : StrokeFont::glyph(c)->strokes)
      for (const auto& p : s) y = std::max(y, p[1]);
    return y;
  };
  auto bottom = [](char c) {
    double y = 1e9;
    for (const auto& s : StrokeFont::glyph(c)->strokes)
      for (const auto& p : s) y = std::min(y, p[1]);
    return y;
  };
  for (char c = 'A'; c <= 'Z'; ++c) {
    EXPECT_EQ(top(c), StrokeFont::kCapHeight) << c;
    EXPECT_EQ(bottom(c), c == 'Q' ? -0.5 : 0) << c;
  }
  for (char c = '0'; c <= '9'; ++c) EXPECT_EQ(top(c), StrokeFont::kCapHeight) << c;
  for (char c : std::string("acemnorsuvwxz")) {
    EXPECT_EQ(top(c), StrokeFont::kXHeight) << c;
    EXPECT_EQ(bottom(c), 0) << c;
  }
  for (char c : std::string("gjpqy")) EXPECT_EQ(bottom(c), StrokeFont::kDescent) << c;
  EXPECT_EQ(StrokeFont::advance('H'), 5);
  EXPECT_EQ(StrokeFont::advance('i'), 2);
}

// ---- TT -------------------------------------------------------------------------------------

class TypesetterTest : public KeptInterpreterFixture {
 protected:
  std::string path(const std::string& name) const { return (fs::path(dir_.path()) / name).string(); }
  std::string slurp(const std::string& name) const { return dir_.read(name); }

  void run(const std::string& text) {
    fresh_interp();
    run_program(Script::from_text(text, path("part.sbp")));
  }
  Diagnostic run_error(const std::string& text) {
    auto script = Script::from_text(text, path("part.sbp"));
    fresh_interp();
    return program_error(script, text);
  }

  // The XY box of the moves made below the surface.
  struct Box {
    double x0 = 1e9, y0 = 1e9, x1 = -1e9, y1 = -1e9, zmin = 1e9;
  };
  Box cut_box() const {
    Box b;
    for (const CanonMove& m : sink.moves) {
      if (m.kind != MoveKind::Line) continue;
      b.zmin = std::min(b.zmin, m.to[2]);
      if (m.to[2] < 0 && m.from[2] < 0) {
        for (const Vec6* p : {&m.from, &m.to}) {
          b.x0 = std::min(b.x0, (*p)[0]), b.x1 = std::max(b.x1, (*p)[0]);
          b.y0 = std::min(b.y0, (*p)[1]), b.y1 = std::max(b.y1, (*p)[1]);
        }
      }
    }
    return b;
  }

 private:
  TempDir dir_{"typesetter_test"};
};

TEST_F(TypesetterTest, TtEngravesTheLettersWhereAsked) {
  // "HI" 0.6 tall: H is 4 units wide, a gap of 1, I 2: 0.7 wide at 0.1 per unit.
  run("TT, sign.sbp, HI, 2, 3, 0.6, 0.05\nFP, sign.sbp\n");
  EXPECT_TRUE(printed.starts_with("TT wrote 2 characters (6 strokes) to " + path("sign.sbp")))
      << printed;
  const Box b = cut_box();
  EXPECT_NEAR(b.x0, 2, 1e-9);
  EXPECT_NEAR(b.x1, 2.7, 1e-9);
  EXPECT_NEAR(b.y0, 3, 1e-9);
  EXPECT_NEAR(b.y1, 3.6, 1e-9);
  EXPECT_NEAR(b.zmin, -0.05, 1e-9);
  // The first stroke: H's left stem, up from the start of the baseline, at move speed.
  const std::string text = slurp("sign.sbp");
  EXPECT_TRUE(text.find("' H\nJ2, 2, 3\nMZ, -0.05\nM2, 2, 3.6\nJZ, ") != std::string::npos) << text;
  // Every stroke starts at safe Z (the profile's above the surface) and ends there.
  const double safe = settings.cutter.safe_z;
  int plunges = 0;
  for (size_t i = 1; i < sink.moves.size(); ++i)
    if (sink.moves[i].to[2] < 0 && sink.moves[i].from[2] >= 0) {
      ++plunges;
      EXPECT_NEAR(sink.moves[i].from[2], safe, 1e-9);
    }
  EXPECT_EQ(plunges, 6);  // H 3, I 3
  EXPECT_NEAR(sink.moves.back().to[2], safe, 1e-9);
}

TEST_F(TypesetterTest, PassesGoBackAlongTheStrokeOneDeeperEachTime) {
  run("TT, l.sbp, l, 0, 0, 0.6, 0.1, 2\nFP, l.sbp\n");
  // l is one stroke from (0.05, 0.6) down to (0.05, 0): down, then back up one deeper.
  EXPECT_NE(slurp("l.sbp").find("J2, 0.05, 0.6\nMZ, -0.05\nM2, 0.05, 0\nMZ, -0.1\nM2, 0.05, "
                                "0.6\nJZ, "),
            std::string::npos)
      << slurp("l.sbp");
  EXPECT_NEAR(cut_box().zmin, -0.1, 1e-9);
}

TEST_F(TypesetterTest, ADotIsAPlunge) {
  run("TT, dot.sbp, \".\", 1, 1, 0.6, 0.02, , 0.5\n");
  EXPECT_NE(slurp("dot.sbp").find("JZ, 0.5\n' .\nJ2, 1.05, 1\nMZ, -0.02\nJZ, 0.5\n"),
            std::string::npos)
      << slurp("dot.sbp");
}

TEST_F(TypesetterTest, TheAngleTurnsTheBaselineAboutTheStart) {
  run("TT, up.sbp, \"L-\", 5, 1, 0.6, 0.05, 1, , 90\nFP, up.sbp\n");
  // Turned a quarter left: the text runs up +Y from (5, 1), the letters' tops toward -X.
  const Box b = cut_box();
  EXPECT_NEAR(b.x0, 5 - 0.6, 1e-9);  // L's top
  EXPECT_NEAR(b.x1, 5, 1e-9);        // the baseline
  EXPECT_NEAR(b.y0, 1, 1e-9);
  EXPECT_NEAR(b.y1, 1 + 0.8, 1e-9);  // L 4 + gap 1 + "-" 3 = 8 units
}

TEST_F(TypesetterTest, SpacesAdvanceAndEveryCharacterIsDrawn) {
  std::string all;
  for (char c = ' '; c <= '~'; ++c)
    if (c != '"') all += c;
  run("TT, all.sbp, \"" + all + "\", 0, 0, 0.06, 0.01\n");
  const std::string text = slurp("all.sbp");
  EXPECT_NE(text.find("' ~\n"), std::string::npos);
  EXPECT_NE(text.find("' ,\n"), std::string::npos);
  EXPECT_TRUE(printed.starts_with("TT wrote 94 characters (")) << printed;
}

TEST_F(TypesetterTest, ErrorsAreLocatedAndWriteNothing) {
  struct Case {
    std::string line;
    int column;
    std::string message;
  } cases[] = {
      {"TT, x.sbp, \"Caf\xc3\xa9\", 0, 0, 1, 0.1", 12,
       "TT: character 4 of the text is outside ASCII; the font draws the printable ASCII "
       "characters (space to ~) only"},
      {"TT, x.sbp, \"   \", 0, 0, 1, 0.1", 12, "TT needs some text to engrave (parameter 2)"},
      {"TT, x.sbp, AB, 0, 0, 0, 0.1", 22, "height (TT) is 0; it must be above 0"},
      {"TT, x.sbp, AB, 0, 0, 1, -0.1", 25, "depth (TT) is -0.1; it must be above 0"},
      {"TT, x.sbp, AB, 0, 0, 1, 0.1, 0", 30, "passes (TT) is 0; it must be a whole number"},
      {"TT, x.sbp, AB, 0, 0, 1", 1, "TT needs its parameter 6 (depth)"},
  };
  for (const Case& c : cases) {
    const Diagnostic d = run_error(c.line + "\n");
    EXPECT_TRUE(d.message.starts_with(c.message)) << c.line << ": " << d.message;
    EXPECT_EQ(d.loc.column, c.column) << c.line;
  }
  EXPECT_FALSE(fs::exists(path("x.sbp")));
  EXPECT_TRUE(sink.moves.empty());
}

TEST_F(TypesetterTest, TheTableSaysWhatTtLacks) {
  const CommandSpec* tt = CommandTable::standard().find("TT");
  EXPECT_NE(tt->coverage, "");
  EXPECT_NE(tt->coverage, "not implemented");
  EXPECT_NE(std::string(tt->coverage).find("V-carving"), std::string::npos);
}

}  // namespace
}  // namespace gantry
