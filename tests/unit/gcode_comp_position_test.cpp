// #5420-#5425 (the current position) with cutter radius compensation on (docs/gcode.md,
// "Cutter radius compensation"). The golden values are LinuxCNC 2.9's rs274 output for the
// same programs: its MESSAGE lines for (DEBUG, ...), its refusal of an expression reading them
// ("Cannot read current position with cutter radius compensation on").
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "../support/interpreter_fixture.hpp"
namespace gantry {
namespace {

class GcodeCompPosition : public InterpreterFixture<> {
 protected:
  GcodeCompPosition() { settings.machine.limit_checking = false; }

  std::string printed(const std::string& text) {
    io.printed.clear();
    run_script(Script::from_text(text, "t.ngc"));
    return io.printed;
  }
  std::vector<Diagnostic> errors(const std::string& text) {
    RecordingSink s;  // the run's moves stay in `sink`
    return errors_of(check_script(Script::from_text(text, "t.ngc"), {}, &s));
  }
};

// rs274: MESSAGE(" a 1.000000 0.250000"), (" b 0.750000 1.000000"), (" c 0.000000 0.750000"):
// each move's compensated end point, before its corner is joined to the next move (which
// is held back); after G40 the programmed end point (" d 0.000000 1.000000"), then (" e
// 3.000000 1.000000") after the move that leaves the path.
TEST_F(GcodeCompPosition, MessagesShowTheCompensatedEndOfTheHeldBackMove) {
  EXPECT_EQ(printed("G20 G17 G90 F10\nG0 X0 Y0 Z0\nG41.1 D0.5\nG1 X1\n(DEBUG, a #5420 #5421)\n"
                    "G1 Y1\n(DEBUG, b #5420 #5421)\nG1 X0\n(DEBUG, c #5420 #5421)\nG40\n"
                    "(DEBUG, d #5420 #5421)\nG0 X3\n(DEBUG, e #5420 #5421)\nM2\n"),
            "a 1.000000 0.250000\nb 0.750000 1.000000\nc 0.000000 0.750000\n"
            "d 0.000000 1.000000\ne 3.000000 1.000000\n");
  // G42.1: MESSAGE(" a 1.000000 -0.250000 0.000000").
  EXPECT_EQ(printed("G20 G17 G90 F10\nG0 X0 Y0 Z0\nG42.1 D0.5\nG1 X1 Y0\n"
                    "(DEBUG, a #5420 #5421 #5422)\nG40\nM2\n"),
            "a 1.000000 -0.250000 0.000000\n");
  // In G18: MESSAGE(" a 1.000000 0.000000 -0.250000").
  EXPECT_EQ(printed("G20 G18 G90 F10\nG0 X0 Y0 Z0\nG41.1 D0.5\nG1 X1\n"
                    "(DEBUG, a #5420 #5421 #5422)\nG40\nM2\n"),
            "a 1.000000 0.000000 -0.250000\n");
}

// rs274 refuses an expression reading #5420-#5425 while compensation is on, even before the
// first compensated move, for Z too; Gantry refuses it located at the parameter.
TEST_F(GcodeCompPosition, ExpressionsCannotReadThePositionWhileCompensationIsOn) {
  for (const std::string& text :
       {std::string("G20 F10\nG0 X0 Y0\nG41.1 D0.5\nG1 X1\n#1=#5420\nG40\nM2\n"),
        std::string("G20 F10\nG0 X0 Y0\nG41.1 D0.5\n#1=#5420\nG1 X1\nG40\nM2\n"),
        std::string("G20 F10\nG0 X0 Y0\nG41.1 D0.5\nG1 X1\n#1=#5422\nG40\nM2\n")}) {
    const std::vector<Diagnostic> e = errors(text);
    ASSERT_FALSE(e.empty()) << text;
    EXPECT_EQ(e[0].loc.line, text.find("G1 X1\n#1") != std::string::npos ? 5 : 4) << text;
    EXPECT_NE(e[0].message.find("cannot be read while cutter radius compensation is on"),
              std::string::npos)
        << e[0].message;
  }
  const std::vector<Diagnostic> e =
      errors("G20 F10\nG0 X0 Y0\nG41.1 D0.5\nG1 X1\nG1 Y[#5421+1]\nG40\nM2\n");
  ASSERT_FALSE(e.empty());
  EXPECT_EQ(e[0].loc.line, 5);
  // Before G41 and after G40 they read as always.
  EXPECT_TRUE(errors("G20 F10\nG0 X2 Y0\n#1=#5420\nG41.1 D0.5\nG1 X[#1+1]\nG40\nG1 X0\n"
                     "#2=#5420\nM2\n")
                  .empty());
}

}  // namespace
}  // namespace gantry
