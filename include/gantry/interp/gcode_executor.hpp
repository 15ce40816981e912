// G-code blocks to canonical moves, through the same CommandContext OpenSBP's commands use
// (docs/gcode.md): one set of modes and parameters per interpreter.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gantry/interp/command_context.hpp"  // CommandContext
#include "gantry/interp/operator_io.hpp"  // OperatorIO
#include "gantry/lang/gcode.hpp"          // GcodeBlock, GcodeParameters

namespace gantry {

class GcodeExecutor : private GcodeParameters {
 public:
  // `end_program`: M2 and M30 end the running file.
  GcodeExecutor(CommandContext& ctx, OperatorIO& io, std::function<void()> end_program);
  ~GcodeExecutor();
  // A G-code file starts: its modes start from their defaults (docs/gcode.md, "Modes").
  // `typed`: lines typed at the console, whose G92 offsets stay (WinCNC).
  void begin_file(bool typed = false);
  // A pass of a G-code file ends (its last line at `loc` ran, or M2/M30): moves that cutter
  // compensation held back for their corner go out.
  void end_file(const SourceLoc& loc);
  // A file called from a G-code file starts (WinCNC's M98 file, a subroutine's file): its
  // modes go on; its G92 offsets are saved to be restored when it is left (WinCNC, for M98's
  // file, `restore_g92`) unless it gives L92.
  void enter_file(bool restore_g92);
  // The file is left for good: WinCNC restores the G92 offsets it began with unless it gave
  // L92.
  void leave_file();
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
  struct Comp;  // cutter radius compensation (gcode_cutter_comp.cpp)
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
    // Canned cycles (gcode_cycles.cpp): the words a cycle keeps while its code stays (the
    // depth along the cycle axis, R, Q: machine units; P seconds; G87's I J K), and the
    // cycle axis's level where the series of cycles began (G98 returns there).
    std::optional<double> cycle_depth, cycle_r, cycle_q, cycle_p;
    std::optional<std::array<double, 3>> cycle_ijk;
    std::optional<double> cycle_initial;
    std::array<double, 3> last_ijk{0, 0, 0};  // WinCNC: a missing I or J keeps the last
  };

  // GcodeParameters
  double numbered(int n, const SourceLoc* at) const override;
  const double* named(std::string_view name) const override;

