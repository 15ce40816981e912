// The part-file language as implemented, end to end: text in, canonical moves, variables,
// operator traffic and located errors out. Golden tests of the handbook's example programs
// (spec language.md §6, with the expectations of §7), regression tests for defects found in
// FabMo's interpreter, and every program statement with its error cases.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <deque>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "../support/interpreter_fixture.hpp"
#include "../support/temp_dir.hpp"
#include "../support/where.hpp"
#include "gantry/canon/canon_move.hpp"
#include "gantry/core/diagnostic.hpp"
#include "gantry/core/diagnostic_log.hpp"
#include "gantry/interp/interpreter.hpp"
#include "gantry/interp/operator_io.hpp"
#include "gantry/interp/persistent_store.hpp"
#include "gantry/interp/value.hpp"
#include "gantry/lang/script.hpp"
#include "gantry/settings/settings.hpp"

namespace gantry {
namespace {

namespace fs = std::filesystem;

// ---- helpers ----------------------------------------------------------------------------

// Collects every move, and when each flush came (how many moves had been emitted by then).
class FlushTrackingSink : public MotionSink {
 public:
  void move(const CanonMove& m) override {
    if (m.kind == MoveKind::Stop) {  // MS and JS punctuation: tested in interpreter_test
      ++stops;
      return;
    }
    moves.push_back(m);
    flushes_seen_by_move.push_back(flushes);
  }
  void flush() override {
    ++flushes;
    moves_at_flush.push_back(moves.size());
  }
  int stops = 0;

  std::vector<CanonMove> moves;
  std::vector<int> flushes_seen_by_move;  // flushes so far, when each move arrived
  std::vector<size_t> moves_at_flush;
  int flushes = 0;
};

// An operator that records every question and answers from a script of its own.
class RecordingIO : public OperatorIO {
 public:
  struct Call {
    std::string kind;  // print, confirm, ask, choose, warn
    std::string text;  // the message, prompt or body
    std::string variable;
    std::string default_value;
    std::vector<std::string> buttons;
    size_t default_button = 0;
    std::string title;
    SourceLoc loc;
  };

  void print(std::string_view text) override {
    printed += text;
    calls.push_back({"print", std::string(text), {}, {}, {}, 0, {}, {}});
  }
  bool confirm(std::string_view message, const SourceLoc& loc) override {
    calls.push_back({"confirm", std::string(message), {}, {}, {}, 0, {}, loc});
    return confirm_answer;
  }
  std::optional<std::string> ask(std::string_view prompt, std::string_view variable,
                                 std::string_view default_value, const SourceLoc& loc) override {
    calls.push_back({"ask",
                     std::string(prompt),
                     std::string(variable),
                     std::string(default_value),
                     {},
                     0,
                     {},
                     loc});
    if (answers.empty()) return std::nullopt;
    std::optional<std::string> a = answers.front();
    answers.pop_front();
    return a;
  }
  std::string choose(std::string_view text, const std::vector<std::string>& buttons,
                     size_t default_button, std::string_view title, const SourceLoc& loc) override {
    calls.push_back(
        {"choose", std::string(text), {}, {}, buttons, default_button, std::string(title), loc});
    return choice ? *choice : buttons.at(default_button);
  }
  void warn(const Diagnostic& d) override {
    warnings.push_back(d);
    calls.push_back({"warn", d.message, {}, {}, {}, 0, {}, d.loc});
  }

  // The calls of one kind, in order.
  std::vector<Call> of(std::string_view kind) const {
    std::vector<Call> out;
    for (const Call& c : calls)
      if (c.kind == kind) out.push_back(c);
    return out;
  }

  std::vector<Call> calls;
  std::string printed;
  std::vector<Diagnostic> warnings;
  bool confirm_answer = true;
  std::deque<std::optional<std::string>> answers;  // INPUT answers in order; empty cancels
  std::optional<std::string> choice;               // MSGBOX: the button pressed (default: default)
};

// "FILE:LINE:COL" of a location, so that one expectation checks all three.
Vec6 at(double x, double y = 0, double z = 0, double a = 0, double b = 0, double c = 0) {
  Vec6 v;
  v << x, y, z, a, b, c;
  return v;
}

std::string show(const Vec6& v) {
  std::ostringstream s;
  s << "(" << v[0] << ", " << v[1] << ", " << v[2] << ", " << v[3] << ", " << v[4] << ", " << v[5]
    << ")";
  return s.str();
}

void expect_vec(const Vec6& actual, const Vec6& expected, const std::string& what = "") {
  for (int i = 0; i < kAxisCount; ++i)
    EXPECT_NEAR(actual[i], expected[i], 1e-12)
        << what << " axis " << kAxisLetters[i] << ": " << show(actual) << " vs " << show(expected);
}

// One expected straight move: its class and its end point (its start is the previous end).
struct Step {
  SpeedClass cls;
  Vec6 to;
};
constexpr SpeedClass kMove = SpeedClass::Move;
constexpr SpeedClass kJog = SpeedClass::Jog;

// The moves are exactly `steps`, a continuous path from `start`.
void expect_path(const std::vector<CanonMove>& moves, const std::vector<Step>& steps,
                 Vec6 start = Vec6::Zero()) {
  ASSERT_EQ(moves.size(), steps.size());
  Vec6 from = start;
  for (size_t i = 0; i < steps.size(); ++i) {
    const std::string what = "move " + std::to_string(i);
    EXPECT_EQ(moves[i].kind, MoveKind::Line) << what;
    EXPECT_EQ(moves[i].speed_class, steps[i].cls) << what;
    expect_vec(moves[i].from, from, what + " from");
    expect_vec(moves[i].to, steps[i].to, what + " to");
    from = steps[i].to;
  }
}

bool has_error(const std::vector<Diagnostic>& ds) {
  for (const Diagnostic& d : ds)
    if (d.severity == Severity::Error) return true;
  return false;
}

std::string all(const std::vector<Diagnostic>& ds) {
  std::string out;
  for (const Diagnostic& d : ds) out += format(d) + "\n";
  return out;
}

enum class Ending { Normal, Error, NeedsOperator, OperatorStop };

const char* ending_name(Ending e) {
  switch (e) {
    case Ending::Normal:
      return "normal";
    case Ending::Error:
      return "error";
    case Ending::NeedsOperator:
      return "needs-operator";
    default:
      return "operator-stop";
  }
}

struct Outcome {
  Ending ending = Ending::Normal;
  Diagnostic diag;
};

class LanguageTest : public BasicKeptInterpreterFixture<FlushTrackingSink> {
 protected:
  // The scripted operator made from `yes` and `inputs` as the test set them, or `rec`.
  OperatorIO& operator_io() override {
    if (use_recording_io) return rec;
    scripted_.emplace(yes, inputs, &printed);
    return *scripted_;
  }
  const ScriptedIO& scripted() {
    interp();
    return *scripted_;
  }

  TempDir& dir() {
    if (!dir_) dir_.emplace("language_test");
    return *dir_;
  }

  // Runs a script and says how it ended.
  Outcome execute(const std::shared_ptr<const Script>& script) {
    try {
      interp().run(script);
      return {};
    } catch (const NeedsOperator& e) {
      return {Ending::NeedsOperator, e.diagnostic()};
    } catch (const OperatorStop& e) {
      return {Ending::OperatorStop, e.diagnostic()};
    } catch (const GantryError& e) {
      return {Ending::Error, e.diagnostic()};
    }
  }
  // Runs a script on an interpreter of its own (same settings and options, no operator).
  Outcome execute_fresh(const std::shared_ptr<const Script>& script) {
    FlushTrackingSink s;
    ScriptedIO io(true, {});
    PersistentStore st;
    Interpreter fresh(settings, s, io, st, options);
    try {
      fresh.run(script);
      return {};
    } catch (const GantryError& e) {
      return {Ending::Error, e.diagnostic()};
    }
  }
  Outcome execute(std::string_view text, const std::string& name = "part.sbp") {
    return execute(Script::from_text(std::string(text), name));
  }

  // Runs `text` (as part.sbp); any error fails the test.
  void run(std::string_view text) {
    const auto script = Script::from_text(std::string(text), "part.sbp");
    EXPECT_FALSE(has_error(script->errors())) << all(script->errors());
    const Outcome o = execute(script);
    EXPECT_EQ(o.ending, Ending::Normal) << ending_name(o.ending) << ": " << format(o.diag);
  }
  // Runs the file at `path`; any error fails the test.
  void run_file(const std::string& path) {
    const Outcome o = execute(Script::load(path));
    EXPECT_EQ(o.ending, Ending::Normal) << ending_name(o.ending) << ": " << format(o.diag);
  }
  // Runs expecting an error (not an operator stop); returns it.
  Diagnostic run_error(std::string_view text) {
    const Outcome o = execute(text);
    EXPECT_EQ(o.ending, Ending::Error) << "from:\n" << text;
    return o.diag;
  }
  Diagnostic run_file_error(const std::string& path) {
    const Outcome o = execute(Script::load(path));
    EXPECT_EQ(o.ending, Ending::Error) << "from " << path;
    return o.diag;
  }
  std::vector<Diagnostic> check(std::string_view text) {
    return interp().check(Script::from_text(std::string(text), "part.sbp"));
  }

  const Value* var(std::string_view upper_name) { return interp().variable(upper_name); }
  void expect_number(std::string_view name, double expected) {
    const Value* v = var(name);
    ASSERT_NE(v, nullptr) << "&" << name << " is undefined";
    ASSERT_TRUE(v->is_number()) << "&" << name << " holds the text \"" << v->str() << "\"";
    EXPECT_DOUBLE_EQ(v->num(), expected) << "&" << name;
  }
  void expect_text(std::string_view name, std::string_view expected) {
    const Value* v = var(name);
    ASSERT_NE(v, nullptr) << "&" << name << " is undefined";
    ASSERT_TRUE(v->is_string()) << "&" << name << " holds the number " << v->num();
    EXPECT_EQ(v->str(), expected) << "&" << name;
  }

  // The scripted operator (the CLI's --yes / --input), unless use_recording_io.
  bool yes = true;
  std::map<std::string, std::string> inputs;
  bool use_recording_io = false;
  RecordingIO rec;

