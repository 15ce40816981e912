// The toolpath of a part file as a preview draws it: one small record per straight segment,
// so a million-segment file stays near 20 MB. Shared by `gantry preview` and the console
// window's 3D view.
#pragma once

#include <Eigen/Geometry>  // AlignedBox3f

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "gantry/core/diagnostic.hpp"          // Diagnostic
#include "gantry/interp/persistent_store.hpp"  // PersistentStore
#include "gantry/interp/program_check.hpp"     // JobOptions
#include "gantry/canon/canon_move.hpp"        // CanonMove
#include "gantry/settings/settings.hpp"        // Settings

namespace gantry {

// Cut: a move at move speed (M*, C*); Jog: at jog speed (J*); Keypad: a keypad jog.
enum class PathKind : std::uint8_t { Cut, Jog, Keypad };

// One straight piece of the path. It ends at (x, y, z) (machine frame, Toolpath::units) and
// starts where the previous one ended (the first at Toolpath::start). `line`: the source
// line of the statement that made it (in the file that statement is in: FP and C<n> files
// number their own lines). `tool`: the cutter it was cut with (0 the one at the start, k
// cutter_changes[k - 1]; 255 for the 255th change and later); `units`: the units the file
// wrote its numbers in when it was made (Units as a byte). Both fill bytes the struct has
// anyway: it stays 20 bytes.
struct ToolpathSegment {
  float x, y, z;
  std::uint32_t line;
  PathKind kind;
  std::uint8_t tool = 0;
  std::uint8_t units = 0;
};

struct Toolpath {
  Eigen::Vector3f start = Eigen::Vector3f::Zero();  // where the first segment starts
  std::vector<ToolpathSegment> segments;            // arcs as chords within the chord tolerance
  Eigen::AlignedBox3f bounds;   // of every segment, start included (empty: no segments)
  std::size_t moves = 0;        // canonical moves (lines, arcs, dwells, stops, outputs)
  double estimated_time_s = 0;  // the planner's cycle time (0 unless asked for)
  // What the check found: errors (soft limits, syntax, a missing file ...) and warnings,
  // each with its file, line and column. A move refused by the soft limits is not drawn:
  // the tool stays where it was, as it would on the machine.
  std::vector<Diagnostic> violations;
  bool cancelled = false;  // ToolpathOptions::cancel stopped the load part-way
  // Where the cutter changed (G-code's M6, a VC in the file, an &Tool + C9 tool change):
  // from segment `first` on, the cutter is tool `tool` (0: none named), `diameter` across
  // (from the tool table when one is configured, else VC's); `line` is the statement at
  // which it changed (the C9 or M6 line, or the next move's for a VC).
  struct CutterChange {
    std::size_t first;
    double diameter;
    std::uint32_t line = 0;
    int tool = 0;
  };
  std::vector<CutterChange> cutter_changes;
  double cutter_diameter = 0;  // the cutter at the start (VC's), in `units`
  int tool = 0;                // the tool in the spindle at the start (0: none named)
  // Spindle speeds (TR, G-code's S): from segment `first` on, `rpm`.
  struct SpindleChange {
    std::size_t first;
    double rpm;
    std::uint32_t line;
  };
  std::vector<SpindleChange> spindle_changes;
  // The planner's timeline (with ToolpathOptions::estimate): each move that made segments,
  // by the segment after its last (`end`) and the machine time when it ends, in order.
  struct TimeMark {
    std::size_t end;
    double end_s;
  };
  std::vector<TimeMark> timeline;
  // The units of the coordinates, the bounds and the cutter diameters: those the file left
  // in force (VD, G-code's G20/G21), or the profile's. A file that changes units part-way
  // has its earlier segments converted, so the whole path is in one unit.
  Units units = Units::Inches;
  // Rotary axes wrapped on a cylinder (VD's rotary unit degrees; load_toolpath sets them):
  // A turns about the X axis (a ShopBot indexer lies along X), B about the Y axis, each
  // through the machine origin's Y and Z (Z zeroed on the axis' centre line). A point is
  // drawn where it is on the turning work: (X, Y, Z) turned back by -A about X (and -B
  // about Y), so a move of A alone at Z = r draws an arc of radius r about the X axis.
  bool wrap_a = false, wrap_b = false;

  // Appends the segments of one canonical move (lines and arcs; the others only count).
  void add(const CanonMove& m, double chord_tolerance);
  // Where a machine position is drawn: X, Y, Z, wrapped by A and B (wrap_a, wrap_b).
  Eigen::Vector3f drawn(const Vec6& p) const;
  bool has_errors() const;  // any violation of Severity::Error
};

struct ToolpathOptions {
  // How the file is interpreted, as `gantry moves` does it: `yes` and `inputs` answer
  // PAUSE and INPUT, `interpreter` (macros folder, dialect), `check_budget`, and
  // `feed_override` for the estimate.
  JobOptions job;
  const PersistentStore* store = nullptr;  // the $variables the file reads; null: none
  bool estimate = false;                   // also plan the moves for estimated_time_s
  // Called every few tens of thousands of segments with the toolpath so far, on the thread
  // that loads (it must copy what it keeps: the toolpath grows after the call returns).
  std::function<void(const Toolpath& so_far)> progress;
  const std::atomic<bool>* cancel = nullptr;  // set: the load stops soon, `cancelled` set
};

// The toolpath as it stands at machine time `seconds` (from the timeline; a move under way
// is cut at the segment its share of the move's time reaches), or after line `line`'s first
// run (every segment up to the last of the first run of segments from that line; a line that
// makes no segment: up to the first segment of a later line). The tool and spindle changes
// and the bounds follow the shorter path.
Toolpath played_to_time(const Toolpath& path, double seconds);
Toolpath played_to_line(const Toolpath& path, std::uint32_t line);

// Interprets a part file with no machine (as `gantry moves` does) into its toolpath.
// Never throws on a bad file: a file that cannot be read or parsed gives violations (and
// the segments of whatever ran). Settings give the chord tolerance and the soft limits.
Toolpath load_toolpath(const std::string& path, const Settings& settings,
                       const ToolpathOptions& opts = {});

}  // namespace gantry
