// Cutter radius compensation (G40-G42.1) and the canned cycles G73-G89 in the XY, ZX and
// YZ planes (docs/gcode.md): golden canonical moves from LinuxCNC 2.9's rs274 (run with a
// tool table of T1 D0.25 and T2 D0.125; its 4-decimal output, zero-length moves left out),
// and the refusals with their location, the refused block moving nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "../support/interpreter_fixture.hpp"
namespace gantry {
namespace {

using AskingIO = AnsweringIO;

// One canonical call as rs274 prints it: J traverse, L feed, A arc (x y z the end; cu cv the
// centre on the plane's axes; turn +1 counter-clockwise, -1 clockwise), D dwell (x: seconds),
// O spindle (x: 1 on, 0 off). Where the spindle never runs, rs274's STOP_SPINDLE_TURNING at M2
// is left out: Gantry switches off only an output that is on.
struct Row {
  char kind;
  double x, y, z, cu, cv;
  int turn;
};

// rs274's tool table, as Gantry's G10 L1 gives it.
constexpr const char* kTools = "G10 L1 P1 R0.125\nG10 L1 P2 R0.0625\n";

class GcodeCompCycles : public InterpreterFixture<AskingIO> {
 protected:
  GcodeCompCycles() { settings.machine.limit_checking = false; }

  std::vector<CanonMove> run(const std::string& text) {
    return run_script(Script::from_text(kTools + text, "t.ngc"));
  }
  // The moves of `text` against rs274's, within 1e-4 (its output has 4 decimals).
  void expect_moves(const std::string& text, const std::vector<Row>& want, bool outputs) {
    std::vector<CanonMove> got;
    for (const CanonMove& m : run(text))
      if (m.kind == MoveKind::Line || m.kind == MoveKind::Arc || m.kind == MoveKind::Dwell ||
          (outputs && m.kind == MoveKind::Output && m.output == 1))
        got.push_back(m);
    ASSERT_EQ(got.size(), want.size()) << text;
    for (size_t i = 0; i < want.size(); ++i) {
      const Row& w = want[i];
      const CanonMove& m = got[i];
      const std::string at = "move " + std::to_string(i) + " (line " +
                             std::to_string(m.loc.line - 2) + ") of\n" + text;
      switch (w.kind) {
        case 'D':
          ASSERT_EQ(m.kind, MoveKind::Dwell) << at;
          EXPECT_NEAR(m.dwell_s, w.x, 1e-9) << at;
          continue;
        case 'O':
          ASSERT_EQ(m.kind, MoveKind::Output) << at;
          EXPECT_EQ(m.output_on, w.x == 1) << at;
          continue;
        case 'A':
          ASSERT_EQ(m.kind, MoveKind::Arc) << at;
          EXPECT_NEAR(m.center_x, w.cu, 1e-4) << at;
          EXPECT_NEAR(m.center_y, w.cv, 1e-4) << at;
          EXPECT_GT(m.sweep * w.turn, 0) << at;  // the direction
          EXPECT_LE(std::abs(m.sweep), 2 * M_PI + 1e-9) << at;
          break;
        default:
          ASSERT_EQ(m.kind, MoveKind::Line) << at;
          EXPECT_EQ(m.speed_class, w.kind == 'J' ? SpeedClass::Jog : SpeedClass::Move) << at;
      }
      EXPECT_NEAR(m.to[0], w.x, 1e-4) << at;
      EXPECT_NEAR(m.to[1], w.y, 1e-4) << at;
      EXPECT_NEAR(m.to[2], w.z, 1e-4) << at;
    }
  }

