// The fast reading of the common statements (parse_common_statement): what it accepts, and
// that every line it accepts, from the part files at hand and from random lines, reads
// exactly as the general parser reads it; and how a script keeps a loop's lines it read.
#include <gtest/gtest.h>

#include <cstdlib>     // getenv
#include <cstring>     // memcmp
#include <filesystem>  // the part files
#include <fstream>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "../support/same_statement.hpp"   // common_statement_mismatch
#include "gantry/lang/check_only.hpp"      // ExprCheckOnly
#include "gantry/lang/expr_node.hpp"       // a number node's value
#include "gantry/lang/number_literal.hpp"  // literal::value, parse_number_literal
#include "gantry/lang/parser.hpp"
#include "gantry/lang/script.hpp"

namespace gantry {
namespace {

const auto kFile = std::make_shared<const std::string>("part.sbp");

// Empty when parse_common_statement rejects `line` or reads it as parse_line does.
std::string mismatch(const std::string& line, Statement* fast, bool* accepted = nullptr) {
  const bool ok = parse_common_statement(line, kFile, 7, fast);
  if (accepted) *accepted = ok;
  if (!ok) return {};
  return testing::common_statement_mismatch(*fast, parse_line(line, kFile, 7));
}

TEST(CommonStatement, ReadsTheCommonShapesAsTheParserDoes) {
  const std::vector<std::string> lines = {
      "&x = 1",
      "  &x=1.5  ",
      "&Foo_2 = &a + 12.5 * 2 - ABS(&b - 3)",
      "&b = (&a MOD 5) + SQR(13) / 4",
      "&i = -.25",
      "&x = 1e3",
      "&s = &a & &b",
      "&t = %(1) + 2",
      "&t = $tool.length * 2",
      "&x=&x+1",
      "\t&x =\t-&y ^ 2",
      "&d = &d + SIN(&a / 103) * 3",
      "&m = MIN(1, 2, &c, 4)",
      "&_ = 0",
      "IF &b > 6 THEN GOTO S1",
      "if &c < 0 then goto l12",
      "IF &x > 1.5 THEN &x = &x - 0.5",
      "IF (&a = 1) AND (&b <> 2) THEN GOSUB SUB_3",
      "IF &answer = Cancel THEN GOTO done",
      "IF &a THEN RETURN",
      "IF NOT &a THEN RETURN",
      "IF&a=1 THEN GOTO X",
      "IF &a = 1 THEN  &b=2",
      "GOTO LOOP",
      "goto loop",
      "GOSUB SUB3",
      "  GOSUB\tx_1  ",
      "RETURN",
      "return   ",
      "LOOP:",
      "l12:",
      "  Sub_3:",
      "1:",
      "GOTO:",
      "REMOVE:",
      "M3:",
  };
  Statement fast;  // reused line after line, as the interpreter does
  for (const std::string& line : lines) {
    SCOPED_TRACE(line);
    bool accepted = false;
    EXPECT_EQ(mismatch(line, &fast, &accepted), "");
    EXPECT_TRUE(accepted);
  }
}

TEST(CommonStatement, LeavesEverythingElseToTheGeneralParser) {
  for (const std::string line : {
           "",
           " ",
           "&",
           "' comment",
           "REM x",
           "&x = 1 ' why",
           "&s = \"text\"",
           "&x := 1",
           "$x = 1",
           "%(1) = 2",
           "&x[1] = 2",
           "&x.y = 2",
           "&1x = 2",
           "&x =",
           "&x == 1",
           "&x = Material Surface",
           "&x = &y +",
           "&x = SQR(1, 2)",
           "&x 1 = 2",
           "IF &a > 1 THEN MX, 1",
           "IF &a > 1 THEN",
           "IF THEN GOTO X",
           "IF &a > 1 GOTO X",
           "IF &a > 1 THEN IF &b THEN GOTO X",
           "IF &a > 1 THEN GOTO X:",
           "IF &a > 1 THEN GOTO A B",
           "IF &a > 1 THEN END",
           "IF &a > ) THEN GOTO X",
           "IFX = 1",
           "GOTO",
           "GOTO A B",
           "GOTO X:",
           "GOTO-X",
           "GOSUB",
           "GOTOX",
           "RETURN 5",
           "RETURN: 5",
           "END",
           "MX, 1",
           "START LOOP:",
           "N10:",
           "G1:",
           "M30:",
           "X: MX, 1",
           ":",
           "a-b:",
       }) {
    SCOPED_TRACE(line);
    Statement fast;
    EXPECT_FALSE(parse_common_statement(line, kFile, 1, &fast));
  }
}

// Checked without trees (the load pass): accepted all the same, the statement's parts the
// same, its expressions placeholders.
TEST(CommonStatement, ChecksWithoutBuildingTreesUnderExprCheckOnly) {
  Statement fast;
  const ExprCheckOnly check;
  ASSERT_TRUE(parse_common_statement("IF &a > 1 THEN &b = &a * 2", kFile, 3, &fast));
  const auto& s = std::get<IfStmt>(fast.body);
  EXPECT_EQ(std::get<AssignStmt>(s.action->body).target.name, "B");
  EXPECT_FALSE(parse_common_statement("IF &a > 1 THEN &b = &a *", kFile, 3, &fast));
}

// The lines of every part file at hand: parts/, tests/data, the shared corpus (beside the
// source tree, when it is there) and $GANTRY_CORPUS.
std::vector<std::string> corpus_lines() {
  std::vector<std::string> dirs = {GANTRY_SOURCE_DIR "/parts", GANTRY_SOURCE_DIR "/tests/data",
                                   GANTRY_SOURCE_DIR "/../shared/corpus"};
  if (const char* extra = std::getenv("GANTRY_CORPUS")) dirs.emplace_back(extra);
  std::vector<std::string> lines;
  for (const std::string& dir : dirs) {
    std::error_code ec;
    if (!std::filesystem::is_directory(dir, ec)) continue;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(dir, ec)) {
      if (!entry.is_regular_file()) continue;
      const std::string ext = entry.path().extension().string();
      if (ext != ".sbp" && ext != ".SBP" && ext != ".txt") continue;
      std::ifstream in(entry.path(), std::ios::binary);
      std::stringstream text;
      text << in.rdbuf();
      const auto script = Script::from_text(text.str(), entry.path().string());
      for (Cursor c = script->start(), next; !script->at_end(c); c = next)
        lines.emplace_back(script->line_at(c, &next));
    }
  }
  return lines;
}

TEST(CommonStatement, EveryCorpusLineItAcceptsReadsAsTheParserReadsIt) {
  const std::vector<std::string> lines = corpus_lines();
  ASSERT_GT(lines.size(), 1000u);
  Statement fast;
  size_t accepted = 0;
  for (const std::string& line : lines) {
    bool ok = false;
    const std::string why = mismatch(line, &fast, &ok);
    EXPECT_EQ(why, "") << "line: " << line;
    accepted += ok;
  }
  EXPECT_GT(accepted, 100u);  // the corpus has its assignments, IFs and labels
}

// Random lines from the pieces the common shapes are made of, and corpus lines with random
// edits: whatever is accepted must read as the general parser reads it.
TEST(CommonStatement, RandomLinesItAcceptsReadAsTheParserReadsThem) {
  const std::vector<std::string> pieces = {
      "&",   "&a",   "&x1",  "&_b",  "$v",   "%(",     "=",    "==",    ":=",     ":",      " ",
      "  ",  "\t",   "1",    "2.5",  ".5",   "1e3",    "-",    "+",     "*",      "/",      "\\",
      "^",   "(",    ")",    "[",    "]",    ",",      "\"",   "'",     "<",      ">",      "<>",
      "<=",  ">=",   "IF ",  "if",   "THEN", " THEN ", "then", "GOTO ", "GOSUB ", "RETURN", "MOD",
      "AND", " OR ", "NOT ", "SIN(", "ABS(", "MIN(",   "L1",   "sub_2", "X",      "N10",    "G1",
      "MX",  "REM",  "END",  "é",    "0",    "_",      "\r",   ";",     "!",      "#",      ".",
  };
  std::mt19937 rng(27);
  Statement fast;
  size_t accepted = 0;
  auto pick = [&](size_t n) { return std::uniform_int_distribution<size_t>(0, n - 1)(rng); };
  // Whole lines from the pieces, seeded with the shapes so that many are accepted.
  const std::vector<std::string> starts = {"&a = ", "IF ", "GOTO ",          "GOSUB ",
                                           "",      "L",   "IF &a > 1 THEN "};
  for (int n = 0; n < 200000; ++n) {
    std::string line = starts[pick(starts.size())];
    const size_t len = pick(8);
    for (size_t k = 0; k < len; ++k) line += pieces[pick(pieces.size())];
    bool ok = false;
    const std::string why = mismatch(line, &fast, &ok);
    ASSERT_EQ(why, "") << "line: " << line;
    accepted += ok;
  }
  EXPECT_GT(accepted, 5000u);
  // Corpus lines edited at random: a character dropped, doubled or replaced.
  const std::vector<std::string> lines = corpus_lines();
  for (int n = 0; n < 100000 && !lines.empty(); ++n) {
    std::string line = lines[pick(lines.size())];
    const int edits = 1 + static_cast<int>(pick(3));
    for (int k = 0; k < edits && !line.empty(); ++k) {
      const size_t at = pick(line.size());
      switch (pick(3)) {
        case 0:
          line.erase(at, 1);
          break;
        case 1:
          line.insert(at, 1, line[at]);
          break;
        default:
          line[at] = pieces[pick(pieces.size())][0];
      }
    }
    ASSERT_EQ(mismatch(line, &fast), "") << "line: " << line;
  }
}

// Number literals without an exponent are read by the fast exact path (literal::plain_value)
// in parse_number_literal and the expression lexer: the same doubles as from_chars gives.
TEST(CommonStatement, NumberLiteralsReadTheSameDoublesAsFromChars) {
  std::mt19937 rng(2027);
  auto pick = [&](int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng); };
  const SourceLoc at{kFile, 1, 1};
  for (int n = 0; n < 200000; ++n) {
    std::string lit;
    const int whole = pick(25), decimals = pick(3) == 0 ? -1 : pick(25);
    for (int k = 0; k < whole; ++k) lit += static_cast<char>('0' + pick(10));
    if (decimals >= 0) lit += '.';
    for (int k = 0; k < decimals; ++k) lit += static_cast<char>('0' + pick(10));
    if (literal::scan(lit, 0) != lit.size() || lit.empty()) continue;
    SCOPED_TRACE(lit);
    const std::optional<double> want = literal::value(lit);
    const std::optional<double> got = parse_number_literal(lit);
    ASSERT_EQ(want.has_value(), got.has_value());
    if (want) {
      ASSERT_EQ(std::memcmp(&*want, &*got, sizeof(double)), 0);
    }
    const ExprParse p = parse_expression(lit, at);
    ASSERT_EQ(want.has_value(), p.expr.has_value());
    if (want) {
      ASSERT_EQ(std::memcmp(&*want, &p.expr->root()->number, sizeof(double)), 0);
    }
  }
  // With an exponent the lexer takes the general reading; an `e` without digits after it is
  // no exponent (`5e` is 5 and a word), whatever the digits before it.
  for (int n = 0; n < 50000; ++n) {
    std::string lit;
    const int whole = 1 + pick(20), decimals = pick(3) == 0 ? -1 : pick(20);
    for (int k = 0; k < whole; ++k) lit += static_cast<char>('0' + pick(10));
    if (decimals >= 0) lit += '.';
    for (int k = 0; k < decimals; ++k) lit += static_cast<char>('0' + pick(10));
    std::string exp = pick(2) ? "e" : "E";
    if (pick(2)) exp += pick(2) ? "+" : "-";
    const std::string digits = std::to_string(pick(400));
    SCOPED_TRACE(lit + exp + digits);
    const std::optional<double> want = literal::value(lit + exp + digits);
    const ExprParse p = parse_expression(lit + exp + digits, at);
    ASSERT_EQ(want.has_value(), p.expr.has_value());
    if (want) {
      ASSERT_EQ(std::memcmp(&*want, &p.expr->root()->number, sizeof(double)), 0);
    }
    const ExprParse no_exponent = parse_expression(lit + exp + " + 1", at);
    ASSERT_FALSE(no_exponent.expr);  // the literal, then a word: two values without an operator
    ASSERT_EQ(no_exponent.error->loc.column, static_cast<int>(lit.size()) + 1);
  }
  for (const std::string& big : {std::string(400, '9'), std::string(400, '9') + ".5"}) {
    EXPECT_FALSE(parse_number_literal(big));
    EXPECT_FALSE(parse_expression(big, at).expr);
  }
}

// A loop's line read by read_common twice is kept in the parse cache, as parse() keeps one;
// the third pass takes it from there (read_common says no, parse() has it).
TEST(CommonStatement, AScriptKeepsALoopsLinesOnceReadTwice) {
  const auto script = Script::from_text("X:\n&i = &i + 1\nGOTO X\n", "loop.sbp");
  ASSERT_TRUE(script->ok());
  Cursor c, next;
  script->line_at(script->start(), &c);  // the second line
  const std::string line(script->line_at(c, &next));
  Statement out;
  EXPECT_TRUE(script->read_common(c, line, next, &out));
  EXPECT_TRUE(script->read_common(c, line, next, &out));
  EXPECT_FALSE(script->read_common(c, line, next, &out));
  Cursor after;
  const std::shared_ptr<const LineParse> kept = script->parse(c, &after);
  ASSERT_TRUE(kept->statement);
  EXPECT_EQ(after.offset, next.offset);
  EXPECT_EQ(testing::statement_mismatch(out, *kept->statement), "");
  EXPECT_EQ(testing::common_statement_mismatch(out, parse_line(line, script->name(), 2)), "");
}

}  // namespace
}  // namespace gantry
