// Friendly Motion's Alt-F keys at the session level (session/fm_hot_keys): the key names, the
// teach log a console writes, and a hot key pressed at a running program's STEP question,
// through the controller and the operator mailbox both front ends use.
#include "gantry/session/fm_hot_keys.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <thread>

#include "../support/temp_dir.hpp"
#include "gantry/commands/command_table.hpp"
#include "gantry/lang/script.hpp"
#include "gantry/session/console_words.hpp"
#include "gantry/session/operator_io.hpp"
#include "sim/sim_card.hpp"

namespace gantry {
namespace {

TEST(FmHotKeys, AltF1ToAltF10AreTheHotKeys) {
  EXPECT_EQ(session::fm_hot_key("Alt+F1"), 1);
  EXPECT_EQ(session::fm_hot_key("Alt+F7"), 7);
  EXPECT_EQ(session::fm_hot_key("Alt+F10"), 10);
  for (const char* other : {"F1", "Alt+F11", "Alt+F12", "Alt+F0", "Alt+F01", "Ctrl+Alt+F1",
                            "Alt+Shift+F1", "Alt+a", "Alt+F"})
    EXPECT_FALSE(session::fm_hot_key(other)) << other;
}

TEST(FmHotKeys, TeachIsAConsoleWord) {
  using Word = session::TypedLine::Word;
  const session::TypedLine t = session::read_typed_line("teach part.fm");
  EXPECT_EQ(t.word, Word::Teach);
  EXPECT_EQ(t.rest, "part.fm");
  EXPECT_EQ(session::read_typed_line("TEACH OFF").word, Word::Teach);
  EXPECT_EQ(session::read_typed_line("TE, 1").word, Word::None);
}

// The manual's Appendix 1: jog, Alt-F1 logs the position, Alt-F7-F10 the laser and shutter.
TEST(FmTeachLog, WritesAProgramThatRunsAsTaught) {
  const TempDir dir("fm_keys");
  const std::string path = dir.path("teach.fm");
  session::FmKeys keys;
  FriendlyMotionSettings fm;  // the laser is output 1
  Settings settings = default_settings();
  SimCard card{settings};
  session::OperatorMailbox io{true, {}};
  PersistentStore store;
  Controller c{settings, card, io, store};

  // At rest with no teach log, a hot key says what it is for.
  session::FmKeys::Result r = keys.key(1, false, c, io, Vec6::Zero(), fm);
  EXPECT_TRUE(r.error);
  EXPECT_EQ(r.message,
            "Alt-F1: no Friendly Motion program runs (N10001) and no teach log is open (TEACH "
            "file)");

  r = keys.teach(path, Units::Inches);
  ASSERT_FALSE(r.error) << r.message;
  EXPECT_TRUE(keys.teaching());
  Vec6 at = Vec6::Zero();
  at << 1.25, -0.5, 0, 0, 0, 0;
  r = keys.key(1, false, c, io, at, fm);
  EXPECT_FALSE(r.error);
  EXPECT_EQ(r.message, "taught X1.2500Y-0.5000");
  EXPECT_TRUE(r.typed.empty());  // a position switches nothing
  r = keys.key(7, false, c, io, at, fm);
  EXPECT_EQ(r.typed, "SO, 1, 1");  // the laser's gate, switched as a typed SO
  r = keys.key(9, false, c, io, at, fm);
  EXPECT_EQ(r.typed, "SO, 2, 1");  // the shutter
  at << 3, -0.00001, 0, 0, 0, 0;   // -0.0000 is written 0.0000
  keys.key(1, false, c, io, at, fm);
  keys.key(10, false, c, io, at, fm);
  keys.key(8, false, c, io, at, fm);
  r = keys.key(4, false, c, io, at, fm);  // not a teach key: nothing written
  EXPECT_TRUE(r.error);
  EXPECT_NE(r.message.find("does nothing in teach mode"), std::string::npos);
  r = keys.teach("", Units::Inches);
  EXPECT_NE(r.message.find("6 lines so far"), std::string::npos) << r.message;
  r = keys.teach("off", Units::Inches);
  EXPECT_NE(r.message.find("6 lines taught"), std::string::npos) << r.message;
  EXPECT_FALSE(keys.teaching());
  EXPECT_EQ(dir.read("teach.fm"),
            "! taught at the Gantry console: Alt-F1 positions, Alt-F7-F10 outputs\r\n"
            "G70 G90\r\n"
            "X1.2500Y-0.5000\r\n"
            "M100\r\n"
            "M102\r\n"
            "X3.0000Y0.0000\r\n"
            "M103\r\n"
            "M101\r\n"
            "M0\r\n");
  // The log reads back as Friendly Motion (its first line is a ! comment) with no error.
  const auto s = Script::load(path, CommandTable::standard().is_command(), std::nullopt);
  EXPECT_TRUE(s->fm());
  EXPECT_TRUE(s->ok());
  // Millimetres: G71, three decimals; a laser the profile does not name cannot be taught.
  r = keys.teach(path, Units::Millimetres);
  ASSERT_FALSE(r.error);
  at << 10, 20, 0, 0, 0, 0;
  keys.key(1, false, c, io, at, fm);
  fm.laser_output = 0;
  r = keys.key(7, false, c, io, at, fm);
  EXPECT_TRUE(r.error);
  EXPECT_NE(r.message.find("names no laser output"), std::string::npos);
  keys.teach("OFF", Units::Millimetres);
  EXPECT_NE(dir.read("teach.fm").find("G71 G90\r\nX10.000Y20.000\r\nM0\r\n"), std::string::npos);
  // A log that cannot be written is an error, located by its path.
  r = keys.teach("/nonexistent/folder/teach.fm", Units::Inches);
  EXPECT_TRUE(r.error);
  EXPECT_NE(r.message.find("cannot write /nonexistent/folder/teach.fm"), std::string::npos);
}

// Waits (without timing anything) until the running file asks a question; fails the test if
// the file ends first.
std::optional<session::Question> question_of(Controller& c, session::OperatorMailbox& io) {
  for (int i = 0; i < 20000; ++i) {
    if (std::optional<session::Question> q = io.question()) return q;
    if (c.wait_for(std::chrono::milliseconds(1))) break;
  }
  return io.question();
}

// "The Alternate Function Keys (Alt-F1 to Alt-F-10) directly call and execute the subroutines
// N10001 to N10010 ... When subroutine execution is completed, the system returns to the STEP
// mode." Through the controller and the mailbox, as both consoles send their keys.
TEST(FmHotKeys, AKeyAtTheStepQuestionRunsItsSubroutineThenSteps) {
  Settings settings = default_settings();
  SimCard card{settings};
  session::OperatorMailbox io{false, {}};
  PersistentStore store;
  Controller c{settings, card, io, store};
  // No program runs: refused, and nothing is kept for the next run.
  session::HotKeyPress p = session::press_fm_hot_key(c, io, 1);
  EXPECT_FALSE(p.outcome);
  EXPECT_NE(p.outcome.reason.find("no program runs"), std::string::npos);

  const char* program = "G70 G91 F1\nM0\nX1\nM0\nN10001 Y1\nM6\n";
  ASSERT_TRUE(c.run(Script::from_text(program, "hot.fm")));
  std::optional<session::Question> q = question_of(c, io);
  ASSERT_TRUE(q);
  EXPECT_EQ(q->title, "Friendly Motion");
  EXPECT_NE(q->text.find("M0"), std::string::npos);
  // Alt-F1 at the M0's question: it answers Step, and N10001 runs before line 3.
  p = session::press_fm_hot_key(c, io, 1);
  ASSERT_TRUE(p.outcome) << p.outcome.reason;
  EXPECT_TRUE(p.answered);
  q = question_of(c, io);
  ASSERT_TRUE(q);
  EXPECT_NE(q->text.find("STEP: line 3"), std::string::npos) << q->text;
  // The subroutine has run (Y), line 3 (X) not yet: the machine waits in STEP.
  EXPECT_DOUBLE_EQ(c.modal().position[1], 1.0);
  EXPECT_DOUBLE_EQ(c.modal().position[0], 0.0);
  // Alt-F2: this program has no N10002; the key answers Step and the run is told so.
  p = session::press_fm_hot_key(c, io, 2);
  ASSERT_TRUE(p.outcome);
  q = question_of(c, io);
  ASSERT_TRUE(q);
  EXPECT_NE(q->text.find("STEP: line 3"), std::string::npos) << q->text;
  io.answer("Auto");
  c.wait();
  EXPECT_EQ(c.status().state, MachineState::Idle);
  EXPECT_DOUBLE_EQ(c.modal().position[0], 1.0);
  EXPECT_DOUBLE_EQ(c.modal().position[1], 1.0);
  const std::string said = io.take_output();
  EXPECT_NE(said.find("Alt-F1: N10001"), std::string::npos) << said;
  EXPECT_NE(said.find("N10002, which this program does not have"), std::string::npos) << said;
}

}  // namespace
}  // namespace gantry
