// O-words (docs/gcode.md, "O-words"): subroutines, if, loops, Fanuc M98/M99, subroutine
// files and WinCNC's M98 file. The golden moves are LinuxCNC 2.9's rs274 output for the same
// programs (its STRAIGHT_TRAVERSE end points, noted beside each); the refusals are located.
#include <gtest/gtest.h>

#include <unistd.h>  // getpid

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "../support/interpreter_fixture.hpp"
#include "gantry/interp/operator_io.hpp"
namespace gantry {
namespace {

namespace fs = std::filesystem;

using QuietIO = AnsweringIO;

class OwordTest : public InterpreterFixture<QuietIO> {
 protected:
  OwordTest() { settings.machine.limit_checking = false; }

  std::vector<Vec6> ends(const std::vector<CanonMove>& moves) {
    std::vector<Vec6> out;
    for (const CanonMove& m : moves)
      if (m.kind == MoveKind::Line || m.kind == MoveKind::Arc) out.push_back(m.to);
    return out;
  }
  std::vector<Vec6> run(std::shared_ptr<const Script> script, InterpreterOptions o = {}) {
    return ends(run_script(std::move(script), o));
  }
  std::vector<Vec6> run(const std::string& text) { return run(Script::from_text(text, "t.ngc")); }
  // What a check finds (the load pass's errors included).
  std::vector<Diagnostic> check(std::shared_ptr<const Script> script, InterpreterOptions o = {}) {
    if (o.statement_budget == 0) o.statement_budget = 100000;  // as the CLI bounds a check
    return errors_of(check_script(std::move(script), o));
  }
  std::vector<Diagnostic> check(const std::string& text) {
    return check(Script::from_text(text, "t.ngc"));
  }
  // A refused program: what the check finds; a run of it moves nothing (a script with a load
  // error does not start; one refused when it runs is stopped by the check every run makes
  // first, which found the error).
  std::vector<Diagnostic> refused(const std::string& text) {
    const std::vector<Diagnostic> errors = check(text);
    EXPECT_FALSE(errors.empty()) << "no error for:\n" << text;
    const auto script = Script::from_text(text, "t.ngc");
    if (!script->ok()) {
      sink = RecordingSink();
      Interpreter interp(settings, sink, io, store);
      EXPECT_THROW(interp.run(script), GantryError) << text;
      EXPECT_TRUE(ends(sink.moves).empty()) << text;
    }
    return errors;
  }
};
void expect_moves(const std::vector<Vec6>& got, const std::vector<Vec6>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < want.size(); ++i)
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(got[i][a], want[i][a], 1e-9) << "move " << i;
}

// One of `errors` says `words`, at line:column.
void expect_at(const std::vector<Diagnostic>& errors, int line, int column,
               const std::string& words) {
  std::string all;
  for (const Diagnostic& d : errors) {
    all += d.message + "\n";
    if (d.message.find(words) == std::string::npos) continue;
    EXPECT_EQ(d.loc.line, line) << d.message;
    EXPECT_EQ(d.loc.column, column) << d.message;
    return;
  }
  ADD_FAILURE() << "no error saying \"" << words << "\" among:\n" << all;
}

// rs274: (2,0,0) (5,13,7) (8,1,7) (1,0,7) (9,0,7). The call's #1-#30 are its own (the ones
// not given read 0), named parameters are local, #31 and #<_value> are shared.
TEST_F(OwordTest, SubroutineArgumentsLocalsAndReturnValue) {
  const std::string text =
      "#1=5\n#31=1\n#<loc> = 8\n"
      "o<s> sub\n  G0 X#1 Y#2\n  #1=9\n  #31=7\n  #<loc> = 2\n  o<s> return [#1 + #3]\n"
      "o<s> endsub\n"
      "#2=3\no<s> call [2] [0] [4]\nG0 X#1 Y#<_value> Z#31\nG0 X#<loc> Y#<_value_returned>\n"
      "o<s> call [1]\nG0 X#<_value>\nM2\n";
  expect_moves(run(text), {v6(2, 0), v6(5, 13, 7), v6(8, 1, 7), v6(1, 0, 7), v6(9, 0, 7)});
  EXPECT_TRUE(check(text).empty());
}

// rs274: (12,0,0) then Y20 down to Y12, and "Too many subroutine levels" at the 10th call.
TEST_F(OwordTest, RecursionAndTheNestingLimit) {
  const std::string fact =
      "o<fact> sub\n  o1 if [#1 LE 1]\n    o<fact> return [1]\n  o1 endif\n"
      "  o<fact> call [#1 - 1]\no<fact> endsub [#1 * #<_value>]\n"
      "o<fact> call [5]\nG0 X[#<_value> / 10]\n";
  expect_moves(run(fact + "M2\n"), {v6(12, 0)});
  const std::string deep = fact +
                           "o<r> sub\n  G0 Y#1\n  o<r> call [#1-1]\no<r> endsub\n"
                           "o<r> call [20]\nM2\n";
  expect_at(refused(deep), 11, 3, "nested 9 deep");
  std::vector<Vec6> want{v6(12, 0)};
  for (int y = 20; y >= 12; --y) want.push_back(v6(12, y));
  sink = RecordingSink();
  Interpreter interp(settings, sink, io, store);
  EXPECT_THROW(interp.run(Script::from_text(deep, "t.ngc")), GantryError);
  expect_moves(ends(sink.moves), want);  // a run without its check stops where rs274 does
}

// rs274: (1,0) (3,0) (4,0) (5,1) (5,1,6) then (1,2) (2,2) (3,2); repeat [-1] runs nothing.
TEST_F(OwordTest, DoWhileIfElseifElseBreakContinueRepeat) {
  const std::string text =
      "#1=0\no10 do\n  #1=[#1+1]\n  o12 if [#1 EQ 5]\n    #2=1\n  o12 elseif [#1 EQ 6]\n"
      "    o10 break\n  o12 else\n    #2=0\n  o12 endif\n  o11 if [#1 EQ 2]\n"
      "    o10 continue\n  o11 endif\n  G0 X#1 Y#2\no10 while [#1 LT 10]\nG0 Z#1\n"
      "#3=0\no20 repeat [2.6]\n  #3=[#3+1]\n  #4=0\n  o21 while [#4 LT 2]\n    #4=[#4+1]\n"
      "    o22 if [#4 EQ 1]\n      o21 continue\n    o22 endif\n    G0 X#3 Y#4 Z0\n"
      "  o21 endwhile\no20 endrepeat\no30 repeat [-1]\n  G0 X99\no30 endrepeat\nM2\n";
  expect_moves(run(text),
               {v6(1, 0), v6(3, 0), v6(4, 0), v6(5, 1), v6(5, 1, 6), v6(1, 2), v6(2, 2), v6(3, 2)});
  EXPECT_TRUE(check(text).empty());
}

// The same o-number in a subroutine and in the main program: separate scopes (rs274: X2, X1).
TEST_F(OwordTest, ControlNumbersAreScopedPerSubroutine) {
  expect_moves(run("o<s> sub\no1 if [1]\nG0 X1\no1 endif\no<s> endsub\no1 if [1]\nG0 X2\n"
                   "o1 endif\no<s> call\nM2\n"),
               {v6(2, 0), v6(1, 0)});
  // Names in any case, spaces in the name (rs274: X4).
  expect_moves(run("O<S> SUB\nG0 X#1\nO<S> ENDSUB\nO< s > CALL [4]\nM2\n"), {v6(4, 0)});
}

// `#1=4` then `X[LN[#1]]`, and a while loop computing positions: the check computes the
// program's real values, and runs (rs274: 1.3863; 1; 1.4142,0.6931; 1.7321,1.0986).
TEST_F(OwordTest, CheckComputesTheValuesTheLoopsCompute) {
  const std::string text =
      "#1=4\nG0 X[LN[#1]]\n#2=1\no1 while [#2 LT 4]\n  G0 X[SQRT[#2]] Y[LN[#2]]\n"
      "  #2=[#2+1]\no1 endwhile\nM2\n";
  EXPECT_TRUE(check(text).empty());
  expect_moves(run(text), {v6(std::log(4.0), 0), v6(1, 0), v6(std::sqrt(2.0), std::log(2.0)),
                           v6(std::sqrt(3.0), std::log(3.0))});
  // A loop that never ends is bounded by the check's statement budget.
  InterpreterOptions o;
  o.statement_budget = 1000;
  const auto errors = check(Script::from_text("o1 while [1]\nG0 X1\no1 endwhile\n", "t.ngc"), o);
  ASSERT_FALSE(errors.empty());
  EXPECT_NE(errors.front().message.find("loops here without end"), std::string::npos);
}

// The operator's stop (Ctrl-C) ends an endless O-word loop, as it ends a GOTO loop.
TEST_F(OwordTest, StopEndsAnEndlessLoop) {
  class StopAfter : public MotionSink {
   public:
    explicit StopAfter(std::atomic<bool>& stop) : stop_(stop) {}
    void move(const CanonMove&) override {
      if (++moves == 5) stop_ = true;
    }
    void flush() override {}
    int moves = 0;

   private:
    std::atomic<bool>& stop_;
  };
  std::atomic<bool> stop{false};
  StopAfter sink(stop);
  InterpreterOptions o;
  o.stop_check = &stop;
  Interpreter interp(settings, sink, io, store, o);
  EXPECT_THROW(interp.run(Script::from_text(
                   "#1=0\no1 while [1]\n#1=[#1+1]\nG0 X[#1 MOD 2]\no1 endwhile\n", "t.ngc")),
               OperatorStop);
  EXPECT_EQ(sink.moves, 5);
}

// rs274: o100 and o<100> name one subroutine (each calls the other's, X1; both defined:
// "redefining sub: o|100| already defined"), o0100 is o100, but o<0100> is not o<100> (a
// name, not a number: "EOF ... seeking o-word: o<100>"); names ignore case.
TEST_F(OwordTest, NumberedAndNamedOwordsShareOneNamespaceAsInLinuxCnc) {
  expect_moves(run("o100 sub\nG0 X1\no100 endsub\no<100> call\nM2\n"), {v6(1, 0)});
  expect_moves(run("o<100> sub\nG0 X1\no<100> endsub\no100 call\nM2\n"), {v6(1, 0)});
  expect_moves(run("o0100 sub\nG0 X1\no0100 endsub\no100 call\nM2\n"), {v6(1, 0)});
  expect_moves(run("o100 sub\nG0 X1\no100 endsub\no0100 call\nM2\n"), {v6(1, 0)});
  expect_moves(run("o<abc> sub\nG0 X1\no<abc> endsub\no<ABC> call\nM2\n"), {v6(1, 0)});
  expect_at(refused("o100 sub\nG0 X1\no100 endsub\no<100> sub\nG0 X2\no<100> endsub\n"
                    "o100 call\nM2\n"),
            4, 1, "is defined twice: first at line 1");
  expect_at(refused("o<0100> sub\nG0 X1\no<0100> endsub\no<100> call\nM2\n"), 4, 1, "no 100.ngc");
}

// rs274: (1,0) (2,0) (3,0) (3,3) (3,3,1): M98 P100 L3, L0 runs nothing, #1 is shared.
TEST_F(OwordTest, FanucM98M99AndProgramNumbers) {
  const std::string text =
      "O0001 (main)\n#1=0\nM98 P100 L3\nG0 Y#1\nM98 P100 L0\nM98 P200\nM30\n"
      "O100\n#1=[#1+1]\nG0 X#1\nM99\nO200\nG0 Z1\nM99\n";
  expect_moves(run(text), {v6(1, 0), v6(2, 0), v6(3, 0), v6(3, 3), v6(3, 3, 1)});
  EXPECT_TRUE(check(text).empty());
  // M99 in the main program ends it, as rs274 does (X1 only).
  expect_moves(run("G0 X1\nM99\nG0 X2\n"), {v6(1, 0)});
  // An O1234 header alone or with its title, and mid-file (rs274 passes over it).
  expect_moves(run("%\nO1234 (title)\nG0 X1\nO1235\nG0 X2\nM2\n%\n"), {v6(1, 0), v6(2, 0)});
  expect_at(refused("M98 P200\nM30\nO100\nG0 X1\nM99\n"), 1, 5, "no subprogram O200");
}

class OwordFileTest : public OwordTest {
 protected:
  OwordFileTest() {
    dir = fs::temp_directory_path() / ("gantry_oword_" + std::to_string(::getpid()));
    fs::create_directories(dir / "lib");
  }
  ~OwordFileTest() override { fs::remove_all(dir); }
  std::string write(const std::string& name, const std::string& text) {
    const fs::path p = dir / name;
    std::ofstream(p) << text;
    return p.string();
  }
  fs::path dir;
};

// rs274 with boxy.ngc beside the program: (2,3) then (6,3).
TEST_F(OwordFileTest, SubroutineFilesByName) {
  write("boxy.ngc", "o<boxy> sub\nG0 X#1 Y#2\no<boxy> endsub [#1 * #2]\nM2\n");
  const std::string main = write("main.ngc", "o<boxy> call [2] [3]\nG0 X#<_value>\nM2\n");
  expect_moves(run(Script::load(main)), {v6(2, 3), v6(6, 3)});
  EXPECT_TRUE(check(Script::load(main)).empty());
  // From a subroutine folder (--subroutines), and refused without it.
  write("lib/lift.ngc", "o<lift> sub\nG0 Z#1\no<lift> endsub\n");
  const std::string lifts = write("lifts.ngc", "G0 X1\no<lift> call [2]\nG0 X3\nM2\n");
  InterpreterOptions o;
  o.subroutine_dirs = {(dir / "lib").string()};
  expect_moves(run(Script::load(lifts), o), {v6(1, 0), v6(1, 0, 2), v6(3, 0, 2)});
  expect_at(check(Script::load(lifts)), 2, 1, "no lift.ngc");
  // A file without the subroutine its name promises.
  write("empty.ngc", "G0 X1\n");
  expect_at(check(Script::load(write("calls.ngc", "o<empty> call\nM2\n"))), 1, 1,
            "does not define o<empty> sub");
}

// The profile's `subroutines` folders (relative to the profile's folder) serve o<name> call
// after --subroutines' folders; a folder that is not there is an error at the key.
TEST_F(OwordFileTest, ProfileSubroutineFolders) {
  fs::create_directories(dir / "prof" / "subs");
  fs::create_directories(dir / "first");
  write("prof/subs/lift.ngc", "o<lift> sub\nG0 Z#1\no<lift> endsub\n");
  const std::string origin = (dir / "prof" / "machine.toml").string();
  SettingsLoad l = parse_settings("subroutines = [\"subs\"]\n" + default_profile_text(), origin);
  ASSERT_TRUE(l.ok()) << l.errors[0].message;
  ASSERT_EQ(l.settings.subroutine_paths.size(), 1u);
  settings.subroutine_paths = l.settings.subroutine_paths;
  const std::string lifts = write("lifts.ngc", "G0 X1\no<lift> call [2]\nG0 X3\nM2\n");
  expect_moves(run(Script::load(lifts)), {v6(1, 0), v6(1, 0, 2), v6(3, 0, 2)});
  EXPECT_TRUE(check(Script::load(lifts)).empty());
  // --subroutines' folder comes first: its lift.ngc wins.
  write("first/lift.ngc", "o<lift> sub\nG0 Y#1\no<lift> endsub\n");
  InterpreterOptions o;
  o.subroutine_dirs = {(dir / "first").string()};
  expect_moves(run(Script::load(lifts), o), {v6(1, 0), v6(1, 2), v6(3, 2)});
  // Without the key, the call is refused at the call.
  settings.subroutine_paths.clear();
  expect_at(check(Script::load(lifts)), 2, 1, "no lift.ngc");
  // A folder that is not there: located at the key, in the profile's file.
  l = parse_settings("\nsubroutines = [\"subs\", \"nosuch\"]\n" + default_profile_text(), origin);
  ASSERT_EQ(l.errors.size(), 1u);
  EXPECT_EQ(*l.errors[0].loc.file, origin);
  EXPECT_EQ(l.errors[0].loc.line, 2);
  EXPECT_NE(l.errors[0].message.find("subroutines names the folder \"nosuch\""), std::string::npos)
      << l.errors[0].message;
  EXPECT_NE(l.errors[0].message.find("does not exist"), std::string::npos);
}

// WinCNC's M98 <file> (the manual: "m98 Texas.tap"): the file runs, M99 ends it.
TEST_F(OwordFileTest, WincncM98File) {
  write("Texas.tap", "G0 X5\nM99\nG0 X7\n");
  const std::string main = write("main.tap", "G0 X1\nm98 Texas.tap\nG0 Y2\n");
  settings.gcode_dialect = GcodeDialect::WinCNC;
  expect_moves(run(Script::load(main)), {v6(1, 0), v6(5, 0), v6(5, 2)});
  settings.gcode_dialect = GcodeDialect::Standard;
  expect_at(check(Script::load(main)), 2, 5, "gcode_dialect = \"wincnc\"");
}

// WinCNC, L92: "The current G92 Local Coordinate system is saved every time a program is
// started or a subprogram is called using M98. When the program is finished, the original G92
// system is restored"; "L92 causes the normal G92 coordinate restore to be skipped after the
// program containing the L92 is finished". The caller's G92 X0 at machine X1 makes X2 machine
// 3; the sub's G92.1 X10 (local X0 at machine 10) makes it 12 when kept.
TEST_F(OwordFileTest, WincncM98FileRestoresTheCallersG92UnlessL92) {
  settings.gcode_dialect = GcodeDialect::WinCNC;
  const std::string sub = "G92.1 X10\nG0 X0\n";
  write("m99.tap", sub + "M99\nG0 X7\n");
  write("eof.tap", sub);
  write("keep.tap", "L92\n" + sub + "M99\n");
  for (const char* call : {"M98 m99.tap", "M98 eof.tap", "M98.1 m99.tap", "M98.1 eof.tap"}) {
    const std::string main =
        write("main.tap", std::string("G0 X1\nG92 X0\n") + call + "\nG0 X2\nG0 X0\n");
    expect_moves(run(Script::load(main)), {v6(1, 0), v6(10, 0), v6(3, 0), v6(1, 0)});
    EXPECT_TRUE(check(Script::load(main)).empty()) << call;
  }
  const std::string main = write("main.tap", "G0 X1\nG92 X0\nM98 keep.tap\nG0 X2\n");
  expect_moves(run(Script::load(main)), {v6(1, 0), v6(10, 0), v6(12, 0)});
  // Two calls deep: each file gets back the offsets it made the call with.
  write("outer.tap", "G92.1 X20\nM98 m99.tap\nG0 X1\nM99\n");
  const std::string nested = write("main.tap", "G0 X1\nG92 X0\nM98 outer.tap\nG0 X2\n");
  expect_moves(run(Script::load(nested)), {v6(1, 0), v6(10, 0), v6(21, 0), v6(3, 0)});
}

// LinuxCNC's refusals, found by the load pass where they can be seen without running, each
// located, and nothing moves.
TEST_F(OwordTest, RefusalsAreLocated) {
  expect_at(refused("G0 X1\no100 endif\nM2\n"), 2, 1, "o100 endif ends no o100 if");
  expect_at(refused("o100 while [1]\nG0 X1\no101 endwhile\nM2\n"), 3, 1,
            "does not match the innermost open block, o100 while at line 1");
  expect_at(refused("o100 if [1]\nG0 X1\nM2\n"), 1, 1, "o100 if is never closed");
  expect_at(refused("o<nosuch> call\nM2\n"), 1, 1, "no o<nosuch> sub");
  expect_at(refused("o100 sub\no100 endsub\no100 sub\no100 endsub\nM2\n"), 3, 1,
            "o100 is defined twice: first at line 1");
  expect_at(refused("G0 X1\n  o100 return\nM2\n"), 2, 3, "outside any subroutine");
  expect_at(refused("o100 endsub\nM2\n"), 1, 1, "outside any subroutine");
  expect_at(refused("o<a> sub\no<b> sub\no<b> endsub\no<a> endsub\nM2\n"), 2, 1,
            "cannot be nested");
  expect_at(refused("o1 if [1]\nG0 X1\no1 endif\no1 if [1]\nG0 X2\no1 endif\nM2\n"), 4, 1,
            "used for another block already, at line 1");
  expect_at(refused("o10 repeat [3]\n o10 break\no10 endrepeat\nM2\n"), 2, 2,
            "while and do loops only");
  expect_at(refused("o10 while [1]\no11 continue\no10 endwhile\nM2\n"), 2, 1,
            "no o11 while or do loop");
  expect_at(refused("o1 if [1]\no1 else\no1 elseif [1]\no1 endif\nM2\n"), 3, 1,
            "else is the last branch");
  expect_at(refused("o100 if [1] G0 X1\no100 endif\nM2\n"), 1, 13, "values are written in");
  expect_at(refused("o100 if\no100 endif\nM2\n"), 1, 8, "needs its value in brackets");
  expect_at(refused("o100 iff [1]\nM2\n"), 1, 6, "not an O-word keyword");
  expect_at(refused("o[#1] call\nM2\n"), 1, 2, "computed O numbers");
  expect_at(refused("G0 X1\no1 if [LN[0]]\no1 endif\nM2\n"), 2, 8, "LN[0] is not defined");
  // A condition that depends on values: refused by the check, with the value it computes.
  expect_at(refused("#1=0\no<s> sub\n  o1 if [1 / #1]\n  o1 endif\no<s> endsub\no<s> call\nM2\n"),
            3, 12, "division by zero");
}

}  // namespace
}  // namespace gantry
