#include <gtest/gtest.h>

#include <string>
#include <variant>
#include <vector>

#include "../support/where.hpp"
#include "gantry/core/diagnostic.hpp"
#include "gantry/lang/parser.hpp"
#include "gantry/lang/script.hpp"

namespace gantry {
namespace {

// Every line of a text, parsed: its statements in order and the errors of the lines that
// are not statements (the label index's own checks are tested with Script).
struct Program {
  std::shared_ptr<const std::string> file;
  std::vector<Statement> statements;
  std::vector<Diagnostic> errors;
  bool ok() const { return errors.empty(); }
};

Program parse_lines(const Script& script) {
  Program p;
  p.file = script.name();
  if (!script.ok() && script.line_count() == 0) p.errors = script.errors();
  for (Cursor c = script.start(); !script.at_end(c);) {
    Cursor next;
    const std::shared_ptr<const LineParse> lp = script.parse(c, &next);
    if (lp->statement) p.statements.push_back(*lp->statement);
    if (lp->error) p.errors.push_back(*lp->error);
    c = next;
  }
  return p;
}

Program parse(std::string_view text) {
  return parse_lines(*Script::from_text(std::string(text), "part.sbp"));
}

Program parse_file(const std::string& path) {
  return parse_lines(*Script::load(path));
}

// The command of statement i; fails the test if it is not a command.
const CommandStmt& command(const Program& p, size_t i) {
  static const CommandStmt none{};
  if (i >= p.statements.size()) {
    ADD_FAILURE() << "no statement " << i << "; the program has " << p.statements.size();
    return none;
  }
  const auto* cmd = std::get_if<CommandStmt>(&p.statements[i].body);
  if (!cmd) {
    ADD_FAILURE() << "statement " << i << " is not a command";
    return none;
  }
  return *cmd;
}

std::vector<std::string> param_texts(const CommandStmt& cmd) {
  std::vector<std::string> out;
  for (const Arg& p : cmd.args) out.push_back(p.text);
  return out;
}

// "FILE:LINE:COL" of a location, so that one expectation checks all three.
using Texts = std::vector<std::string>;

// ---- comments and blank lines

TEST(Parser, EmptyTextGivesNoStatementsAndNoErrors) {
  const Program p = parse("");
  EXPECT_TRUE(p.ok());
  EXPECT_TRUE(p.statements.empty());
  ASSERT_TRUE(p.file);
  EXPECT_EQ(*p.file, "part.sbp");
}

TEST(Parser, BlankAndWhitespaceOnlyLinesAreSkipped) {
  const Program p = parse("\n   \n\t\nMX, 1\n\n");
  ASSERT_TRUE(p.ok());
  ASSERT_EQ(p.statements.size(), 1u);
  EXPECT_EQ(p.statements[0].loc.line, 4);
}

TEST(Parser, ApostropheCommentLinesAreSkipped) {
  const Program p = parse("' a comment, with commas\n   ' indented comment\nMX, 1\n");
  ASSERT_TRUE(p.ok());
  ASSERT_EQ(p.statements.size(), 1u);
  EXPECT_EQ(command(p, 0).code, "MX");
  EXPECT_EQ(p.statements[0].loc.line, 3);
}

TEST(Parser, RemCommentLinesAreSkippedInAnyCase) {
  const Program p = parse("REM a remark, MX 5\nrem lower case\n  Rem\tmixed\nREM\nMY, 2\n");
  ASSERT_TRUE(p.ok());
  ASSERT_EQ(p.statements.size(), 1u);
  EXPECT_EQ(command(p, 0).code, "MY");
  EXPECT_EQ(p.statements[0].loc.line, 5);
}

TEST(Parser, WordStartingWithRemIsNotAComment) {
  const Program p = parse("REMARK 5\n");
  ASSERT_EQ(p.errors.size(), 1u);
  EXPECT_TRUE(p.statements.empty());
  EXPECT_EQ(where(p.errors[0].loc), "part.sbp:1:1");
  EXPECT_NE(p.errors[0].message.find("unknown statement 'REMARK'"), std::string::npos)
      << p.errors[0].message;
}

// ---- commands and their parameters

TEST(Parser, CommandCodeIsUpperCased) {
  const Program p = parse("mx, 5\nJz, 1\n");
  ASSERT_TRUE(p.ok());
  ASSERT_EQ(p.statements.size(), 2u);
  EXPECT_EQ(command(p, 0).code, "MX");
  EXPECT_EQ(command(p, 1).code, "JZ");
}

TEST(Parser, CommandWithoutParameters) {
  const Program p = parse("SA\n");
  ASSERT_TRUE(p.ok());
  ASSERT_EQ(p.statements.size(), 1u);
  EXPECT_EQ(command(p, 0).code, "SA");
  EXPECT_TRUE(command(p, 0).args.empty());
}

TEST(Parser, SpaceCommaAndCommaSpaceSeparatorsAreEquivalent) {
  for (const char* text : {"MX 5", "MX, 5", "MX,5", "MX\t5"}) {
    SCOPED_TRACE(text);
    const Program p = parse(text);
    ASSERT_TRUE(p.ok());
    ASSERT_EQ(p.statements.size(), 1u);
    EXPECT_EQ(command(p, 0).code, "MX");
    EXPECT_EQ(param_texts(command(p, 0)), Texts{"5"});
  }
}

// The handbook's rule: a run of spaces is the separator, so a comma after it opens a blank
// first field. `M2 , 4.2` moves Y, not X.
TEST(Parser, SpaceThenCommaLeavesTheFirstParameterBlank) {
  for (const char* text : {"M2 , 4.2", "M2,, 4.2"}) {
    SCOPED_TRACE(text);
    const Program p = parse(text);
    ASSERT_TRUE(p.ok());
    EXPECT_EQ(param_texts(command(p, 0)), (Texts{"", "4.2"}));
  }
  EXPECT_EQ(param_texts(command(parse("M2 4.2"), 0)), Texts{"4.2"});
}

TEST(Parser, ParametersAreTrimmed) {
  const Program p = parse("M3,  1 ,\t2\t,3   \n");
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(param_texts(command(p, 0)), (Texts{"1", "2", "3"}));
}

TEST(Parser, SpaceSeparatorKeepsFollowingCommaSeparatedParameters) {
  const Program p = parse("M3 1, 2, 3\n");
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(param_texts(command(p, 0)), (Texts{"1", "2", "3"}));
}

TEST(Parser, BlankParameterIsKeptAsEmptyText) {
  const Program p = parse("M3, , 2\n");
  ASSERT_TRUE(p.ok());
  const CommandStmt& cmd = command(p, 0);
  ASSERT_EQ(cmd.args.size(), 2u);
  EXPECT_TRUE(cmd.args[0].blank());
  EXPECT_EQ(cmd.args[0].text, "");
  EXPECT_FALSE(cmd.args[1].blank());
  EXPECT_EQ(cmd.args[1].text, "2");
}

TEST(Parser, AdjacentCommasGiveBlankParameters) {
  const Program p = parse("M3,,,4\n");
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(param_texts(command(p, 0)), (Texts{"", "", "4"}));
}

TEST(Parser, TrailingBlankParametersAreDropped) {
  const Program p = parse("MX, 5,\nM3, 1, , ,\nM3, , ,\n");
  ASSERT_TRUE(p.ok());
  ASSERT_EQ(p.statements.size(), 3u);
  EXPECT_EQ(param_texts(command(p, 0)), Texts{"5"});
  EXPECT_EQ(param_texts(command(p, 1)), Texts{"1"});
  EXPECT_TRUE(command(p, 2).args.empty());
}

TEST(Parser, TrailingCommentAfterParametersIsIgnored) {
  const Program p = parse("M2, 1, 2 ' go to 1, 2, 3\n");
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(param_texts(command(p, 0)), (Texts{"1", "2"}));
}

TEST(Parser, CommentDirectlyAfterParameterOrCode) {
  const Program p = parse("MX, 5' tight comment\nSA ' distance mode\nSR'x\n");
  ASSERT_TRUE(p.ok());
  ASSERT_EQ(p.statements.size(), 3u);
  EXPECT_EQ(param_texts(command(p, 0)), Texts{"5"});
  EXPECT_TRUE(command(p, 1).args.empty());
  EXPECT_EQ(command(p, 2).code, "SR");
  EXPECT_TRUE(command(p, 2).args.empty());
}

TEST(Parser, QuotedParameterKeepsCommasAndApostrophes) {
  const Program p = parse("MX, \"a, it's\", 2\n");
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(param_texts(command(p, 0)), (Texts{"\"a, it's\"", "2"}));
}

// ---- labels and END

TEST(Parser, LabelIsUpperCasedAndLocated) {
  const Program p = parse("SA\n  start:\nLOOP_2 :  ' comment\n");
  ASSERT_TRUE(p.ok());
  ASSERT_EQ(p.statements.size(), 3u);
  const auto* l1 = std::get_if<LabelStmt>(&p.statements[1].body);
  const auto* l2 = std::get_if<LabelStmt>(&p.statements[2].body);
  ASSERT_NE(l1, nullptr);
  ASSERT_NE(l2, nullptr);
  EXPECT_EQ(l1->name, "START");
  EXPECT_EQ(l2->name, "LOOP_2");
  EXPECT_EQ(where(p.statements[1].loc), "part.sbp:2:3");
  EXPECT_EQ(where(p.statements[2].loc), "part.sbp:3:1");
}

TEST(Parser, TextAfterLabelIsAnErrorAtTheText) {
  const Program p = parse("START: MX, 5\n");
  EXPECT_TRUE(p.statements.empty());
  ASSERT_EQ(p.errors.size(), 1u);
  EXPECT_EQ(where(p.errors[0].loc), "part.sbp:1:8");
  EXPECT_EQ(p.errors[0].message,
            "unexpected text after the label; put the next statement on its own line");
}

TEST(Parser, EndInAnyCaseIsAnEndStatement) {
  const Program p = parse("MX, 1\nend\n  END ' done\n");
  ASSERT_TRUE(p.ok());
  ASSERT_EQ(p.statements.size(), 3u);
  EXPECT_TRUE(std::holds_alternative<EndStmt>(p.statements[1].body));
  EXPECT_TRUE(std::holds_alternative<EndStmt>(p.statements[2].body));
  EXPECT_EQ(where(p.statements[2].loc), "part.sbp:3:3");
}

TEST(Parser, EndWithParametersIsAnErrorAtTheParameter) {
  const Program p = parse("END 5\n");
  EXPECT_TRUE(p.statements.empty());
  ASSERT_EQ(p.errors.size(), 1u);
  EXPECT_EQ(where(p.errors[0].loc), "part.sbp:1:5");
  EXPECT_EQ(p.errors[0].message, "END takes no parameters, or a message in quotes");
}

TEST(Parser, StatementsAfterEndAreStillParsed) {
  const Program p = parse("END\nMX, 1\n");
  ASSERT_TRUE(p.ok());
  ASSERT_EQ(p.statements.size(), 2u);
  EXPECT_EQ(command(p, 1).code, "MX");
}

// ---- line endings

TEST(Parser, WindowsLineEndingsParseLikeUnix) {
  const Program p = parse("' comment\r\nSA\r\nMX, 5\r\nM3, 1, , 2 \r\nSTART:\r\nEND\r\n");
  ASSERT_TRUE(p.ok()) << format(p.errors.front());
  ASSERT_EQ(p.statements.size(), 5u);
  EXPECT_EQ(command(p, 0).code, "SA");
  EXPECT_TRUE(command(p, 0).args.empty());
  EXPECT_EQ(param_texts(command(p, 1)), Texts{"5"});
  EXPECT_EQ(param_texts(command(p, 2)), (Texts{"1", "", "2"}));
  ASSERT_TRUE(std::holds_alternative<LabelStmt>(p.statements[3].body));
  EXPECT_EQ(std::get<LabelStmt>(p.statements[3].body).name, "START");
  EXPECT_TRUE(std::holds_alternative<EndStmt>(p.statements[4].body));
  EXPECT_EQ(p.statements[4].loc.line, 6);
}

TEST(Parser, WindowsLineEndingsKeepColumns) {
  const Program p = parse("SA\r\n  MX, 5\r\n");
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(where(p.statements[1].loc), "part.sbp:2:3");
  EXPECT_EQ(where(command(p, 1).args[0].loc), "part.sbp:2:7");
}

TEST(Parser, LastLineWithoutNewlineIsParsed) {
  const Program p = parse("SA\nMX, 5");
  ASSERT_TRUE(p.ok());
  ASSERT_EQ(p.statements.size(), 2u);
  EXPECT_EQ(param_texts(command(p, 1)), Texts{"5"});
}

// ---- locations

TEST(Parser, StatementLocationIsTheFirstCharacterOfTheCode) {
  const Program p = parse("SA\n\n   mx, 5\n");
  ASSERT_TRUE(p.ok());
  ASSERT_EQ(p.statements.size(), 2u);
  EXPECT_EQ(where(p.statements[0].loc), "part.sbp:1:1");
  EXPECT_EQ(where(p.statements[1].loc), "part.sbp:3:4");
}

TEST(Parser, ParameterLocationsAreTheirFirstCharacter) {
  // Columns: M3 at 1, "1.5" at 5, "-2" at 11, "3" at 15.
  const Program p = parse("SA\nM3, 1.5,  -2 ,3\n");
  ASSERT_TRUE(p.ok());
  const CommandStmt& cmd = command(p, 1);
  ASSERT_EQ(cmd.args.size(), 3u);
  EXPECT_EQ(where(cmd.args[0].loc), "part.sbp:2:5");
  EXPECT_EQ(where(cmd.args[1].loc), "part.sbp:2:11");
  EXPECT_EQ(where(cmd.args[2].loc), "part.sbp:2:15");
}

TEST(Parser, SpaceSeparatedParameterLocation) {
  const Program p = parse("MX   7\n");
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(where(command(p, 0).args[0].loc), "part.sbp:1:6");
}

TEST(Parser, BlankParameterIsLocatedJustAfterItsComma) {
  // `M3, , 2`: the blank field starts at column 4, right after the comma at column 3.
  const Program p = parse("M3, , 2\n");
  ASSERT_TRUE(p.ok());
  const CommandStmt& cmd = command(p, 0);
  ASSERT_EQ(cmd.args.size(), 2u);
  EXPECT_EQ(where(cmd.args[0].loc), "part.sbp:1:4");
  EXPECT_EQ(where(cmd.args[1].loc), "part.sbp:1:7");
}

TEST(Parser, AllLocationsShareTheFileName) {
  const Program p = parse_lines(*Script::from_text("MX, 1\n", "dir/job.sbp"));
  ASSERT_TRUE(p.ok());
  ASSERT_TRUE(p.file);
  EXPECT_EQ(*p.file, "dir/job.sbp");
  EXPECT_EQ(p.statements[0].loc.file, p.file);
  EXPECT_EQ(command(p, 0).args[0].loc.file, p.file);
}

// ---- errors

TEST(Parser, UnknownLongStatementIsAnErrorAtItsStart) {
  const Program p = parse("SA\n  PAUSEX 3\n");
  ASSERT_EQ(p.errors.size(), 1u);
  EXPECT_EQ(where(p.errors[0].loc), "part.sbp:2:3");
  EXPECT_EQ(p.errors[0].severity, Severity::Error);
  EXPECT_EQ(p.errors[0].message,
            "unknown statement 'PAUSEX'; commands are two characters, such as MX or J3, and "
            "statements are words such as IF, GOTO or PAUSE");
  ASSERT_EQ(p.statements.size(), 1u);  // only SA
}

TEST(Parser, CodeStartingWithADigitIsAnError) {
  const Program p = parse("3M, 1\n");
  EXPECT_TRUE(p.statements.empty());
  ASSERT_EQ(p.errors.size(), 1u);
  EXPECT_EQ(where(p.errors[0].loc), "part.sbp:1:1");
  EXPECT_NE(p.errors[0].message.find("unknown statement '3M'"), std::string::npos);
}

TEST(Parser, OneLetterCodeIsAnError) {
  const Program p = parse("M 5\n");
  EXPECT_TRUE(p.statements.empty());
  ASSERT_EQ(p.errors.size(), 1u);
  EXPECT_EQ(where(p.errors[0].loc), "part.sbp:1:1");
  EXPECT_NE(p.errors[0].message.find("unknown statement 'M'"), std::string::npos);
}

TEST(Parser, CodeRunIntoNumberWithoutSeparatorIsAnError) {
  // `MX5` is not taken as `MX, 5`: the handbook requires a separator (`M23, 4.2` is wrong).
  const Program p = parse("SA\nMX5\n");
  ASSERT_EQ(p.statements.size(), 1u);
  ASSERT_EQ(p.errors.size(), 1u);
  EXPECT_EQ(where(p.errors[0].loc), "part.sbp:2:3");
  EXPECT_EQ(p.errors[0].message, "expected a space or a comma after the command MX; write `MX, 5`");
}

TEST(Parser, CodeRunIntoSignedNumberIsAnErrorAtTheNumber) {
  const Program p = parse("MX-5\n");
  EXPECT_TRUE(p.statements.empty());
  ASSERT_EQ(p.errors.size(), 1u);
  EXPECT_EQ(where(p.errors[0].loc), "part.sbp:1:3");
  EXPECT_EQ(p.errors[0].message,
            "expected a space or a comma after the command MX; write `MX, -5`");
}

TEST(Parser, MissingSeparatorSuggestionStopsAtComma) {
  const Program p = parse("M2.5, 1\n");
  ASSERT_EQ(p.errors.size(), 1u);
  EXPECT_EQ(where(p.errors[0].loc), "part.sbp:1:3");
  EXPECT_EQ(p.errors[0].message,
            "expected a space or a comma after the command M2; write `M2, .5`");
}

TEST(Parser, MissingSeparatorSuggestionOnAWindowsLineHasNoCarriageReturn) {
  const Program p = parse("MX-5\r\nMX-5 ' c\n");
  ASSERT_EQ(p.errors.size(), 2u);
  EXPECT_EQ(where(p.errors[0].loc), "part.sbp:1:3");
  EXPECT_EQ(p.errors[0].message,
            "expected a space or a comma after the command MX; write `MX, -5`");
  EXPECT_EQ(where(p.errors[1].loc), "part.sbp:2:3");
  EXPECT_EQ(p.errors[1].message,
            "expected a space or a comma after the command MX; write `MX, -5`");
}

TEST(Parser, UnexpectedCharacterAtStatementStart) {
  const Program p = parse("  , MX 5\n");
  EXPECT_TRUE(p.statements.empty());
  ASSERT_EQ(p.errors.size(), 1u);
  EXPECT_EQ(where(p.errors[0].loc), "part.sbp:1:3");
  EXPECT_EQ(p.errors[0].message,
            "unexpected ',' at the start of a statement; a line starts with a "
            "command, a statement, a label or a comment");
}

TEST(Parser, UnclosedQuoteIsAnError) {
  const Program p = parse("SA\nMX \"abc\n");
  ASSERT_EQ(p.statements.size(), 1u);
  ASSERT_EQ(p.errors.size(), 1u);
  EXPECT_EQ(where(p.errors[0].loc), "part.sbp:2:4");
  EXPECT_EQ(p.errors[0].message, "this parameter opens a quote (\") that is never closed");
}

TEST(Parser, UnclosedQuoteHidesApostropheComment) {
  // The apostrophe is inside the open quote, so it does not start a comment.
  const Program p = parse("MX \"abc ' not a comment\n");
  ASSERT_EQ(p.errors.size(), 1u);
  EXPECT_EQ(where(p.errors[0].loc), "part.sbp:1:4");
}

TEST(Parser, UnclosedQuoteAfterCommaIsLocatedAtTheQuote) {
  const Program p = parse("MX, \"abc\n");
  ASSERT_EQ(p.errors.size(), 1u);
  EXPECT_EQ(where(p.errors[0].loc), "part.sbp:1:5");
}

TEST(Parser, BadLineAddsNoStatement) {
  const Program p = parse("MX, \"abc\nMY, 1\n");
  ASSERT_EQ(p.errors.size(), 1u);
  ASSERT_EQ(p.statements.size(), 1u);
  EXPECT_EQ(command(p, 0).code, "MY");
}

TEST(Parser, EveryBadLineIsReportedAndGoodLinesAreKept) {
  const Program p = parse(
      "SA\n"           // 1
      "PAUSEX 3\n"     // 2
      "MX, 1\n"        // 3
      "MX5\n"          // 4
      "' comment\n"    // 5
      "MY \"open\n"    // 6
      "START: MX 1\n"  // 7
      "END 1\n"        // 8
      "  *\n"          // 9
      "MY, 2\n");      // 10
  ASSERT_EQ(p.errors.size(), 6u);
  EXPECT_EQ(where(p.errors[0].loc), "part.sbp:2:1");
  EXPECT_EQ(where(p.errors[1].loc), "part.sbp:4:3");
  EXPECT_EQ(where(p.errors[2].loc), "part.sbp:6:4");
  EXPECT_EQ(where(p.errors[3].loc), "part.sbp:7:8");
  EXPECT_EQ(where(p.errors[4].loc), "part.sbp:8:5");
  EXPECT_EQ(where(p.errors[5].loc), "part.sbp:9:3");
  ASSERT_EQ(p.statements.size(), 3u);
  EXPECT_EQ(p.statements[0].loc.line, 1);
  EXPECT_EQ(p.statements[1].loc.line, 3);
  EXPECT_EQ(p.statements[2].loc.line, 10);
  EXPECT_FALSE(p.ok());
}

TEST(Parser, ErrorFormatsAsFileLineColumn) {
  const Program p = parse("\nPAUSEX 3\n");
  ASSERT_EQ(p.errors.size(), 1u);
  EXPECT_EQ(format(p.errors[0]),
            "part.sbp:2:1: error: unknown statement 'PAUSEX'; commands are two characters, such "
            "as MX or J3, and statements are words such as IF, GOTO or PAUSE");
}

// ---- files

// ---- spellings from ShopBot's own files (issue 21)

// `C#, n` is ShopBot's spelling of `C<n>`: the number is the first parameter.
TEST(Parser, ComputedCustomCutTakesItsNumberFromTheFirstParameter) {
  const Program p = parse("C#,90\nC#, &tool, 2\nc# 5\nC#7\nC211\n");
  ASSERT_TRUE(p.ok()) << format(p.errors[0]);
  ASSERT_EQ(p.statements.size(), 5u);
  const auto* c90 = std::get_if<CustomCutStmt>(&p.statements[0].body);
  ASSERT_TRUE(c90);
  EXPECT_EQ(c90->number, 90);
  EXPECT_FALSE(c90->computed);
  EXPECT_TRUE(c90->args.empty());
  const auto* var = std::get_if<CustomCutStmt>(&p.statements[1].body);
  ASSERT_TRUE(var);
  ASSERT_TRUE(var->computed);
  EXPECT_EQ(var->computed->text, "&tool");
  EXPECT_EQ(where(var->computed->loc), "part.sbp:2:5");
  EXPECT_EQ(param_texts(CommandStmt{"", var->args}), (Texts{"2"}));
  EXPECT_EQ(std::get<CustomCutStmt>(p.statements[2].body).number, 5);
  EXPECT_EQ(std::get<CustomCutStmt>(p.statements[3].body).number, 7);
  EXPECT_EQ(std::get<CustomCutStmt>(p.statements[4].body).number, 211);  // FabMo's macro numbers
}

TEST(Parser, ComputedCustomCutErrors) {
  const Program p = parse("C#\nC#, 2.5\nC#, clamps\nC#, &n +\n");
  ASSERT_EQ(p.errors.size(), 4u);
  EXPECT_EQ(format(p.errors[0]),
            "part.sbp:1:3: error: C# needs the number of the custom cut: write `C#, 90` to run "
            "custom cut 90");
  EXPECT_EQ(format(p.errors[1]),
            "part.sbp:2:5: error: custom cuts are numbered 0 to 9999; C# was given 2.5");
  EXPECT_EQ(format(p.errors[2]),
            "part.sbp:3:5: error: C# needs a number or a variable, not 'clamps': write `C#, 90` "
            "or `C#, &n`");
  EXPECT_EQ(where(p.errors[3].loc), "part.sbp:4:9");
}

// ShopBot's files abbreviate ON INPUT to ON INP, as FabMo accepts.
TEST(Parser, OnInpIsOnInput) {
  const Program p = parse("ON INP(&a,1) GOTO hit\nON inp (3, 1) GOSUB x\nON INP(3,1)\n");
  ASSERT_TRUE(p.ok()) << format(p.errors[0]);
  ASSERT_EQ(p.statements.size(), 3u);
  const auto& first = std::get<OnInputStmt>(p.statements[0].body);
  ASSERT_TRUE(first.action);
  EXPECT_EQ(std::get<JumpStmt>(first.action->body).label, "HIT");
  const auto& second = std::get<OnInputStmt>(p.statements[1].body);
  ASSERT_TRUE(second.action);
  EXPECT_TRUE(std::get<JumpStmt>(second.action->body).gosub);
  EXPECT_FALSE(std::get<OnInputStmt>(p.statements[2].body).action);  // clears the handler
  const Program bad = parse("ON INPX(3,1) GOTO a\n");
  ASSERT_EQ(bad.errors.size(), 1u);
  EXPECT_EQ(format(bad.errors[0]),
            "part.sbp:1:4: error: expected INPUT after ON: ON INPUT(switch, state)");
}

// The handbook: strings work with or without quotation marks; in an IF test unquoted words
// beside a comparison are text.
TEST(Parser, IfTestTakesUnquotedWordsBesideAComparison) {
  const Program p = parse(
      "IF &msganswer = Cancel THEN END\n"
      "IF &PWZorigin = Material Surface THEN GOTO top\n"
      "IF Cancel THEN END\n");
  ASSERT_EQ(p.errors.size(), 1u);
  EXPECT_EQ(where(p.errors[0].loc), "part.sbp:3:4");
  ASSERT_EQ(p.statements.size(), 2u);
  EXPECT_TRUE(std::holds_alternative<IfStmt>(p.statements[1].body));
}

// A '(' in a MSGBOX's unquoted text is text: the commas after it still split the box.
TEST(Parser, MsgBoxTextMayHoldParentheses) {
  const Program p = parse(
      "MSGBOX(Remove the clamps (all four) then press OK,OKCANCEL,Title)\n"
      "MSGBOX(Remove the clamps (all four then press OK,OKCANCEL,Clamps (1/2)\n"
      "MSGBOX(\"Width \" & ROUND(&w, 2),YesNo,Check)\n");
  ASSERT_TRUE(p.ok()) << format(p.errors[0]);
  ASSERT_EQ(p.statements.size(), 3u);
  const auto& balanced = std::get<MsgBoxStmt>(p.statements[0].body);
  EXPECT_EQ(balanced.body.text, "Remove the clamps (all four) then press OK");
  EXPECT_EQ(balanced.buttons.text, "OKCANCEL");
  EXPECT_EQ(balanced.title.text, "Title");
  const auto& lone = std::get<MsgBoxStmt>(p.statements[1].body);
  EXPECT_EQ(lone.body.text, "Remove the clamps (all four then press OK");
  EXPECT_EQ(lone.buttons.text, "OKCANCEL");
  EXPECT_EQ(where(lone.buttons.loc), "part.sbp:2:50");
  EXPECT_EQ(lone.title.text, "Clamps (1/2");
  const auto& call = std::get<MsgBoxStmt>(p.statements[2].body);
  EXPECT_EQ(call.body.text, "\"Width \" & ROUND(&w, 2)");
  EXPECT_EQ(call.buttons.text, "YesNo");
}

TEST(Parser, IntegerDivisionAndDigitLeadingNamesParse) {
  const Program p = parse("&3zero_input = (&x)\\1\n&5AX_offset = 7 \\ 2\n");
  ASSERT_TRUE(p.ok()) << format(p.errors[0]);
  ASSERT_EQ(p.statements.size(), 2u);
  const auto& a = std::get<AssignStmt>(p.statements[0].body);
  EXPECT_EQ(a.target.name, "3ZERO_INPUT");
  EXPECT_TRUE(a.value.is_expression());
  EXPECT_EQ(std::get<AssignStmt>(p.statements[1].body).target.name, "5AX_OFFSET");
}

TEST(ParseFile, MissingFileIsOneErrorNamingIt) {
  const std::string path = std::string(GANTRY_SOURCE_DIR) + "/tests/data/no_such_file.sbp";
  const Program p = parse_file(path);
  EXPECT_TRUE(p.statements.empty());
  ASSERT_EQ(p.errors.size(), 1u);
  EXPECT_EQ(where(p.errors[0].loc), path + ":0:0");
  EXPECT_EQ(p.errors[0].message, "cannot open the part file: there is no such file");
  EXPECT_EQ(format(p.errors[0]),
            path + ": error: cannot open the part file: there is no such file");
}

TEST(ParseFile, DirectoryIsAnUnreadableFile) {
  const std::string path = std::string(GANTRY_SOURCE_DIR) + "/tests/data";
  const Program p = parse_file(path);
  ASSERT_EQ(p.errors.size(), 1u);
  EXPECT_EQ(where(p.errors[0].loc), path + ":0:0");
  EXPECT_EQ(p.errors[0].message, "cannot open the part file: it is a folder, not a file");
}

TEST(ParseFile, ReadsAndLocatesAFile) {
  const std::string path = std::string(GANTRY_SOURCE_DIR) + "/tests/data/unknown_command.sbp";
  const Program p = parse_file(path);
  ASSERT_TRUE(p.ok());
  ASSERT_TRUE(p.file);
  EXPECT_EQ(*p.file, path);
  ASSERT_EQ(p.statements.size(), 3u);
  EXPECT_EQ(command(p, 1).code, "QQ");
  EXPECT_EQ(param_texts(command(p, 1)), (Texts{"1", "2"}));
  EXPECT_EQ(where(p.statements[1].loc), path + ":3:1");
  EXPECT_EQ(where(command(p, 2).args[0].loc), path + ":4:5");
}

}  // namespace
}  // namespace gantry
