// Starting a part file at a line (InterpreterOptions::start_line, `gantry run --from-line`,
// FG): the lines before it run without motion, output or questions and leave the modes,
// variables, values and location a full run would have at that line; the tool then rises to
// Safe-Z, crosses and goes down there; a start line that cannot be reached is a located error
// and nothing moves (docs/language.md, "Starting at a line").
#include <gtest/gtest.h>

#include <array>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "../support/interpreter_fixture.hpp"
#include "../support/memory_files.hpp"
#include "gantry/core/diagnostic.hpp"
#include "gantry/interp/file_system.hpp"
#include "gantry/interp/interpreter.hpp"
#include "gantry/interp/operator_io.hpp"
#include "gantry/interp/persistent_store.hpp"
#include "gantry/lang/script.hpp"

namespace gantry {
namespace {

// Answers nothing by itself: a PAUSE or MSGBOX that reaches it is counted (and continued);
// PRINT "MARK" calls `mark` the first time, with the interpreter between two statements.
class MarkIO : public OperatorIO {
 public:
  void print(std::string_view text) override {
    printed += text;
    if (text.find("MARK") != std::string_view::npos && !marked && mark) {
      marked = true;
      mark();
    }
  }
  bool confirm(std::string_view, const SourceLoc&) override {
    ++questions;
    return true;
  }
  std::optional<std::string> ask(std::string_view, std::string_view variable, std::string_view,
                                 const SourceLoc&) override {
    ++asked;
    const auto it = answers.find(std::string(variable));
    return it == answers.end() ? std::nullopt : std::optional<std::string>(it->second);
  }
  std::string choose(std::string_view, const std::vector<std::string>& buttons, size_t def,
                     std::string_view, const SourceLoc&) override {
    ++questions;
    return buttons[def];
  }
  void warn(const Diagnostic&) override {}

  std::function<void()> mark;
  bool marked = false;
  int questions = 0, asked = 0;
  std::map<std::string, std::string> answers;
  std::string printed;
};

// What the interpreter holds at the MARK line.
struct Snapshot {
  ModalState state;
  Settings settings;
  std::map<std::string, std::optional<std::string>> vars;
  size_t moves_before = 0;  // moves the sink had received by then
};

class StartAtLine : public KeptInterpreterFixture {
 protected:
  StartAtLine() {
    settings.machine.limit_checking = false;
    settings.cutter.safe_z = 0.75;
  }
  OperatorIO& operator_io() override { return io; }  // the MarkIO below

  // A new interpreter that starts its files at line `from` (0: all of it).
  Interpreter& start_at(int from, bool dry_run = false) {
    options = InterpreterOptions();
    options.files = &files;
    options.start_line = from;
    options.dry_run = dry_run;
    return fresh_interp();
  }

  // Runs `text` as part.sbp from line `from` (0: all of it) on a fresh interpreter.
  void run(std::string_view text, int from = 0) {
    run_result = run_quietly(text, from);
    if (run_result) ADD_FAILURE() << format(*run_result);
  }
  std::optional<Diagnostic> run_quietly(std::string_view text, int from) {
    sink = RecordingSink();
    io = MarkIO();
    snap.reset();
    start_at(from);
    io.mark = [this] { snap = take(); };
    auto script = Script::from_text(std::string(text), "part.sbp");
    if (!script->ok()) return script->errors().front();
    try {
      interp().run(script);
    } catch (const GantryError& e) {
      return e.diagnostic();
    }
    return std::nullopt;
  }
  // The same, through check(): the diagnostics.
  std::vector<Diagnostic> check(std::string_view text, int from) {
    sink = RecordingSink();
    return start_at(from, true).check(Script::from_text(std::string(text), "part.sbp"));
  }
  Snapshot take() {
    Snapshot s;
    s.state = interp().state();
    s.settings = interp().settings();
    for (const char* name : names) {
      const Value* v = interp().variable(name);
      s.vars[name] = v ? std::optional<std::string>(v->to_string()) : std::nullopt;
    }
    s.moves_before = sink.moves.size();
    return s;
  }