 private:
  std::optional<TempDir> dir_;
  std::optional<ScriptedIO> scripted_;
};

const std::string kUnknownSuffix = "; see docs/commands.md for the commands Gantry knows";

// =========================================================================================
// 1. The handbook's example programs (spec language.md §6), as golden tests
// =========================================================================================

// Example 1 — simple rectangle. §7.12: ends at X10 Y10 Z0.5, cutting the path
// (10,10)→(20,10)→(20,5)→(10,5)→(10,10) at Z -0.25.
TEST_F(LanguageTest, Example1SimpleRectangle) {
  run(R"sbp(JZ, .5
J2, 10, 10
MZ, -.25
M2, 20, 10
M2, 20, 5
M2, 10, 5
M2, 10, 10
JZ, .5
)sbp");
  expect_path(moves(), {{kJog, at(0, 0, .5)},
                        {kJog, at(10, 10, .5)},
                        {kMove, at(10, 10, -.25)},
                        {kMove, at(20, 10, -.25)},
                        {kMove, at(20, 5, -.25)},
                        {kMove, at(10, 5, -.25)},
                        {kMove, at(10, 10, -.25)},
                        {kJog, at(10, 10, .5)}});
  for (size_t i = 0; i < moves().size(); ++i)
    EXPECT_EQ(where(moves()[i].loc), "part.sbp:" + std::to_string(i + 1) + ":1");
  expect_vec(state().position, at(10, 10, .5));
  EXPECT_EQ(sink.flushes, 1);
}

// Example 2, verbatim: `M23, 4.2` is rejected, and the handbook's wrapped comment lines are
// not comments in a real file.
const char* const kExample2 = R"sbp(M2, 3, 4.2      'ok ... using comma as Command separator
M2 3, 4.2      'ok ... using space as Command separator
M23, 4.2       'WRONG ... no separator
M2,, 4.2       'This commands moves Y to 4.2 because first
                comma is the separator (no X value)
M2 , 4.2       'This commands moves Y to 4.2 because space
                is the separator (no X value)
M2, 4.2        'This commands moves X to 4.2 because comma
                is the separator (thus no Y value)
M2 4.2         'This commands also moves X to 4.2 (no Y value)
)sbp";

TEST_F(LanguageTest, Example2VerbatimRejectsM23AndTheWrappedCommentLines) {
  const auto script = Script::from_text(kExample2, "part.sbp");
  const std::vector<Diagnostic>& errors = script->errors();
  ASSERT_EQ(errors.size(), 2u) << all(errors);
  EXPECT_EQ(format(errors[0]),
            "part.sbp:3:3: error: expected a space or a comma after the command M2; write "
            "`M2, 3`");
  EXPECT_EQ(format(errors[1]),
            "part.sbp:5:17: error: unknown statement 'comma'; commands are two characters, such "
            "as MX or J3, and statements are words such as IF, GOTO or PAUSE");
  // A file with a syntax error never starts: nothing moves.
  const Outcome o = execute(script);
  EXPECT_EQ(o.ending, Ending::Error);
  EXPECT_EQ(where(o.diag.loc), "part.sbp:3:3");
  EXPECT_TRUE(moves().empty());
}

// The wrapped "is the separator ..." lines are syntactically a command IS; running reaches
// them and stops there.
TEST_F(LanguageTest, Example2WrappedLineIsAnUnknownCommandWhenReached) {
  const Diagnostic d = run_error("M2, 4.2\n                is the separator (no X value)\n");
  EXPECT_EQ(format(d), "part.sbp:2:17: error: unknown command 'IS'" + kUnknownSuffix);
}

// §7.6-10: each separator form, from X1 Y1 so that an axis left alone is visible.
TEST_F(LanguageTest, Example2EachSeparatorFormMovesTheDocumentedAxes) {
  const std::pair<const char*, Vec6> cases[] = {
      {"M2, 3, 4.2      'ok ... using comma as Command separator", at(3, 4.2)},
      {"M2 3, 4.2      'ok ... using space as Command separator", at(3, 4.2)},
      {"M2,, 4.2       'This commands moves Y to 4.2 because first", at(1, 4.2)},
      {"M2 , 4.2       'This commands moves Y to 4.2 because space", at(1, 4.2)},
      {"M2, 4.2        'This commands moves X to 4.2 because comma", at(4.2, 1)},
      {"M2 4.2         'This commands also moves X to 4.2 (no Y value)", at(4.2, 1)}};
  for (const auto& [line, target] : cases) {
    SCOPED_TRACE(line);
    sink.moves.clear();
    run(std::string("SA\nM2, 1, 1\n") + line + "\n");
    ASSERT_EQ(moves().size(), 2u);
    expect_vec(moves()[1].from, at(1, 1));
    expect_vec(moves()[1].to, target);
    EXPECT_EQ(moves()[1].speed_class, kMove);
  }
}

// Example 2 with the wrong line and the wrapped lines removed runs: only two of its lines
// change the position.
TEST_F(LanguageTest, Example2WithoutTheWrongLinesRuns) {
  run(R"sbp(M2, 3, 4.2      'ok ... using comma as Command separator
M2 3, 4.2      'ok ... using space as Command separator
M2,, 4.2       'This commands moves Y to 4.2 because first
M2 , 4.2       'This commands moves Y to 4.2 because space
M2, 4.2        'This commands moves X to 4.2 because comma
M2 4.2         'This commands also moves X to 4.2 (no Y value)
)sbp");
  expect_path(moves(), {{kMove, at(3, 4.2)}, {kMove, at(4.2, 4.2)}});
  EXPECT_EQ(where(moves()[1].loc), "part.sbp:5:1");
  EXPECT_EQ(interp().statements_executed(), 6u);
}

// Example 3 — master file ALLPARTS.SBP. Per §8 A1 the `2` is parameter 5 (repetitions), so
// MYPART.SBP runs twice at each spot, without offset; the master continues after each FP.
TEST_F(LanguageTest, Example3MasterFileRunsMyPartAtEachSpot) {
  settings.axes[0].max = 48;  // the master moves to X40
  dir().write("MYPART.SBP", "SR\nMX, 1\nMY, 1\nSA\n");
  const std::string master =
      dir().write("ALLPARTS.SBP", R"sbp('Start of master Part File ALLPARTS.SBP
M2, 10, 4           'move to location to start first part
  FP,  MYPART.SBP , , , , 2   'execute with 2D offset
M2, 20, 4           'move to start of second part
  FP,  MYPART.SBP , , , , 2   'execute with 2D offset
M2, 30, 4           '... and so on
  FP,  MYPART.SBP , , , , 2
M2, 40, 4
  FP,  MYPART.SBP , , , , 2
)sbp");
  EXPECT_TRUE(Script::load(master)->errors().empty());
  run_file(master);
  std::vector<Step> expected;
  for (double x : {10, 20, 30, 40}) {
    expected.push_back({kMove, at(x, 4)});
    expected.push_back({kMove, at(x + 1, 4)});  // first repetition
    expected.push_back({kMove, at(x + 1, 5)});
    expected.push_back({kMove, at(x + 2, 5)});  // second repetition, from where the first ended
    expected.push_back({kMove, at(x + 2, 6)});
  }
  expect_path(moves(), expected);
  // The moves are located in the file that made them.
  EXPECT_EQ(where(moves()[0].loc), master + ":2:1");
  EXPECT_EQ(where(moves()[1].loc), dir().path("MYPART.SBP") + ":2:1");
  EXPECT_EQ(where(moves()[4].loc), dir().path("MYPART.SBP") + ":3:1");
  EXPECT_EQ(where(moves()[5].loc), master + ":4:1");
  expect_vec(state().position, at(42, 6));
  EXPECT_TRUE(state().absolute);
}

// Example 4 — variables, all of the handbook's lines in one file. §7.18-23, §7.29.
TEST_F(LanguageTest, Example4Variables) {
  run(R"sbp(&Zdepth = -0.52
MZ, &Zdepth
&MyVariable = 5.0
&MyNewVariable = &MyVariable * 2.31-2
&MyString = test string      'string variable without quotes
&MyString = "test string"    'or, string variable with quotes
&firstname = Bill
&newstring = "My name is " & &firstname
M2, 1.5, 3.25
&Y_now = %(2)
)sbp");
  expect_path(moves(), {{kMove, at(0, 0, -0.52)}, {kMove, at(1.5, 3.25, -0.52)}});
  expect_number("ZDEPTH", -0.52);
  expect_number("MYVARIABLE", 5.0);
  expect_number("MYNEWVARIABLE", 5.0 * 2.31 - 2);
  EXPECT_EQ(format_number(var("MYNEWVARIABLE")->num()), "9.55");
  expect_text("MYSTRING", "test string");
  expect_text("FIRSTNAME", "Bill");
  expect_text("NEWSTRING", "My name is Bill");
  expect_number("Y_NOW", 3.25);
}

TEST_F(LanguageTest, Example4UnquotedAndQuotedStringsAreTheSame) {
  run("&MyString = test string      'string variable without quotes\n&a = &MyString\n");
  expect_text("A", "test string");
  run("&MyString = \"test string\"    'or, string variable with quotes\n");
  expect_text("MYSTRING", "test string");
  run("IF &MyString = &a THEN &same = 1\n");
  expect_number("SAME", 1);
}

// Example 5 — INPUT special cases: a prompt built from a variable (semicolon form) and a
// default value (colon form). §7.60-61.
TEST_F(LanguageTest, Example5InputDynamicPromptAndDefault) {
  use_recording_io = true;
  rec.answers = {"Y", "8"};
  run(R"sbp(&variable = 42
INPUT "You Entered - " & &variable & " Is this Correct? Y or N"; &test1
&default = 7.5
INPUT "Displaying default value - ": &default, &newvar
)sbp");
  const auto asks = rec.of("ask");
  ASSERT_EQ(asks.size(), 2u);
  EXPECT_EQ(asks[0].text, "You Entered - 42 Is this Correct? Y or N");
  EXPECT_EQ(asks[0].variable, "&TEST1");
  EXPECT_EQ(asks[0].default_value, "");
  EXPECT_EQ(where(asks[0].loc), "part.sbp:2:1");
  EXPECT_EQ(asks[1].text, "Displaying default value - ");
  EXPECT_EQ(asks[1].variable, "&NEWVAR");
  EXPECT_EQ(asks[1].default_value, "7.5");
  expect_text("TEST1", "Y");
  expect_text("NEWVAR", "8");
  expect_number("DEFAULT", 7.5);  // the default variable itself is not changed
}

// Example 6 — MSGBOX. §7.62: the pressed button's caption goes to &msganswer.
TEST_F(LanguageTest, Example6MsgBoxYesNo) {
  use_recording_io = true;
  rec.choice = "No";
  run("MSGBOX ( Do you want to open the keypad?, YesNo, Start Keypad?)\n");
  const auto boxes = rec.of("choose");
  ASSERT_EQ(boxes.size(), 1u);
  EXPECT_EQ(boxes[0].text, "Do you want to open the keypad?");
  EXPECT_EQ(boxes[0].buttons, (std::vector<std::string>{"Yes", "No"}));
  EXPECT_EQ(boxes[0].default_button, 0u);
  EXPECT_EQ(boxes[0].title, "Start Keypad?");
  expect_text("MSGANSWER", "No");
  EXPECT_EQ(state().speeds.move.xy, 2.0);  // not the MS command
}

TEST_F(LanguageTest, Example6MsgBoxYesNoWithYesPressesYes) {
  run("MSGBOX ( Do you want to open the keypad?, YesNo, Start Keypad?)\n");
  expect_text("MSGANSWER", "Yes");
}

TEST_F(LanguageTest, Example6MsgBoxCriticalIsOkOnly) {
  use_recording_io = true;
  run("MSGBOX (You can not cut plywood that thick with that size bit!,16,Thickness problem!)\n");
  const auto boxes = rec.of("choose");
  ASSERT_EQ(boxes.size(), 1u);
  EXPECT_EQ(boxes[0].text, "You can not cut plywood that thick with that size bit!");
  EXPECT_EQ(boxes[0].buttons, (std::vector<std::string>{"OK"}));
  EXPECT_EQ(boxes[0].title, "Thickness problem!");
  expect_text("MSGANSWER", "OK");
}

// As typeset in the handbook the second MSGBOX wraps onto two lines: both are syntax errors.
TEST_F(LanguageTest, Example6WrappedMsgBoxIsTwoSyntaxErrors) {
  const auto script = Script::from_text(
      "MSGBOX (You can not cut plywood that thick with that size\n"
      "        bit!,16,Thickness problem!)\n",
      "part.sbp");
  ASSERT_EQ(script->errors().size(), 2u) << all(script->errors());
  EXPECT_EQ(format(script->errors()[0]), "part.sbp:1:8: error: MSGBOX is missing its ')'");
  EXPECT_EQ(format(script->errors()[1]),
            "part.sbp:2:9: error: unknown statement 'bit'; commands are two characters, such as "
            "MX or J3, and statements are words such as IF, GOTO or PAUSE");
}

// Example 7 — OPEN: a relative name is created in the part file's folder.
TEST_F(LanguageTest, Example7OpenCreatesTheFileInThePartFileFolder) {
  dir().write("myfile.sbp", "old contents\n");
  run_file(dir().write("ex7.sbp", "OPEN \"myfile.sbp\" FOR OUTPUT as #1\nCLOSE #1\n"));
  EXPECT_EQ(dir().read("myfile.sbp"), "");  // overwritten
}

// §6 Example 7 / §5.14, docs/language.md §5.3: `myfolder\myfile.sbp` is the sub-folder
// myfolder on Linux too.
TEST_F(LanguageTest, Example7OpenWithBackslashUsesTheSubFolder) {
  fs::create_directories(dir().path("myfolder"));
  const Outcome o = execute(Script::load(dir().write(
      "ex7.sbp", "OPEN \"myfolder\\myfile.sbp\" FOR OUTPUT as #1\nWRITE #1, \"x\"\nCLOSE #1\n")));
  const bool in_sub_folder = dir().exists("myfolder/myfile.sbp");
  const bool stray_file = dir().exists("myfolder\\myfile.sbp");
  EXPECT_EQ(o.ending, Ending::Normal) << format(o.diag);
  EXPECT_TRUE(in_sub_folder);
  EXPECT_EQ(dir().read("myfolder/myfile.sbp"), "x\n");
  EXPECT_FALSE(stray_file);
}

// §5.14, docs/language.md §5.3: a drive letter is refused, with the column of the name; it
// never becomes part of a file name.
TEST_F(LanguageTest, Example7OpenWithADriveLetterIsNotAFileName) {
  const Outcome o = execute(Script::load(
      dir().write("ex7.sbp", "OPEN \"C:\\myfolder\\myfile.sbp\" FOR OUTPUT as #1\nCLOSE #1\n")));
  const bool stray_file = dir().exists("C:\\myfolder\\myfile.sbp");
  EXPECT_EQ(o.ending, Ending::Error);
  EXPECT_EQ(o.diag.loc.line, 1);
  EXPECT_EQ(o.diag.loc.column, 6);
  EXPECT_EQ(o.diag.message,
            "C:\\myfolder\\myfile.sbp names a Windows drive; give a path on this machine, "
            "relative to the part file's folder or absolute");
  EXPECT_FALSE(stray_file);
}

// Example 8 — PAUSE shows the comment line just above it. As typeset, the comment wraps and
// its second line ("Continue)") is a syntax error.
TEST_F(LanguageTest, Example8VerbatimWrappedCommentIsASyntaxError) {
  const auto script = Script::from_text(
      "' Is the Vacuum Pump on? .... (Hit OK or ENTER when Ready to  \nContinue)  \nPAUSE\n",
      "part.sbp");
  ASSERT_EQ(script->errors().size(), 1u) << all(script->errors());
  EXPECT_EQ(format(script->errors()[0]),
            "part.sbp:2:1: error: unknown statement 'Continue'; commands are two characters, "
            "such as MX or J3, and statements are words such as IF, GOTO or PAUSE");
}

TEST_F(LanguageTest, Example8PauseShowsThePrecedingComment) {
  use_recording_io = true;
  run("' Is the Vacuum Pump on? .... (Hit OK or ENTER when Ready to Continue)  \nPAUSE\n");
  const auto asked = rec.of("confirm");
  ASSERT_EQ(asked.size(), 1u);
  EXPECT_EQ(asked[0].text, "Is the Vacuum Pump on? .... (Hit OK or ENTER when Ready to Continue)");
  EXPECT_EQ(where(asked[0].loc), "part.sbp:2:1");
  EXPECT_TRUE(moves().empty());
}

TEST_F(LanguageTest, Example8PauseCancelEndsTheRun) {
  use_recording_io = true;
  rec.confirm_answer = false;
  const Outcome o = execute(
      "' Is the Vacuum Pump on? .... (Hit OK or ENTER when Ready to Continue)  \n"
      "PAUSE\nMX, 1\n");
  EXPECT_EQ(o.ending, Ending::OperatorStop);
  EXPECT_EQ(format(o.diag), "part.sbp:2:1: error: stopped by the operator at PAUSE");
  EXPECT_TRUE(moves().empty());
}

TEST_F(LanguageTest, Example8TimedPauseIsADwell) {
  use_recording_io = true;
  run("MX, 1\n'Finished the first Cut-Out, Moving on to the Second  \nPAUSE 5\n");
  ASSERT_EQ(moves().size(), 2u);
  const CanonMove& d = moves()[1];
  EXPECT_EQ(d.kind, MoveKind::Dwell);
  EXPECT_DOUBLE_EQ(d.dwell_s, 5.0);
  expect_vec(d.from, at(1));
  expect_vec(d.to, at(1));
  EXPECT_EQ(where(d.loc), "part.sbp:3:1");
  EXPECT_TRUE(rec.of("confirm").empty());  // a timed pause asks nothing
}

// §2.8 [DOC]: "the comment is displayed for 5 seconds" — it must reach the operator somehow.
TEST_F(LanguageTest, Example8TimedPauseShowsThePrecedingComment) {
  use_recording_io = true;
  run("'Finished the first Cut-Out, Moving on to the Second  \nPAUSE 5\n");
  ASSERT_EQ(rec.calls.size(), 1u);  // shown, not asked: a timed pause needs no answer
  EXPECT_EQ(rec.calls[0].kind, "print");
  EXPECT_EQ(rec.calls[0].text, "Finished the first Cut-Out, Moving on to the Second\n");
  ASSERT_EQ(moves().size(), 1u);
  EXPECT_EQ(moves()[0].kind, MoveKind::Dwell);
  EXPECT_DOUBLE_EQ(moves()[0].dwell_s, 5.0);
}

// Example 9 — PLAY plays nothing on Gantry: a warning, and the file goes on. §7.91.
TEST_F(LanguageTest, Example9PlayWarnsAndContinues) {
  run("PLAY C:\\WINDOWS\\Media\\tada.wav  \nPAUSE 2\nMX, 1\n");
  ASSERT_EQ(scripted().warnings().size(), 1u);
  EXPECT_EQ(format(scripted().warnings()[0]),
            "part.sbp:1:1: warning: PLAY C:\\WINDOWS\\Media\\tada.wav: Gantry plays no sounds; the "
            "file continues");
  ASSERT_EQ(moves().size(), 2u);
  EXPECT_EQ(moves()[0].kind, MoveKind::Dwell);
  EXPECT_DOUBLE_EQ(moves()[0].dwell_s, 2.0);
  expect_vec(moves()[1].to, at(1));
}

// Example 10 — PRINT separators; exact strings per §2.10 REC.
TEST_F(LanguageTest, Example10PrintSemicolonFormKeepsTheText) {
  run("&firstvar = \"My number\"\nPRINT &firstvar; \" = 123,456 \"\n");
  EXPECT_EQ(printed, "My number = 123,456 \n");
}

TEST_F(LanguageTest, Example10PrintCommaFormSplitsAtEveryComma) {
  const auto script =
      Script::from_text("&firstvar = \"My number\"  \nPRINT &firstvar, \" = 123,456 \"\n", "p.sbp");
  ASSERT_FALSE(has_error(script->errors())) << all(script->errors());
  const Outcome o = execute(script);
  EXPECT_EQ(o.ending, Ending::Normal) << format(o.diag);
  EXPECT_EQ(printed, "My number      = 123     456 \n");
}

// Example 11 — a documented file: comments, REM, blank and indented lines change nothing.
// CR is not implemented yet.
const char* const kExample11 = R"sbp('This is an example of documenting a file
'You can use an apostrophe (or a REM) at start of a line
REM You can use an REM (or an apostrophe) at start of a line
'This file is to create a rectangle (written by me, 1/1/2000)
' ... none of the above effects the cutting of your file
' ... the line below is left blank for legibility

JZ, .5                                'this line pulls the bit up
J2, 10, 10                            'you can add a comment to a line
CR, 10, 5, , , , -.25, , , 1
    'You can indent lines or comments and add blank lines

'The End
)sbp";

TEST_F(LanguageTest, Example11PassesTheSyntaxPassAndCutsTheRectangle) {
  const auto script = Script::from_text(kExample11, "part.sbp");
  EXPECT_TRUE(script->errors().empty()) << all(script->errors());
  EXPECT_EQ(script->line_count(), 13);
  const Outcome o = execute(script);
  EXPECT_EQ(o.ending, Ending::Normal) << format(o.diag);
  // CR 10 x 5 from (10, 10), plunge -.25 from Z 0 (its ninth parameter), then back up to the
  // Z it started at, .5 (docs/cuts.md D9; up to Safe-Z, 1, before issue 21).
  expect_path(moves(), {{kJog, at(0, 0, .5)},
                        {kJog, at(10, 10, .5)},
                        {kMove, at(10, 10, 0)},
                        {kMove, at(10, 10, -.25)},
                        {kMove, at(10, 15, -.25)},
                        {kMove, at(20, 15, -.25)},
                        {kMove, at(20, 10, -.25)},
                        {kMove, at(10, 10, -.25)},
                        {kJog, at(10, 10, .5)}});
}

TEST_F(LanguageTest, Example11WithoutCrRuns) {
  std::string text = kExample11;
  text.erase(text.find("CR, 10"), std::string("CR, 10, 5, , , , -.25, , , 1\n").size());
  run(text);
  expect_path(moves(), {{kJog, at(0, 0, .5)}, {kJog, at(10, 10, .5)}});
  EXPECT_EQ(where(moves()[0].loc), "part.sbp:8:1");
  EXPECT_EQ(where(moves()[1].loc), "part.sbp:9:1");
  EXPECT_EQ(interp().statements_executed(), 2u);  // comments and blank lines are no statements
  EXPECT_EQ(printed, "");
}

// Example 12 — SHELL. Disabled unless allowed; `&` joins without a space (§8 A28).
const char* const kExample12 = R"sbp(SHELL, "sedit.exe c:\sbparts\sample_shopbot_logo.sbp"
SHELL, "C:\windows\notepad.exe", 1, SYNC
&filepath = "c:\sbparts\sample_shopbot_logo.sbp"
&run_this = "sedit.exe" & &filepath
SHELL, &run_this, 1, ASYNC
)sbp";

TEST_F(LanguageTest, Example12ShellIsDisabledByDefault) {
  const auto script = Script::from_text(kExample12, "part.sbp");
  EXPECT_TRUE(script->errors().empty()) << all(script->errors());
  const Outcome o = execute(script);
  EXPECT_EQ(o.ending, Ending::Error);
  EXPECT_EQ(format(o.diag),
            "part.sbp:1:1: error: SHELL starts other programs and is disabled; run with "
            "--allow-shell to permit it");
}

// A dry run (gantry check) starts no program, but still reports a SHELL that the real run
// would refuse.
TEST_F(LanguageTest, Example12DryRunSkipsShellAndJoinsWithoutASpace) {
  options.dry_run = true;
  options.allow_shell = true;
  run(kExample12);
  expect_text("FILEPATH", "c:\\sbparts\\sample_shopbot_logo.sbp");
  expect_text("RUN_THIS", "sedit.exec:\\sbparts\\sample_shopbot_logo.sbp");
}

TEST_F(LanguageTest, Example12DryRunStillReportsADisabledShell) {
  options.dry_run = true;
  EXPECT_EQ(format(run_error(kExample12)),
            "part.sbp:1:1: error: SHELL starts other programs and is disabled; run with "
            "--allow-shell to permit it");
}

// Example 13 — a virtual tool with a variable parameter: TR sets the spindle's speed (with no
// speed output in the profile it is recorded, with one warning); TC (the copy machine) checks
// its parameters like any command.
TEST_F(LanguageTest, Example13VirtualToolTakesVariableParameters) {
  const auto script = Script::from_text("&speed = 11500\nTR, &speed\n", "part.sbp");
  EXPECT_TRUE(script->errors().empty());
  const Outcome o = execute(script);
  EXPECT_EQ(o.ending, Ending::Normal) << format(o.diag);
  expect_number("SPEED", 11500);
  EXPECT_EQ(state().spindle_rpm, 11500);
  EXPECT_TRUE(Script::from_text("TC, 1500, small, 2\nTC, &some_value\n", "p.sbp")->ok());
  // TC is a known code (the copy machine tool); its parameter 2 is a number, not "small".
  EXPECT_EQ(format(run_error("TC, 1500, small, 2\n")).rfind("part.sbp:1:11: error: ", 0), 0u)
      << format(run_error("TC, 1500, small, 2\n"));
}

