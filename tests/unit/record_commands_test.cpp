// The command record (RA RI RP RR RS RZ), SI, MN and MI: what is recorded, what playing it
// back moves, the files RS and SI write, and their errors (located, nothing moved).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../support/interpreter_fixture.hpp"
#include "../support/temp_dir.hpp"
#include "gantry/commands/command_table.hpp"
#include "gantry/core/diagnostic.hpp"
#include "gantry/interp/interpreter.hpp"
#include "gantry/lang/script.hpp"
#include "gantry/settings/settings.hpp"

namespace gantry {
namespace {

namespace fs = std::filesystem;

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// One interpreter for the whole test, as a console session keeps one. type() runs a line as
// the console does (each line on its own) and records it; run() runs a part file.
class RecordTest : public KeptInterpreterFixture {
 protected:
  RecordTest() {
    settings.axes[0].max = 40;  // room for SB3's drilling example (X to 32.5)
    interp();
  }

  std::string path(const std::string& name) const { return (fs::path(dir_.path()) / name).string(); }

  // A line typed at the console: run, then recorded (as the console front ends do).
  void type(const std::string& line) {
    auto script = Script::from_text(line + "\n", path("console"));
    ASSERT_TRUE(script->ok()) << format(script->errors().front());
    try {
      interp().run(script);
    } catch (const GantryError& e) {
      FAIL() << line << ": " << format(e.diagnostic());
    }
    interp().record_typed(line);
  }
  void type_all(const std::vector<std::string>& lines) {
    for (const std::string& l : lines) type(l);
  }
  // A typed line expected to fail (not recorded, as the console leaves it out).
  Diagnostic type_error(const std::string& line) { return run_error(line + "\n"); }

  void run(const std::string& text) { run_program(Script::from_text(text, path("part.sbp"))); }
  Diagnostic run_error(const std::string& text) {
    return program_error(Script::from_text(text, path("part.sbp")), text);
  }

  std::vector<std::string> recorded() { return interp().recorder().last(1000); }