  std::vector<CanonMove> lines() const {
    std::vector<CanonMove> out;
    for (const CanonMove& m : sink.moves)
      if (m.kind == MoveKind::Line || m.kind == MoveKind::Arc) out.push_back(m);
    return out;
  }

  MemoryFiles files;
  MarkIO io;  // the operator, in place of the fixture's
  std::optional<Snapshot> snap;
  std::optional<Diagnostic> run_result;
  std::vector<const char*> names = {"DEPTH", "COUNT", "N", "ANSWER", "SUBS"};
};

void expect_vec(const Vec6& got, const Vec6& want, const char* what) {
  for (int i = 0; i < kAxisCount; ++i) EXPECT_EQ(got[i], want[i]) << what << " axis " << i;
}
void expect_groups(const GroupSpeeds& a, const GroupSpeeds& b, const char* what) {
  EXPECT_EQ(a.xy, b.xy) << what;
  EXPECT_EQ(a.z, b.z) << what;
  EXPECT_EQ(a.a, b.a) << what;
}

// Every part of the language's state, compared exactly.
void expect_same(const Snapshot& a, const Snapshot& b) {
  expect_vec(a.state.position, b.state.position, "position");
  expect_vec(a.state.zero, b.state.zero, "zero");
  expect_vec(a.state.machine_origin, b.state.machine_origin, "machine origin");
  expect_vec(a.state.tool_offset, b.state.tool_offset, "tool offset");
  EXPECT_EQ(a.state.absolute, b.state.absolute);
  expect_groups(a.state.speeds.move, b.state.speeds.move, "move speeds");
  expect_groups(a.state.speeds.jog, b.state.speeds.jog, "jog speeds");
  EXPECT_EQ(a.state.outputs, b.state.outputs);
  EXPECT_EQ(a.state.last_xy_move, b.state.last_xy_move);
  EXPECT_EQ(a.state.cg_center_offset, b.state.cg_center_offset);
  EXPECT_EQ(a.state.tabs_on, b.state.tabs_on);
  EXPECT_EQ(a.state.tab_count, b.state.tab_count);
  EXPECT_EQ(a.state.tab_travel, b.state.tab_travel);
  EXPECT_EQ(a.state.tab_lift, b.state.tab_lift);
  EXPECT_EQ(a.state.preview.has_value(), b.state.preview.has_value());
  EXPECT_EQ(a.settings.cutter.diameter, b.settings.cutter.diameter);
  EXPECT_EQ(a.settings.cutter.safe_z, b.settings.cutter.safe_z);
  EXPECT_EQ(a.settings.ramps.move_ramp_speed.xy, b.settings.ramps.move_ramp_speed.xy);
  EXPECT_EQ(a.vars, b.vars);
}

// A file that sets a bit of everything before its MARK line (20), which then cuts on.
constexpr std::string_view kEverything =
    "' setup\n"                       // 1
    "MS, 2.5, 1.25\n"                 // 2
    "JS, 6, 3\n"                      // 3
    "VS, 1.5\n"                       // 4
    "&depth = -0.25\n"                // 5
    "&count = 0\n"                    // 6
    "SO, 1, 1\n"                      // 7
    "J3, 2, 3, 1\n"                   // 8
    "ZX\n"                            // 9
    "ZY\n"                            // 10
    "VC, 0.125, , , 0.5\n"            // 11
    "SR\n"                            // 12
    "M3, 1, 1, &depth\n"              // 13
    "CG, , 1, 0, 0.5, 0\n"            // 14: a half circle, I and J kept
    "VR, 0.3\n"                       // 15
    "LOOP:\n"                         // 16
    "&count = &count + 1\n"           // 17
    "M2, 0.5, 0.25\n"                 // 18: SR: each pass 0.5, 0.25 further
    "IF &count < 3 THEN GOTO LOOP\n"  // 19
    "PRINT \"MARK\"\n"                // 20
    "M2, -1, 0\n"                     // 21
    "SA\n"                            // 22
    "M2, 0, 0\n";                     // 23

TEST_F(StartAtLine, ThePrefixLeavesModesVariablesValuesAndPositionAsAFullRunDoes) {
  run(kEverything);
  ASSERT_TRUE(snap);
  const Snapshot full = *snap;
  const std::vector<CanonMove> full_moves = sink.moves;
  EXPECT_EQ(full.state.position[0], 3.5);  // 1 + 1 (the CG) + 3 x 0.5 (the loop), from ZX
  EXPECT_EQ(full.state.position[1], 1.75);
  EXPECT_EQ(*full.vars.at("COUNT"), "3");

  run(kEverything, 20);
  ASSERT_TRUE(snap);
  expect_same(*snap, full);
  // From the start line on, the moves are those of the full run from the same point.
  const std::vector<CanonMove> tail(sink.moves.begin() + static_cast<long>(snap->moves_before),
                                    sink.moves.end());
  const std::vector<CanonMove> full_tail(full_moves.begin() + static_cast<long>(full.moves_before),
                                         full_moves.end());
  ASSERT_EQ(tail.size(), full_tail.size());
  ASSERT_FALSE(tail.empty());
  for (size_t i = 0; i < tail.size(); ++i) {
    EXPECT_EQ(tail[i].kind, full_tail[i].kind) << i;
    expect_vec(tail[i].from, full_tail[i].from, "from");
    expect_vec(tail[i].to, full_tail[i].to, "to");
    EXPECT_EQ(tail[i].loc.line, full_tail[i].loc.line) << i;
  }
}

// Inside a loop, the start line is the first time the line is reached.
TEST_F(StartAtLine, InALoopTheStartIsTheFirstPass) {
  const std::string text =
      "&n = 0\n"                      // 1
      "AGAIN:\n"                      // 2
      "&n = &n + 1\n"                 // 3
      "J2, &n, 1\n"                   // 4
      "PRINT \"MARK\"\n"              // 5
      "IF &n < 4 THEN GOTO AGAIN\n";  // 6
  run(text);
  ASSERT_TRUE(snap);
  const Snapshot full = *snap;
  EXPECT_EQ(*full.vars.at("N"), "1");
  run(text, 5);
  ASSERT_TRUE(snap);
  expect_same(*snap, full);
  EXPECT_EQ(io.printed, "MARK\nMARK\nMARK\nMARK\n");  // the first pass's PRINT and three more
}

// In a subroutine, too: the GOSUB before it is remembered, so RETURN goes back to it.
TEST_F(StartAtLine, InASubroutineTheReturnGoesBackToTheCall) {
  const std::string text =
      "&subs = 0\n"          // 1
      "GOSUB CUT\n"          // 2
      "J2, 5, 5\n"           // 3
      "GOSUB CUT\n"          // 4
      "END\n"                // 5
      "CUT:\n"               // 6
      "&subs = &subs + 1\n"  // 7
      "PRINT \"MARK\"\n"     // 8
      "M2, &subs, 0\n"       // 9
      "RETURN\n";            // 10
  run(text);
  ASSERT_TRUE(snap);
  const Snapshot full = *snap;
  const std::vector<CanonMove> full_lines = lines();
  run(text, 8);
  ASSERT_TRUE(snap);
  expect_same(*snap, full);
  // Line 9 of the first call, the J2 of line 3, line 9 of the second call: the whole run's
  // moves, with no approach (the tool is where the file has it at line 8: 0, 0, 0).
  const std::vector<CanonMove> got = lines();
  ASSERT_EQ(got.size(), 3u);
  ASSERT_EQ(full_lines.size(), 3u);
  const int want_lines[] = {9, 3, 9};
  for (size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].loc.line, want_lines[i]) << i;
    expect_vec(got[i].from, full_lines[i].from, "from");
    expect_vec(got[i].to, full_lines[i].to, "to");
  }
}