// Example 14 — WRITE. §7.77-79: all three forms write `M2, 23.5, 23.5`-style lines.
TEST_F(LanguageTest, Example14WriteForms) {
  run_file(dir().write("ex14.sbp", R"sbp(OPEN "out.txt" FOR OUTPUT AS #1
&someVar = 23.5  
Write #1; "&myVar = "; &someVar
&someVar = 23.5  
Write #1; "M2, "; &someVar; ", "; &someVar
&someVar = 23.5  
Write #1, "M2", &someVar, &someVar
CLOSE #1
)sbp"));
  EXPECT_EQ(dir().read("out.txt"), "&myVar = 23.5\nM2, 23.5, 23.5\nM2, 23.5, 23.5\n");
}

// Example 15 — setup lines.
const char* const kExample15 = R"sbp('Setup lines for this file
  VS, 1.25, .45, , 2.75, .80   'to set speeds
  VC, .25                     'always a .25 in cutter for this file
  SA                           'distances will be absolute
)sbp";

// VC's diameter is a permanent value (only VS, VU, VI, VL and SF revert with the file).
TEST_F(LanguageTest, Example15SetsTheCutterForGood) {
  std::string text = kExample15;
  text.replace(text.find("VC, .25"), 7, "VC, .375");  // the default is .25 already
  run(text);
  EXPECT_TRUE(state().absolute);
  EXPECT_DOUBLE_EQ(interp().settings().cutter.diameter, .375);
  EXPECT_DOUBLE_EQ(state().speeds.move.xy, 2.0);  // while VS's speeds reverted
}

TEST_F(LanguageTest, Example15WithoutVcSetsSpeedsThatRevertAtTheEnd) {
  std::string text = kExample15;
  text.erase(text.find("  VC"), text.find("  SA") - text.find("  VC"));
  run(text);
  EXPECT_TRUE(state().absolute);
  // §5.4 / §7.101: VS values set in a file revert when it ends.
  EXPECT_DOUBLE_EQ(state().speeds.move.xy, 2.0);
  EXPECT_DOUBLE_EQ(state().speeds.move.b, 10.0);
  EXPECT_DOUBLE_EQ(state().speeds.jog.xy, 6.0);
}

// §8 A2: under the 8-parameter VS order the line means XY move 1.25, Z move .45, B move 2.75
// and XY jog .80.
TEST_F(LanguageTest, Example15VsValuesFollowTheEightParameterOrder) {
  run("  VS, 1.25, .45, , 2.75, .80   'to set speeds\nMX, 1\nJX, 2\n");
  ASSERT_EQ(moves().size(), 2u);
  const GroupSpeeds& m = moves()[0].speeds;
  EXPECT_DOUBLE_EQ(m.xy, 1.25);
  EXPECT_DOUBLE_EQ(m.z, .45);
  EXPECT_DOUBLE_EQ(m.a, 10);
  EXPECT_DOUBLE_EQ(m.b, 2.75);
  const GroupSpeeds& j = moves()[1].speeds;
  EXPECT_DOUBLE_EQ(j.xy, .80);
  EXPECT_DOUBLE_EQ(j.z, 3);
}

// Example 16 — the handbook's one-line examples.
TEST_F(LanguageTest, Example16IfCountEqualsTwentyBranchesOnlyAtTwenty) {
  const char* text = "IF &Count = 20 THEN GOTO TWENTY\nPRINT \"not\"\nEND\nTWENTY:\nPRINT \"20\"\n";
  run(std::string("&Count = 20\n") + text);
  EXPECT_EQ(printed, "20\n");
  printed.clear();
  run(std::string("&Count = 19\n") + text);
  EXPECT_EQ(printed, "not\n");
}

TEST_F(LanguageTest, Example16GreaterThanIsValidButArrowIsNot) {
  run("&varA = 3\n&varB = 2\nIF &varA > &varB THEN &bigger = 1\n");
  expect_number("BIGGER", 1);
  const auto script =
      Script::from_text("&varA = 3\n&varB = 2\nIF &varA => &varB THEN &b = 1\n", "part.sbp");
  ASSERT_EQ(script->errors().size(), 1u) << all(script->errors());
  EXPECT_EQ(format(script->errors()[0]), "part.sbp:3:10: error: '=>' is not an operator; write >=");
}

TEST_F(LanguageTest, Example16OnInputRegistersWithoutRunningItsAction) {
  const auto script = Script::from_text("ON INPUT(2,1) VA, 0.0\nMX, 1\n", "part.sbp");
  EXPECT_TRUE(script->errors().empty()) << all(script->errors());
  const Outcome o = execute(script);
  EXPECT_EQ(o.ending, Ending::Normal) << format(o.diag);  // VA only runs when input 2 closes
  expect_path(moves(), {{kMove, at(1)}});
}

TEST_F(LanguageTest, Example16PauseThreeAndPauseUntil) {
  use_recording_io = true;
  run("PAUSE 3\nPAUSE UNTIL 5, 1\n");
  ASSERT_EQ(moves().size(), 1u);
  EXPECT_EQ(moves()[0].kind, MoveKind::Dwell);
  EXPECT_DOUBLE_EQ(moves()[0].dwell_s, 3.0);
  const auto asked = rec.of("confirm");
  ASSERT_EQ(asked.size(), 1u);
  EXPECT_EQ(asked[0].text, "Continue? (waiting for input 5 to close)");
  EXPECT_EQ(where(asked[0].loc), "part.sbp:2:1");
}

// The derived illustrations of §6 [REC].
TEST_F(LanguageTest, DerivedCountingLoopPrintsIEquals5) {
  run(R"sbp('counting loop built from a label and IF ... THEN GOTO
&i = 0
LOOP:
&i = &i + 1
IF &i < 5 THEN GOTO LOOP
PRINT "i = "; &i
END
)sbp");
  EXPECT_EQ(printed, "i = 5\n");
  expect_number("I", 5);
}

TEST_F(LanguageTest, DerivedGosubPrintsInSubThenBack) {
  run("GOSUB SHOW\nPRINT \"back\"\nEND\nSHOW:\nPRINT \"in sub\"\nRETURN\n");
  EXPECT_EQ(printed, "in sub\nback\n");
}

TEST_F(LanguageTest, DerivedGosubWithoutEndRunsTheSubroutineAgainAndFails) {
  const Diagnostic d = run_error("GOSUB SHOW\nPRINT \"back\"\nSHOW:\nPRINT \"in sub\"\nRETURN\n");
  EXPECT_EQ(format(d),
            "part.sbp:5:1: error: RETURN without GOSUB; put END before the subroutines so the "
            "file does not run into them");
  EXPECT_EQ(printed, "in sub\nback\nin sub\n");
}

// =========================================================================================
// 2. Regression tests for defects of FabMo's interpreter
// =========================================================================================

// FabMo read `MSGBOX(` as the command MS with parameters.
TEST_F(LanguageTest, FabMoMsgBoxWithoutASpaceIsAMessageBoxNotMs) {
  use_recording_io = true;
  rec.choice = "No";
  run("MSGBOX(Proceed?,YesNo,Check)\nmsgbox(\"Depth \" & 2, 0, \"Info\")\nMX, 1\n");
  const auto boxes = rec.of("choose");
  ASSERT_EQ(boxes.size(), 2u);
  EXPECT_EQ(boxes[0].text, "Proceed?");
  EXPECT_EQ(boxes[0].buttons, (std::vector<std::string>{"Yes", "No"}));
  EXPECT_EQ(boxes[0].title, "Check");
  EXPECT_EQ(boxes[1].text, "Depth 2");
  EXPECT_EQ(boxes[1].buttons, (std::vector<std::string>{"OK"}));
  EXPECT_EQ(boxes[1].title, "Info");
  expect_text("MSGANSWER", "No");
  // The move speeds are the profile's: no MS ran.
  ASSERT_EQ(moves().size(), 1u);
  EXPECT_DOUBLE_EQ(moves()[0].speeds.xy, 2.0);
  EXPECT_DOUBLE_EQ(moves()[0].speeds.z, 0.5);
}

// FabMo evaluated `-(&b)` to a string.
TEST_F(LanguageTest, FabMoNegatedParenthesisedVariableIsANumber) {
  run("&b = 2\n&a = -(&b)\n&c = -(&b) * 2\nMZ, -(&b)\n&s = \"1.5\"\n&t = -(&s)\n");
  expect_number("A", -2);
  expect_number("C", -4);
  expect_number("T", -1.5);
  expect_path(moves(), {{kMove, at(0, 0, -2)}});
}

// FabMo evaluated `8/4/2` right to left (8/(4/2) = 4).
TEST_F(LanguageTest, FabMoDivisionIsLeftAssociative) {
  run("&x = 8/4/2\nMX, 8/4/2\n&y = 2^3^2\n&z = 12 - 4 - 2\n");
  expect_number("X", 1);
  expect_number("Y", 64);
  expect_number("Z", 6);
  expect_path(moves(), {{kMove, at(1)}});
}

// FabMo flushed (stopped) motion at every assignment and IF. The sink is flushed exactly
// once, after the last move.
TEST_F(LanguageTest, FabMoAssignmentsAndIfsDoNotFlushMotion) {
  run(R"sbp(MX, 1
&a = 2
IF &a = 2 THEN MX, &a
&b = &a + 1
IF &b > 100 THEN MX, 0
&i = 0
LOOP:
&i = &i + 1
MY, &i
IF &i < 3 THEN GOTO LOOP
MX, 3
)sbp");
  ASSERT_EQ(moves().size(), 6u);
  for (size_t i = 0; i < moves().size(); ++i)
    EXPECT_EQ(sink.flushes_seen_by_move[i], 0) << "a flush before move " << i;
  EXPECT_EQ(sink.moves_at_flush, (std::vector<size_t>{6}));
}

// FabMo reported wrong line numbers after CRLF line endings, blank lines and comments.
TEST_F(LanguageTest, FabMoRuntimeErrorLineAfterCrlfBlankLinesAndComments) {
  const Diagnostic d =
      run_error("SA\r\n\r\n' a comment\r\nREM a remark\r\n\r\n   \r\n  QQ, 1\r\nMX, 1\r\n");
  EXPECT_EQ(format(d), "part.sbp:7:3: error: unknown command 'QQ'" + kUnknownSuffix);
}

TEST_F(LanguageTest, FabMoSyntaxErrorLineAfterCrlfBlankLinesAndComments) {
  const auto script =
      Script::from_text("SA\r\n\r\n'c\r\nMX, 1  ' inline\r\n\r\nM23, 4\r\n", "part.sbp");
  ASSERT_EQ(script->errors().size(), 1u);
  EXPECT_EQ(format(script->errors()[0]),
            "part.sbp:6:3: error: expected a space or a comma after the command M2; write "
            "`M2, 3`");
}

TEST_F(LanguageTest, FabMoLineNumbersWithOldMacLineEndings) {
  const Diagnostic d = run_error("SA\r\r'c\rMX, 1\r  QQ\r");
  EXPECT_EQ(where(d.loc), "part.sbp:5:3");
  ASSERT_EQ(moves().size(), 1u);
  EXPECT_EQ(where(moves()[0].loc), "part.sbp:4:1");
}

// After jumps back and forth the lines stay right.
TEST_F(LanguageTest, FabMoLineNumbersAfterJumpsInACrlfFile) {
  const Diagnostic d = run_error(
      "&i = 0\r\n"
      "\r\n"
      "TOP:\r\n"
      "' count\r\n"
      "&i = &i + 1\r\n"
      "IF &i = 3 THEN GOSUB BROKEN\r\n"
      "GOTO TOP\r\n"
      "BROKEN:\r\n"
      "\r\n"
      "  MX, &i, 7\r\n"
      "RETURN\r\n");
  EXPECT_EQ(format(d), "part.sbp:10:11: error: MX takes 1 parameter; this is parameter 2");
  expect_number("I", 3);
}

// Moves are located in the lines that made them, through comments and CRLF.
TEST_F(LanguageTest, FabMoMoveLocationsAfterCrlfAndComments) {
  run("' header\r\n\r\nREM x\r\n\tMX, 1\r\n' c\r\n   MY, 2 ' why\r\n");
  ASSERT_EQ(moves().size(), 2u);
  EXPECT_EQ(where(moves()[0].loc), "part.sbp:4:2");
  EXPECT_EQ(where(moves()[1].loc), "part.sbp:6:4");
}

TEST_F(LanguageTest, FabMoNestedFilesWork) {
  dir().write("child.sbp",
              "' child\r\n&fromchild = &fromparent * 2\r\nMY, 2\r\nFP, grand.sbp\r\nMX, 4\r\n");
  dir().write("grand.sbp", "MZ, -1\n&depth = %(3)\n");
  const std::string main = dir().write(
      "main.sbp", "&fromparent = 21\nMX, 1\nFP, child.sbp\nPRINT &fromchild; \" \"; &depth\n");
  run_file(main);
  expect_path(moves(),
              {{kMove, at(1)}, {kMove, at(1, 2)}, {kMove, at(1, 2, -1)}, {kMove, at(4, 2, -1)}});
  EXPECT_EQ(where(moves()[1].loc), dir().path("child.sbp") + ":3:1");
  EXPECT_EQ(where(moves()[2].loc), dir().path("grand.sbp") + ":1:1");
  EXPECT_EQ(where(moves()[3].loc), dir().path("child.sbp") + ":5:1");
  EXPECT_EQ(printed, "42 -1\n");  // §7.26: variables are shared both ways
}

TEST_F(LanguageTest, FabMoErrorInANestedCrlfFileNamesTheCallingLines) {
  dir().write("inner.sbp", "MX, 1\r\n\r\n' c\r\n  QQ\r\n");
  const std::string outer = dir().write("outer.sbp", "' outer\nFP, inner.sbp\nMX, 2\n");
  const Diagnostic d = run_file_error(outer);
  EXPECT_EQ(format(d), outer + ":2 -> " + dir().path("inner.sbp") +
                           ":4:3: error: unknown command 'QQ'" + kUnknownSuffix);
  ASSERT_EQ(d.via.size(), 1u);
  EXPECT_EQ(where(d.via[0]), outer + ":2:1");
}

// =========================================================================================
// 3. Each statement
// =========================================================================================

// ---- labels and GOTO

TEST_F(LanguageTest, LabelsMayHoldSpacesAndIgnoreCase) {
  run("&n = 0\nmy   Label:\n&n = &n + 1\nIF &n < 3 THEN goto MY LABEL\nGOTO done\nPRINT "
      "\"skipped\"\nDone:\n");
  expect_number("N", 3);
  EXPECT_EQ(printed, "");
}

TEST_F(LanguageTest, GotoWithTheLabelsColonIsAnError) {
  const auto script = Script::from_text("LOOP:\nGOTO LOOP:\n", "part.sbp");
  ASSERT_EQ(script->errors().size(), 1u) << all(script->errors());
  EXPECT_EQ(format(script->errors()[0]),
            "part.sbp:2:10: error: write the label after GOTO or GOSUB without its colon");
}

TEST_F(LanguageTest, GotoJumpsForwardAndBackward) {
  run("GOTO B\nA:\nPRINT \"a\"\nEND\nB:\nPRINT \"b\"\nGOTO A\n");
  EXPECT_EQ(printed, "b\na\n");
}

TEST_F(LanguageTest, DuplicateLabelIsAWarningAndTheFirstWins) {
  const char* text = "GOTO TWICE\nTWICE:\nPRINT \"first\"\nEND\ntwice:\nPRINT \"second\"\n";
  const auto script = Script::from_text(text, "part.sbp");
  EXPECT_TRUE(script->ok());
  ASSERT_EQ(script->errors().size(), 1u);
  EXPECT_EQ(format(script->errors()[0]),
            "part.sbp:5:1: warning: label TWICE is defined again; jumps go to the first one, "
            "line 2");
  run(text);
  EXPECT_EQ(printed, "first\n");
}

TEST_F(LanguageTest, JumpToAMissingLabelIsFoundBeforeAnythingRuns) {
  const char* text =
      "MX, 1\nIF 0 THEN GOTO NOWHERE\nGOSUB Also  Missing\nON INPUT(1, 1) GOTO GONE\n";
  const auto script = Script::from_text(text, "part.sbp");
  ASSERT_EQ(script->errors().size(), 3u) << all(script->errors());
  const char* tail = ": in this file; labels are written on their own line as NAME:";
  EXPECT_EQ(format(script->errors()[0]),
            std::string("part.sbp:2:16: error: no label NOWHERE") + tail);
  EXPECT_EQ(format(script->errors()[1]),
            std::string("part.sbp:3:7: error: no label ALSO MISSING") + tail);
  EXPECT_EQ(format(script->errors()[2]), std::string("part.sbp:4:21: error: no label GONE") + tail);
  const Outcome o = execute(script);
  EXPECT_EQ(o.ending, Ending::Error);
  EXPECT_EQ(where(o.diag.loc), "part.sbp:2:16");
  EXPECT_TRUE(moves().empty());
  EXPECT_EQ(interp().statements_executed(), 0u);
}

TEST_F(LanguageTest, LabelsAreLocalToTheirFile) {
  dir().write("child.sbp", "GOTO PARENTLABEL\n");
  const std::string main = dir().write("main.sbp", "FP, child.sbp\nPARENTLABEL:\n");
  const Diagnostic d = run_file_error(main);
  EXPECT_EQ(where(d.loc), dir().path("child.sbp") + ":1:6");
  EXPECT_EQ(d.message,
            "no label PARENTLABEL: in this file; labels are written on their own line as NAME:");
}

// ---- GOSUB and RETURN

