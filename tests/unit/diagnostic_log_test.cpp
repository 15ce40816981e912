// A check's log: each line's error once, a cap, and one summary line for the rest.
#include <gtest/gtest.h>

#include <string>

#include "gantry/core/diagnostic_log.hpp"

namespace gantry {
namespace {

Diagnostic error_at(int line, std::string message, const char* file = "part.sbp") {
  return {file_loc(file, line, 1), Severity::Error, std::move(message)};
}

TEST(DiagnosticLog, KeepsOneErrorPerLineWhateverItsText) {
  // A loop moving one further each pass fails at the same line with a new number each time.
  DiagnosticLog log;
  EXPECT_TRUE(log.add(error_at(4, "move to X=25.0000 is outside the soft limits")));
  EXPECT_FALSE(log.add(error_at(4, "move to X=26.0000 is outside the soft limits")));
  EXPECT_TRUE(log.add(error_at(4, "move to X=25.0000 is outside", "other.sbp")));
  EXPECT_TRUE(log.add(error_at(5, "move to X=25.0000 is outside the soft limits")));
  EXPECT_EQ(log.kept().size(), 3u);
}

TEST(DiagnosticLog, AFileThatCannotBeReadCountsAtTheLineThatCalledIt) {
  DiagnosticLog log;
  for (const char* name : {"a1.sbp", "a2.sbp"}) {
    Diagnostic d{file_loc(name), Severity::Error, "cannot open the part file"};
    d.via.push_back(file_loc("part.sbp", 3));
    log.add(d);
  }
  EXPECT_EQ(log.kept().size(), 1u);
}

TEST(DiagnosticLog, WarningsRepeatOnlyWithTheSameText) {
  DiagnosticLog log;
  const Diagnostic w{file_loc("part.sbp", 2, 1), Severity::Warning, "PLAY is not played"};
  EXPECT_TRUE(log.add(w));
  EXPECT_FALSE(log.add(w));
  EXPECT_TRUE(log.add(error_at(2, "an error at the same line")));
  EXPECT_EQ(log.kept().size(), 2u);
}

TEST(DiagnosticLog, StopsKeepingAtTheCapAndSummarisesTheRestByKind) {
  DiagnosticLog log(2);
  log.add(error_at(1, "unknown command 'QQ'; see docs/commands.md"));
  EXPECT_FALSE(log.full());
  log.add(error_at(2, "unknown command 'ZZ'; see docs/commands.md"));
  EXPECT_TRUE(log.full());
  EXPECT_EQ(log.summary(), "");  // nothing left out yet
  for (int line = 3; line < 1203; ++line)
    log.add(error_at(line, "unknown command 'Q" + std::to_string(line % 7) + "'; see"));
  for (int line = 2000; line < 2003; ++line)
    log.add(error_at(line, "CG 3: the end is not on the circle (radius 1 from the start)"));
  log.add({file_loc("part.sbp", 9), Severity::Warning, "a warning is still kept"});
  EXPECT_EQ(log.kept().size(), 3u);
  EXPECT_EQ(log.omitted(), 1203u);
  EXPECT_EQ(log.summary(),
            "stopped after 2 errors; 1,203 more not shown: 1,200 'unknown command', 3 'CG #: the "
            "end is not on the circle'");
}

TEST(DiagnosticLog, NamesFourKindsAndCountsTheOthers) {
  DiagnosticLog log(1);
  log.add(error_at(1, "first"));
  const char* kinds[] = {"a", "b", "c", "d", "e", "f"};
  int line = 2;
  for (int k = 0; k < 6; ++k)
    for (int n = 0; n <= 6 - k; ++n) log.add(error_at(line++, kinds[k]));
  EXPECT_EQ(log.summary(),
            "stopped after 1 error; 27 more not shown: 7 'a', 6 'b', 5 'c', 4 'd', 5 of 2 other "
            "kinds");
}

TEST(DiagnosticLog, StoppingShortIsKeptAndTheFirstReasonWins) {
  DiagnosticLog log;
  log.stop_short({file_loc("part.sbp", 3, 1), Severity::Warning, "checking stopped here: INPUT"});
  log.stop_short({file_loc("part.sbp", 5, 1), Severity::Warning, "checking stopped here: later"});
  ASSERT_TRUE(log.stopped_short());
  EXPECT_EQ(log.stopped_short()->loc.line, 3);
  EXPECT_EQ(log.kept().size(), 2u);
  EXPECT_FALSE(log.has_errors());
}

TEST(DiagnosticKind, KeepsTheWordsThatNameTheKind) {
  EXPECT_EQ(diagnostic_kind("unknown command 'QQ'; see docs/commands.md for the commands"),
            "unknown command");
  EXPECT_EQ(diagnostic_kind("move to X=30.0000 is outside the soft limits 0.0000 to 24.0000 in "
                            "(axes.x.min/max in the profile); nothing was moved"),
            "move to # is outside the soft limits # to # in");
  EXPECT_EQ(diagnostic_kind("expected a number for Y location (MY), found 'abc'"),
            "expected a number for Y location");
  EXPECT_EQ(diagnostic_kind("the file asks the operator for \"depth\" now"),
            "the file asks the operator for now");
}

}  // namespace
}  // namespace gantry