// The approach: up to Safe-Z at jog speed, across at jog speed, down at move speed, then the
// start line; nothing before (the MS and JS stops, the moves of lines 3-5, reach no machine).
TEST_F(StartAtLine, TheApproachRisesToSafeZCrossesAndGoesDown) {
  const std::string text =
      "MS, 2, 1\n"         // 1
      "JS, 5, 4\n"         // 2
      "J3, 1, 1, 0.5\n"    // 3
      "M3, 1, 1, -0.25\n"  // 4
      "M2, 3, 1\n"         // 5
      "M2, 3, 3\n";        // 6
  run(text, 6);
  ASSERT_EQ(sink.moves.size(), 4u);
  EXPECT_EQ(interp().moves_emitted(), 4u);  // the moves of lines 3-5 are not counted
  const struct {
    std::array<double, 3> from, to;
    SpeedClass cls;
    double xy, z;
  } want[] = {{{0, 0, 0}, {0, 0, 0.75}, SpeedClass::Jog, 5, 4},
              {{0, 0, 0.75}, {3, 1, 0.75}, SpeedClass::Jog, 5, 4},
              {{3, 1, 0.75}, {3, 1, -0.25}, SpeedClass::Move, 2, 1},
              {{3, 1, -0.25}, {3, 3, -0.25}, SpeedClass::Move, 2, 1}};
  for (size_t i = 0; i < 4; ++i) {
    const CanonMove& m = sink.moves[i];
    EXPECT_EQ(m.kind, MoveKind::Line) << i;
    for (int a = 0; a < 3; ++a) {
      EXPECT_EQ(m.from[a], want[i].from[a]) << i << " axis " << a;
      EXPECT_EQ(m.to[a], want[i].to[a]) << i << " axis " << a;
    }
    EXPECT_EQ(m.speed_class, want[i].cls) << i;
    EXPECT_EQ(m.speeds.xy, want[i].xy) << i;
    EXPECT_EQ(m.speeds.z, want[i].z) << i;
    EXPECT_EQ(m.loc.line, 6) << i;
  }
}