TEST_F(LanguageTest, NestedGosubsReturnInOrder) {
  run(R"sbp(GOSUB OUTER
PRINT "main"
END
OUTER:
PRINT "outer in"
GOSUB INNER
PRINT "outer out"
RETURN
INNER:
PRINT "inner"
RETURN
)sbp");
  EXPECT_EQ(printed, "outer in\ninner\nouter out\nmain\n");
}

TEST_F(LanguageTest, ReturnWithoutGosubIsAnError) {
  const Diagnostic d = run_error("MX, 1\n  RETURN\nMX, 2\n");
  EXPECT_EQ(format(d),
            "part.sbp:2:3: error: RETURN without GOSUB; put END before the subroutines so the "
            "file does not run into them");
  EXPECT_EQ(moves().size(), 1u);
}

// Each file has its own return stack: a child cannot RETURN to its caller's GOSUB.
TEST_F(LanguageTest, ReturnInAChildDoesNotUseTheParentsGosub) {
  dir().write("child.sbp", "RETURN\n");
  const std::string main = dir().write("main.sbp", "GOSUB S\nEND\nS:\nFP, child.sbp\nRETURN\n");
  const Diagnostic d = run_file_error(main);
  EXPECT_EQ(where(d.loc), dir().path("child.sbp") + ":1:1");
  EXPECT_EQ(d.message.rfind("RETURN without GOSUB", 0), 0u) << d.message;
}

TEST_F(LanguageTest, GosubDepthLimitIs256) {
  const Diagnostic d = run_error("&n = 0\nDEEPER:\n&n = &n + 1\nGOSUB DEEPER\n");
  EXPECT_EQ(format(d),
            "part.sbp:4:1: error: GOSUB nested 256 deep without RETURN; a subroutine may be "
            "calling itself");
  expect_number("N", 257);  // 256 GOSUBs were taken, the 257th refused
}

TEST_F(LanguageTest, GosubsNested256DeepAreAllowed) {
  run("&n = 0\nGOSUB R\nPRINT &n\nEND\nR:\n&n = &n + 1\nIF &n < 256 THEN GOSUB R\nRETURN\n");
  EXPECT_EQ(printed, "256\n");
}

// ---- END, ENDALL, EXIT SHOPBOT

TEST_F(LanguageTest, EndInsideASubroutineEndsTheWholeFile) {
  run("GOSUB S\nPRINT \"after\"\nEND\nS:\nPRINT \"in\"\nEND\nPRINT \"never\"\nRETURN\n");
  EXPECT_EQ(printed, "in\n");
}

TEST_F(LanguageTest, EndInANestedFileEndsOnlyThatFile) {
  dir().write("child.sbp", "GOSUB S\nPRINT \"child after\"\nS:\nPRINT \"child sub\"\nEND\n");
  run_file(dir().write("main.sbp", "FP, child.sbp\nPRINT \"parent after\"\n"));
  EXPECT_EQ(printed, "child sub\nparent after\n");
}

TEST_F(LanguageTest, EndWithAMessagePrintsIt) {
  run("&why = \"no stock\"\nEND \"all done\"\nPRINT \"never\"\n");
  EXPECT_EQ(printed, "all done\n");
  printed.clear();
  run("END &why\n");
  EXPECT_EQ(printed, "no stock\n");
  const auto script = Script::from_text("END foo\n", "part.sbp");
  ASSERT_EQ(script->errors().size(), 1u);
  EXPECT_EQ(format(script->errors()[0]),
            "part.sbp:1:5: error: END takes no parameters, or a message in quotes");
}

TEST_F(LanguageTest, EndAllFromANestedFileEndsEveryFile) {
  dir().write("grand.sbp", "VS, 1.5\nPRINT \"grand\"\nENDALL\nPRINT \"grand after\"\n");
  dir().write("child.sbp", "VS, , 0.25\nFP, grand.sbp\nPRINT \"child after\"\n");
  const Outcome o = execute(
      Script::load(dir().write("main.sbp", "FP, child.sbp\nPRINT \"main after\"\nMX, 1\n")));
  EXPECT_EQ(o.ending, Ending::Normal) << format(o.diag);
  EXPECT_EQ(printed, "grand\n");
  EXPECT_TRUE(moves().empty());
  // Every file's VS changes were undone on the way out.
  EXPECT_DOUBLE_EQ(state().speeds.move.xy, 2.0);
  EXPECT_DOUBLE_EQ(state().speeds.move.z, 0.5);
  EXPECT_EQ(sink.flushes, 1);
}

TEST_F(LanguageTest, ExitShopbotEndsTheRun) {
  dir().write("child.sbp", "PRINT \"child\"\nexit   ShopBot\nPRINT \"child after\"\n");
  run_file(dir().write("main.sbp", "FP, child.sbp\nPRINT \"main after\"\n"));
  EXPECT_EQ(printed, "child\n");
  const auto script = Script::from_text("EXIT NOW\n", "part.sbp");
  ASSERT_EQ(script->errors().size(), 1u);
  EXPECT_EQ(format(script->errors()[0]), "part.sbp:1:6: error: write EXIT SHOPBOT");
}

// ---- IF ... THEN

TEST_F(LanguageTest, IfThenRunsACommand) {
  run("IF 1 THEN MX, 2\nIF 0 THEN MX, 5\nif 2 > 1 then my, 3\n");
  expect_path(moves(), {{kMove, at(2)}, {kMove, at(2, 3)}});
  EXPECT_EQ(where(moves()[0].loc), "part.sbp:1:11");
}

TEST_F(LanguageTest, IfThenRunsAnAssignment) {
  run("IF 2 > 1 THEN &a = 5\nIF 2 < 1 THEN &b = 5\n");
  expect_number("A", 5);
  EXPECT_EQ(var("B"), nullptr);
}

TEST_F(LanguageTest, IfThenGotoAndGosub) {
  run("IF 1 THEN GOSUB S\nPRINT \"after\"\nIF 1 THEN GOTO OUT\nPRINT \"skipped\"\nOUT:\nEND\n"
      "S:\nPRINT \"sub\"\nRETURN\n");
  EXPECT_EQ(printed, "sub\nafter\n");
}

TEST_F(LanguageTest, IfThenReturn) {
  run("GOSUB S\nPRINT \"back\"\nEND\nS:\nIF 1 THEN RETURN\nPRINT \"not reached\"\nRETURN\n");
  EXPECT_EQ(printed, "back\n");
}

TEST_F(LanguageTest, IfThenPrintComparesTextWithoutCase) {
  run("&s = yes\nIF &s = \"YES\" THEN PRINT \"same\"\nIF \"abc\" <> \"ABC\" THEN PRINT \"diff\"\n");
  EXPECT_EQ(printed, "same\n");  // §7.24
}

TEST_F(LanguageTest, IfThenEnd) {
  run("IF 1 THEN END\nMX, 1\n");
  EXPECT_TRUE(moves().empty());
  run("IF 0 THEN END\nMX, 1\n");
  EXPECT_EQ(moves().size(), 1u);
}

// §7.40-41: comparisons are -1 or 0; AND, OR and NOT combine them.
TEST_F(LanguageTest, ComparisonsAreMinusOneOrZero) {
  run("&t = 3 > 2\n&f = 3 < 2\n&a = 1\n&b = 1\n&same = &a = &b\n"
      "IF &t AND NOT &f THEN &x = 1\nIF &f OR &t THEN &y = 1\nIF NOT (&f OR &f) THEN &z = 1\n");
  expect_number("T", -1);
  expect_number("F", 0);
  expect_number("SAME", -1);
  expect_number("X", 1);
  expect_number("Y", 1);
  expect_number("Z", 1);
}

TEST_F(LanguageTest, IfWithoutThenIsAnError) {
  const auto script = Script::from_text("MX, 1\nIF 1 MX, 1\n", "part.sbp");
  ASSERT_EQ(script->errors().size(), 1u);
  EXPECT_EQ(format(script->errors()[0]),
            "part.sbp:2:1: error: IF needs THEN: write IF test THEN statement");
  EXPECT_EQ(format(Script::from_text("IF 1 THEN\n", "p.sbp")->errors().at(0)),
            "p.sbp:1:6: error: THEN needs a statement after it");
  EXPECT_EQ(format(Script::from_text("IF 1 THEN IF 1 THEN MX, 1\n", "p.sbp")->errors().at(0)),
            "p.sbp:1:11: error: IF ... THEN takes one plain statement: not IF, ON INPUT or a "
            "label");
  EXPECT_EQ(format(Script::from_text("IF 1 => 0 THEN MX, 1\n", "p.sbp")->errors().at(0)),
            "p.sbp:1:6: error: '=>' is not an operator; write >=");
}

// §3.5: an undefined variable in a numeric context is "undefined variable &NAME".
TEST_F(LanguageTest, IfOnAnUndefinedVariableNamesIt) {
  const Diagnostic d = run_error("IF &flag THEN MX, 1\n");
  EXPECT_TRUE(moves().empty());
  EXPECT_EQ(d.message, "undefined variable &FLAG; set it before this line");
  EXPECT_EQ(d.loc.line, 1);
}

// ---- ON INPUT

TEST_F(LanguageTest, OnInputRegistersAndClearsWithoutRunningTheAction) {
  run("ON INPUT(2, 1) GOTO STOPPED\n&sw = 3\nON INPUT(&sw, 3) MX, 5\nON INPUT(4, 0) &hit = 1\n"
      "ON INPUT(4, 2) PRINT \"off\"\nON INPUT(2, 1)\nON INPUT(12, 0)\nMX, 1\nEND\nSTOPPED:\n"
      "MX, 9\n");
  expect_path(moves(), {{kMove, at(1)}});
  EXPECT_EQ(var("HIT"), nullptr);
  EXPECT_EQ(printed, "");
}

TEST_F(LanguageTest, OnInputErrors) {
  EXPECT_EQ(format(run_error("MX, 1\nON INPUT(13, 1) MX, 1\n")),
            "part.sbp:2:1: error: input switch 13 does not exist; inputs are 1 to 12");
  EXPECT_EQ(format(run_error("ON INPUT(0, 1)\n")),
            "part.sbp:1:1: error: input switch 0 does not exist; inputs are 1 to 12");
  EXPECT_EQ(format(run_error("ON INPUT(2.5, 1)\n")),
            "part.sbp:1:1: error: input switch 2.5 does not exist; inputs are 1 to 12");
  EXPECT_EQ(format(run_error("ON INPUT(2, 4) MX, 1\n")),
            "part.sbp:1:1: error: ON INPUT state 4 is not 0 (off), 1 (on), 2 (off, ramped) or 3 "
            "(on, ramped)");
  EXPECT_EQ(format(Script::from_text("ON INPUT 2, 1\n", "p.sbp")->errors().at(0)),
            "p.sbp:1:10: error: expected '(' after ON INPUT");
  EXPECT_EQ(format(Script::from_text("ON INPUT(2 1)\n", "p.sbp")->errors().at(0)),
            "p.sbp:1:9: error: ON INPUT needs (switch, state), e.g. ON INPUT(2, 1) GOTO STOPPED");
}

// ---- PAUSE

TEST_F(LanguageTest, TimedPauseIsADwell) {
  run("MX, 1\nPAUSE 2.5\n&t = 1.25\n  PAUSE &t\nPAUSE &t * 2\nPAUSE 0\n");
  ASSERT_EQ(moves().size(), 4u);
  const double expected[] = {2.5, 1.25, 2.5};
  const char* lines[] = {"part.sbp:2:1", "part.sbp:4:3", "part.sbp:5:1"};
  for (int i = 0; i < 3; ++i) {
    const CanonMove& m = moves()[static_cast<size_t>(i) + 1];
    EXPECT_EQ(m.kind, MoveKind::Dwell);
    EXPECT_DOUBLE_EQ(m.dwell_s, expected[i]);
    expect_vec(m.from, at(1));
    expect_vec(m.to, at(1));
    EXPECT_EQ(where(m.loc), lines[i]);
  }
  EXPECT_EQ(interp().moves_emitted(), 4u);
}

// Issue 22: PAUSE 1e20 overflowed the step generator's ticks (garbled steps, status "done");
// PAUSE 1e12 ran for ever; PAUSE -1 was skipped without a word. Each is now refused by the
// check, located, before anything moves; the longest wait is the profile's max_dwell_s.
TEST_F(LanguageTest, AWaitOutOfRangeIsALocatedErrorOfTheCheck) {
  const std::string range =
      " s is out of range: a part file may wait 0 to 86400 s "
      "(machine.max_dwell_s in the profile)";
  const std::pair<const char*, std::string> cases[] = {
      {"MX, 0.5\nPAUSE 1e20\nMX, 1\n", "part.sbp:2:1: error: a wait of 1e+20" + range},
      {"MX, 0.5\nPAUSE 1e12\n", "part.sbp:2:1: error: a wait of 1000000000000" + range},
      {"PAUSE -1\n", "part.sbp:1:1: error: a wait of -1" + range},
      {"&t = 86400\nPAUSE &t + 0.5\n", "part.sbp:2:1: error: a wait of 86400.5" + range},
      {"&d = 0\nPAUSE 0/&d\n", "part.sbp:2:9: error: division by zero"},  // no NaN gets this far
  };
  for (const auto& [text, says] : cases) {
    const std::vector<Diagnostic> found = check(text);
    ASSERT_FALSE(found.empty()) << text;
    EXPECT_EQ(format(found[0]).substr(0, says.size()), says) << text;
  }
  run("PAUSE 86400\n");  // the longest is allowed
  ASSERT_FALSE(moves().empty());
  EXPECT_EQ(moves().back().kind, MoveKind::Dwell);
  EXPECT_EQ(moves().back().dwell_s, 86400);
}

TEST_F(LanguageTest, TheLongestWaitIsTheProfilesMaxDwell) {
  settings.machine.max_dwell_s = 60;
  EXPECT_EQ(format(run_error("PAUSE 61\n")),
            "part.sbp:1:1: error: a wait of 61 s is out of range: a part file may wait 0 to 60 s "
            "(machine.max_dwell_s in the profile); give a shorter time, or raise the profile's "
            "maximum");
  EXPECT_TRUE(moves().empty());
}

// A distance past any table is refused even with the soft limits off (SF, 0): its step count
// would near a double's precision (docs/reliability.md).
TEST_F(LanguageTest, AMoveBeyondAnyTableIsRefusedWithSoftLimitsOff) {
  settings.machine.limit_checking = false;
  run("MX, 500000\n");
  EXPECT_EQ(format(run_error("MX, 2e6\n")),
            "part.sbp:1:1: error: move to X=2000000 is out of range: no axis may go beyond "
            "1000000 in from the table base; nothing was moved");
  EXPECT_EQ(moves().size(), 1u);
}

// A circle beyond any table, soft limits or not: its points are out of range (its chords
// would outgrow memory; G2's turns are bounded by their chord count, GcodeTest).
TEST_F(LanguageTest, ACircleBeyondAnyTableIsRefusedWithSoftLimitsOff) {
  settings.machine.limit_checking = false;
  const Diagnostic d = run_error("MX, 1\nCC, 1e11, T\n");
  EXPECT_EQ(d.loc.line, 2);
  EXPECT_NE(d.message.find("is out of range: no axis may go beyond 1000000 in from the table "
                           "base; nothing was moved"),
            std::string::npos)
      << d.message;
  EXPECT_EQ(moves().size(), 1u);
}

TEST_F(LanguageTest, JoinedTextIsBounded) {
  const Diagnostic d = run_error("&s = \"0123456789abcdef\"\nL:\n&s = &s & &s\nGOTO L\n");
  EXPECT_EQ(d.loc.line, 3);
  EXPECT_NE(d.message.find("this text would be 2097152 bytes long; a value holds at most "
                           "1048576 bytes"),
            std::string::npos)
      << d.message;
}

// Values from INPUT are text; a number in a text is still a number of seconds (§3.2, §2.8).
TEST_F(LanguageTest, PauseWithANumberTypedByTheOperatorWaits) {
  inputs = {{"&T", "2"}};
  yes = false;
  const Outcome o = execute("INPUT \"Seconds?\" &t\nPAUSE &t\n");
  EXPECT_EQ(o.ending, Ending::Normal) << format(o.diag);
  ASSERT_EQ(moves().size(), 1u);
  EXPECT_EQ(moves()[0].kind, MoveKind::Dwell);
  EXPECT_DOUBLE_EQ(moves()[0].dwell_s, 2.0);
}

TEST_F(LanguageTest, PauseWithAMessageAsksTheOperator) {
  run("PAUSE \"Load the next board\"\nMX, 1\n");  // --yes continues
  EXPECT_EQ(moves().size(), 1u);
  EXPECT_EQ(printed, "");
}

TEST_F(LanguageTest, PauseWithAMessageWithoutYesNeedsTheOperator) {
  yes = false;
  const Outcome o = execute("MX, 1\nPAUSE \"Load the next board\"\nMX, 2\n");
  EXPECT_EQ(o.ending, Ending::NeedsOperator);
  EXPECT_EQ(format(o.diag),
            "part.sbp:2:1: error: the file waits for the operator (\"Load the next board\"); run "
            "from a terminal, or with --yes to continue every pause");
  expect_path(moves(), {{kMove, at(1)}});
  // The moves before the question play out before it is asked, and the run's end flushes.
  EXPECT_EQ(sink.flushes, 2);
}

TEST_F(LanguageTest, PauseMessageAndOptions) {
  use_recording_io = true;
  run("&n = 2\nPAUSE \"Change to bit \" & &n, OKTEXT=\"Done\", CANCELTEXT = \"Stop\"\n");
  const auto asked = rec.of("confirm");
  ASSERT_EQ(asked.size(), 1u);
  EXPECT_EQ(asked[0].text, "Change to bit 2");
  EXPECT_EQ(format(run_error("PAUSE \"x\", FOO=1\n")),
            "part.sbp:1:16: error: unknown option FOO; use OKTEXT, CANCELTEXT or TITLE");
}

