// Friendly Motion commands to canonical moves, through the same CommandContext OpenSBP's
// commands and G-code's blocks use (docs/friendlymotion.md). The interpreter runs the flow
// (N, J, K, M0, M2, M6, the input waits); this runs everything else, and keeps the language's
// state: V0-V99, @0-@9, the modes, the user coordinate system, the data files.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>

#include "gantry/interp/command_context.hpp"  // CommandContext
#include "gantry/interp/fm_data_files.hpp"    // FmDataFiles: G20-G27
#include "gantry/interp/operator_io.hpp"      // OperatorIO
#include "gantry/lang/fm.hpp"                 // FmLine, FmCommand

namespace gantry {

// The title of Friendly Motion's STEP questions (STEP, M0: Step, Auto, Stop), by which a front
// end knows that a hot key may answer one (session::press_fm_hot_key).
inline constexpr std::string_view kFmStepTitle = "Friendly Motion";

class FmExecutor {
 public:
  FmExecutor(CommandContext& ctx, OperatorIO& io);
  // A Friendly Motion file starts: the power-up state (G91, G2, the profile's units, no
  // scaling, no user coordinates, no profile, normal run, 1" characters). Variables and
  // strings start at 0 and empty (V75 at 1, V86-V89 from the profile's speeds).
  void begin_file();
  // The file ends: open data files are closed, a profile ends at rest.
  void end_file(const SourceLoc& loc);
  // Runs one command of `line` (not N, J, K, M0, M2, M6 or an input wait: the
  // interpreter's). `loc` is the command's.
  void execute(const FmCommand& c, const FmLine& line, const SourceLoc& loc);
  // The value of expression `expr` of `line` (`line_loc` locates its errors by column).
  double value(const FmLine& line, int expr, const SourceLoc& line_loc) const;
  double variable(int n) const;
  bool dry_run() const { return dry_run_; }

 private:
  void reset();  // the power-up state (begin_file without telling the preview)
  // Program values (inches or mm as G70/G71 say) to machine units.
  double unit() const;
  // Where the table is in user coordinates (machine units): the inverse of to_machine.
  std::array<double, 2> user_xy() const;
  // User coordinates (machine units) to working coordinates: O + R(theta) * S * p.
  std::array<double, 2> to_machine(double x, double y) const;
  std::array<double, 2> rotate(double x, double y) const;  // R(theta) only
  void move(const FmCommand& c, const FmLine& line, const SourceLoc& loc);
  void arc(const FmCommand& c, const FmLine& line, const SourceLoc& loc);
  void line_to(const Vec6& target, const SourceLoc& loc);
  void after_move(const SourceLoc& loc);  // outside a profile the table stops after each move
  void assign(int n, double v, const SourceLoc& loc);
  void feed_in_range(double f, const SourceLoc& loc) const;  // F, FX, FY: the table's range
  void g_code(const FmCommand& c, const FmLine& line, const SourceLoc& loc);
  void m_code(int code, const FmCommand& c, const SourceLoc& loc);
  void output(int code, const SourceLoc& loc);
  // Output switch k on or off, at rest; the laser's (friendly_motion.laser_output) then waits
  // its on or off time, so the beam is steady before the next move.
  void switch_output(int k, bool on, const SourceLoc& loc);
  void relay(const FmCommand& c, const FmLine& line, const SourceLoc& loc);  // PA# PB# PD
  int laser_output() const;  // the beam's output switch, 0: none
  void user_system(char form, const SourceLoc& loc);
  void units(bool metric);
  std::string show_text(const FmCommand& c) const;  // G58 / G25
  std::string file_name(const FmCommand& c, const SourceLoc& loc);
  void scribe(const FmCommand& c, const SourceLoc& loc);
  void read_values(const FmCommand& c, const FmLine& line, const SourceLoc& loc);

  CommandContext& ctx_;
  OperatorIO& io_;
  std::array<double, 100> v_{};
  std::array<std::string, 10> strings_;
  bool incremental_ = true;
  bool clockwise_ = true;
  bool metric_ = false;
  bool profile_ = false;
  bool dry_run_ = false;
  std::array<double, 2> scale_{1, 1};
  // The user coordinate system (G60X, G60A): origin (machine units) and angle, radians.
  bool ucs_ = false;
  std::array<double, 2> origin_{0, 0};
  double theta_ = 0;
  double char_size_ = 1;  // G19: the characters' height in program units
  FmDataFiles data_;      // G20-G27
  bool laser_warned_ = false;
  bool analog_warned_ = false;
};

}  // namespace gantry