// Above Safe-Z already (the tool, or the place it goes to): it never goes down to travel.
TEST_F(StartAtLine, TheApproachNeverGoesDownToCross) {
  run("J3, 1, 1, 2\nM2, 2, 2\n", 2);  // the target is at Z 2, above Safe-Z 0.75
  ASSERT_EQ(sink.moves.size(), 3u);
  EXPECT_EQ(sink.moves[0].to[2], 2);  // straight up to 2
  EXPECT_EQ(sink.moves[1].to[0], 1);  // across at 2
  EXPECT_EQ(sink.moves[1].to[2], 2);
  EXPECT_EQ(sink.moves[2].to[0], 2);  // the start line: no descent was needed
  // The file itself moved the tool's real position up first: a second run starting there.
  settings.cutter.safe_z = -1;  // Safe-Z below the tool: it stays at its own height, 0
  run("M3, 1, 1, -0.5\nMX, 2\n", 2);
  ASSERT_EQ(sink.moves.size(), 3u);
  EXPECT_EQ(sink.moves[0].to[0], 1);  // across at Z 0 (no rise: 0 is above Safe-Z)
  EXPECT_EQ(sink.moves[0].to[2], 0);
  EXPECT_EQ(sink.moves[0].speed_class, SpeedClass::Jog);
  EXPECT_EQ(sink.moves[1].to[2], -0.5);  // down at move speed
  EXPECT_EQ(sink.moves[1].speed_class, SpeedClass::Move);
  EXPECT_EQ(sink.moves[2].to[0], 2);
}

// An approach that would leave the soft limits is an error at the start line, found before
// anything (an output switch included) is sent.
TEST_F(StartAtLine, AnApproachOutsideTheSoftLimitsMovesNothing) {
  settings.machine.limit_checking = true;
  settings.cutter.safe_z = 10;  // above Z's travel (5.5): the rise cannot be made
  const std::optional<Diagnostic> d = run_quietly("SO, 1, 1\nM3, 1, 1, -0.25\nMX, 2\n", 3);
  ASSERT_TRUE(d);
  EXPECT_EQ(d->loc.line, 3);
  EXPECT_EQ(d->message.rfind("move to Z=10.0000 is outside the soft limits", 0), 0u) << d->message;
  for (const CanonMove& m : sink.moves) EXPECT_NE(m.kind, MoveKind::Output);
  for (const CanonMove& m : sink.moves) EXPECT_NE(m.kind, MoveKind::Line);
}

