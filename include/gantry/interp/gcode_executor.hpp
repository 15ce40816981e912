// G-code blocks to canonical moves, through the same CommandContext OpenSBP's commands use
// (docs/gcode.md): one set of modes and parameters per interpreter.
#pragma once

#include <array>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "gantry/interp/interpreter.hpp"  // CommandContext
#include "gantry/interp/operator_io.hpp"  // OperatorIO
#include "gantry/lang/gcode.hpp"          // GcodeBlock, GcodeParameters

namespace gantry {

class GcodeExecutor : private GcodeParameters {
 public:
  // `end_program`: M2 and M30 end the running file.
  GcodeExecutor(CommandContext& ctx, OperatorIO& io, std::function<void()> end_program);
  // A G-code file starts: its modes start from their defaults (docs/gcode.md, "Modes").
  void begin_file();
  // Checks the block (modal groups, which words go with which codes, values), then runs it
  // in the standard order; a located error otherwise.
  void execute(const GcodeBlock& block, const SourceLoc& loc);

  // O-word subroutines and M98 (gcode_scopes.cpp). A call has its own #1-#30 (`args`, the
  // rest 0, as LinuxCNC 2.9) unless `numbered_local` is false (M98: shared with the caller),
  // and its own named parameters but those starting with `_`; leave_call gives the caller's
  // back. `returned`: #<_value> and #<_value_returned> (cleared by every call).
  void enter_call(const std::vector<double>& args, bool numbered_local);
  void leave_call();
  void reset_calls();  // a new run: no call is open, #<_value> is 0
  size_t call_depth() const { return scopes_.size(); }
  void set_returned(std::optional<double> value);
  // The value of a word or an O-word's expression (`expr` -1: `number`).
  double value(const GcodeBlock& b, double number, int expr, const SourceLoc& loc) const;
  // M2's end of the program (M99 in the main program too, as rs274 does).
  void end_program(const SourceLoc& loc);

  // The units program values are in.
  enum class ProgramUnits { Inches, Millimetres, Centimetres };

 private:
  struct Words;
  struct Modes {
    int motion = -1;  // G code x10 of the motion mode (G1: 10, G38.2: 382); -1 none (G80)
    ArcPlane plane = ArcPlane::XY;
    bool incremental = false;   // G91
    bool arc_absolute = false;  // G90.1
    bool inverse_time = false;  // G93
    bool retract_to_r = false;  // G99
    bool exact_stop = false;    // G61
    ProgramUnits units = ProgramUnits::Inches;
    ProgramUnits previous_units = ProgramUnits::Inches;  // WinCNC's G23
    double feed = 0;                                     // machine units per second (G94)
    // Canned cycles: the retained Z, R, Q (machine units) and P, and the Z where the series
    // of cycles began (G98 returns there).
    std::optional<double> cycle_z, cycle_r, cycle_q;
    double cycle_p = 0;
    double cycle_start_z = 0;
    std::array<double, 3> last_ijk{0, 0, 0};  // WinCNC: a missing I or J keeps the last
  };

  // GcodeParameters
  double numbered(int n, const SourceLoc& loc) const override;
  double named(std::string_view name, const SourceLoc& loc) const override;
  bool exists(std::string_view name) const override;

  void read_words(const GcodeBlock& b, const SourceLoc& loc, Words& w);
  void check_words(const Words& w, const SourceLoc& loc);
  void run(const Words& w, const SourceLoc& loc);

  // Program units to machine units: per axis (A, B, C in degrees stay) and for lengths.
  Vec6 axis_scale() const;
  double length_scale() const;
  // Program coordinates (machine units) of the tool, and the file coordinates of a point.
  Vec6 program_position() const;
  Vec6 to_file(const Vec6& program) const;
  Vec6 axis_target(const Words& w, const Vec6& from, bool incremental) const;
  void set_zero(const Vec6& zero);
  void select_system(int n);
  double feed_for(const Words& w, double length, const SourceLoc& loc) const;
  void line(const Vec6& target, SpeedClass cls, double speed, const SourceLoc& loc);
  void motion(const Words& w, const SourceLoc& loc);
  void arc(const Words& w, bool clockwise, const SourceLoc& loc);
  void canned_cycle(const Words& w, const SourceLoc& loc);
  void probe(const Words& w, const SourceLoc& loc);
  void non_modal(const Words& w, int code, const SourceLoc& loc);
  void coordinate_data(const Words& w, const SourceLoc& loc);  // G10

  CommandContext& ctx_;
  OperatorIO& io_;
  std::function<void()> end_program_;
  Modes modes_;
  int selected_tool_ = 0;  // T
  std::unordered_map<int, double> params_;
  std::map<std::string, double, std::less<>> named_;
  Vec6 probed_ = Vec6::Zero();  // #5061..: where the last probe stopped
  bool probe_hit_ = false;      // #5070
  struct Scope {                // what a call hides of its caller's parameters
    std::array<std::optional<double>, 30> numbered;
    bool numbered_local = true;
    std::vector<std::pair<std::string, double>> named;
  };
  std::vector<Scope> scopes_;
};

}  // namespace gantry