  void read_words(const GcodeBlock& b, const SourceLoc& loc, Words& w);
  void set_parameters(const GcodeBlock& b, const SourceLoc& loc);  // the block's #n = v
  void check_words(const Words& w, const SourceLoc& loc);
  void run(const Words& w, const SourceLoc& loc);
  // (MSG,...), (PRINT,...), (DEBUG,...) print; (ABORT,...) stops with a located error.
  void message(const GcodeBlock& b, const SourceLoc& loc);

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
  // The same from `from`, the program position (saves computing it again: the hot path).
  void line(const Vec6& from, const Vec6& target, SpeedClass cls, double speed,
            const SourceLoc& loc);
  void motion(const Words& w, const SourceLoc& loc);
  void arc(const Words& w, bool clockwise, const SourceLoc& loc);
  void canned_cycle(const Words& w, const SourceLoc& loc);
  void check_cycle_words(const Words& w, int motion, const SourceLoc& loc) const;
  void cycle_mode(int was);  // the motion mode changed from `was`
  void probe(const Words& w, const SourceLoc& loc);
  void non_modal(const Words& w, int code, const SourceLoc& loc);
  void coordinate_data(const Words& w, const SourceLoc& loc);  // G10
  // The tool table (gcode_tools.cpp).
  ToolTable& tool_table(const SourceLoc& loc);
  const ToolEntry& tool_entry(int number, const SourceLoc& at);
  void tool_change(const Words& w, const SourceLoc& loc);  // T, M6, M61
  void tool_length(const Words& w, const SourceLoc& loc);  // G43, G43.1, G49
  void tool_data(const Words& w, const SourceLoc& loc);    // G10 L1, L10, L11
  void tool_measure(const Words& w, const SourceLoc& loc);  // G37: on the tool-length sensor
  std::optional<double> tool_parameter(int n) const;       // #5400-#5413
  // Cutter radius compensation (gcode_cutter_comp.cpp).
  void check_comp_words(const Words& w, int motion, const SourceLoc& loc) const;
  void cutter_comp(const Words& w, const SourceLoc& loc);  // G40, G41, G42, G41.1, G42.1
  bool comp_active() const;                                // on, with a tool radius above 0
  // Where a move starts as programmed (with compensation on, the programmed path, not the
  // tool's offset one), for incremental words and arc centres.
  Vec6 motion_start() const;
  // #5420-#5425 (gcode_cutter_comp.cpp): where the program is, the held-back compensated move
  // counted; `at` an expression's (refused while compensation is on), null for a message's.
  Vec6 current_position(const SourceLoc* at) const;
  void comp_line(const Vec6& target, bool rapid, double speed, const SourceLoc& loc);
  void comp_arc(const Vec6& end, double cu, double cv, int turn, double speed,
                const SourceLoc& loc);
  void moved_straight();  // a straight move was made (an arc may follow G40 again)
  void check_arc_allowed(const SourceLoc& loc) const;
  // Runs `action` now, or after the moves compensation holds back (LinuxCNC's queue).
  void deferred(std::function<void()> action);
  // The WinCNC dialect's own codes (gcode_wincnc.cpp, docs/gcode.md "The WinCNC dialect").
  Vec6 program_from_table_base(const Vec6& table_base, unsigned axes) const;
  void wincnc_lift(const SourceLoc& loc);                                 // G53 alone, G0.1
  void wincnc_g53(const Words& w, const SourceLoc& loc);                  // G53 [X Y Z]
  void wincnc_words(Words& w, const SourceLoc& loc);                      // L words, owned axes
  void wincnc_codes(const Words& w, const SourceLoc& loc);                // G0.1, M11-M37, L-codes
  void wincnc_home(const Words& w, const SourceLoc& loc);                 // G28 [axes]
  double wincnc_brace(std::string_view text, const SourceLoc& at) const;  // {TH1+2}

  CommandContext& ctx_;
  OperatorIO& io_;
  std::function<void()> end_program_;
  Modes modes_;
  int selected_tool_ = 0;         // T
  bool tool_note_given_ = false;  // this file was told the implicit table's tools have length 0
  bool table_read_ = false;       // this file compared the table file with the one in memory
  static constexpr int kLastSettable = 5000;  // #1-#5000 a program sets; above: the machine's
  std::vector<double> params_ = std::vector<double>(kLastSettable + 1);  // #0 reads 0 too
  std::vector<std::pair<int, double>> assigned_;  // a block's settings (read_words), reused
  std::map<std::string, double, std::less<>> named_;
  Vec6 probed_ = Vec6::Zero();  // #5061..: where the last probe stopped
  bool probe_hit_ = false;      // #5070
  std::unique_ptr<Comp> comp_;
  // WinCNC: the next block is skipped (M17.1 ... L113); the virtual inputs L60/L61 set; the
  // position L3 stored (table base); each running file's G92 offsets, restored when it ends
  // unless it gave L92.
  bool skip_next_ = false;
  const std::string* prompt_ = nullptr;  // the running block's [comment]: G4's prompt
  std::uint64_t virtual_inputs_ = 0;
  Vec6 l3_position_ = Vec6::Zero();
  unsigned l3_axes_ = 0;  // the axes L3 stored (bit 0 X .. 5 C)
  struct FileG92 {
    Vec6 offset;
    bool keep = false;
  };
  std::vector<FileG92> file_g92_;
  struct Scope {  // what a call hides of its caller's parameters
    std::array<double, 30> numbered;
    bool numbered_local = true;
    std::vector<std::pair<std::string, double>> named;
  };
  std::vector<Scope> scopes_;
};

}  // namespace gantry