// What the machine did not see: the values change (once), then the output switches the lines
// before left on; PRINT, PAUSE and MSGBOX there show and ask nothing; INPUT still asks.
TEST_F(StartAtLine, TheMachineCatchesUpWithValuesAndOutputsAndTheOperatorIsNotAsked) {
  io.answers["&ANSWER"] = "7";
  const std::string text =
      "PRINT \"before\"\n"            // 1
      "PAUSE\n"                       // 2
      "MSGBOX(\"Sure?\", YesNo)\n"    // 3
      "SO, 2, 1\n"                    // 4
      "SO, 3, 1\n"                    // 5
      "SO, 3, 0\n"                    // 6
      "VR, 0.3\n"                     // 7
      "INPUT \"How many\" &answer\n"  // 8
      "PRINT \"after\"\n"             // 9
      "MX, 1\n";                      // 10
  sink = RecordingSink();
  io.answers["&ANSWER"] = "7";
  start_at(9);
  interp().run(Script::from_text(text, "part.sbp"));
  EXPECT_EQ(io.printed, "after\n");
  EXPECT_EQ(io.questions, 0);
  EXPECT_EQ(io.asked, 1);
  ASSERT_NE(interp().variable("ANSWER"), nullptr);
  EXPECT_EQ(interp().variable("ANSWER")->to_string(), "7");
  ASSERT_EQ(sink.changes.size(), 1u);
  EXPECT_EQ(sink.changes[0].ramps.move_ramp_speed.xy, 0.3);
  // A stop (for the values), output 2 on, the move of line 10; then the end of the run
  // switches it off again. Output 3 never went on.
  ASSERT_GE(sink.moves.size(), 4u);
  EXPECT_EQ(sink.moves[0].kind, MoveKind::Stop);
  EXPECT_EQ(sink.moves[1].kind, MoveKind::Output);
  EXPECT_EQ(sink.moves[1].output, 2);
  EXPECT_TRUE(sink.moves[1].output_on);
  EXPECT_EQ(sink.moves[1].loc.line, 9);
  EXPECT_EQ(sink.moves[2].kind, MoveKind::Line);
  EXPECT_EQ(sink.moves[2].loc.line, 10);
  EXPECT_EQ(sink.moves[3].kind, MoveKind::Output);
  EXPECT_FALSE(sink.moves[3].output_on);
  EXPECT_EQ(sink.moves.size(), 4u);
}

// A blank line, a comment or a label starts at the next statement.
TEST_F(StartAtLine, ABlankCommentOrLabelStartsAtTheNextStatement) {
  run("MX, 1\n\n' cut\nNEXT ONE:\nMY, 2\n", 2);
  const std::vector<CanonMove> got = lines();
  ASSERT_EQ(got.size(), 4u);  // up, across to (1, 0), down to Z 0, then MY
  for (size_t i = 0; i < 3; ++i) EXPECT_EQ(got[i].loc.line, 5) << i;
  EXPECT_EQ(got[1].to[0], 1);
  EXPECT_EQ(got[1].to[2], 0.75);
  EXPECT_EQ(got[2].to[2], 0);
  EXPECT_EQ(got[3].to[1], 2);
  EXPECT_EQ(got[3].loc.line, 5);
}

TEST_F(StartAtLine, AStartLinePastTheEndIsALocatedErrorAndNothingMoves) {
  const std::optional<Diagnostic> d = run_quietly("MX, 1\nMY, 1\n' the end\n\n", 3);
  ASSERT_TRUE(d);
  EXPECT_EQ(format(*d),
            "part.sbp:3: error: start line 3 is past the end of part.sbp: it has 4 lines and no "
            "statement from line 3 on; nothing was moved");
  EXPECT_TRUE(sink.moves.empty());
  const std::optional<Diagnostic> far = run_quietly("MX, 1\n", 40);
  ASSERT_TRUE(far);
  EXPECT_EQ(far->loc.line, 40);
  EXPECT_TRUE(sink.moves.empty());
}