 private:
  TempDir dir_{"record_test"};
};

// The straight moves' end points and speed classes, which replaying must reproduce.
struct Leg {
  Vec6 to;
  SpeedClass cls;
  double speed;  // the class's XY speed
  bool operator==(const Leg& o) const {
    return (to - o.to).norm() < 1e-12 && cls == o.cls && speed == o.speed;
  }
};
std::vector<Leg> legs(const std::vector<CanonMove>& moves, size_t from = 0) {
  std::vector<Leg> out;
  for (size_t i = from; i < moves.size(); ++i)
    if (moves[i].kind == MoveKind::Line)
      out.push_back({moves[i].to, moves[i].speed_class, moves[i].speeds.xy});
  return out;
}

// ---- what is recorded -------------------------------------------------------------------------

TEST_F(RecordTest, Fact148_TypedLinesAreRecordedFromTheStart) {
  EXPECT_TRUE(interp().recorder().active());
  type_all({"JX, 1", "  MY, 2  ", "&D = 0.5", "' a comment"});
  EXPECT_EQ(recorded(), (std::vector<std::string>{"JX, 1", "MY, 2", "&D = 0.5"}));
}

TEST_F(RecordTest, RecordCommandsLabelsAndBrokenLinesAreNotRecorded) {
  type_all({"JX, 1", "RA", "RZ", "JX, 2", "RI", "RA", "RP", "RR, 1", "RS, keep"});
  EXPECT_EQ(recorded(), std::vector<std::string>{"JX, 2"});
  EXPECT_FALSE(interp().record_typed("START:"));
  EXPECT_FALSE(interp().record_typed("IF 1 THEN"));
  EXPECT_FALSE(interp().record_typed("GOTO"));
  EXPECT_FALSE(interp().record_typed(""));
  EXPECT_TRUE(interp().record_typed("MX, 3"));
  EXPECT_EQ(interp().recorder().size(), 2u);
}

TEST_F(RecordTest, LinesRunFromPartFilesAreNotRecorded) {
  type("JX, 1");
  run("JX, 2\nJY, 3\nSI, \"JZ, 0.5\"\n");
  EXPECT_EQ(recorded(), std::vector<std::string>{"JX, 1"});
}

TEST_F(RecordTest, Fact149_RiPausesWithoutErasingAndRaResumes) {
  type_all({"JX, 1", "RI", "JX, 2", "RA", "JX, 3"});
  EXPECT_EQ(recorded(), (std::vector<std::string>{"JX, 1", "JX, 3"}));
  EXPECT_TRUE(contains(printed, "Recording paused (1 kept; RA resumes)")) << printed;
  EXPECT_TRUE(contains(printed, "Recording typed commands (1 kept)")) << printed;
}

TEST_F(RecordTest, Fact153_RzEmptiesTheRecordAndKeepsItsState) {
  type_all({"JX, 1", "JX, 2", "RZ"});
  EXPECT_EQ(interp().recorder().size(), 0u);
  EXPECT_TRUE(interp().recorder().active());
  type_all({"RI", "JX, 3", "RZ", "JX, 4"});
  EXPECT_EQ(interp().recorder().size(), 0u);
  EXPECT_FALSE(interp().recorder().active());
  EXPECT_TRUE(contains(printed, "Record cleared; recording is paused (RA resumes)")) << printed;
}

TEST_F(RecordTest, Fact151_TheLast100LinesAreKept) {
  for (int i = 1; i <= 105; ++i) EXPECT_TRUE(interp().record_typed("MX, " + std::to_string(i % 20)));
  ASSERT_EQ(interp().recorder().size(), 100u);
  EXPECT_EQ(recorded().front(), "MX, 6");  // lines 1 to 5 went
  EXPECT_EQ(recorded().back(), "MX, 5");
  EXPECT_EQ(interp().recorder().last(2), (std::vector<std::string>{"MX, 4", "MX, 5"}));
}

// ---- playing back -----------------------------------------------------------------------------

TEST_F(RecordTest, Fact154_RrARepeatsTheTypedDrillingStep) {
  type_all({"SA", "M3, 1, 1, .2", "SR", "RZ", "MZ, -.45", "JZ, .45", "JX, 1.5", "RI"});
  const size_t typed = sink.moves.size();
  type("RR, A, 20");
  // 20 more holes, 1.5 apart: the tool ends at X 32.5, Z .2 (21 holes from X 1 to 31).
  EXPECT_NEAR(interp().state().position[0], 32.5, 1e-9);
  EXPECT_NEAR(interp().state().position[2], 0.2, 1e-9);
  const std::vector<Leg> played = legs(sink.moves, typed);
  ASSERT_EQ(played.size(), 60u);
  int holes = 0;
  for (const Leg& l : played) holes += l.to[2] < 0 && l.cls == SpeedClass::Move;
  EXPECT_EQ(holes, 20);
  EXPECT_NEAR(played[0].to[0], 2.5, 1e-9);  // the second hole
  EXPECT_NEAR(played[0].to[2], -0.25, 1e-9);
}

TEST_F(RecordTest, ReplayMakesTheSameMovesAsTypingAgain) {
  const std::vector<std::string> lines = {
      "SR", "MZ, -.45", "JZ, .45", "J2, 1.5, 0.25", "MS, 2, 1", "M3, 0.5, 0, -0.1", "MZ, 0.1"};
  type("M3, 1, 1, .2");
  type("RZ");
  type_all(lines);
  const size_t typed = sink.moves.size();
  type("RR, A, 3");
  const std::vector<Leg> replayed = legs(sink.moves, typed);

  // The same session typed by hand: the lines three more times.
  RecordingSink by_hand;
  Interpreter other(settings, by_hand, io, store, options);
  auto type_into = [&](const std::string& line) {
    other.run(Script::from_text(line + "\n", path("console")));
  };
  type_into("M3, 1, 1, .2");
  for (int pass = 0; pass < 4; ++pass)
    for (const std::string& l : lines) type_into(l);
  const std::vector<Leg> expected = legs(by_hand.moves, typed);
  ASSERT_EQ(replayed.size(), 15u);
  EXPECT_EQ(replayed, expected);
  EXPECT_TRUE(interp().state().position.isApprox(other.state().position, 1e-12));
}

TEST_F(RecordTest, Fact150_RpPlaysEverythingOnce) {
  type_all({"SR", "JX, 1", "JY, 2"});
  const size_t typed = sink.moves.size();
  type("RP");
  const std::vector<Leg> played = legs(sink.moves, typed);
  ASSERT_EQ(played.size(), 2u);
  EXPECT_EQ(played[0].to[0], 2);
  EXPECT_EQ(played[1].to[1], 4);
  EXPECT_FALSE(interp().state().absolute);  // SR was played too
}

TEST_F(RecordTest, Fact151_RrDefaultsToTheLastLineAndCountsBack) {
  type_all({"SR", "JX, 1", "JY, 2", "JZ, 0.5"});
  size_t before = sink.moves.size();
  type("RR");
  ASSERT_EQ(sink.moves.size(), before + 1);
  EXPECT_EQ(sink.moves.back().to[2], 1);  // only JZ again
  before = sink.moves.size();
  type("RR, 2, 2");
  const std::vector<Leg> played = legs(sink.moves, before);
  ASSERT_EQ(played.size(), 4u);  // JY, JZ, JY, JZ
  EXPECT_EQ(played[0].to[1], 4);
  EXPECT_EQ(played[1].to[2], 1.5);
  EXPECT_EQ(played[2].to[1], 6);
  EXPECT_EQ(played[3].to[2], 2);
  EXPECT_EQ(played[3].to[0], 1);  // X never moved again
}

TEST_F(RecordTest, RrErrorsAreLocatedAndPlayNothing) {
  type_all({"SR", "JX, 1", "JY, 1"});
  const size_t before = sink.moves.size();
  struct Case {
    std::string line;
    int column;
    std::string message;
  } cases[] = {
      {"RR, 4", 5,
       "RR: 4 commands back, but the record holds 3 commands; nothing was done "
       "(RR, A plays them all)"},
      {"RR, 0", 5, "RR parameter 1 (commands back) is '0'; give a whole number from 1, or A"},
      {"RR, 1.5", 5, "RR parameter 1 (commands back) is '1.5'"},
      {"RR, B", 5, "RR parameter 1 (commands back) is 'B'"},
      {"RR, 1, 0", 8, "RR parameter 2 (repetitions) is 0; allowed: 1 to 1000000"},
      {"RR, 1, 2.5", 8, "RR parameter 2 (repetitions) must be a whole number"},
  };
  for (const Case& c : cases) {
    const Diagnostic d = type_error(c.line);
    EXPECT_TRUE(d.message.starts_with(c.message)) << c.line << ": " << d.message;
    EXPECT_EQ(d.loc.column, c.column) << c.line;
  }
  EXPECT_EQ(sink.moves.size(), before);
}

TEST_F(RecordTest, PlayingAnEmptyRecordSaysSo) {
  type_all({"RP", "RR, A", "RS"});
  EXPECT_TRUE(sink.moves.empty());
  EXPECT_EQ(printed,
            "RP: the record is empty; nothing was played\n"
            "RR: the record is empty; nothing was played\n"
            "RS: the record is empty; no file was written\n");
  EXPECT_FALSE(fs::exists(path("SBTEMP.SBP")));
  const Diagnostic d = type_error("RR");  // one back, of none
  EXPECT_TRUE(d.message.starts_with("RR: 1 command back, but the record holds 0 commands"))
      << d.message;
}

TEST_F(RecordTest, AnErrorInAPlayedLineIsLocatedInTheRecord) {
  settings.axes[0].max = 24;
  fresh_interp();
  type_all({"SR", "JY, 1", "JX, 10"});
  const Diagnostic d = run_error("RR, 2, 3\n");  // the second pass's JX reaches X 30 > 24
  ASSERT_TRUE(d.loc.file);
  EXPECT_EQ(*d.loc.file, "(record)");
  EXPECT_EQ(d.loc.line, 2);
  ASSERT_EQ(d.via.size(), 1u);
  EXPECT_EQ(d.via[0].line, 1);  // the RR line
  EXPECT_NEAR(interp().state().position[0], 20, 1e-12);
}

TEST_F(RecordTest, PlayedLinesChangeValuesForGoodAsTypedOnes) {
  // In a part file, VS and SF last until the file ends; played from the record, as typed
  // lines, they stay, even when the file that plays them set its own speed before.
  run("VS, 3\nSF, 0\n");
  EXPECT_EQ(interp().state().speeds.move.xy, 2);
  EXPECT_TRUE(interp().settings().machine.limit_checking);
  interp().record_typed("VS, 3");
  interp().record_typed("SF, 0");
  run("VS, 2.5\nRP\n");
  EXPECT_EQ(interp().state().speeds.move.xy, 3);
  EXPECT_FALSE(interp().settings().machine.limit_checking);
}

TEST_F(RecordTest, PlayedLinesAreNotScaledByTheFileThatPlaysThem) {
  type_all({"SR", "JX, 1"});
  std::ofstream(path("twice.sbp")) << "RP\n";
  run("FP, twice.sbp, 2, 2, 2\n");
  ASSERT_EQ(legs(sink.moves).size(), 2u);
  EXPECT_EQ(legs(sink.moves)[1].to[0], 2);  // 1 further, not 2
}

// ---- RS -------------------------------------------------------------------------------------

TEST_F(RecordTest, Fact152_RsSavesAPartFileThatRunsTheSame) {
  type_all({"SR", "JX, 1", "JY, 2", "MZ, -0.1"});
  type("RS, drill");
  const std::string text = slurp(path("drill.sbp"));
  EXPECT_EQ(text,
            "' 4 commands typed at the Gantry console, oldest first (saved by RS)\n"
            "SR\nJX, 1\nJY, 2\nMZ, -0.1\n");
  EXPECT_TRUE(contains(printed, "RS saved 4 commands in " + path("drill.sbp"))) << printed;
  // Nothing else was left in the folder (the file was written beside and renamed).
  int files = 0;
  for (const auto& e : fs::directory_iterator(path(""))) files += e.is_regular_file();
  EXPECT_EQ(files, 1);
  // Run as a part file from where the record ran, it moves as the replay does.
  const size_t before = sink.moves.size();
  type("RP");
  const std::vector<Leg> replayed = legs(sink.moves, before);
  const size_t mid = sink.moves.size();
  run("FP, drill.sbp\n");
  EXPECT_EQ(legs(sink.moves, mid).size(), 3u);
  for (size_t i = 0; i < 3; ++i)  // relative moves: each ends the replay's distance further on
    EXPECT_TRUE((legs(sink.moves, mid)[i].to - replayed[i].to).isApprox(Vec6(1, 2, -0.1, 0, 0, 0)))
        << i;
}

TEST_F(RecordTest, RsNamesCountsAndFolders) {
  type_all({"JX, 1", "JY, 2", "JZ, 0.5"});
  type("RS");
  EXPECT_TRUE(contains(slurp(path("SBTEMP.SBP")), "JX, 1\nJY, 2\nJZ, 0.5\n"));
  type("RS, last.txt, 2");
  EXPECT_EQ(slurp(path("last.txt")),
            "' 2 commands typed at the Gantry console, oldest first (saved by RS)\n"
            "JY, 2\nJZ, 0.5\n");
  EXPECT_FALSE(fs::exists(path("last.txt.sbp")));
  // The parts folder FS sets.
  fs::create_directories(path("jobs"));
  run("FS, jobs\nRS, one, 1\n");
  EXPECT_EQ(slurp(path("jobs/one.sbp")),
            "' 1 command typed at the Gantry console, oldest first (saved by RS)\nJZ, 0.5\n");
  // Replacing a file replaces all of it.
  type("RS, last.txt, 1");
  EXPECT_EQ(slurp(path("last.txt")),
            "' 1 command typed at the Gantry console, oldest first (saved by RS)\nJZ, 0.5\n");
}

TEST_F(RecordTest, RsErrorsWriteNothing) {
  type_all({"JX, 1", "JY, 2"});
  Diagnostic d = type_error("RS, x, 3");
  EXPECT_TRUE(
      d.message.starts_with("RS: 3 commands back, but the record holds 2 commands; "
                            "nothing was done (a blank saves them all)"))
      << d.message;
  EXPECT_EQ(d.loc.column, 8);
  EXPECT_FALSE(fs::exists(path("x.sbp")));
  d = type_error("RS, nowhere/x");
  EXPECT_TRUE(
      d.message.starts_with("cannot write " + path("nowhere/x.sbp") + ": there is no folder"))
      << d.message;
  EXPECT_FALSE(fs::exists(path("nowhere")));
  d = run_error("RS, part.sbp\n");  // the file that is running
  EXPECT_TRUE(contains(d.message, "is running; a command cannot rewrite a running part file"))
      << d.message;
}

TEST_F(RecordTest, ACheckWritesNoFile) {
  InterpreterOptions dry;
  dry.dry_run = true;
  RecordingSink none;
  Interpreter checker(settings, none, io, store, dry);
  checker.record_typed("JX, 1");
  const std::vector<Diagnostic> errors =
      checker.check(Script::from_text("RS, checked\nSI, \"JY, 1\"\n", path("part.sbp")));
  EXPECT_TRUE(errors.empty()) << format(errors.front());
  EXPECT_FALSE(fs::exists(path("checked.sbp")));
  EXPECT_FALSE(fs::exists(path("temp_code.sbp")));
  EXPECT_EQ(legs(none.moves).size(), 1u);  // SI's line ran in the check
}

// ---- SI -------------------------------------------------------------------------------------

TEST_F(RecordTest, Fact160_SiRunsItsLinesAndSavesThemInTempCode) {
  type("SI, \"JX, 1\", \"MY, 2\", SR, \"JX, 0.5\"");
  const std::vector<Leg> l = legs(sink.moves);
  ASSERT_EQ(l.size(), 3u);
  EXPECT_EQ(l[0].to[0], 1);
  EXPECT_EQ(l[0].cls, SpeedClass::Jog);
  EXPECT_EQ(l[1].to[1], 2);
  EXPECT_EQ(l[1].cls, SpeedClass::Move);
  EXPECT_EQ(l[2].to[0], 1.5);
  EXPECT_FALSE(interp().state().absolute);
  EXPECT_EQ(slurp(path("temp_code.sbp")), "JX, 1\nMY, 2\nSR\nJX, 0.5\n");
  // The SI line itself is what the record keeps: playing it sends the lines again.
  EXPECT_EQ(recorded(), std::vector<std::string>{"SI, \"JX, 1\", \"MY, 2\", SR, \"JX, 0.5\""});
}

TEST_F(RecordTest, SiWithABrokenLineRunsNone) {
  const Diagnostic d = run_error("SI, \"JX, 1\", GOTO\n");
  EXPECT_TRUE(sink.moves.empty());
  ASSERT_TRUE(d.loc.file);
  EXPECT_EQ(*d.loc.file, path("temp_code.sbp"));
  EXPECT_EQ(d.loc.line, 2);
}

TEST_F(RecordTest, SiWithoutLinesShowsTheLastOnes) {
  type("SI");
  EXPECT_TRUE(contains(printed, "none were given, and none were sent before")) << printed;
  printed.clear();
  type("SI, \"JX, 1\"");
  type("SI");
  EXPECT_EQ(printed, "SI: no lines given. The last lines sent (" + path("temp_code.sbp") +
                         "):\nJX, 1\nFP, temp_code.sbp sends them again\n");
  EXPECT_EQ(sink.moves.size(), 1u);
}

// ---- MN, MI ---------------------------------------------------------------------------------

TEST_F(RecordTest, Fact128_MnMovesTheToolAndKeepsItsLocation) {
  run("J3, 1, 2, 0.5\nMN, 0.1, -0.2\n");
  ASSERT_EQ(sink.moves.size(), 2u);
  EXPECT_TRUE(sink.moves[1].to.isApprox(Vec6(1.1, 1.8, 0.5, 0, 0, 0)));
  EXPECT_EQ(sink.moves[1].speed_class, SpeedClass::Move);
  const ModalState& st = interp().state();
  EXPECT_TRUE(st.position.isApprox(Vec6(1, 2, 0.5, 0, 0, 0)));  // the location reads the same
  EXPECT_TRUE(interp().snapshot().table_base.isApprox(Vec6(1.1, 1.8, 0.5, 0, 0, 0)));
  // What follows is shifted by the nudge; ST gives the true location back.
  run("MX, 3\nST\n");
  EXPECT_NEAR(sink.moves.back().to[0], 3.1, 1e-12);
  EXPECT_TRUE(interp().state().position.isApprox(Vec6(3.1, 1.8, 0.5, 0, 0, 0)));
}

TEST_F(RecordTest, MnOutsideTheLimitsChangesNothing) {
  run("JX, 1\n");
  const Diagnostic d = run_error("MN, , 30\n");
  EXPECT_EQ(d.loc.line, 1);
  EXPECT_EQ(sink.moves.size(), 1u);
  EXPECT_TRUE(interp().state().zero.isZero(0));
  EXPECT_TRUE(interp().state().position.isApprox(Vec6(1, 0, 0, 0, 0, 0)));
}

TEST_F(RecordTest, MnWithoutADistanceSaysSo) {
  run("MN\nMN, 0, , 0\n");
  EXPECT_TRUE(sink.moves.empty());
  EXPECT_TRUE(contains(printed, "MN: no distance given, nothing moved")) << printed;
}

// MI's kinds of moves, in order: I+ an independent start, I- its stop, L a line.
std::string mi_stream(const std::vector<CanonMove>& moves) {
  std::string out;
  for (const CanonMove& m : moves)
    if (m.kind == MoveKind::Independent)
      out += m.independent.running() ? "I+ " : "I- ";
    else if (m.kind == MoveKind::Line)
      out += "L ";
  return out;
}

TEST_F(RecordTest, MiTurnsAnAxisBesideTheMovesUntilItIsStopped) {
  run("MI, B, 1, 45\nMX, 1\nPRINT \"on \"; %(123)\nMY, 1\nMI, B\nPRINT \"off \"; %(123)\nMX, 2\n");
  EXPECT_EQ(mi_stream(sink.moves), "I+ L L I- L ");
  EXPECT_TRUE(contains(printed, "on 1")) << printed;  // %(123) IndexerON
  EXPECT_TRUE(contains(printed, "off 0")) << printed;
  const CanonMove& start = sink.moves[0];
  EXPECT_EQ(start.independent.axis, 4);
  EXPECT_EQ(start.independent.speed, 45);
  EXPECT_EQ(start.independent.accel, settings.axes[4].max_accel);
  EXPECT_EQ(start.loc.line, 1);
  EXPECT_FALSE(interp().state().independent);
}

TEST_F(RecordTest, MiDirectionZeroOrMinusOneTurnsTheOtherWayAndOscillatesToThatSide) {
  run("MZ, 1\nMI, A, 0, 30\nMX, 1\n");
  EXPECT_EQ(sink.moves[1].independent.speed, -30);
  sink.moves.clear();
  run("MZ, 1\nMI, Z, -1, , 2, 0.1\nMX, 2\n");
  ASSERT_EQ(mi_stream(sink.moves), "I+ L I- ");  // the file's end stops it
  EXPECT_EQ(sink.moves[0].independent.frequency, 2);
  EXPECT_EQ(sink.moves[0].independent.travel, -0.1);
  EXPECT_EQ(sink.moves[0].independent.speed, 0);
}

TEST_F(RecordTest, MiRestsWhenTheMachineWaitsAndStartsAgainWithTheNextMove) {
  // Reading an input plays the moves out (the machine comes to rest): the next move starts
  // the axis again, once.
  run("MI, B, 1, 45\nMX, 1\n&s = %(51)\nMY, 1\nMX, 0\n");
  EXPECT_EQ(mi_stream(sink.moves), "I+ L I+ L L I- ");
}

TEST_F(RecordTest, AMoveOfTheAxisMiMovesIsRefusedAndNamesTheMiLine) {
  const Diagnostic d = run_error("MI, B, 1, 45\nMX, 1\nMB, 90\n");
  EXPECT_EQ(d.loc.line, 3);
  EXPECT_TRUE(contains(d.message, "which MI moves on its own (line 1)")) << d.message;
  EXPECT_TRUE(contains(d.message, "MI, B")) << d.message;
  EXPECT_EQ(mi_stream(sink.moves), "I+ L I- ");  // no B move; the error's end stops B
  // An arc about the oscillating axis moves it too.
  sink.moves.clear();
  const Diagnostic z = run_error("MZ, 1\nMI, Z, 1, , 2, 0.1\nJ3, 1, 1, 1.5\n");
  EXPECT_EQ(z.loc.line, 3);
}

TEST_F(RecordTest, MiRefusesWhatItCannotDoAndNothingMoves) {
  struct Case {
    std::string file;
    int column;
    std::string says;
  };
  const std::vector<Case> cases = {
      {"MI, X, 1, 2\n", 5, "X is a linear axis"},
      {"MI, B, 1, 200\n", 11, "above B's limit of 90 per second"},
      {"MI, B, 1, 10, 2, 1\n", 15, "not both"},
      {"MI, Z, 1, , 5, 0.1\n", 13, "at most 2.85 Hz for that distance"},
      {"MI, Z, 1, , 2\n", 1, "needs a distance of at least one step"},
      {"MI, Z, 1, , 2, 0.00001\n", 16, "needs a distance of at least one step"},
      {"MZ, 5.45\nMI, Z, 1, , 1, 0.1\n", 1, "outside the soft limits"},
      {"MI, Q, 1, 10\n", 5, "Q"},
      {"MI, B, 2, 10\n", 8, "-1"},
      {"MI, B, 1, 10\nMI, A, 1, 10\n", 5, "B moves on its own already (line 1)"},
  };
  for (const Case& c : cases) {
    sink.moves.clear();
    const Diagnostic d = run_error(c.file);
    EXPECT_TRUE(contains(d.message, c.says)) << c.file << d.message;
    EXPECT_EQ(d.loc.column, c.column) << c.file << d.message;
    for (const CanonMove& m : sink.moves)  // nothing started on the refused line
      EXPECT_FALSE(m.kind == MoveKind::Independent && m.loc.line == d.loc.line) << c.file;
  }
}

TEST_F(RecordTest, MiTypedAloneIsRefusedAndMiStopOfNothingSaysSo) {
  const auto typed = [&](const std::string& line) -> Diagnostic {
    try {
      interp().run(Script::from_text(line + "\n", path("console")), /*typed=*/true);
    } catch (const GantryError& e) {
      return e.diagnostic();
    }
    return {};
  };
  EXPECT_TRUE(contains(typed("MI, B, 1, 45").message, "typed alone it would stop again"));
  EXPECT_TRUE(sink.moves.empty());
  EXPECT_EQ(typed("MI").message, "");
  EXPECT_TRUE(contains(printed, "MI: B is not moving on its own; nothing to stop")) << printed;
  EXPECT_EQ(CommandTable::standard().find("MI")->coverage.substr(0, 29),
            "runs within a part file only ");
}

TEST_F(RecordTest, TheTableDescribesWhatIsImplemented) {
  const CommandTable& t = CommandTable::standard();
  for (const char* code : {"RA", "RI", "RP", "RR", "RZ", "MN"})
    EXPECT_EQ(t.find(code)->coverage, "") << code;
  for (const char* code : {"RS", "SI"}) {
    EXPECT_NE(t.find(code)->coverage, "") << code;
    EXPECT_NE(t.find(code)->coverage, "not implemented") << code;
  }
  EXPECT_EQ(t.find("SI")->group, CommandGroup::Settings);
  EXPECT_EQ(t.find("RR")->group, CommandGroup::Record);
}

}  // namespace
}  // namespace gantry
