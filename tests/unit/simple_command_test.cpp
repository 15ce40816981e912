// The fast reading of simple command lines: what it accepts, and that what it accepts reads
// exactly as the general parser reads it.
#include <gtest/gtest.h>

#include <cmath>    // HUGE_VAL
#include <cstring>  // memcmp: -0 and 0 differ
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "../support/same_statement.hpp"   // simple_command_mismatch
#include "gantry/lang/number_literal.hpp"  // literal::value
#include "gantry/lang/parser.hpp"
#include "gantry/lang/script.hpp"
#include "lang/simple_command.hpp"  // simple_command_code

namespace gantry {
namespace {

const auto kFile = std::make_shared<const std::string>("part.sbp");

TEST(SimpleCommand, AcceptsCommandsWithPlainNumbersAndReadsThemAsTheParserDoes) {
  const std::vector<std::string> lines = {
      "M3, 1.5, -2, .25",
      "mx 5",
      "M2 , 4.2",
      "MX,",
      "J2,+.5,-0.",
      "  M3,1,,3,, \t",
      "MS, 4, 2",
      "m3,\t1.,  -.5 ,7",
      "J5,1,2,3,4,5",
      "MZ",
      "SA",
      "VS,,,,,2.5",
      "M2, 0000012.5",
      "M2, 1234567890123456, 0.1234567890123456789",
      "JH ,",
      "Z2",
      "MX, 99999999999999999999999999999999999999",
  };
  Statement fast;  // reused line after line, as the interpreter does
  for (size_t i = 0; i < lines.size(); ++i) {
    SCOPED_TRACE(lines[i]);
    EXPECT_TRUE(is_simple_command(lines[i]));
    ASSERT_TRUE(parse_simple_command(lines[i], kFile, static_cast<int>(i) + 1, &fast));
    EXPECT_EQ(testing::simple_command_mismatch(fast, parse_line(lines[i], kFile, i + 1)), "");
  }
}

TEST(SimpleCommand, LeavesEverythingElseToTheGeneralParser) {
  for (const std::string line : {"",
                                 "   ",
                                 "' comment",
                                 "REM x",
                                 "C3",
                                 "c12, 1",
                                 "IF 1 THEN MX, 2",
                                 "ON INPUT(1,1) END",
                                 "M3, 1e3",
                                 "M3, 1E-2",
                                 "M3, &x",
                                 "M3, 1 ' why",
                                 "MX:",
                                 "START:",
                                 "MXY, 1",
                                 "M3, - 5",
                                 "M3, .",
                                 "M3, +",
                                 "M3, -",
                                 "M3, 1.2.3",
                                 "M3, (1)",
                                 "M3, \"1\"",
                                 "M3, 1 2",
                                 "M3,5%",
                                 "MX, 1, 2x",
                                 "&x = 1",
                                 "M",
                                 "3M, 1",
                                 "M_, 1",
                                 "END",
                                 "GOTO A",
                                 "MX, 0x10",
                                 "MX;1",
                                 "MX, 123456789012345678901234567890123456789012"}) {
    SCOPED_TRACE(line);
    Statement st;
    EXPECT_FALSE(is_simple_command(line));
    EXPECT_FALSE(parse_simple_command(line, kFile, 1, &st));
  }
}

TEST(SimpleCommand, ReusedStorageHoldsOnlyTheCurrentLine) {
  Statement st;
  ASSERT_TRUE(parse_simple_command("M5, 1, 2, 3, 4, 5", kFile, 1, &st));
  ASSERT_TRUE(parse_simple_command("MX, , 7", kFile, 2, &st));
  EXPECT_EQ(testing::simple_command_mismatch(st, parse_line("MX, , 7", kFile, 2)), "");
  const auto& cmd = std::get<CommandStmt>(st.body);
  ASSERT_EQ(cmd.args.size(), 2u);
  EXPECT_TRUE(cmd.args[0].blank());
  EXPECT_EQ(cmd.args[0].loc.column, 4);  // a blank sits just after its comma
  EXPECT_EQ(*cmd.args[1].number, 7.0);
}

TEST(SimpleCommand, DecimalsRoundLikeTheLibraryConversion) {
  // Fast path (<= 15 digits) and slow path (more) both give the correctly rounded double.
  Statement st;
  for (const std::string lit : {"0.1", "0.3", "123456.789012345", "9007199254740993",
                                "0.000000000000000000001", "1.7976931348623157"}) {
    SCOPED_TRACE(lit);
    ASSERT_TRUE(parse_simple_command("MX, " + lit, kFile, 1, &st));
    EXPECT_EQ(*std::get<CommandStmt>(st.body).args[0].number, std::stod(lit));
  }
}

// The numbers are valued while their digits are scanned: the same doubles as from_chars
// (literal::value) for random literals and signs, short and long; is_simple_command gives the
// code parse_simple_command reads (simple_command_code, the load pass's check).
TEST(SimpleCommand, RandomNumbersReadTheSameDoublesAsFromCharsAndTheCodeIsTheCommands) {
  std::mt19937 rng(27);
  auto pick = [&](int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng); };
  Statement st;
  for (int n = 0; n < 100000; ++n) {
    std::string line = std::string(pick(2) ? "m" : "J") + static_cast<char>('2' + pick(4));
    std::vector<std::string> lits;
    const int params = 1 + pick(5);
    for (int p = 0; p < params; ++p) {
      std::string lit;
      const int whole = pick(20), decimals = pick(3) == 0 ? -1 : pick(19);  // <= 40 characters
      for (int k = 0; k < whole; ++k) lit += static_cast<char>('0' + pick(10));
      if (decimals >= 0) lit += '.';
      for (int k = 0; k < decimals; ++k) lit += static_cast<char>('0' + pick(10));
      if (lit.empty() || lit == ".") lit = "0";
      const int sign = pick(3);
      lits.push_back(lit);
      line += (pick(2) ? ", " : ",") + std::string(sign == 0 ? "-" : sign == 1 ? "+" : "") + lit;
      if (sign == 0) lits.back() = "-" + lit;
    }
    SCOPED_TRACE(line);
    char code[2] = {};
    ASSERT_TRUE(is_simple_command(line));
    ASSERT_TRUE(simple_command_code(line, code));
    ASSERT_TRUE(parse_simple_command(line, kFile, 1, &st));
    const auto& cmd = std::get<CommandStmt>(st.body);
    EXPECT_EQ(std::string(code, 2), cmd.code);
    ASSERT_EQ(cmd.args.size(), lits.size());
    for (size_t i = 0; i < lits.size(); ++i) {
      const bool neg = lits[i][0] == '-';
      const std::optional<double> v = literal::value(neg ? lits[i].substr(1) : lits[i]);
      const double want = v ? (neg ? -*v : *v) : (neg ? -HUGE_VAL : HUGE_VAL);
      ASSERT_TRUE(cmd.args[i].number);
      ASSERT_EQ(std::memcmp(&want, &*cmd.args[i].number, sizeof(double)), 0) << lits[i];
    }
    if (n % 100 == 0) {  // and the whole statement as the general parser reads it
      ASSERT_EQ(testing::simple_command_mismatch(st, parse_line(line, kFile, 1)), "");
    }
  }
}

TEST(ScriptParseCache, ALineParsedAgainComesFromTheCacheAndEvictionKeepsItRight) {
  std::string text;
  for (int i = 0; i < 5000; ++i)
    text += "&x" + std::to_string(i) + " = " + std::to_string(i) + "\n";
  const auto script = Script::from_text(text, "part.sbp");
  Cursor c = script->start(), next;
  const auto first = script->parse(c, &next);
  EXPECT_EQ(script->parse(c, &next).get(), first.get());            // a hit: the same parse
  for (Cursor k = next; !script->at_end(k);) script->parse(k, &k);  // fills every slot
  const auto again = script->parse(c, &next);
  ASSERT_TRUE(again->statement);
  EXPECT_EQ(std::get<AssignStmt>(again->statement->body).target.name, "X0");
  EXPECT_EQ(next.line, 2);
}

}  // namespace
}  // namespace gantry