TEST_F(StartAtLine, ALineNeverReachedIsALocatedErrorAndNothingMoves) {
  const std::optional<Diagnostic> d =
      run_quietly("MX, 1\nGOTO ON\nMY, 1\nON:\nMZ, -1\nEND\nMX, 9\n", 3);
  ASSERT_TRUE(d);
  EXPECT_EQ(format(*d),
            "part.sbp:3: error: line 3 of part.sbp is never reached when the file runs (it is "
            "after its END, in a subroutine no GOSUB calls, or jumped over); nothing was moved");
  EXPECT_TRUE(sink.moves.empty());
  // After END, too; and ENDALL before it.
  ASSERT_TRUE(run_quietly("MX, 1\nEND\nMX, 9\n", 3));
  EXPECT_TRUE(sink.moves.empty());
  ASSERT_TRUE(run_quietly("MX, 1\nENDALL\nMX, 9\n", 3));
  EXPECT_TRUE(sink.moves.empty());
}

// SP ... SM: the moves between reach no motor, so a start there has nothing to resume from.
TEST_F(StartAtLine, AStartLineInsideAPreviewIsALocatedErrorAndNothingMoves) {
  const std::optional<Diagnostic> d = run_quietly("MX, 1\nSP\nMY, 1\nMY, 2\nSM\nMX, 3\n", 4);
  ASSERT_TRUE(d);
  EXPECT_EQ(format(*d),
            "part.sbp:4: error: line 4 is inside a preview (SP before it, and no SM yet): "
            "nothing reached the machine there, so there is no place to resume from; start "
            "before the SP or after the SM; nothing was moved");
  EXPECT_TRUE(sink.moves.empty());
  run("MX, 1\nSP\nMY, 1\nSM\nMX, 3\n", 5);  // after the SM: fine
  EXPECT_EQ(lines().back().to[0], 3);
}

// The check before a run finds the same errors, so `gantry run --from-line` refuses first.
TEST_F(StartAtLine, TheCheckReportsAStartLineThatCannotBeReached) {
  const std::vector<Diagnostic> found = check("MX, 1\nEND\nMX, 9\n", 3);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].severity, Severity::Error);
  EXPECT_EQ(found[0].loc.line, 3);
  EXPECT_NE(found[0].message.find("is never reached"), std::string::npos);
  EXPECT_TRUE(check("MX, 1\nMX, 9\n", 2).empty());
}

// Fact 106 (as far as Gantry goes): FG runs a file from a chosen line, like FP with a start
// line, its parameter 10.
TEST_F(StartAtLine, Fact106_FgRunsAFileFromAChosenLine) {
  files.texts["part.sbp"] = "M3, 1, 1, -0.1\nM2, 2, 1\nM2, 2, 2\n";
  run("J2, 5, 5\nFG, part.sbp, , , , , , , , , 3\nMX, 0\n");
  const std::vector<CanonMove> got = lines();
  ASSERT_EQ(got.size(), 6u);
  const std::array<double, 3> want[] = {{5, 5, 0},    {5, 5, 0.75}, {2, 1, 0.75},
                                        {2, 1, -0.1}, {2, 2, -0.1}, {0, 2, -0.1}};
  for (size_t i = 0; i < got.size(); ++i)
    for (int a = 0; a < 3; ++a) EXPECT_EQ(got[i].to[a], want[i][a]) << i << " axis " << a;
  EXPECT_EQ(got[1].speed_class, SpeedClass::Jog);
  EXPECT_EQ(got[3].speed_class, SpeedClass::Move);
  EXPECT_EQ(*got[1].loc.file, "part.sbp");
  EXPECT_EQ(got[1].loc.line, 3);
}

TEST_F(StartAtLine, FgStartLineErrorsAreLocatedAtItsParameter) {
  files.texts["part.sbp"] = "MX, 1\n";
  const std::optional<Diagnostic> d = run_quietly("J2, 5, 5\nFG, part.sbp, , , , , , , , , 7\n", 0);
  ASSERT_TRUE(d);
  EXPECT_EQ(d->loc.line, 2);
  EXPECT_EQ(d->loc.column, 31);
  EXPECT_EQ(d->message,
            "start line 7 is past the end of part.sbp: it has 1 lines and no statement from "
            "line 7 on; nothing was moved");
  const std::optional<Diagnostic> zero = run_quietly("FG, part.sbp, , , , , , , , , 0\n", 0);
  ASSERT_TRUE(zero);
  EXPECT_EQ(zero->message, "FG parameter 10 (start line) is 0; allowed: 1 to 1000000000");
}

}  // namespace
}  // namespace gantry