// A bare PAUSE shows the full-line comment just above it, else "Continue?" (§7.53, §8 A17).
TEST_F(LanguageTest, BarePauseShowsOnlyTheCommentLineJustAboveIt) {
  use_recording_io = true;
  run("PAUSE\n"  // first line: nothing above
      "'Clamp the board\n"
      "PAUSE\n"  // the comment
      "REM   Check the bit  \n"
      "  PAUSE\n"  // REM, trimmed
      "' far away\n"
      "\n"
      "PAUSE\n"  // a blank line between: no comment
      "MX, 1 ' inline comment\n"
      "PAUSE\n"  // an inline comment is not a full-line comment
      "'Windows line\r\n"
      "PAUSE\r\n");  // CRLF: no carriage return in the message
  const auto asked = rec.of("confirm");
  ASSERT_EQ(asked.size(), 6u);
  EXPECT_EQ(asked[0].text, "Continue?");
  EXPECT_EQ(asked[1].text, "Clamp the board");
  EXPECT_EQ(asked[2].text, "Check the bit");
  EXPECT_EQ(asked[3].text, "Continue?");
  EXPECT_EQ(asked[4].text, "Continue?");
  EXPECT_EQ(asked[5].text, "Windows line");
  EXPECT_EQ(where(asked[2].loc), "part.sbp:5:3");
}

TEST_F(LanguageTest, BarePauseAfterAJumpShowsTheCommentAboveThePause) {
  use_recording_io = true;
  run("GOTO THERE\n'not this one\nTHERE:\n'Vacuum on?\nPAUSE\n");
  const auto asked = rec.of("confirm");
  ASSERT_EQ(asked.size(), 1u);
  EXPECT_EQ(asked[0].text, "Vacuum on?");
}

TEST_F(LanguageTest, BarePauseInANestedFileShowsThatFilesComment) {
  use_recording_io = true;
  dir().write("child.sbp", "'Child says hello\nPAUSE\n");
  run_file(dir().write("main.sbp", "'Main comment\nFP, child.sbp\n"));
  const auto asked = rec.of("confirm");
  ASSERT_EQ(asked.size(), 1u);
  EXPECT_EQ(asked[0].text, "Child says hello");
  EXPECT_EQ(where(asked[0].loc), dir().path("child.sbp") + ":2:1");
}

TEST_F(LanguageTest, BarePauseWithoutYesNeedsTheOperator) {
  yes = false;
  const Outcome o = execute("'Is the vacuum on?\nPAUSE\n");
  EXPECT_EQ(o.ending, Ending::NeedsOperator);
  EXPECT_EQ(o.diag.message,
            "the file waits for the operator (\"Is the vacuum on?\"); run from a terminal, or with "
            "--yes to continue every pause");
}

TEST_F(LanguageTest, PauseUntilWaitsForAnInputThatIsNotInTheState) {
  use_recording_io = true;
  run("'Close the door\nPAUSE UNTIL 3, 1\nPAUSE UNTIL 5, 0\n&i = 4\npause until &i + 1, 1\n");
  const auto asked = rec.of("confirm");
  ASSERT_EQ(asked.size(), 2u);  // input 5 is already open (level-triggered, §8 A51)
  EXPECT_EQ(asked[0].text, "Close the door (waiting for input 3 to close)");
  EXPECT_EQ(where(asked[0].loc), "part.sbp:2:1");
  EXPECT_EQ(asked[1].text, "Continue? (waiting for input 5 to close)");
}

TEST_F(LanguageTest, PauseUntilCancelAndErrors) {
  use_recording_io = true;
  rec.confirm_answer = false;
  const Outcome o = execute("PAUSE UNTIL 5, 1\nMX, 1\n");
  EXPECT_EQ(o.ending, Ending::OperatorStop);
  EXPECT_EQ(format(o.diag), "part.sbp:1:1: error: stopped by the operator at PAUSE UNTIL");
  EXPECT_TRUE(moves().empty());
  EXPECT_EQ(format(run_error("PAUSE UNTIL 13, 1\n")),
            "part.sbp:1:1: error: input switch 13 does not exist; inputs are 1 to 12");
  EXPECT_EQ(format(Script::from_text("PAUSE UNTIL 5\n", "p.sbp")->errors().at(0)),
            "p.sbp:1:7: error: PAUSE UNTIL needs an input and a state, e.g. PAUSE UNTIL 5, 1");
}

TEST_F(LanguageTest, PauseMessageWithAVariableAsks) {
  use_recording_io = true;
  rec.answers = {" 0.75 "};
  run("PAUSE \"How thick is the board?\", &thick\nMZ, -&thick\n");
  const auto asked = rec.of("ask");
  ASSERT_EQ(asked.size(), 1u);
  EXPECT_EQ(asked[0].text, "How thick is the board?");
  EXPECT_EQ(asked[0].variable, "&THICK");
  EXPECT_EQ(asked[0].default_value, "");
  EXPECT_EQ(where(asked[0].loc), "part.sbp:1:1");
  expect_text("THICK", " 0.75 ");
  expect_path(moves(), {{kMove, at(0, 0, -0.75)}});
}

TEST_F(LanguageTest, PauseMessageWithAVariableFromScriptedInputs) {
  inputs = {{"&THICK", "0.5"}};
  run("PAUSE \"How thick?\", &thick\n");
  expect_text("THICK", "0.5");
}

// ---- INPUT

TEST_F(LanguageTest, InputOneVariableFromScriptedInputs) {
  inputs = {{"&DEPTH", "  -0.5  "}};
  run("INPUT \"Depth?\" &depth\nMZ, &depth\n");
  expect_text("DEPTH", "-0.5");  // trimmed text; a number when used as one
  expect_path(moves(), {{kMove, at(0, 0, -0.5)}});
}

TEST_F(LanguageTest, InputSeveralVariablesSplitAtCommas) {
  use_recording_io = true;
  rec.answers = {" 1, two ,\"3\""};
  run("&b = old\nINPUT \"Three values\", &a, &b, &c\n");
  const auto asked = rec.of("ask");
  ASSERT_EQ(asked.size(), 1u);
  EXPECT_EQ(asked[0].text, "Three values");
  EXPECT_EQ(asked[0].variable, "&A,&B,&C");
  expect_text("A", "1");
  expect_text("B", "two");  // overwritten (§7.59)
  expect_text("C", "3");
}

TEST_F(LanguageTest, InputSeveralVariablesFromScriptedInputs) {
  inputs = {{"&W", "10"}, {"&H", "5.5"}};
  run("INPUT \"Width, height\"; &w, &h\nM2, &w, &h\n");
  expect_text("W", "10");
  expect_text("H", "5.5");
  expect_path(moves(), {{kMove, at(10, 5.5)}});
}

TEST_F(LanguageTest, InputDefaultWithColon) {
  use_recording_io = true;
  rec.answers = {"3", ""};
  run("&size = 2.5\nINPUT \"Size\": &size\n&d = 1\nINPUT \"Count\": &d, &count\n");
  const auto asked = rec.of("ask");
  ASSERT_EQ(asked.size(), 2u);
  EXPECT_EQ(asked[0].default_value, "2.5");
  EXPECT_EQ(asked[0].variable, "&SIZE");  // one variable: default and receiver
  EXPECT_EQ(asked[1].default_value, "1");
  EXPECT_EQ(asked[1].variable, "&COUNT");
  expect_text("SIZE", "3");
  expect_text("COUNT", "");  // §7.57: an empty answer to one variable is the empty text
}

TEST_F(LanguageTest, InputWithTooFewValuesIsAnError) {
  use_recording_io = true;
  rec.answers = {"1"};
  const Diagnostic d = run_error("MX, 1\nINPUT \"Size\" &w, &h\n");
  EXPECT_EQ(format(d), "part.sbp:2:1: error: INPUT needs 2 values separated by commas and got 1");
}

TEST_F(LanguageTest, InputWithoutAnAnswerNeedsTheOperator) {
  yes = true;  // --yes does not answer INPUT
  const Outcome o = execute("INPUT \"Depth?\" &depth\n");
  EXPECT_EQ(o.ending, Ending::NeedsOperator);
  EXPECT_EQ(format(o.diag),
            "part.sbp:1:1: error: the file asks the operator for &DEPTH; run from a terminal, or "
            "give it with --input '&DEPTH=VALUE'");
}

TEST_F(LanguageTest, InputCancelEndsTheRun) {
  use_recording_io = true;  // no answers: cancel
  const Outcome o = execute("INPUT \"Depth?\" &depth\nMX, 1\n");
  EXPECT_EQ(o.ending, Ending::OperatorStop);
  EXPECT_EQ(format(o.diag), "part.sbp:1:1: error: stopped by the operator at INPUT");
  EXPECT_TRUE(moves().empty());
}

TEST_F(LanguageTest, InputTakesAtMostTenVariables) {
  EXPECT_TRUE(Script::from_text("INPUT \"x\" &a,&b,&c,&d,&e,&f,&g,&h,&i,&j\n", "p.sbp")->ok());
  const auto script = Script::from_text("INPUT \"x\" &a,&b,&c,&d,&e,&f,&g,&h,&i,&j,&k\n", "p.sbp");
  ASSERT_EQ(script->errors().size(), 1u);
  EXPECT_EQ(format(script->errors()[0]), "p.sbp:1:11: error: INPUT takes at most 10 variables");
}

// ---- PRINT

TEST_F(LanguageTest, PrintCommaModeJoinsWithFiveSpaces) {
  run("&x = 2.5\nPRINT \"a\", 1, &x, \"b c\"\n");
  EXPECT_EQ(printed, "a     1     2.5     b c\n");
}

TEST_F(LanguageTest, PrintSemicolonModeJoinsWithNothing) {
  run("PRINT \"x = \"; 1/4; \"!\"; 1/3\n");
  EXPECT_EQ(printed, "x = 0.25!0.3333333\n");
}

TEST_F(LanguageTest, PrintTrailingSemicolonKeepsTheLineOpen) {
  run("PRINT \"a\";\nPRINT \"b\"\nPRINT \"c\", \"d\";\nPRINT\nPRINT\n");
  EXPECT_EQ(printed, "ab\nc     d\n\n");
}

TEST_F(LanguageTest, PrintSemicolonInsideACommaListIsAnError) {
  const auto script = Script::from_text("PRINT \"a\", \"b\"; \"c\"\n", "part.sbp");
  ASSERT_EQ(script->errors().size(), 1u);
  EXPECT_EQ(format(script->errors()[0]),
            "part.sbp:1:15: error: a ';' inside a comma-separated list: use ',' between items (a "
            "';' may only end the line)");
}

// §7.86: an undefined variable prints as its own name, as written.
TEST_F(LanguageTest, PrintOfAnUndefinedVariableShowsItsName) {
  run("PRINT &Not_Set\nPRINT \"v=\"; &nope; \".\"\nPRINT &also, 1\n");
  EXPECT_EQ(printed, "&Not_Set\nv=&nope.\n&also     1\n");
}

// ---- MSGBOX

TEST_F(LanguageTest, MsgBoxYesPressesTheDefaultButton) {
  const std::pair<const char*, const char*> cases[] = {
      {"YesNo", "Yes"},   {"260", "No"},
      {"4 + 256", "No"},  {"276", "No"},
      {"OKCancel", "OK"}, {"abortretryignore", "Abort"},
      {"515", "Cancel"},  {"RetryCancel", "Retry"},
      {"Question", "OK"}, {"3 + 512", "Cancel"},
      {"0", "OK"}};
  for (const auto& [type, answer] : cases) {
    SCOPED_TRACE(type);
    run(std::string("MSGBOX(Go on?, ") + type + ", Title)\n");
    expect_text("MSGANSWER", answer);
  }
}

TEST_F(LanguageTest, MsgBoxButtonSetsAndDefaults) {
  use_recording_io = true;
  run("MSGBOX(Sure?, 276, Danger)\nMSGBOX(Just so you know)\n");
  const auto boxes = rec.of("choose");
  ASSERT_EQ(boxes.size(), 2u);
  EXPECT_EQ(boxes[0].buttons, (std::vector<std::string>{"Yes", "No"}));
  EXPECT_EQ(boxes[0].default_button, 1u);  // §7.63: 276 = YesNo + Critical + second default
  EXPECT_EQ(boxes[0].title, "Danger");
  EXPECT_EQ(boxes[1].text, "Just so you know");
  EXPECT_EQ(boxes[1].buttons, (std::vector<std::string>{"OK"}));
  EXPECT_EQ(boxes[1].title, "Gantry");
  expect_text("MSGANSWER", "OK");
}

// §7.65: an invalid type value is a plain OK box.
TEST_F(LanguageTest, MsgBoxInvalidTypeNumberIsOkOnly) {
  use_recording_io = true;
  run("MSGBOX(A, 6, T)\nMSGBOX(B, 1000, T)\nMSGBOX(C, 2.5, T)\nMSGBOX(D, 80, T)\n");
  const auto boxes = rec.of("choose");
  ASSERT_EQ(boxes.size(), 4u);
  for (const auto& b : boxes) EXPECT_EQ(b.buttons, (std::vector<std::string>{"OK"})) << b.text;
}

// §7.65 "any incorrect value will default to 0", words included (docs/language.md §4.12, A27).
TEST_F(LanguageTest, MsgBoxUnknownTypeNameIsOkOnly) {
  use_recording_io = true;
  const Outcome o = execute("MSGBOX(Hi, YesOrNo, T)\n");
  EXPECT_EQ(o.ending, Ending::Normal) << format(o.diag);
  const auto boxes = rec.of("choose");
  ASSERT_EQ(boxes.size(), 1u);
  EXPECT_EQ(boxes[0].buttons, (std::vector<std::string>{"OK"}));
  EXPECT_EQ(boxes[0].title, "T");
  expect_text("MSGANSWER", "OK");
}

TEST_F(LanguageTest, MsgBoxWithoutYesNeedsTheOperator) {
  yes = false;
  const Outcome o = execute("MSGBOX(Proceed?, YesNo, Check)\n");
  EXPECT_EQ(o.ending, Ending::NeedsOperator);
  EXPECT_EQ(format(o.diag),
            "part.sbp:1:1: error: MSGBOX asks the operator (\"Proceed?\"); run from a terminal, or "
            "with --yes to press its default button");
}

TEST_F(LanguageTest, MsgBoxWithOneButtonNeedsNobody) {
  yes = false;
  run("MSGBOX(Done, OKOnly, T)\n");
  expect_text("MSGANSWER", "OK");
}

// ---- DIALOG, FAIL

TEST_F(LanguageTest, DialogWithOnlyCancelTextEndsTheRun) {
  use_recording_io = true;
  const Outcome o = execute("MX, 1\nDIALOG \"Job done\", CANCELTEXT=\"Quit\"\nMX, 2\n");
  EXPECT_EQ(o.ending, Ending::OperatorStop);
  EXPECT_EQ(format(o.diag), "part.sbp:2:1: error: the file ended at DIALOG: Job done");
  const auto boxes = rec.of("choose");
  ASSERT_EQ(boxes.size(), 1u);
  EXPECT_EQ(boxes[0].text, "Job done");
  EXPECT_EQ(boxes[0].buttons, (std::vector<std::string>{"Quit"}));
  expect_path(moves(), {{kMove, at(1)}});
}

TEST_F(LanguageTest, DialogWithOkTextAsksToContinue) {
  use_recording_io = true;
  run("DIALOG(\"Turn on the spindle\", OKTEXT=\"Done\", CANCELTEXT=\"Stop\")\nMX, 1\n");
  const auto asked = rec.of("confirm");
  ASSERT_EQ(asked.size(), 1u);
  EXPECT_EQ(asked[0].text, "Turn on the spindle");
  EXPECT_EQ(moves().size(), 1u);
  rec.confirm_answer = false;
  const Outcome o = execute("DIALOG \"Again?\", OKTEXT=\"Yes\"\n");
  EXPECT_EQ(o.ending, Ending::OperatorStop);
  EXPECT_EQ(format(o.diag), "part.sbp:1:1: error: stopped by the operator at DIALOG");
  EXPECT_EQ(
      format(run_error("DIALOG \"x\", FOO=1\n")),
      "part.sbp:1:17: error: unknown DIALOG option FOO; use OKTEXT, CANCELTEXT, TITLE or TIMER");
}

TEST_F(LanguageTest, FailStopsWithItsMessage) {
  EXPECT_EQ(format(run_error("MX, 1\n&t = 2\n  FAIL \"board too thick: \" & &t\nMX, 2\n")),
            "part.sbp:3:3: error: FAIL: board too thick: 2");
  EXPECT_EQ(moves().size(), 1u);
  EXPECT_EQ(format(run_error("FAIL\n")), "part.sbp:1:1: error: FAIL: the file stopped itself");
}

// ---- OPEN, WRITE, PRINT #, INPUT #, CLOSE