  // The first error a check finds.
  Diagnostic error(const std::string& text) {
    return first_error_of(check_script(Script::from_text(kTools + text, "t.ngc")), text);
  }
};

// cyc_xy.ngc
const char* k_cyc_xy =
    "G20 G17 G90 F10\n"
    "G0 X0 Y0 Z1\n"
    "M3 S1000\n"
    "G98 G85 X1 Y1 Z-0.5 R0.1\n"
    "G99 G86 X2 Z-0.5 R0.1 P0.5\n"
    "G98 G89 X3 Y2 Z-0.4 R0.2 P0.25\n"
    "G87 X4 Y2 I0.1 J0.2 K-0.3 Z-0.5 R0.1\n"
    "G99 G88 X5 Y1 Z-0.5 R0.1 P0.5\n"
    "G80\n"
    "M2\n";
const std::vector<Row> w_cyc_xy = {{'J', 0.0000, 0.0000, 1.0000, 0, 0, 0},
                                   {'O', 1, 0, 0, 0, 0, 0},
                                   {'J', 1.0000, 1.0000, 1.0000, 0, 0, 0},
                                   {'J', 1.0000, 1.0000, 0.1000, 0, 0, 0},
                                   {'L', 1.0000, 1.0000, -0.5000, 0, 0, 0},
                                   {'L', 1.0000, 1.0000, 0.1000, 0, 0, 0},
                                   {'J', 1.0000, 1.0000, 1.0000, 0, 0, 0},
                                   {'J', 2.0000, 1.0000, 1.0000, 0, 0, 0},
                                   {'J', 2.0000, 1.0000, 0.1000, 0, 0, 0},
                                   {'L', 2.0000, 1.0000, -0.5000, 0, 0, 0},
                                   {'D', 0.5000, 0, 0, 0, 0, 0},
                                   {'O', 0, 0, 0, 0, 0, 0},
                                   {'J', 2.0000, 1.0000, 0.1000, 0, 0, 0},
                                   {'O', 1, 0, 0, 0, 0, 0},
                                   {'J', 3.0000, 2.0000, 1.0000, 0, 0, 0},
                                   {'J', 3.0000, 2.0000, 0.2000, 0, 0, 0},
                                   {'L', 3.0000, 2.0000, -0.4000, 0, 0, 0},
                                   {'D', 0.2500, 0, 0, 0, 0, 0},
                                   {'L', 3.0000, 2.0000, 1.0000, 0, 0, 0},
                                   {'J', 4.0000, 2.0000, 1.0000, 0, 0, 0},
                                   {'J', 4.0000, 2.0000, 0.1000, 0, 0, 0},
                                   {'J', 4.1000, 2.2000, 0.1000, 0, 0, 0},
                                   {'O', 0, 0, 0, 0, 0, 0},
                                   {'J', 4.1000, 2.2000, -0.5000, 0, 0, 0},
                                   {'J', 4.0000, 2.0000, -0.5000, 0, 0, 0},
                                   {'O', 1, 0, 0, 0, 0, 0},
                                   {'L', 4.0000, 2.0000, -0.3000, 0, 0, 0},
                                   {'L', 4.0000, 2.0000, -0.5000, 0, 0, 0},
                                   {'O', 0, 0, 0, 0, 0, 0},
                                   {'J', 4.1000, 2.2000, -0.5000, 0, 0, 0},
                                   {'J', 4.1000, 2.2000, 1.0000, 0, 0, 0},
                                   {'J', 4.0000, 2.0000, 1.0000, 0, 0, 0},
                                   {'O', 1, 0, 0, 0, 0, 0},
                                   {'J', 5.0000, 1.0000, 1.0000, 0, 0, 0},
                                   {'J', 5.0000, 1.0000, 0.1000, 0, 0, 0},
                                   {'L', 5.0000, 1.0000, -0.5000, 0, 0, 0},
                                   {'D', 0.5000, 0, 0, 0, 0, 0},
                                   {'O', 0, 0, 0, 0, 0, 0},
                                   {'O', 1, 0, 0, 0, 0, 0},
                                   {'O', 0, 0, 0, 0, 0, 0}};

// cyc_g18.ngc
const char* k_cyc_g18 =
    "G20 G90 F10\n"
    "G0 X0 Y2 Z0\n"
    "G18 G98 G81 X1 Z1 Y-0.5 R0.1\n"
    "G99 G83 X2 Z1 Y-0.5 R0.1 Q0.25\n"
    "G98 G85 X3 Z2 Y-0.3 R0.2\n"
    "G80\n"
    "M2\n";
const std::vector<Row> w_cyc_g18 = {
    {'J', 0.0000, 2.0000, 0.0000, 0, 0, 0},  {'J', 1.0000, 2.0000, 1.0000, 0, 0, 0},
    {'J', 1.0000, 0.1000, 1.0000, 0, 0, 0},  {'L', 1.0000, -0.5000, 1.0000, 0, 0, 0},
    {'J', 1.0000, 2.0000, 1.0000, 0, 0, 0},  {'J', 2.0000, 2.0000, 1.0000, 0, 0, 0},
    {'J', 2.0000, 0.1000, 1.0000, 0, 0, 0},  {'L', 2.0000, -0.1500, 1.0000, 0, 0, 0},
    {'J', 2.0000, 0.1000, 1.0000, 0, 0, 0},  {'J', 2.0000, -0.1400, 1.0000, 0, 0, 0},
    {'L', 2.0000, -0.4000, 1.0000, 0, 0, 0}, {'J', 2.0000, 0.1000, 1.0000, 0, 0, 0},
    {'J', 2.0000, -0.3900, 1.0000, 0, 0, 0}, {'L', 2.0000, -0.5000, 1.0000, 0, 0, 0},
    {'J', 2.0000, 0.1000, 1.0000, 0, 0, 0},  {'J', 3.0000, 2.0000, 2.0000, 0, 0, 0},
    {'J', 3.0000, 0.2000, 2.0000, 0, 0, 0},  {'L', 3.0000, -0.3000, 2.0000, 0, 0, 0},
    {'L', 3.0000, 0.2000, 2.0000, 0, 0, 0},  {'J', 3.0000, 2.0000, 2.0000, 0, 0, 0}};

// cyc_g19.ngc
const char* k_cyc_g19 =
    "G20 G90 F10\n"
    "G0 X2 Y0 Z0\n"
    "G19 G98 G82 Y1 Z1 X-0.5 R0.1 P0.2\n"
    "G91 G81 Y1 Z0.5 X-0.6 R-1.5 L2\n"
    "G90 G89 Y4 Z1 X-0.2 R0.5 P0.1\n"
    "G80\n"
    "M2\n";
const std::vector<Row> w_cyc_g19 = {{'J', 2.0000, 0.0000, 0.0000, 0, 0, 0},
                                    {'J', 2.0000, 1.0000, 1.0000, 0, 0, 0},
                                    {'J', 0.1000, 1.0000, 1.0000, 0, 0, 0},
                                    {'L', -0.5000, 1.0000, 1.0000, 0, 0, 0},
                                    {'D', 0.2000, 0, 0, 0, 0, 0},
                                    {'J', 2.0000, 1.0000, 1.0000, 0, 0, 0},
                                    {'J', 2.0000, 2.0000, 1.5000, 0, 0, 0},
                                    {'J', 0.5000, 2.0000, 1.5000, 0, 0, 0},
                                    {'L', -0.1000, 2.0000, 1.5000, 0, 0, 0},
                                    {'J', 2.0000, 2.0000, 1.5000, 0, 0, 0},
                                    {'J', 2.0000, 3.0000, 2.0000, 0, 0, 0},
                                    {'J', 0.5000, 3.0000, 2.0000, 0, 0, 0},
                                    {'L', -0.1000, 3.0000, 2.0000, 0, 0, 0},
                                    {'J', 2.0000, 3.0000, 2.0000, 0, 0, 0},
                                    {'J', 2.0000, 4.0000, 1.0000, 0, 0, 0},
                                    {'J', 0.5000, 4.0000, 1.0000, 0, 0, 0},
                                    {'L', -0.2000, 4.0000, 1.0000, 0, 0, 0},
                                    {'D', 0.1000, 0, 0, 0, 0, 0},
                                    {'L', 2.0000, 4.0000, 1.0000, 0, 0, 0}};

// cyc_g91.ngc
const char* k_cyc_g91 =
    "G20 G17 G90 F10\n"
    "G0 X0 Y0 Z1\n"
    "G91 G99 G81 X1 Z-0.5 R-0.8 L2\n"
    "X1\n"
    "G98 G73 X1 Z-0.5 R-0.8 Q0.2\n"
    "G90 G80\n"
    "M2\n";
const std::vector<Row> w_cyc_g91 = {
    {'J', 0.0000, 0.0000, 1.0000, 0, 0, 0},  {'J', 1.0000, 0.0000, 1.0000, 0, 0, 0},
    {'J', 1.0000, 0.0000, 0.2000, 0, 0, 0},  {'L', 1.0000, 0.0000, -0.3000, 0, 0, 0},
    {'J', 1.0000, 0.0000, 0.2000, 0, 0, 0},  {'J', 2.0000, 0.0000, 0.2000, 0, 0, 0},
    {'L', 2.0000, 0.0000, -0.3000, 0, 0, 0}, {'J', 2.0000, 0.0000, 0.2000, 0, 0, 0},
    {'J', 3.0000, 0.0000, 0.2000, 0, 0, 0},  {'L', 3.0000, 0.0000, -0.3000, 0, 0, 0},
    {'J', 3.0000, 0.0000, 0.2000, 0, 0, 0},  {'J', 4.0000, 0.0000, 1.0000, 0, 0, 0},
    {'J', 4.0000, 0.0000, 0.2000, 0, 0, 0},  {'L', 4.0000, 0.0000, -0.0000, 0, 0, 0},
    {'J', 4.0000, 0.0000, 0.0100, 0, 0, 0},  {'L', 4.0000, 0.0000, -0.2000, 0, 0, 0},
    {'J', 4.0000, 0.0000, -0.1900, 0, 0, 0}, {'L', 4.0000, 0.0000, -0.3000, 0, 0, 0},
    {'J', 4.0000, 0.0000, 1.0000, 0, 0, 0}};

// outside_g41.ngc
const char* k_outside_g41 =
    "G20 G17 G90 F10\n"
    "T1 M6\n"
    "G0 X-1 Y-1 Z0\n"
    "G41 G1 X0 Y0\n"
    "X2\n"
    "Y2\n"
    "X0\n"
    "Y0\n"
    "G40 X-1 Y-1\n"
    "M2\n";
const std::vector<Row> w_outside_g41 = {{'J', -1.0000, -1.0000, 0.0000, 0, 0, 0},
                                        {'L', -0.0884, 0.0884, 0.0000, 0, 0, 0},
                                        {'A', 0.0000, 0.1250, 0.0000, 0.0000, 0.0000, -1},
                                        {'L', 1.8750, 0.1250, 0.0000, 0, 0, 0},
                                        {'L', 1.8750, 1.8750, 0.0000, 0, 0, 0},
                                        {'L', 0.1250, 1.8750, 0.0000, 0, 0, 0},
                                        {'L', 0.1250, 0.0000, 0.0000, 0, 0, 0},
                                        {'L', -1.0000, -1.0000, 0.0000, 0, 0, 0}};

// pocket_g41.ngc
const char* k_pocket_g41 =
    "G20 G17 G90 F10\n"
    "T2 M6\n"
    "G0 X1 Y1 Z0.1\n"
    "G1 Z-0.1\n"
    "G41 G1 X1 Y0\n"
    "X2\n"
    "Y2\n"
    "X0\n"
    "Y0\n"
    "X1\n"
    "G40 X1 Y1\n"
    "M2\n";
const std::vector<Row> w_pocket_g41 = {
    {'J', 1.0000, 1.0000, 0.1000, 0, 0, 0},  {'L', 1.0000, 1.0000, -0.1000, 0, 0, 0},
    {'L', 1.0625, 0.0625, -0.1000, 0, 0, 0}, {'L', 1.9375, 0.0625, -0.1000, 0, 0, 0},
    {'L', 1.9375, 1.9375, -0.1000, 0, 0, 0}, {'L', 0.0625, 1.9375, -0.1000, 0, 0, 0},
    {'L', 0.0625, 0.0625, -0.1000, 0, 0, 0}, {'L', 1.0000, 0.0625, -0.1000, 0, 0, 0},
    {'L', 1.0000, 1.0000, -0.1000, 0, 0, 0}};

// rounded_g42.ngc
const char* k_rounded_g42 =
    "G20 G17 G90 F10\n"
    "T1 M6\n"
    "G0 X-1 Y0.5 Z0\n"
    "G42 G1 X0 Y0.5\n"
    "Y1.5\n"
    "G2 X0.5 Y2 I0.5 J0\n"
    "G1 X2.5\n"
    "G2 X3 Y1.5 I0 J-0.5\n"
    "G1 Y0.5\n"
    "G2 X2.5 Y0 I-0.5 J0\n"
    "G1 X0.5\n"
    "G2 X0 Y0.5 I0 J0.5\n"
    "G40 G1 X-1\n"
    "M2\n";
const std::vector<Row> w_rounded_g42 = {
    {'J', -1.0000, 0.5000, 0.0000, 0, 0, 0},           {'L', 0.0000, 0.3750, 0.0000, 0, 0, 0},
    {'A', 0.1250, 0.5000, 0.0000, 0.0000, 0.5000, 1},  {'L', 0.1250, 1.5000, 0.0000, 0, 0, 0},
    {'A', 0.5000, 1.8750, 0.0000, 0.5000, 1.5000, -1}, {'L', 2.5000, 1.8750, 0.0000, 0, 0, 0},
    {'A', 2.8750, 1.5000, 0.0000, 2.5000, 1.5000, -1}, {'L', 2.8750, 0.5000, 0.0000, 0, 0, 0},
    {'A', 2.5000, 0.1250, 0.0000, 2.5000, 0.5000, -1}, {'L', 0.5000, 0.1250, 0.0000, 0, 0, 0},
    {'A', 0.1250, 0.5000, 0.0000, 0.5000, 0.5000, -1}, {'L', -1.0000, 0.5000, 0.0000, 0, 0, 0}};

// pocket_arcs_g41.ngc
const char* k_pocket_arcs_g41 =
    "G20 G17 G90 F10\n"
    "T2 M6\n"
    "G0 X1.5 Y1 Z0\n"
    "G41 G1 X1.5 Y0\n"
    "X2.5\n"
    "G3 X3 Y0.5 I0 J0.5\n"
    "G1 Y1.5\n"
    "G3 X2.5 Y2 I-0.5 J0\n"
    "G1 X0.5\n"
    "G3 X0 Y1.5 I0 J-0.5\n"
    "G1 Y0.5\n"
    "G3 X0.5 Y0 I0.5 J0\n"
    "G1 X1.5\n"
    "G40 G1 X1.5 Y1\n"
    "M2\n";
const std::vector<Row> w_pocket_arcs_g41 = {
    {'J', 1.5000, 1.0000, 0.0000, 0, 0, 0}, {'L', 1.5625, 0.0625, 0.0000, 0, 0, 0},
    {'L', 2.5000, 0.0625, 0.0000, 0, 0, 0}, {'A', 2.9375, 0.5000, 0.0000, 2.5000, 0.5000, 1},
    {'L', 2.9375, 1.5000, 0.0000, 0, 0, 0}, {'A', 2.5000, 1.9375, 0.0000, 2.5000, 1.5000, 1},
    {'L', 0.5000, 1.9375, 0.0000, 0, 0, 0}, {'A', 0.0625, 1.5000, 0.0000, 0.5000, 1.5000, 1},
    {'L', 0.0625, 0.5000, 0.0000, 0, 0, 0}, {'A', 0.5000, 0.0625, 0.0000, 0.5000, 0.5000, 1},
    {'L', 1.5000, 0.0625, 0.0000, 0, 0, 0}, {'L', 1.5000, 1.0000, 0.0000, 0, 0, 0}};

// mixed.ngc
const char* k_mixed =
    "G20 G17 G90 F10\n"
    "G10 L1 P1 R0.1\n"
    "T1 M6\n"
    "G0 X0 Y0 Z1\n"
    "G42 G0 X1 Y0\n"
    "G1 Z-0.2 F5\n"
    "X3 F10\n"
    "G3 X4 Y1 R1\n"
    "G2 X5 Y2 I1 J0\n"
    "G1 X4 Y3\n"
    "G0 X2 Y3\n"
    "G91 G1 X-1 Y-1\n"
    "G90 G40 G1 X0 Y0\n"
    "M2\n";
const std::vector<Row> w_mixed = {{'J', 0.0000, 0.0000, 1.0000, 0, 0, 0},
                                  {'J', 1.0000, -0.1000, 1.0000, 0, 0, 0},
                                  {'L', 1.0000, -0.1000, -0.2000, 0, 0, 0},
                                  {'L', 3.0000, -0.1000, -0.2000, 0, 0, 0},
                                  {'A', 4.1000, 1.0000, -0.2000, 3.0000, 1.0000, 1},
                                  {'A', 5.0000, 1.9000, -0.2000, 5.0000, 1.0000, -1},
                                  {'A', 5.0707, 2.0707, -0.2000, 5.0000, 2.0000, 1},
                                  {'L', 4.0707, 3.0707, -0.2000, 0, 0, 0},
                                  {'J', 4.0000, 3.1000, -0.2000, 0, 0, 0},
                                  {'J', 2.0000, 3.1000, -0.2000, 0, 0, 0},
                                  {'A', 1.9293, 3.0707, -0.2000, 2.0000, 3.0000, 1},
                                  {'L', 0.9293, 2.0707, -0.2000, 0, 0, 0},
                                  {'L', 0.0000, 0.0000, -0.2000, 0, 0, 0}};

// arc_arc.ngc
const char* k_arc_arc =
    "G20 G17 G90 F10\n"
    "T2 M6\n"
    "G0 X0 Y-1 Z0\n"
    "G41 G1 X0 Y0\n"
    "G3 X2 Y0 I1 J0\n"
    "G3 X4 Y0 I1 J0\n"
    "G1 Y-1\n"
    "G40 G1 X5 Y-1\n"
    "M2\n";
const std::vector<Row> w_arc_arc = {{'J', 0.0000, -1.0000, 0.0000, 0, 0, 0},
                                    {'L', -0.0625, 0.0000, 0.0000, 0, 0, 0},
                                    {'A', 0.0625, 0.0000, 0.0000, 0.0000, 0.0000, -1},
                                    {'A', 1.9375, 0.0000, 0.0000, 1.0000, 0.0000, 1},
                                    {'A', 2.0625, 0.0000, 0.0000, 2.0000, 0.0000, -1},
                                    {'A', 3.9375, 0.0000, 0.0000, 3.0000, 0.0000, 1},
                                    {'A', 4.0625, 0.0000, 0.0000, 4.0000, 0.0000, -1},
                                    {'L', 4.0625, -1.0000, 0.0000, 0, 0, 0},
                                    {'L', 5.0000, -1.0000, 0.0000, 0, 0, 0}};

// entry_arc.ngc
const char* k_entry_arc =
    "G20 G17 G90 F10\n"
    "T2 M6\n"
    "G0 X1 Y0 Z0\n"
    "G41 G3 X0 Y1 I-1 J0\n"
    "G1 X-1\n"
    "G40 X-1 Y2\n"
    "M2\n";
const std::vector<Row> w_entry_arc = {{'J', 1.0000, 0.0000, 0.0000, 0, 0, 0},
                                      {'A', 0.0000, 0.9375, 0.0000, 0.0000, -0.0646, 1},
                                      {'L', -1.0000, 0.9375, 0.0000, 0, 0, 0},
                                      {'L', -1.0000, 2.0000, 0.0000, 0, 0, 0}};

// g18.ngc
const char* k_g18 =
    "G20 G18 G90 F10\n"
    "T2 M6\n"
    "G0 X-1 Y0 Z-1\n"
    "G41 G1 X0 Z0\n"
    "X2\n"
    "Z2\n"
    "G40 X3 Z3\n"
    "M2\n";
const std::vector<Row> w_g18 = {
    {'J', -1.0000, 0.0000, -1.0000, 0, 0, 0}, {'L', 0.0259, 0.0000, -0.0625, 0, 0, 0},
    {'L', 2.0000, 0.0000, -0.0625, 0, 0, 0},  {'A', 2.0625, 0.0000, 0.0000, 0.0000, 2.0000, -1},
    {'L', 2.0625, 0.0000, 2.0000, 0, 0, 0},   {'L', 3.0000, 0.0000, 3.0000, 0, 0, 0}};

// g41_1.ngc
const char* k_g41_1 =
    "G20 G17 G90 F10\n"
    "G0 X-1 Y-1 Z0\n"
    "G42.1 D0.5 G1 X0 Y0\n"
    "Y2\n"
    "X2\n"
    "G40 X3 Y3\n"
    "G41.1 D-0.2 G1 X4 Y3\n"
    "X5\n"
    "Y4\n"
    "G40 X6 Y6\n"
    "M2\n";
const std::vector<Row> w_g41_1 = {{'J', -1.0000, -1.0000, 0.0000, 0, 0, 0},
                                  {'L', 0.1768, -0.1768, 0.0000, 0, 0, 0},
                                  {'A', 0.2500, 0.0000, 0.0000, 0.0000, 0.0000, 1},
                                  {'L', 0.2500, 1.7500, 0.0000, 0, 0, 0},
                                  {'L', 2.0000, 1.7500, 0.0000, 0, 0, 0},
                                  {'L', 3.0000, 3.0000, 0.0000, 0, 0, 0},
                                  {'L', 4.0000, 2.9000, 0.0000, 0, 0, 0},
                                  {'L', 5.0000, 2.9000, 0.0000, 0, 0, 0},
                                  {'A', 5.1000, 3.0000, 0.0000, 5.0000, 3.0000, 1},
                                  {'L', 5.1000, 4.0000, 0.0000, 0, 0, 0},
                                  {'L', 6.0000, 6.0000, 0.0000, 0, 0, 0}};

// concave.ngc
const char* k_concave =
    "G20 G17 G90 F10\n"
    "T2 M6\n"
    "G0 X-1 Y0 Z0\n"
    "G41 G1 X0 Y0\n"
    "G2 X2 Y0 I1 J0\n"
    "G2 X4 Y0 I1 J0\n"
    "G1 X5\n"
    "G3 X6 Y1 I0 J1\n"
    "G1 X4\n"
    "G40 X4 Y3\n"
    "M2\n";
const std::vector<Row> w_concave = {{'J', -1.0000, 0.0000, 0.0000, 0, 0, 0},
                                    {'L', -0.0607, 0.0625, 0.0000, 0, 0, 0},
                                    {'A', 2.0000, 0.3590, 0.0000, 1.0000, 0.0000, -1},
                                    {'A', 4.0607, 0.0625, 0.0000, 3.0000, 0.0000, -1},
                                    {'L', 5.0000, 0.0625, 0.0000, 0, 0, 0},
                                    {'A', 5.9354, 0.9375, 0.0000, 5.0000, 1.0000, 1},
                                    {'L', 4.0000, 0.9375, 0.0000, 0, 0, 0},
                                    {'L', 4.0000, 3.0000, 0.0000, 0, 0, 0}};

// circle.ngc
const char* k_circle =
    "G20 G17 G90 F10\n"
    "G10 L1 P1 R0.125\n"
    "T1 M6\n"
    "G0 X3 Y1 Z0\n"
    "G41 G1 X2 Y1\n"
    "G3 X2 Y1 I-1 J0\n"
    "G40 G1 X3 Y1\n"
    "G42 G1 X2 Y1\n"
    "G2 X2 Y1 I-1 J0 Z-0.5\n"
    "G40 G1 X3 Y1\n"
    "M2\n";
const std::vector<Row> w_circle = {{'J', 3.0000, 1.0000, 0.0000, 0, 0, 0},
                                   {'L', 2.0000, 0.8750, 0.0000, 0, 0, 0},
                                   {'A', 1.8750, 1.0000, 0.0000, 2.0000, 1.0000, -1},
                                   {'A', 1.8750, 1.0000, 0.0000, 1.0000, 1.0000, 1},
                                   {'L', 3.0000, 1.0000, 0.0000, 0, 0, 0},
                                   {'L', 2.0000, 1.1250, 0.0000, 0, 0, 0},
                                   {'A', 1.8750, 1.0000, 0.0000, 2.0000, 1.0000, 1},
                                   {'A', 1.8750, 1.0000, -0.5000, 1.0000, 1.0000, -1},
                                   {'L', 3.0000, 1.0000, -0.5000, 0, 0, 0}};

// incr.ngc
const char* k_incr =
    "G20 G17 G91 F10\n"
    "G10 L1 P1 R0.1\n"
    "T1 M6\n"
    "G42 G1 X1 Y0\n"
    "X2\n"
    "G3 X1 Y1 I0 J1\n"
    "G1 Y1 Z-0.2\n"
    "G2 X-1 Y1 I-1 J0\n"
    "G1 X-2\n"
    "Y-3\n"
    "G40 X-1 Y-1\n"
    "G90 M2\n";
const std::vector<Row> w_incr = {{'L', 1.0000, -0.1000, 0.0000, 0, 0, 0},
                                 {'L', 3.0000, -0.1000, 0.0000, 0, 0, 0},
                                 {'A', 4.1000, 1.0000, 0.0000, 3.0000, 1.0000, 1},
                                 {'L', 4.1000, 2.0000, -0.2000, 0, 0, 0},
                                 {'A', 3.9000, 2.0000, -0.2000, 4.0000, 2.0000, 1},
                                 {'A', 3.0000, 2.9000, -0.2000, 3.0000, 2.0000, -1},
                                 {'A', 3.0000, 3.1000, -0.2000, 3.0000, 3.0000, 1},
                                 {'L', 1.0000, 3.1000, -0.2000, 0, 0, 0},
                                 {'A', 0.9000, 3.0000, -0.2000, 1.0000, 3.0000, 1},
                                 {'L', 0.9000, 0.0000, -0.2000, 0, 0, 0},
                                 {'L', 0.0000, -1.0000, -0.2000, 0, 0, 0}};

}  // namespace

// ---- canned cycles ----------------------------------------------------------------------

TEST_F(GcodeCompCycles, BoringCyclesG85ToG89InTheXyPlane) {
  std::vector<Row> want = w_cyc_xy;
  // Deliberate difference (docs/gcode.md): after G88's pause Gantry retracts to the
  // clearance level (R, G99) itself and then starts the spindle; LinuxCNC leaves the
  // retract to the operator's hand and restarts the spindle at once.
  ASSERT_GE(want.size(), 3u);
  want.insert(want.end() - 2, {'J', 5, 1, 0.1, 0, 0, 0});  // before the spindle starts, M2
  expect_moves(k_cyc_xy, want, true);
  // G87 asks the operator to turn the tool going in and coming out; G88 to retract.
  ASSERT_EQ(io.questions.size(), 3u);
  EXPECT_NE(io.questions[0].find("G87"), std::string::npos);
  EXPECT_NE(io.questions[1].find("G87"), std::string::npos);
  EXPECT_NE(io.questions[2].find("G88"), std::string::npos);
}

TEST_F(GcodeCompCycles, CyclesInTheZxPlaneDrillAlongY) {
  expect_moves(k_cyc_g18, w_cyc_g18, false);
}

TEST_F(GcodeCompCycles, CyclesInTheYzPlaneDrillAlongXWithRepeats) {
  expect_moves(k_cyc_g19, w_cyc_g19, false);
}

TEST_F(GcodeCompCycles, IncrementalCyclesMeasureRFromTheLevelWhereTheSeriesBegan) {
  // G99 leaves the tool at R, but the next block's R is still measured from Z1.
  expect_moves(k_cyc_g91, w_cyc_g91, false);
}

// rs274's rows of a millimetre program, in the inch machine's units.
std::vector<Row> from_mm(std::vector<Row> rows) {
  for (Row& r : rows)
    if (r.kind == 'J' || r.kind == 'L') {
      r.x /= 25.4;
      r.y /= 25.4;
      r.z /= 25.4;
    }
  return rows;
}

// gen_cycle_inc_continued.ngc: in G91 a block without R and Z drills at the series' R and
// bottom, R still measured from the level where the series began.
TEST_F(GcodeCompCycles, IncrementalCycleBlocksWithoutRAndZKeepTheSeriesLevels) {
  expect_moves(
      "G21 G17 G90 F300\n"
      "G0 X0 Y0 Z15\n"
      "G91 G99 G81 X25 Y12.5 Z-20 R-12.5 L2\n"
      "X-12.5 Y0\n"
      "X0 Y20 L2\n"
      "G90 G80\n"
      "G0 X0 Y0 Z25\n"
      "M2\n",
      from_mm({{'J', 0, 0, 15, 0, 0, 0},
               {'J', 25, 12.5, 15, 0, 0, 0},
               {'J', 25, 12.5, 2.5, 0, 0, 0},
               {'L', 25, 12.5, -17.5, 0, 0, 0},
               {'J', 25, 12.5, 2.5, 0, 0, 0},
               {'J', 50, 25, 2.5, 0, 0, 0},
               {'L', 50, 25, -17.5, 0, 0, 0},
               {'J', 50, 25, 2.5, 0, 0, 0},
               {'J', 37.5, 25, 2.5, 0, 0, 0},
               {'L', 37.5, 25, -17.5, 0, 0, 0},
               {'J', 37.5, 25, 2.5, 0, 0, 0},
               {'J', 37.5, 45, 2.5, 0, 0, 0},
               {'L', 37.5, 45, -17.5, 0, 0, 0},
               {'J', 37.5, 45, 2.5, 0, 0, 0},
               {'J', 37.5, 65, 2.5, 0, 0, 0},
               {'L', 37.5, 65, -17.5, 0, 0, 0},
               {'J', 37.5, 65, 2.5, 0, 0, 0},
               {'J', 0, 0, 25, 0, 0, 0}}),
      false);
}

// gen_cycle_mode_switch.ngc: G98 after G99 in one series retracts to the Z where the series
// began, not to R.
TEST_F(GcodeCompCycles, G98AfterG99InASeriesRetractsToTheSeriesFirstLevel) {
  expect_moves(
      "G20 G17 G90 F20\n"
      "G0 X0 Y0 Z0.6\n"
      "G98 G81 X1 Y1 Z-0.75 R0.1\n"
      "G99 X2\n"
      "X3\n"
      "G98 X4\n"
      "G80\n"
      "G0 Z1\n"
      "M2\n",
      {{'J', 0, 0, 0.6, 0, 0, 0},
       {'J', 1, 1, 0.6, 0, 0, 0},
       {'J', 1, 1, 0.1, 0, 0, 0},
       {'L', 1, 1, -0.75, 0, 0, 0},
       {'J', 1, 1, 0.6, 0, 0, 0},
       {'J', 2, 1, 0.6, 0, 0, 0},
       {'J', 2, 1, 0.1, 0, 0, 0},
       {'L', 2, 1, -0.75, 0, 0, 0},
       {'J', 2, 1, 0.1, 0, 0, 0},
       {'J', 3, 1, 0.1, 0, 0, 0},
       {'L', 3, 1, -0.75, 0, 0, 0},
       {'J', 3, 1, 0.1, 0, 0, 0},
       {'J', 4, 1, 0.6, 0, 0, 0},
       {'J', 4, 1, 0.1, 0, 0, 0},
       {'L', 4, 1, -0.75, 0, 0, 0},
       {'J', 4, 1, 0.6, 0, 0, 0},
       {'J', 4, 1, 1, 0, 0, 0}},
      false);
}

// gen_cycle_r_raised.ngc: a higher R in a G99 series: one traverse to the next hole at the
// new R (the series began above it), no rise at the old hole.
TEST_F(GcodeCompCycles, AHigherRInAG99SeriesGoesToTheNextHoleAndRInOneTraverse) {
  expect_moves(
      "G20 G17 G90 F20\n"
      "G0 X0 Y0 Z0.6\n"
      "G99 G81 X1 Y1 Z-0.75 R0.1\n"
      "X2 R0.2\n"
      "X3\n"
      "G80\n"
      "G0 Z1\n"
      "M2\n",
      {{'J', 0, 0, 0.6, 0, 0, 0},
       {'J', 1, 1, 0.6, 0, 0, 0},
       {'J', 1, 1, 0.1, 0, 0, 0},
       {'L', 1, 1, -0.75, 0, 0, 0},
       {'J', 1, 1, 0.1, 0, 0, 0},
       {'J', 2, 1, 0.2, 0, 0, 0},
       {'L', 2, 1, -0.75, 0, 0, 0},
       {'J', 2, 1, 0.2, 0, 0, 0},
       {'J', 3, 1, 0.2, 0, 0, 0},
       {'L', 3, 1, -0.75, 0, 0, 0},
       {'J', 3, 1, 0.2, 0, 0, 0},
       {'J', 3, 1, 1, 0, 0, 0}},
      false);
}

// gen_cycle_modal.ngc: a file starts in G99 (retract to R), as LinuxCNC's interpreter does.
TEST_F(GcodeCompCycles, AFileStartsInG99) {
  expect_moves(
      "G21 G90 F200\n"
      "G0 X0 Y0 Z10\n"
      "G81 X10 Y10 Z-3 R2\n"
      "Y20\n"
      "X20\n"
      "Z-5\n"
      "R5 X30\n"
      "G82 P0.2 R5 Z-5 X40\n"
      "G80\n"
      "G0 Z10\n"
      "M2\n",
      from_mm({{'J', 0, 0, 10, 0, 0, 0},   {'J', 10, 10, 10, 0, 0, 0}, {'J', 10, 10, 2, 0, 0, 0},
               {'L', 10, 10, -3, 0, 0, 0}, {'J', 10, 10, 2, 0, 0, 0},  {'J', 10, 20, 2, 0, 0, 0},
               {'L', 10, 20, -3, 0, 0, 0}, {'J', 10, 20, 2, 0, 0, 0},  {'J', 20, 20, 2, 0, 0, 0},
               {'L', 20, 20, -3, 0, 0, 0}, {'J', 20, 20, 2, 0, 0, 0},  {'L', 20, 20, -5, 0, 0, 0},
               {'J', 20, 20, 2, 0, 0, 0},  {'J', 30, 20, 5, 0, 0, 0},  {'L', 30, 20, -5, 0, 0, 0},
               {'J', 30, 20, 5, 0, 0, 0},  {'J', 40, 20, 5, 0, 0, 0},  {'L', 40, 20, -5, 0, 0, 0},
               {'D', 0.2, 0, 0, 0, 0, 0},  {'J', 40, 20, 5, 0, 0, 0},  {'J', 40, 20, 10, 0, 0, 0}}),
      false);
}

// gen_cycle_peck_multiple.ngc on an inch machine: millimetre depths that are a whole number
// of pecks end in the last full peck, not a sliver after it.
TEST_F(GcodeCompCycles, PecksOfAMillimetreProgramOnAnInchMachineEndWithoutASliver) {
  ASSERT_EQ(settings.units, Units::Inches);
  expect_moves(
      "G21 G90 F200\n"
      "G0 X0 Y0 Z15\n"
      "G98 G83 X25 Y25 Z-12.5 R2.5 Q7.5\n"
      "G73 X50 Z-12.5 R2.5 Q5\n"
      "G80\n"
      "G0 Z15\n"
      "M2\n",
      from_mm({{'J', 0, 0, 15, 0, 0, 0},
               {'J', 25, 25, 15, 0, 0, 0},
               {'J', 25, 25, 2.5, 0, 0, 0},
               {'L', 25, 25, -5, 0, 0, 0},
               {'J', 25, 25, 2.5, 0, 0, 0},
               {'J', 25, 25, -4.746, 0, 0, 0},
               {'L', 25, 25, -12.5, 0, 0, 0},
               {'J', 25, 25, 15, 0, 0, 0},
               {'J', 50, 25, 15, 0, 0, 0},
               {'J', 50, 25, 2.5, 0, 0, 0},
               {'L', 50, 25, -2.5, 0, 0, 0},
               {'J', 50, 25, -2.246, 0, 0, 0},
               {'L', 50, 25, -7.5, 0, 0, 0},
               {'J', 50, 25, -7.246, 0, 0, 0},
               {'L', 50, 25, -12.5, 0, 0, 0},
               {'J', 50, 25, 15, 0, 0, 0}}),
      false);
}

TEST_F(GcodeCompCycles, CycleRefusalsAreLocatedAndNothingMoves) {
  struct Case {
    const char* text;
    int line, column;  // in `text`
    const char* says;
  };
  const Case cases[] = {
      {"G20 F10 M3\nG84 X1 Y1 Z-0.5 R0.1\n", 2, 1, "G84 (tapping) is not supported"},
      {"G20 F10\nG81 X1 Y1 Z-0.1 R0.1 A90\n", 2, 22, "A cannot go with a canned cycle (G81)"},
      {"G20 F10\nG86 X1 Y1 Z-0.5 R0.1 P1\n", 2, 1, "G86 needs the spindle on (M3)"},
      {"G20 F10 M3\nG88 X1 Y1 Z-0.5 R0.1\n", 2, 1, "G88 needs P"},
      {"G20 F10\nG82 X1 Y1 Z-0.5 R0.1\n", 2, 1, "G82 needs P"},
      {"G20 F10\nG81 X1 Y1 Z-0.5 R0.1\nG82 X2\n", 3, 1, "G82 needs Z"},
      {"G20 F10\nG85 X1 Y1 Z-0.5 R0.1 L0\n", 2, 22, "L0 is not a number of repeats"},
      {"G20 F10\nG85 X1 Y1 Z-0.5 R0.1 L2.5\n", 2, 22, "L2.5 is not a number of repeats"},
      {"G20 G93\nG81 X1 Y1 Z-0.5 R0.1 F1\n", 2, 1, "inverse time"},
      {"G20 F10\nG85 X1 Y1 Z0.2 R0.1\n", 2, 1, "bottom Z is above the retract level"},
      {"G20 F10 G18\nG81 X1 Z1 Y0.2 R0.1\n", 2, 1, "bottom Y is above the retract level"},
      {"G20 F10 G19\nG81 Y1 Z1 R0.1\n", 2, 1, "G81 needs X, the bottom of the hole"},
      {"G20 F10 M3\nG87 X1 Y1 Z-0.5 R0.1 I0.1 J0\n", 2, 1, "G87 needs I, J and K"},
      {"G20 F10\nG85 X1 Y1 Z-0.5 R0.1 Q0.1\n", 2, 22, "Q is the peck depth"},
      {"G20 F10\nG85 X1 Y1 Z-0.5 R0.1 P1\n", 2, 22, "P goes with"},
      {"G20 F10\nG89 X1 Y1 Z-0.5 R0.1 P-1\n", 2, 22, "P, the dwell, cannot be negative"},
      {"G20 F10\nG0 X-1 Y-1\nG41 G1 X0 Y0\nG81 X1 Y1 Z-0.5 R0.1\n", 4, 1,
       "cannot run with cutter radius compensation on"},
  };
  for (const Case& c : cases) {
    const Diagnostic d = error(c.text);
    EXPECT_EQ(d.loc.line, c.line + 2) << c.text << d.message;
    EXPECT_EQ(d.loc.column, c.column) << c.text << d.message;
    EXPECT_NE(d.message.find(c.says), std::string::npos) << c.text << d.message;
    // The check before a run stops it there; run unchecked, the refused block moves nothing.
    EXPECT_THROW(run(c.text), GantryError) << c.text;
    for (const CanonMove& m : sink.moves) EXPECT_LT(m.loc.line, d.loc.line) << c.text;
  }
}

// ---- cutter radius compensation ---------------------------------------------------------

TEST_F(GcodeCompCycles, CompOutsideASquareRoundsTheConvexCornersAndExitsOnG40) {
  expect_moves(k_outside_g41, w_outside_g41, false);
}

TEST_F(GcodeCompCycles, CompInsideAPocketCutsTheConcaveCornersShort) {
  expect_moves(k_pocket_g41, w_pocket_g41, false);
}

TEST_F(GcodeCompCycles, CompInsideARoundedPocketShrinksTheArcs) {
  expect_moves(k_rounded_g42, w_rounded_g42, false);
  expect_moves(k_pocket_arcs_g41, w_pocket_arcs_g41, false);
}

TEST_F(GcodeCompCycles, CompWithRapidsZMovesIncrementalMovesAndBothArcSides) {
  expect_moves(k_mixed, w_mixed, false);
}

TEST_F(GcodeCompCycles, CompRoundsTheConvexCornersBetweenArcs) {
  expect_moves(k_arc_arc, w_arc_arc, false);
}

TEST_F(GcodeCompCycles, CompConcaveCornersLineToArcArcToArcAndArcToLine) {
  expect_moves(k_concave, w_concave, false);
}

TEST_F(GcodeCompCycles, CompAroundFullCirclesAndAHelixBothSides) {
  expect_moves(k_circle, w_circle, false);
}

TEST_F(GcodeCompCycles, CompWithIncrementalWordsFromTheProgrammedPoint) {
  expect_moves(k_incr, w_incr, false);
}

TEST_F(GcodeCompCycles, CompEntryByAnArc) {
  expect_moves(k_entry_arc, w_entry_arc, false);
}

TEST_F(GcodeCompCycles, CompInTheZxPlane) {
  expect_moves(k_g18, w_g18, false);
}

TEST_F(GcodeCompCycles, CompWithTheDiameterGivenAndANegativeOneSwitchingSides) {
  expect_moves(k_g41_1, w_g41_1, false);
}

TEST_F(GcodeCompCycles, CompHoldsOutputsAndDwellsBehindTheMoveBeforeTheCorner) {
  // rs274: the entry line, DWELL, M8 (flood), then the corner arc.
  const auto moves =
      run("G20 G17 G90 F10\nT1 M6\nG0 X-1 Y-1 Z0\nG41 G1 X0 Y0\nG4 P1\nM8\nX1\n"
          "G40 X2 Y-1\nM2\n");
  std::vector<MoveKind> kinds;
  for (const CanonMove& m : moves)
    if (m.kind == MoveKind::Line || m.kind == MoveKind::Arc || m.kind == MoveKind::Dwell ||
        (m.kind == MoveKind::Output && m.output == 2))
      kinds.push_back(m.kind);
  const std::vector<MoveKind> want = {MoveKind::Line,   MoveKind::Line, MoveKind::Dwell,
                                      MoveKind::Output, MoveKind::Arc,  MoveKind::Line,
                                      MoveKind::Line};
  ASSERT_GE(kinds.size(), want.size());
  for (size_t i = 0; i < want.size(); ++i) EXPECT_EQ(kinds[i], want[i]) << "move " << i;
}

TEST_F(GcodeCompCycles, CompRefusalsAreLocatedAndNothingMoves) {
  struct Case {
    const char* text;
    int line, column;  // in `text`
    const char* says;
  };
  const char* start = "G20 G17 G90 F10\nT1 M6\nG0 X-1 Y-1 Z0\n";  // 3 lines
  const Case cases[] = {
      // rs274: Straight feed in concave corner cannot be reached by the tool without gouging
      {"G41 G1 X0 Y0\nX1\nY1\nX0.9 Y0.1\n", 4, 1, "cannot reach the concave corner"},
      // rs274: Length of cutter compensation entry move is not greater than the tool radius
      {"G41 G1 X-0.95 Y-0.95\n", 1, 1, "not longer than the tool radius"},
      // rs274: Tool radius not less than arc radius with comp
      {"G41 G1 X0 Y0\nX1\nG3 X1 Y0.2 I0 J0.1\n", 3, 1, "not less than the arc's radius"},
      // rs274: Cutter radius compensation allowed only in XY, XZ planes
      {"G19 G41 G1 X0 Y0\n", 1, 5, "XY (G17) and ZX (G18) planes only"},
      {"G41 G1 X0 Y0\nG41 X1\n", 2, 1, "already on"},
      {"G41 G1 X0 Y0\nG18 X1\n", 2, 1, "cannot change the plane"},
      {"G41 G1 X0 Y0\nG28\n", 2, 1, "G28 cannot be used"},
      {"G41 G1 X0 Y0\nG92 X0\n", 2, 1, "cannot change the axis offsets"},
      {"G41 G1 X0 Y0\nG55 X1\n", 2, 1, "cannot change the coordinate system"},
      {"G41 G1 X0 Y0\nG53 X1\n", 2, 1, "G53 cannot be used"},
      {"G41 G1 X0 Y0\nG38.2 X1\n", 2, 1, "cannot probe"},
      {"G41 G1 X0 Y0\nG43 H1 X1\n", 2, 1, "cannot change the tool length offset"},
      {"G41 G1 X0 Y0\nT2 M6\n", 2, 1, "M6: cannot change tools"},
      // rs274: The move just after exiting cutter compensation mode must be straight
      {"G41 G1 X0 Y0\nX1\nG40\nG2 X2 Y0 I0.5\n", 4, 1, "must be straight, not an arc"},
      // (A tool missing from a configured table: GcodeToolTable.AToolMissingFrom...)
      // rs274: G41 requires D word to be a whole number
      {"G41 D1.5 G1 X0 Y0\n", 1, 5, "D is a tool number"},
      // rs274: G41.1 with no D word
      {"G41.1 G1 X0 Y0\n", 1, 1, "G41.1 needs D"},
      // rs274: G41.1 with L word, but plane is not G18
      {"G41.1 D0.5 L2 G1 X0 Y0\n", 1, 12, "L is a lathe tool's orientation"},
      {"G1 D1 X0 Y0\n", 1, 4, "D goes with G41/G42"},
  };
  for (const Case& c : cases) {
    const std::string text = std::string(start) + c.text;
    const Diagnostic d = error(text);
    EXPECT_EQ(d.loc.line, c.line + 5) << text << d.message;
    EXPECT_EQ(d.loc.column, c.column) << text << d.message;
    EXPECT_NE(d.message.find(c.says), std::string::npos) << text << d.message;
    EXPECT_THROW(run(text), GantryError) << text;
    for (const CanonMove& m : sink.moves) EXPECT_LT(m.loc.line, d.loc.line) << text;
  }
}

TEST_F(GcodeCompCycles, CompIsRefusedInGcodeLinesOfAnOpenSbpFile) {
  sink = RecordingSink();
  InterpreterOptions o;
  o.dry_run = true;
  Interpreter interp(settings, sink, io, store, o);
  const std::vector<Diagnostic> found =
      interp.check(Script::from_text("G20 F10\nG41.1 D0.25 G1 X1 Y1\n", "t.sbp"));
  ASSERT_FALSE(found.empty());
  EXPECT_EQ(found[0].loc.line, 2);
  EXPECT_NE(found[0].message.find("not in G-code lines of an OpenSBP file"), std::string::npos)
      << found[0].message;
}

}  // namespace gantry
