// The keyword statements' table: the parser runs on it, `help` answers from it for every
// statement and custom cut (issue 25: `help PAUSE`, `help IF`, `help C2` were "unknown
// command"), and docs/language.md lists the same statements.
#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>

#include "gantry/commands/command_docs.hpp"
#include "gantry/interp/file_system.hpp"  // shipped_macro_folder
#include "gantry/lang/parser.hpp"
#include "gantry/lang/statement_table.hpp"

namespace gantry {
namespace {

const std::vector<std::string> kShipped{shipped_macro_folder()};

TEST(StatementTable, EveryKeywordParsesAsItsStatementNotAsACommand) {
  auto file = std::make_shared<const std::string>("t.sbp");
  std::set<Keyword> seen;
  for (const StatementSpec& s : statement_table()) {
    seen.insert(s.keyword);
    EXPECT_EQ(find_statement(std::string(s.word)), &s);
    // The keyword alone, in lower case: a statement, or the statement's own complaint.
    std::string lower(s.word);
    for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    const LineParse p = parse_line(lower, file, 1);
    if (p.error) {
      EXPECT_EQ(p.error->message.find("unknown command"), std::string::npos)
          << s.word << ": " << p.error->message;
    } else {
      EXPECT_TRUE(p.statement.has_value()) << s.word;
    }
  }
  EXPECT_EQ(seen.size(), static_cast<size_t>(Keyword::DataSend) + 1) << "a Keyword has no row";
  EXPECT_EQ(find_statement("MX"), nullptr);
  EXPECT_EQ(find_statement("pause")->keyword, Keyword::Pause);
}

TEST(StatementTable, DocsListTheSameStatementsAndEverySectionExists) {
  std::ifstream in(std::string(GANTRY_SOURCE_DIR) + "/docs/language.md");
  std::stringstream buf;
  buf << in.rdbuf();
  const std::string doc = buf.str();
  for (const StatementSpec& s : statement_table()) {
    const std::string heading = "\n### " + std::string(s.section) + " ";
    const std::string chapter = "\n## " + std::string(s.section) + ". ";
    EXPECT_TRUE(doc.find(heading) != std::string::npos || doc.find(chapter) != std::string::npos)
        << s.word << " names section " << s.section;
  }
  // Each keyword the docs' statement index shows in backticks is in the table.
  const size_t from = doc.find("| statement | section |");
  const size_t to = doc.find("\n\n", from);
  ASSERT_NE(from, std::string::npos);
  std::istringstream rows(doc.substr(from, to - from));
  int keywords = 0;
  for (std::string row; std::getline(rows, row);)
    for (size_t b = row.find('`'); b != std::string::npos; b = row.find('`', b + 1)) {
      const size_t e = row.find('`', b + 1);
      std::string word = row.substr(b + 1, e - b - 1);
      b = e;
      word = word.substr(0, word.find(' '));
      if (word.empty() || !std::isalpha(static_cast<unsigned char>(word[0]))) continue;  // &x =
      ++keywords;
      EXPECT_NE(find_statement(word), nullptr) << word << " is in the docs, not the table";
    }
  EXPECT_GE(keywords, 20);
}

TEST(HelpTopic, AnswersForStatementsCommandsAndCustomCuts) {
  const std::optional<std::string> pause = help_topic("pause", kShipped);
  ASSERT_TRUE(pause);
  EXPECT_TRUE(pause->starts_with("PAUSE - ")) << *pause;
  EXPECT_NE(pause->find("PAUSE UNTIL switch, state"), std::string::npos) << *pause;
  EXPECT_NE(pause->find("section 4.7"), std::string::npos) << *pause;
  const std::optional<std::string> if_help = help_topic("IF", kShipped);
  ASSERT_TRUE(if_help);
  EXPECT_NE(if_help->find("IF test THEN statement"), std::string::npos) << *if_help;
  EXPECT_TRUE(help_topic("MX", kShipped)->starts_with("MX - Move X axis\n"));
  // A custom cut: its macro file's opening comment, where it was found.
  const std::optional<std::string> c2 = help_topic("C2", kShipped);
  ASSERT_TRUE(c2);
  EXPECT_TRUE(c2->starts_with("C2 - custom cut 2: ")) << *c2;
  EXPECT_NE(c2->find("Zero Z with the zero plate"), std::string::npos) << *c2;
  EXPECT_NE(c2->find("C2.sbp"), std::string::npos) << *c2;
  // C3 is also FabMo's command: both are told.
  const std::string c3 = *help_topic("c3", kShipped);
  EXPECT_TRUE(c3.starts_with("C3 - Homing macro (FabMo)\n")) << c3;
  EXPECT_NE(c3.find("Home X, Y and Z on the proximity switches"), std::string::npos) << c3;
  // A custom cut with no file says where it looked.
  const std::string c8 = *help_topic("C8", kShipped);
  EXPECT_NE(c8.find("there is no C8.sbp or macro_8.sbp in " + kShipped[0]), std::string::npos)
      << c8;
  EXPECT_FALSE(help_topic("QQQ", kShipped));
  EXPECT_FALSE(help_topic("C12345", kShipped));  // custom cuts have at most four digits
  EXPECT_FALSE(help_topic("", kShipped));
}

TEST(HelpTopic, EveryCommandAndStatementHasHelpAndTheListNamesThemAll) {
  for (const CommandSpec& s : CommandTable::standard().all())
    EXPECT_TRUE(help_topic(s.code, {})) << s.code;
  const std::string list = command_list(CommandTable::standard());
  for (const StatementSpec& s : statement_table()) {
    const std::optional<std::string> h = help_topic(s.word, {});
    ASSERT_TRUE(h) << s.word;
    EXPECT_TRUE(h->starts_with(std::string(s.word) + " - ")) << *h;
    if (s.keyword != Keyword::DataSend) {
      EXPECT_NE(list.find("\n  " + std::string(s.word) + " "), std::string::npos) << s.word;
    }
  }
}

}  // namespace
}  // namespace gantry