TEST_F(LanguageTest, OpenWriteCloseInputRoundTrip) {
  run_file(dir().write("rt.sbp", R"sbp(&v = 23.5
OPEN "data.txt" FOR OUTPUT AS #1
WRITE #1, "M2", &v, &v
WRITE #1; "a"; 1/4; "b"
WRITE #1, "tail";
WRITE #1, " end"
PRINT #1, "printed", 7
CLOSE #1
OPEN "data.txt" FOR APPEND AS #(2)
WRITE #2; "appended"
CLOSE
OPEN "data.txt" FOR INPUT AS #3
INPUT #3, &code, &x, &y
INPUT #3, &line
INPUT #3, &whole
INPUT #3, &p, &n
INPUT #3, &last
CLOSE #3
)sbp"));
  EXPECT_EQ(dir().read("data.txt"), "M2, 23.5, 23.5\na0.25b\ntail end\nprinted, 7\nappended\n");
  expect_text("CODE", "M2");
  expect_text("X", "23.5");
  expect_text("Y", "23.5");
  expect_text("LINE", "a0.25b");
  expect_text("WHOLE", "tail end");
  expect_text("P", "printed");
  expect_text("N", "7");
  expect_text("LAST", "appended");
}

TEST_F(LanguageTest, InputFromAFileStripsQuotesAndCarriageReturns) {
  dir().write("in.csv", "\"Oak\", 0.75 ,x\r\nnext\r\n");
  run_file(dir().write("r.sbp",
                       "OPEN \"in.csv\" FOR INPUT AS #1\nINPUT #1, &wood, &t\n"
                       "INPUT #1, &n\nCLOSE #1\n"));
  expect_text("WOOD", "Oak");
  expect_text("T", "0.75");
  expect_text("N", "next");
}

TEST_F(LanguageTest, InputPastTheEndOfAFileIsAnError) {
  dir().write("one.txt", "only line\n");
  const Diagnostic d = run_file_error(
      dir().write("r.sbp", "OPEN \"one.txt\" FOR INPUT AS #1\nINPUT #1, &a\n  INPUT #1, &b\n"));
  EXPECT_EQ(where(d.loc), dir().path("r.sbp") + ":3:3");
  EXPECT_EQ(d.message, "INPUT #1 read past the end of " + dir().path("one.txt"));
  expect_text("A", "only line");
}

TEST_F(LanguageTest, FileNumbersAreOneToNine) {
  EXPECT_EQ(format(run_error("OPEN \"x.txt\" FOR OUTPUT AS #10\n")),
            "part.sbp:1:1: error: file number 10 is not 1 to 9");
  EXPECT_EQ(format(run_error("WRITE #0, 1\n")), "part.sbp:1:1: error: file number 0 is not 1 to 9");
  EXPECT_EQ(format(run_error("&n = 3\nWRITE #&n, 1\n")),
            "part.sbp:2:1: error: file #3 is not open; OPEN it first");
  EXPECT_EQ(format(run_error("INPUT #4, &a\n")),
            "part.sbp:1:1: error: file #4 is not open; OPEN it first");
}

TEST_F(LanguageTest, FileModeAndOpenErrors) {
  dir().write("in.txt", "x\n");
  const std::string in = dir().path("in.txt");
  const std::string out = dir().path("out.txt");
  // Each case on a fresh interpreter: files left open by a failed run would interfere.
  const auto err = [&](const std::string& text) {
    const Outcome o = execute_fresh(Script::load(dir().write("f.sbp", text)));
    EXPECT_EQ(o.ending, Ending::Error) << text;
    return o.diag;
  };
  Diagnostic d = err("OPEN \"in.txt\" FOR INPUT AS #1\nWRITE #1, 1\n");
  EXPECT_EQ(d.message, "file #1 was opened FOR INPUT; open it FOR OUTPUT or APPEND to write");
  d = err("OPEN \"out.txt\" FOR OUTPUT AS #1\nINPUT #1, &a\n");
  EXPECT_EQ(d.message, "file #1 was opened for writing; INPUT # reads files opened FOR INPUT");
  d = err("OPEN \"out.txt\" FOR OUTPUT AS #1\nOPEN \"in.txt\" FOR INPUT AS #1\n");
  EXPECT_EQ(d.message, "file #1 is already open (" + out + "); CLOSE it first");
  d = err("OPEN \"absent.txt\" FOR INPUT AS #1\n");
  EXPECT_EQ(where(d.loc), dir().path("f.sbp") + ":1:6");
  EXPECT_EQ(d.message, "cannot read " + dir().path("absent.txt") + ": there is no such file");
}

TEST_F(LanguageTest, CloseOfAFileThatIsNotOpenWarns) {
  run("CLOSE #5\nCLOSE\n");
  ASSERT_EQ(scripted().warnings().size(), 1u);
  EXPECT_EQ(format(scripted().warnings()[0]),
            "part.sbp:1:1: warning: CLOSE #5: that file is not open");
}

// A check follows a file that writes a file and reads it back, in a sandbox: it sees what
// the run would see, and the disk is untouched.
TEST_F(LanguageTest, DryRunReadsBackWhatItWroteWithoutWritingTheDisk) {
  options.dry_run = true;
  run_file(dir().write("rb.sbp",
                       "OPEN \"rb.txt\" FOR OUTPUT AS #1\nWRITE #1, 3\nCLOSE #1\n"
                       "OPEN \"rb.txt\" FOR APPEND AS #1\nWRITE #1, 4\nCLOSE #1\n"
                       "OPEN \"rb.txt\" FOR INPUT AS #2\nINPUT #2, &x\nINPUT #2, &y\nCLOSE\n"));
  expect_text("X", "3");
  expect_text("Y", "4");
  EXPECT_FALSE(dir().exists("rb.txt"));
}

TEST_F(LanguageTest, DryRunWritesNoFiles) {
  options.dry_run = true;
  run_file(dir().write("w.sbp", "OPEN \"out.txt\" FOR OUTPUT AS #1\nWRITE #1, 1\nCLOSE #1\n"));
  EXPECT_FALSE(dir().exists("out.txt"));
}

// §7.76 / §8 A24: user files are closed when the run ends.
TEST_F(LanguageTest, UserFilesAreClosedWhenTheRunEnds) {
  const std::string part =
      dir().write("w.sbp", "OPEN \"out.txt\" FOR OUTPUT AS #1\nWRITE #1, \"line\"\n");
  run_file(part);
  const Outcome second = execute(Script::load(part));
  EXPECT_EQ(second.ending, Ending::Normal) << format(second.diag);
  EXPECT_EQ(dir().read("out.txt"), "line\n");
}

// ---- SHELL, PLAY, WARNING OFF

TEST_F(LanguageTest, ShellIsDisabledByDefault) {
  const Diagnostic d = run_error("MX, 1\nSHELL, \"touch x\"\nMX, 2\n");
  EXPECT_EQ(format(d),
            "part.sbp:2:1: error: SHELL starts other programs and is disabled; run with "
            "--allow-shell to permit it");
  EXPECT_EQ(moves().size(), 1u);
}

TEST_F(LanguageTest, ShellRunsWhenAllowed) {
  options.allow_shell = true;
  const std::string marker = dir().path("made.txt");
  run("&f = \"" + marker + "\"\nSHELL, \"echo hi > \" & &f, 1, SYNC\n");
  EXPECT_EQ(dir().read("made.txt"), "hi\n");
  EXPECT_TRUE(scripted().warnings().empty());
}

TEST_F(LanguageTest, ShellSyncReportsTheExitStatus) {
  options.allow_shell = true;
  run("SHELL, \"exit 3\", 1, SYNC\n");
  ASSERT_EQ(scripted().warnings().size(), 1u);
  EXPECT_EQ(scripted().warnings()[0].message, "SHELL: `exit 3` exited with status 3");
  EXPECT_EQ(where(scripted().warnings()[0].loc), "part.sbp:1:1");
}

TEST_F(LanguageTest, PlayWarnsAndContinues) {
  run("&snd = \"/tmp/ding.wav\"\nPLAY &snd\nPLAY \"quoted.wav\"\nMX, 1\n");
  ASSERT_EQ(scripted().warnings().size(), 2u);
  EXPECT_EQ(scripted().warnings()[0].message,
            "PLAY &snd: Gantry plays no sounds; the file continues");
  EXPECT_EQ(where(scripted().warnings()[1].loc), "part.sbp:3:1");
  EXPECT_EQ(moves().size(), 1u);
}

TEST_F(LanguageTest, WarningOff) {
  run("WARNING OFF\nwarning   off\nMX, 1\n");
  EXPECT_EQ(moves().size(), 1u);
  EXPECT_TRUE(scripted().warnings().empty());
  EXPECT_EQ(format(Script::from_text("WARNING ON\n", "p.sbp")->errors().at(0)),
            "p.sbp:1:9: error: write WARNING OFF");
}

// ---- registry statements

TEST_F(LanguageTest, RegistryUserValueRoundTrip) {
  run("GetUsrVal, &before\nSetUsrVal, 42\nGetUsrVal, &v\nSetUsrVal \"oak\"\nGetUsrVal &w\n");
  expect_text("BEFORE", "");  // never set: the empty text
  expect_number("V", 42);
  expect_text("W", "oak");
  EXPECT_EQ(store.registry()["uValue"], "oak");
}

TEST_F(LanguageTest, RegistryUserValuePersistsAcrossRuns) {
  const std::string path = dir().path("state/persistent.json");
  {
    PersistentStore file_store(path);
    FlushTrackingSink s;
    ScriptedIO io(true, {});
    Interpreter first(settings, s, io, file_store);
    first.run(Script::from_text("SetUsrVal, 7.5\nSetSpindleStatus, 1\n", "a.sbp"));
  }
  PersistentStore reloaded(path);
  FlushTrackingSink s;
  ScriptedIO io(true, {});
  Interpreter second(settings, s, io, reloaded);
  second.run(Script::from_text("GetUsrVal, &v\nGetSpindleStatus, &s\nGetPartFileName, &name\n",
                               "/parts/b.sbp"));
  ASSERT_NE(second.variable("V"), nullptr);
  EXPECT_DOUBLE_EQ(second.variable("V")->num(), 7.5);
  EXPECT_DOUBLE_EQ(second.variable("S")->num(), 1);
  EXPECT_EQ(second.variable("NAME")->str(), "/parts/b.sbp");
}

// §7.94 / §8 A30: SetUsrValClrd is cleared at the start and end of each top-level run.
TEST_F(LanguageTest, RegistryClearedValueDoesNotOutliveTheRun) {
  run("SetUsrValClrd, 5\nGetUsrValClrd, &during\n");
  expect_number("DURING", 5);
  run("GetUsrValClrd, &next\n");
  expect_text("NEXT", "");
}

// ---- assignment

TEST_F(LanguageTest, AssignmentAndWeakAssignment) {
  run("&a = 1\n&a := 2\n&b := 3\n&c=4\n&blank =\n&flag = &a = 1\n");
  expect_number("A", 1);  // := keeps an existing value
  expect_number("B", 3);  // and sets an undefined one
  expect_number("C", 4);
  expect_text("BLANK", "");
  expect_number("FLAG", -1);  // only the first = assigns
}

TEST_F(LanguageTest, BareStringAssignment) {
  run("&s = Material Surface\n&t = don't worry\n&p = C:\\parts\\a.sbp\n&w = T\n");
  expect_text("S", "Material Surface");
  expect_text("T", "don");  // §8 A46: an apostrophe in a bare string starts a comment
  expect_text("P", "C:\\parts\\a.sbp");
  expect_text("W", "T");
}

// Spec §4.7 lists `12 apples` among the bare strings (docs/language.md §4.1, A10).
TEST_F(LanguageTest, BareStringStartingWithADigit) {
  const auto script = Script::from_text("&n = 12 apples\n&m = 12\n", "part.sbp");
  ASSERT_FALSE(has_error(script->errors())) << all(script->errors());
  run("&n = 12 apples\n&m = 12\n");
  expect_text("N", "12 apples");
  expect_number("M", 12);  // the whole text a number: still a number
}

TEST_F(LanguageTest, TextThatCanOnlyBeAnExpressionMustBeOne) {
  const auto script = Script::from_text("&x = SQR(1,2)\n&y = &x +\n", "part.sbp");
  ASSERT_EQ(script->errors().size(), 2u) << all(script->errors());
  EXPECT_EQ(format(script->errors()[0]), "part.sbp:1:6: error: SQR takes 1 argument, not 2");
  EXPECT_EQ(format(script->errors()[1]), "part.sbp:2:10: error: expected a value after '+'");
  EXPECT_EQ(var("X"), nullptr);
}

TEST_F(LanguageTest, AssignmentErrors) {
  EXPECT_EQ(format(Script::from_text("%(1) = 3\n", "p.sbp")->errors().at(0)),
            "p.sbp:1:1: error: system variables %(n) are read-only; assign to a &variable "
            "instead");
  EXPECT_EQ(format(Script::from_text("&a 3\n", "p.sbp")->errors().at(0)),
            "p.sbp:1:1: error: expected '=' after the variable: write &name = value");
}

TEST_F(LanguageTest, VariableNamesIgnoreCase) {
  run("&zDepth = -0.5\nMZ, &ZDEPTH\n&ZDEPTH = &zdepth * 2\n");
  expect_number("ZDEPTH", -1);  // §7.20
  expect_path(moves(), {{kMove, at(0, 0, -0.5)}});
}

TEST_F(LanguageTest, StringJoin) {
  run("&s = \"a\" & 1.5 & \"b\" & (2 + 3)\n&n = 1 + 2 & 3\n&first = Bill\n"
      "&full = \"My name is \" & &first & \"!\"\n");
  expect_text("S", "a1.5b5");
  expect_text("N", "33");
  expect_text("FULL", "My name is Bill!");
}

// ---- persistent $variables

TEST_F(LanguageTest, PersistentVariablesWithPaths) {
  run(R"sbp($x.y = 3
$x.name = "oak"
&i = 2
$list[&i].z = 4.5
$plain = 7
$plain := 8
$fresh := 9
&r = $list[2].z + $x.y + $plain
&s = $x.NAME & "!"
)sbp");
  ASSERT_NE(store.variable("X"), nullptr);
  EXPECT_EQ(*store.variable("X"), nlohmann::json::parse(R"({"Y": 3, "NAME": "oak"})"));
  EXPECT_EQ(*store.variable("LIST"), nlohmann::json::parse(R"([null, null, {"Z": 4.5}])"));
  EXPECT_DOUBLE_EQ(store.variable("PLAIN")->get<double>(), 7);
  EXPECT_DOUBLE_EQ(store.variable("FRESH")->get<double>(), 9);
  expect_number("R", 14.5);
  expect_text("S", "oak!");
}

// FabMo's universal-unit variables, with the values of its runtime's UU_README: [] stores
// inches at [0] and mm at [1], from whichever units are current; `:=` keeps both.
TEST_F(LanguageTest, UniversalUnitVariablesStoreInchesAndMillimetres) {
  run(R"sbp(VD, , , 0
$toolUU[3][].x = 5.5
$safeUU[].z := 1
$safeUU[].z := 2
VD, , , 1
$toolUU[3][].y = 50.8
&in_x = $toolUU[3][0].x
&mm_x = $toolUU[3][%(25)].x
&in_y = $toolUU[3][0].y
&z = $safeUU[0].z
)sbp");
  expect_number("IN_X", 5.5);
  expect_number("MM_X", 139.7);
  expect_number("IN_Y", 2.0);
  expect_number("Z", 1);
  EXPECT_EQ(run_error("$tool[] = 1\n").message,
            "[] is the unit index of universal-unit variables, whose names end in UU; give an "
            "index to $TOOL, or rename it $TOOLUU");
  EXPECT_EQ(run_error("$aUU[][] = 1\n").message,
            "$AUU[][] has more than one []; the unit index [] is given once");
}

TEST_F(LanguageTest, PersistentVariablesAreSavedAndReloaded) {
  const std::string path = dir().path("persistent.json");
  {
    PersistentStore file_store(path);
    FlushTrackingSink s;
    ScriptedIO io(true, {});
    Interpreter first(settings, s, io, file_store);
    first.run(Script::from_text("$tool.diameter = 0.25\n$count = 1\n", "a.sbp"));
  }
  ASSERT_TRUE(fs::exists(path));
  PersistentStore reloaded(path);
  FlushTrackingSink s;
  ScriptedIO io(true, {});
  Interpreter second(settings, s, io, reloaded);
  second.run(Script::from_text("$count = $count + 1\n&d = $tool.diameter\n", "b.sbp"));
  EXPECT_DOUBLE_EQ(second.variable("D")->num(), 0.25);
  EXPECT_DOUBLE_EQ(PersistentStore(path).variable("COUNT")->get<double>(), 2);
}

TEST_F(LanguageTest, UndefinedPersistentVariableIsAnError) {
  const Diagnostic d = run_error("&a = $nope + 1\n");
  EXPECT_EQ(where(d.loc), "part.sbp:1:6");
  EXPECT_EQ(d.message.rfind("undefined persistent variable $NOPE; set it first", 0), 0u)
      << d.message;
}

// ---- system variables

TEST_F(LanguageTest, SystemVariablesReadTheLocationAfterMoves) {
  run("M3, 1.5, 2.25, -0.125\n&x = %(1)\n&y = %(2)\n&z = %(3)\nSR\nMX, 1\n&x2 = %(1)\n");
  expect_number("X", 1.5);
  expect_number("Y", 2.25);
  expect_number("Z", -0.125);
  expect_number("X2", 2.5);
}

TEST_F(LanguageTest, SystemVariableUnits) {
  run("&u = %(25)\n");
  expect_number("U", 0);  // inches
}

TEST_F(LanguageTest, SystemVariableUnitsInMillimetres) {
  settings.units = Units::Millimetres;
  run("&u = %(25)\n");
  expect_number("U", 1);
}

TEST_F(LanguageTest, SystemVariableNumberMayBeAnExpression) {
  run("&n = 2\nMY, 4\n&v = %(&n)\n&w = %(&n + 1)\n&ms = %(71)\nMS, 3\n&ms2 = %(71)\n");
  expect_number("V", 4);
  expect_number("W", 0);
  expect_number("MS", 2);
  expect_number("MS2", 3);
}

TEST_F(LanguageTest, UnknownSystemVariableIsAnError) {
  EXPECT_EQ(format(run_error("MX, 1\n&v = %(999)\n")),
            "part.sbp:2:6: error: unknown system variable %(999); docs/system_variables.md lists "
            "them");
  EXPECT_EQ(format(run_error("&n = 26\n&v = %(&n)\n")),
            "part.sbp:2:6: error: unknown system variable %(26); docs/system_variables.md lists "
            "them");
}

// §7.33: %(61)-%(63) are the offsets and %(66)-%(68) the proportions of the running file.
TEST_F(LanguageTest, SystemVariablesReportTheRunningFilesOffsetAndProportion) {
  dir().write("child.sbp", "&ox = %(61)\n&oy = %(62)\n&px = %(66)\n&py = %(67)\n&pz = %(68)\n");
  run_file(dir().write("main.sbp", "M2, 3, 4\nFP, child.sbp, 2, 3, 0.5, , 2\n"));
  const Value* ox = var("OX");
  const Value* px = var("PX");
  ASSERT_TRUE(ox && px);
  expect_number("OX", 3);
  expect_number("OY", 4);
  expect_number("PX", 2);
  expect_number("PY", 3);
  expect_number("PZ", 0.5);
}

// ---- FP

TEST_F(LanguageTest, FpScalesByItsProportions) {
  dir().write("child.sbp", "M3, 1, 2, -1\n");
  run_file(dir().write("main.sbp", "FP, child.sbp, 2, 3, 0.5\nMX, 1\n"));
  expect_path(moves(), {{kMove, at(2, 6, -0.5)}, {kMove, at(1, 6, -0.5)}});
}

TEST_F(LanguageTest, FpRepeatsTheFile) {
  dir().write("child.sbp", "SR\nMX, 1\nSA\nPRINT \"pass\"\n");
  run_file(dir().write("main.sbp", "FP, child.sbp, , , , 3\nMY, 1\n"));
  expect_path(moves(), {{kMove, at(1)}, {kMove, at(2)}, {kMove, at(3)}, {kMove, at(3, 1)}});
  EXPECT_EQ(printed, "pass\npass\npass\n");
}

TEST_F(LanguageTest, FpTwoDimensionalOffset) {
  dir().write("child.sbp", "M3, 1, 1, -0.5\nM2, 0, 0\n");
  run_file(dir().write("main.sbp", "M3, 5, 5, 1\nFP, child.sbp, , , , , 2\nMX, 1\n"));
  expect_path(moves(), {{kMove, at(5, 5, 1)},
                        {kMove, at(6, 6, -0.5)},
                        {kMove, at(5, 5, -0.5)},
                        {kMove, at(1, 5, -0.5)}});
}

TEST_F(LanguageTest, FpThreeDimensionalOffset) {
  dir().write("child.sbp", "M3, 1, 1, -0.5\nM2, 0, 0\n");
  run_file(dir().write("main.sbp", "M3, 5, 5, 1\nFP, child.sbp, , , , , 1\nMX, 1\n"));
  expect_path(moves(), {{kMove, at(5, 5, 1)},
                        {kMove, at(6, 6, 0.5)},
                        {kMove, at(5, 5, 0.5)},
                        {kMove, at(1, 5, 0.5)}});
}

TEST_F(LanguageTest, FpOffsetAndProportionTogether) {
  dir().write("child.sbp", "M2, 1, 1\n");
  run_file(dir().write("main.sbp", "M3, 5, 5, 1\nFP, child.sbp, 2, 2, , , 2\n"));
  expect_path(moves(), {{kMove, at(5, 5, 1)}, {kMove, at(7, 7, 1)}});
}

// FP's plunge is "the depth of plunge for each repetition of the file … typically used to cut a
// template type of file that did not have plunges in the file itself" (commands.md §3.8).
// As in the spec's pass model (commands.md §3.2) and docs/language.md §5.5 (parameter 7,
// "the first pass included"), pass k runs k plunges down: a 2D template is cut at Z -0.25,
// -0.5 and -0.75.
TEST_F(LanguageTest, FpPlungeCutsATemplateDeeperEachRepetition) {
  dir().write("square.sbp", "M2, 1, 0\nM2, 1, 1\nM2, 0, 1\nM2, 0, 0\n");
  run_file(dir().write("main.sbp", "FP, square.sbp, , , , 3, , -0.25\n"));
  std::vector<double> depths;  // the Z of each XY cut
  for (const CanonMove& m : moves())
    if (m.from[0] != m.to[0] || m.from[1] != m.to[1]) depths.push_back(m.to[2]);
  ASSERT_EQ(depths.size(), 12u);
  for (size_t i = 0; i < depths.size(); ++i)
    EXPECT_DOUBLE_EQ(depths[i], -0.25 * static_cast<double>(i / 4 + 1)) << "cut " << i;
}

TEST_F(LanguageTest, FpParameterErrors) {
  dir().write("c.sbp", "MX, 1\n");
  const auto err = [&](const std::string& line) {
    return run_file_error(dir().write("m.sbp", line + "\n"));
  };
  EXPECT_EQ(err("FP, c.sbp, 0").message,
            "FP proportions must be above 0 (1 keeps the file's size)");
  EXPECT_EQ(err("FP, c.sbp, , , , 1.5").message,
            "FP repetitions must be a whole number, 1 or more");
  EXPECT_EQ(err("FP, c.sbp, , , , , 3").message,
            "FP offset is 0 (none), 1 (3D: X, Y, Z from here) or 2 (2D)");
  const Diagnostic d = err("FP, c.sbp, , , , , 3");
  EXPECT_EQ(where(d.loc), dir().path("m.sbp") + ":1:20");
  EXPECT_TRUE(moves().empty());
}

// A chain of 8 files (the top-level one included) is allowed (§8 A20).
TEST_F(LanguageTest, FpNestsEightFilesDeep) {
  dir().write("rec.sbp", "&d = &d + 1\nIF &d < 8 THEN FP, rec.sbp\n&back = &back + 1\n");
  run_file(dir().write("main.sbp", "&d = 1\n&back = 0\nFP, rec.sbp\n"));
  expect_number("D", 8);
  expect_number("BACK", 7);
}

// A file that calls itself stops at the ninth level; the error names every calling line.
TEST_F(LanguageTest, FpNestingDepthLimitIsEight) {
  const std::string self = dir().write("self.sbp", "' recursion\nMX, 1\n  FP, self.sbp\n");
  const Diagnostic d = run_file_error(self);
  EXPECT_EQ(d.message, "files are nested 8 deep, the most allowed; a file may be calling itself");
  EXPECT_EQ(where(d.loc), self + ":3:3");
  ASSERT_EQ(d.via.size(), 7u);
  for (const SourceLoc& v : d.via) EXPECT_EQ(where(v), self + ":3:3");
  std::string expected;
  for (int i = 0; i < 7; ++i) expected += self + ":3 -> ";
  expected += self +
              ":3:3: error: files are nested 8 deep, the most allowed; a file may be calling "
              "itself";
  EXPECT_EQ(format(d), expected);
  EXPECT_EQ(moves().size(), 1u);  // X reaches 1 once; the other MX, 1 move nothing
}

TEST_F(LanguageTest, ErrorInADeeplyNestedFileNamesTheChain) {
  dir().write("c.sbp", "MX, 1\nMY, 2\n  MZ, abc\n");
  dir().write("b.sbp", "' b\n\nFP, c.sbp\n");
  const std::string a = dir().write("a.sbp", "FP, b.sbp\n");
  const Diagnostic d = run_file_error(a);
  EXPECT_EQ(format(d), a + ":1 -> " + dir().path("b.sbp") + ":3 -> " + dir().path("c.sbp") +
                           ":3:7: error: expected a number for Z location (MZ), found 'abc'");
}

// An FP whose file cannot be read is an error at the FP line; one that does not parse says
// which FP line asked for it.
TEST_F(LanguageTest, MissingFpFileNamesTheCallingLine) {
  const std::string main = dir().write("main.sbp", "MX, 1\nFP, missing.sbp\n");
  const Diagnostic d = run_file_error(main);
  EXPECT_EQ(format(d), main + ":2:1: error: cannot read " + dir().path("missing.sbp") +
                           ": there is no such file");
}

TEST_F(LanguageTest, SyntaxErrorInAnFpFileNamesTheCallingLine) {
  dir().write("bad.sbp", "MX, 1\nM23, 4\n");
  const std::string main = dir().write("main.sbp", "MY, 1\nFP, bad.sbp\n");
  const Diagnostic d = run_file_error(main);
  EXPECT_EQ(where(d.loc), dir().path("bad.sbp") + ":2:3");
  expect_path(moves(), {{kMove, at(0, 1)}});  // the child never started
  ASSERT_EQ(d.via.size(), 1u);
  EXPECT_EQ(where(d.via[0]), main + ":2:1");
}

// docs/language.md §5.3 and §8 A26 (spec §5.1 [REC]): a relative name in FP or OPEN is taken
// from the top-level file's folder, wherever the calling file lives.
TEST_F(LanguageTest, FpAndOpenFindRelativeNamesInTheTopLevelFilesFolder) {
  dir().write("sub/child.sbp",
              "MX, 1\nFP, grand.sbp\nOPEN \"out.txt\" FOR OUTPUT AS #1\nWRITE #1, 1\nCLOSE #1\n");
  dir().write("sub/grand.sbp", "MY, 9\n");  // not this one
  dir().write("grand.sbp", "MY, 2\n");
  run_file(dir().write("main.sbp", "FP, sub/child.sbp\n"));
  expect_path(moves(), {{kMove, at(1)}, {kMove, at(1, 2)}});
  EXPECT_EQ(where(moves()[1].loc), dir().path("grand.sbp") + ":1:1");
  EXPECT_EQ(dir().read("out.txt"), "1\n");
  EXPECT_FALSE(dir().exists("sub/out.txt"));
}

TEST_F(LanguageTest, FpFileNameMayBeAVariable) {
  dir().write("child.sbp", "MX, 2\n");
  run_file(dir().write("main.sbp", "&f = \"child.sbp\"\nFP, &f\n"));
  expect_path(moves(), {{kMove, at(2)}});
}

// §5.4: speeds set by VS in a file are undone when that file ends; speeds set by MS stay
// (even in a file that also used VS).
TEST_F(LanguageTest, VsInsideAnFpChildRevertsWhenTheChildEnds) {
  dir().write("child.sbp", "VS, 3, 0.25\nMS, , , 20\nMY, 1\n");
  dir().write("ms_only.sbp", "MS, , , 30\n");
  run_file(dir().write("main.sbp",
                       "MS, 1\nFP, child.sbp\nMX, 1\nFP, ms_only.sbp\nMX, 2\nVS, 1.5\nMX, 3\n"));
  ASSERT_EQ(moves().size(), 4u);
  EXPECT_DOUBLE_EQ(moves()[0].speeds.xy, 3);  // the child's VS
  EXPECT_DOUBLE_EQ(moves()[0].speeds.z, 0.25);
  EXPECT_DOUBLE_EQ(moves()[0].speeds.a, 20);
  EXPECT_DOUBLE_EQ(moves()[1].speeds.xy, 1);  // the child's VS undone: the parent's MS again
  EXPECT_DOUBLE_EQ(moves()[1].speeds.z, 0.5);
  EXPECT_DOUBLE_EQ(moves()[1].speeds.a, 20);  // the child's MS stays
  EXPECT_DOUBLE_EQ(moves()[2].speeds.a, 30);
  EXPECT_DOUBLE_EQ(moves()[3].speeds.xy, 1.5);
  EXPECT_DOUBLE_EQ(moves()[3].speeds.a, 30);
  // The parent's own VS (XY) is undone when it ends; the MS values stay.
  EXPECT_DOUBLE_EQ(state().speeds.move.xy, 2);
  EXPECT_DOUBLE_EQ(state().speeds.move.z, 0.5);
  EXPECT_DOUBLE_EQ(state().speeds.move.a, 30);
}

// §5.4 [REC]: the restore also happens when a file ends with an error.
TEST_F(LanguageTest, VsRevertsWhenTheRunEndsWithAnError) {
  run_error("VS, 1.5, 0.25\nMX, 1\nQQ\n");
  EXPECT_DOUBLE_EQ(state().speeds.move.xy, 2.0);
  EXPECT_DOUBLE_EQ(state().speeds.move.z, 0.5);
}

// An interpreter runs file after file (the tests above rely on it); a failed run must not
// leave its file behind to be resumed by the next run.
TEST_F(LanguageTest, ARunAfterAFailedRunStartsClean) {
  run_error("MX, 1\nQQ\nMX, 2\n");
  sink.moves.clear();
  const Outcome o = execute("MY, 1\n");
  EXPECT_EQ(o.ending, Ending::Normal) << format(o.diag);
  expect_path(moves(), {{kMove, at(1, 1)}}, at(1));
}

// ---- custom cuts C<n>

TEST_F(LanguageTest, CustomCutsComeFromTheMacroFolder) {
  dir().write("macros/C5.sbp", "MX, 3\n");
  dir().write("macros/macro_6.sbp", "MY, 2\n&fromsix = 6\n");
  options.macro_dir = dir().path("macros");
  run_file(dir().write("main.sbp", "C5\nc6\nMZ, 1\n"));
  expect_path(moves(), {{kMove, at(3)}, {kMove, at(3, 2)}, {kMove, at(3, 2, 1)}});
  EXPECT_EQ(where(moves()[1].loc), dir().path("macros/macro_6.sbp") + ":1:1");
  expect_number("FROMSIX", 6);
}

TEST_F(LanguageTest, CustomCutsDefaultToThePartFilesFolder) {
  dir().write("C3.sbp", "MX, 1\n");
  run_file(dir().write("main.sbp", "C3\n"));
  expect_path(moves(), {{kMove, at(1)}});
}

TEST_F(LanguageTest, MissingCustomCutIsAnError) {
  options.macro_dir = dir().path("macros");
  fs::create_directories(options.macro_dir);
  const Diagnostic d = run_error("MX, 1\n  C8\n");
  EXPECT_EQ(format(d),
            "part.sbp:2:3: error: C8 runs custom cut 8, but there is no C8.sbp or "
            "macro_8.sbp in " +
                options.macro_dir +
                " or " GANTRY_SOURCE_DIR
                "/parts/macros; put the macro in one of them or give its folder with --macros");
}

TEST_F(LanguageTest, ErrorInACustomCutNamesTheCallingLine) {
  dir().write("macros/C2.sbp", "MX, 1\nQQ\n");
  options.macro_dir = dir().path("macros");
  const std::string main = dir().write("main.sbp", "' main\nC2\n");
  EXPECT_EQ(format(run_file_error(main)), main + ":2 -> " + dir().path("macros/C2.sbp") +
                                              ":2:1: error: unknown command 'QQ'" + kUnknownSuffix);
}

// ---- ShopBot's own spellings (issue 21)

// `C#, n` runs custom cut n as `C<n>` does; n may be a variable or an expression.
TEST_F(LanguageTest, ComputedCustomCutRunsTheSameMacro) {
  dir().write("macros/C90.sbp", "MX, 3\n");
  dir().write("macros/macro_211.sbp", "MY, 2\n");
  options.macro_dir = dir().path("macros");
  run_file(dir().write("main.sbp", "C#,90\n&n = 200\nC#, &n + 11\n"));
  expect_path(moves(), {{kMove, at(3)}, {kMove, at(3, 2)}});
  EXPECT_EQ(where(moves()[1].loc), dir().path("macros/macro_211.sbp") + ":1:1");
}

TEST_F(LanguageTest, ComputedCustomCutNeedsAWholeNumber) {
  EXPECT_EQ(format(run_error("&n = 2.5\nC#, &n\n")),
            "part.sbp:2:5: error: custom cuts are numbered 0 to 9999; C# was given 2.5");
  EXPECT_EQ(format(run_error("&n = left\nC#, &n\n")).rfind("part.sbp:2:5: error: ", 0), 0u);
}

// The handbook: MSGBOX's answer goes to &msganswer "so that you can use it in an IF test",
// and strings work with or without quotation marks.
TEST_F(LanguageTest, IfComparesAnUnquotedAnswer) {
  use_recording_io = true;
  rec.choice = "Cancel";
  run("MSGBOX(Remove the clamps (all four) then press OK,OKCANCEL,Clamps)\n"
      "IF &msganswer = Cancel THEN END\n"
      "MX, 1\n");
  const auto boxes = rec.of("choose");
  ASSERT_EQ(boxes.size(), 1u);
  EXPECT_EQ(boxes[0].text, "Remove the clamps (all four) then press OK");
  EXPECT_EQ(boxes[0].buttons, (std::vector<std::string>{"OK", "Cancel"}));
  EXPECT_EQ(boxes[0].title, "Clamps");
  EXPECT_TRUE(moves().empty());
}

// A lone '(' in the box's text used to hide the commas after it: the box was OK-only and
// Cancel could not be pressed.
TEST_F(LanguageTest, MsgBoxWithALoneParenthesisKeepsItsButtons) {
  use_recording_io = true;
  rec.choice = "Cancel";
  run("MSGBOX(Check the bit (1/4 inch,OKCANCEL,Tool)\nIF &msganswer = \"Cancel\" THEN END\n"
      "MX, 1\n");
  const auto boxes = rec.of("choose");
  ASSERT_EQ(boxes.size(), 1u);
  EXPECT_EQ(boxes[0].text, "Check the bit (1/4 inch");
  EXPECT_EQ(boxes[0].buttons, (std::vector<std::string>{"OK", "Cancel"}));
  EXPECT_TRUE(moves().empty());
}

TEST_F(LanguageTest, UnquotedMultiWordValueComparesInAnIfTest) {
  run("&PWZorigin = Material Surface\nIF &PWZorigin = material surface THEN &top = 1\n");
  expect_text("PWZORIGIN", "Material Surface");
  expect_number("TOP", 1);
}

TEST_F(LanguageTest, VariableNamesStartingWithADigitAndIntegerDivision) {
  run("&3zero_input = 7.75\n&5AX_whole = (&3zero_input)\\1\nMX, &5AX_whole\n");
  expect_number("5AX_WHOLE", 7);
  expect_path(moves(), {{kMove, at(7)}});
}

// SB3 ignores parameters past a command's last; ShopBot's own samples write CR with 10 and CP
// with 15. One warning per command and file, at the first extra parameter.
TEST_F(LanguageTest, ExtraTrailingParametersAreIgnoredOncePerCommandAndFile) {
  use_recording_io = true;
  dir().write("child.sbp", "SA, 1\n");
  run_file(dir().write("main.sbp", "SA, 1\nSA, 2, 3\nSR, , 4\nFP, child.sbp\n"));
  ASSERT_EQ(rec.warnings.size(), 3u);
  EXPECT_EQ(format(rec.warnings[0]),
            dir().path("main.sbp") +
                ":1:5: warning: SA takes 0 parameters; parameter 1 and those after it are "
                "ignored, as SB3 ignores them");
  EXPECT_EQ(format(rec.warnings[1]),
            dir().path("main.sbp") +
                ":3:7: warning: SR takes 0 parameters; parameter 2 and those after it are "
                "ignored, as SB3 ignores them");
  EXPECT_EQ(where(rec.warnings[2].loc), dir().path("child.sbp") + ":1:5");
}

// ---- check()

TEST_F(LanguageTest, CheckStopsAnEndlessLoopWithTheStatementBudget) {
  options.statement_budget = 100;
  const std::vector<Diagnostic> ds = check("LOOP:\nMX, 1\nGOTO LOOP\n");
  ASSERT_EQ(ds.size(), 1u) << all(ds);
  // An error, not a warning: a run would loop for ever. The budget is on top of the lines.
  EXPECT_EQ(format(ds[0]),
            "part.sbp:2:1: error: the check ran 103 statements and the file had not ended: it "
            "loops here without end (a GOTO back with no way out?). Nothing ran; if the file is "
            "meant to run that long, give a larger --budget");
  EXPECT_EQ(interp().statements_executed(), 104u);
}

TEST_F(LanguageTest, CheckStopsWhereAnOperatorAnswerIsNeeded) {
  yes = false;
  const std::vector<Diagnostic> ds = check("MX, 1\nQQ\n'Ready?\nPAUSE\nMX, 2\nQQ\n");
  ASSERT_EQ(ds.size(), 2u) << all(ds);
  EXPECT_EQ(format(ds[0]), "part.sbp:2:1: error: unknown command 'QQ'" + kUnknownSuffix);
  EXPECT_EQ(format(ds[1]),
            "part.sbp:4:1: warning: checking stopped here: the file waits for the operator "
            "(\"Ready?\"); run from a terminal, or with --yes to continue every pause");
  EXPECT_EQ(moves().size(), 1u);
}

// A statement that fails differently on every pass (one step further off the table each time)
// is reported once, and the budget still ends the loop.
TEST_F(LanguageTest, CheckReportsALineThatFailsOnEveryPassOnce) {
  options.statement_budget = 1000;
  const std::vector<Diagnostic> ds = check("&x = 20\nLOOP:\n&x = &x + 1\nMX, &x\nGOTO LOOP\n");
  ASSERT_EQ(ds.size(), 2u) << all(ds);
  EXPECT_EQ(format(ds[0]).rfind("part.sbp:4:1: error: move to X=25.0000 is outside the soft "
                                "limits",
                                0),
            0u)
      << format(ds[0]);
  EXPECT_EQ(format(ds[1]).rfind("part.sbp:", 0), 0u);
  EXPECT_NE(ds[1].message.find("the check ran 1005 statements"), std::string::npos);
}

TEST_F(LanguageTest, CheckReportsAMissingFileCalledInALoopOnce) {
  options.statement_budget = 1000;
  const std::string part =
      dir().write("loop.sbp", "&i = 0\nLOOP:\n&i = &i + 1\nFP, missing.sbp\nGOTO LOOP\n");
  DiagnosticLog log;
  interp().check(Script::load(part), log);
  ASSERT_EQ(log.kept().size(), 2u) << all(log.kept());
  EXPECT_EQ(log.kept()[0].loc.line, 4);  // at the FP line itself
  EXPECT_NE(log.kept()[1].message.find("the check ran 1005 statements"), std::string::npos);
  EXPECT_TRUE(log.stopped_short());
}

// A refused move leaves the check where the file meant the tool to be: the relative move and
// the arcs after it are checked from there, and only the refused move is an error.
TEST_F(LanguageTest, CheckGoesOnFromWhereARefusedMoveMeantTheToolToBe) {
  const std::vector<Diagnostic> ds = check(
      "SA\n"
      "J2, 30, 5\n"  // off the 24 in table: refused
      "SR\n"
      "JX, -20\n"  // to X=10
      "SA\n"
      "CG, , 14, 5, 2, 0, T, 1\n"  // half circles about (12, 5), there and back
      "CG, , 10, 5, -2, 0, T, 1\n"
      "SR\n"
      "M2, 3, 1\n");
  ASSERT_EQ(ds.size(), 1u) << all(ds);
  EXPECT_EQ(ds[0].loc.line, 2);
  EXPECT_NE(ds[0].message.find("outside the soft limits"), std::string::npos) << ds[0].message;
  ASSERT_FALSE(moves().empty());
  EXPECT_NEAR(moves().back().to[0], 13, 1e-12);  // SR from (10, 5): where the arcs ended
  EXPECT_NEAR(moves().back().to[1], 6, 1e-12);
}

// A run is not a check: a refused move leaves the location where the tool is.
TEST_F(LanguageTest, ARefusedMoveInARunDoesNotMoveTheLocation) {
  run_error("MX, 2\nMX, 30\n");
  expect_vec(state().position, at(2));
}

TEST_F(LanguageTest, CheckStopsAtItsErrorCapWithoutRunningFurther) {
  DiagnosticLog log(2);
  interp().check(Script::from_text("MX, 30\nMX, 31\nMX, 32\nMX, 33\n", "part.sbp"), log);
  EXPECT_EQ(log.kept().size(), 2u) << all(log.kept());
  EXPECT_TRUE(log.full());
  EXPECT_EQ(interp().statements_executed(), 2u);
}

TEST_F(LanguageTest, CheckStopsWhenAskedToFromAnotherThread) {
  std::atomic<bool> stop{true};  // a signal came before the first statement
  options.stop_check = &stop;
  DiagnosticLog log;
  interp().check(Script::from_text("MX, 1\nMX, 2\n", "part.sbp"), log);
  ASSERT_TRUE(log.stopped_short());
  EXPECT_EQ(format(*log.stopped_short()),
            "part.sbp:1:1: error: the check was stopped here (a signal); the lines from here on "
            "were not checked, and nothing ran");
  EXPECT_TRUE(moves().empty());
}

TEST_F(LanguageTest, CheckStopsShortAtAnInputWithoutAnAnswer) {
  DiagnosticLog log;
  interp().check(Script::from_text("MX, 1\nINPUT \"Depth?\" &d\nMZ, -&d\n", "part.sbp"), log);
  ASSERT_TRUE(log.stopped_short());
  EXPECT_EQ(log.stopped_short()->loc.line, 2);
  EXPECT_FALSE(log.has_errors());
}

TEST_F(LanguageTest, CheckReportsEveryErrorOfAFile) {
  dir().write("child.sbp", "MX, 3\n  QQ\n");
  const std::string part = dir().write("all.sbp", R"sbp(SA
QQ, 1
&depth = SQR(-1)
M23, 4
MX, 30
FAIL "stop"
MX, 2
FP, child.sbp
MY, abc
IF 1 THEN MZ, 1, 2
)sbp");
  const std::vector<Diagnostic> ds = interp().check(Script::load(part));
  std::vector<std::string> got;
  for (const Diagnostic& d : ds) got.push_back(format(d));
  const std::string child = dir().path("child.sbp");
  const std::vector<std::string> expected = {
      part + ":4:3: error: expected a space or a comma after the command M2; write `M2, 3`",
      part + ":2:1: error: unknown command 'QQ'" + kUnknownSuffix,
      part + ":3:14: error: SQR needs a number of at least 0, not -1",
      part +
          ":5:1: error: move to X=30.0000 is outside the soft limits 0.0000 to 24.0000 in "
          "(axes.x.min/max in the profile); nothing was moved",
      part + ":6:1: error: FAIL: stop",
      part + ":8 -> " + child + ":2:3: error: unknown command 'QQ'" + kUnknownSuffix,
      part + ":9:5: error: expected a number for Y location (MY), found 'abc'",
      part + ":10:18: error: MZ takes 1 parameter; this is parameter 2"};
  EXPECT_EQ(got, expected);
  // child.sbp's unknown command is found when it is loaded, so FP refuses it as it refuses a
  // file with a syntax error: its MX, 3 does not run. The refused MX, 30 left the check at
  // X=30, where the file meant the tool to be.
  expect_path(moves(), {{kMove, at(2)}}, at(30));
  EXPECT_EQ(sink.flushes, 1);
}

// A variable whose assignment failed is not reported again where it is used.
TEST_F(LanguageTest, CheckDoesNotRepeatAFailedAssignment) {
  const std::vector<Diagnostic> ds = check("&depth = SQR(-1)\n&d2 = &depth * 2\nMZ, &depth\n");
  ASSERT_GE(ds.size(), 1u);
  EXPECT_EQ(format(ds[0]), "part.sbp:1:14: error: SQR needs a number of at least 0, not -1");
  EXPECT_EQ(ds.size(), 1u) << all(ds);
}

// §3.5: an undefined variable as a numeric command parameter is "undefined variable &NAME".
TEST_F(LanguageTest, UndefinedVariableAsACommandParameterNamesIt) {
  const Diagnostic d = run_error("MZ, &depth\n");
  EXPECT_TRUE(moves().empty());
  EXPECT_EQ(format(d), "part.sbp:1:5: error: undefined variable &DEPTH; set it before this line");
}

// A jump to a missing label is one problem: check reports it once.
TEST_F(LanguageTest, CheckReportsAMissingLabelOnce) {
  const std::vector<Diagnostic> ds = check("MX, 1\nGOTO NOWHERE\n");
  ASSERT_GE(ds.size(), 1u);
  EXPECT_EQ(format(ds[0]),
            "part.sbp:2:6: error: no label NOWHERE: in this file; labels are written on their "
            "own line as NAME:");
  EXPECT_EQ(ds.size(), 1u) << all(ds);
}

// ---- trigonometry

TEST_F(LanguageTest, TrigonometryIsInRadiansByDefault) {
  run("&s = SIN(90)\n&c = COS(3.14159265358979)\n&a = ATN(1)\n");
  expect_number("S", std::sin(90.0));
  EXPECT_NEAR(var("C")->num(), -1, 1e-12);
  expect_number("A", std::atan(1.0));
}

TEST_F(LanguageTest, TrigonometryInDegreesForFabMo) {
  options.trig_in_degrees = true;
  run("&s = SIN(90)\n&c = COS(180)\n&a = ATN(1)\n&t = TAN(45)\n");
  EXPECT_NEAR(var("S")->num(), 1, 1e-12);
  EXPECT_NEAR(var("C")->num(), -1, 1e-12);
  EXPECT_NEAR(var("A")->num(), 45, 1e-12);
  EXPECT_NEAR(var("T")->num(), 1, 1e-12);
}

// ---- §7 facts not covered above

TEST_F(LanguageTest, CommandsAndStatementsIgnoreCase) {
  run("sa\nm2, 1, 1\nMs, 3\nj2 2, 2\nIf 1 Then Print \"ok\"\n");  // §7.2
  expect_path(moves(), {{kMove, at(1, 1)}, {kJog, at(2, 2)}});
  EXPECT_DOUBLE_EQ(state().speeds.move.xy, 3);
  EXPECT_EQ(printed, "ok\n");
}

TEST_F(LanguageTest, CommentsHideCommandsAndQuotesProtectApostrophes) {
  run("' MX, 5\nREM MY, 5\nrem\nMX, 1 ' MY, 5\nPRINT \"it's\" ' comment\n");  // §7.4-5
  expect_path(moves(), {{kMove, at(1)}});
  EXPECT_EQ(printed, "it's\n");
}

TEST_F(LanguageTest, CalculatorExpressions) {
  run("&a = 12+11/16\n&b = -2-7/32\n&c = -(2+7/32)\n&d = 1.5 * SQR(4.2)/(23-12.23)\n");  // §7.110
  expect_number("A", 12.6875);
  expect_number("B", -2.21875);
  expect_number("C", -2.21875);
  EXPECT_EQ(format_number(var("D")->num()), "0.2854304");
}

TEST_F(LanguageTest, ByteOrderMarkAndUnterminatedLastLine) {
  run("\xEF\xBB\xBFMX, 1\nMY, 2");
  expect_path(moves(), {{kMove, at(1)}, {kMove, at(1, 2)}});
  EXPECT_EQ(where(moves()[0].loc), "part.sbp:1:1");
}

// ---- more §7 facts and edge cases

// §7.25: variables keep their values from one run to the next in a session.
TEST_F(LanguageTest, VariablesOutliveTheRunThatSetThem) {
  run("&a = 5\n&s = Bill\n");
  run("PRINT &a; \" \"; &s\n");
  EXPECT_EQ(printed, "5 Bill\n");
}

// §7.36 / §8 A34: %(60) is the running file's name (its absolute path).
TEST_F(LanguageTest, SystemVariableSixtyIsTheRunningFile) {
  dir().write("child.sbp", "&inner = %(60)\n");
  const std::string main = dir().write("main.sbp", "&outer = %(60)\nFP, child.sbp\n");
  run_file(main);
  const Value* outer = var("OUTER");
  ASSERT_NE(outer, nullptr);
  ASSERT_TRUE(outer->is_string());
  expect_text("OUTER", main);
  expect_text("INNER", dir().path("child.sbp"));
}

// A PAUSE argument that can only be meant as an expression must be one, as for commands
// and assignments; the handbook's template `PAUSE time(sec)` is not a runnable line.
TEST_F(LanguageTest, PauseWithABrokenExpressionIsAnError) {
  use_recording_io = true;
  const Outcome o = execute("PAUSE SQR(4\nPRINT \"went on\"\n");
  EXPECT_EQ(o.ending, Ending::Error);
  EXPECT_EQ(format(o.diag), "part.sbp:1:10: error: this '(' is never closed; add ')'");
  EXPECT_TRUE(rec.calls.empty());  // no message shown, nothing printed
}

// §7.58: with several variables an empty answer counts as Cancel.
TEST_F(LanguageTest, InputEmptyAnswerForSeveralVariablesIsCancel) {
  use_recording_io = true;
  rec.answers = {""};
  const Outcome o = execute("INPUT \"Width, height\" &w, &h\nMX, 1\n");
  EXPECT_TRUE(moves().empty());
  EXPECT_EQ(o.ending, Ending::OperatorStop);
  EXPECT_EQ(format(o.diag), "part.sbp:1:1: error: stopped by the operator at INPUT");
}

// §7.81: in the `WRITE #n,` form a comma inside quotes still splits the items.
TEST_F(LanguageTest, WriteCommaFormSplitsInsideQuotes) {
  const std::string part =
      dir().write("w.sbp", "OPEN \"o.txt\" FOR OUTPUT AS #1\nWRITE #1, \"a,b\", 1\nCLOSE #1\n");
  const auto script = Script::load(part);
  ASSERT_FALSE(has_error(script->errors())) << all(script->errors());
  run_file(part);
  EXPECT_EQ(dir().read("o.txt"), "a, b, 1\n");
}

TEST_F(LanguageTest, CloseWithoutANumberClosesEveryFile) {
  run_file(dir().write("c.sbp",
                       "OPEN \"a.txt\" FOR OUTPUT AS #1\nOPEN \"b.txt\" FOR OUTPUT AS #2\nCLOSE\n"
                       "OPEN \"a.txt\" FOR APPEND AS #1\nOPEN \"b.txt\" FOR APPEND AS #2\n"
                       "WRITE #1, 1\nWRITE #2, 2\nCLOSE\n"));
  EXPECT_EQ(dir().read("a.txt"), "1\n");
  EXPECT_EQ(dir().read("b.txt"), "2\n");
  EXPECT_TRUE(scripted().warnings().empty());
}

// §7.74: relative names are found in the part file's folder; sub-folders and absolute paths
// work.
TEST_F(LanguageTest, OpenPathsRelativeToThePartFileOrAbsolute) {
  fs::create_directories(dir().path("sub"));
  const std::string absolute = dir().path("abs.txt");
  run_file(dir().write("p.sbp",
                       "OPEN \"sub/rel.txt\" FOR OUTPUT AS #1\nWRITE #1, \"r\"\n"
                       "OPEN \"" +
                           absolute +
                           "\" FOR OUTPUT AS #2\nWRITE #2, \"a\"\n"
                           "CLOSE\n"));
  EXPECT_EQ(dir().read("sub/rel.txt"), "r\n");
  EXPECT_EQ(dir().read("abs.txt"), "a\n");
}

TEST_F(LanguageTest, PersistentPathShapeErrors) {
  EXPECT_EQ(format(run_error("$x.y = 1\n$x[0] = 2\n")),
            "part.sbp:2:1: error: cannot set index [0]: that part of the variable has named "
            "fields; use .NAME");
  EXPECT_EQ(*store.variable("X"), nlohmann::json::parse(R"({"Y": 1})"));  // unchanged
  EXPECT_EQ(format(run_error("&a = $x.z\n")), "part.sbp:1:6: error: $X.Z is not set");
}

}  // namespace
}  // namespace gantry
