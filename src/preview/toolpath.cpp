// The toolpath of a part file: the check's canonical moves, arcs cut into chords.
#include "gantry/preview/toolpath.hpp"

#include <algorithm>  // any_of
#include <cmath>      // cos, sin, ceil
#include <optional>

#include "gantry/commands/command_table.hpp"  // CommandTable::is_command
#include "gantry/lang/script.hpp"             // Script
#include "gantry/canon/arc_geometry.hpp"      // arc_chords
#include "gantry/motion/lookahead_planner.hpp"  // the estimate and its timeline

namespace gantry {

// The memory figure (docs/preview.md) and the console window's vertex layout rest on it.
static_assert(sizeof(ToolpathSegment) == 20);

namespace {

PathKind path_kind(const CanonMove& m) {
  if (m.keypad) return PathKind::Keypad;
  return m.speed_class == SpeedClass::Jog ? PathKind::Jog : PathKind::Cut;
}

struct Cancelled {};  // thrown through the interpreter to end a cancelled load

// Collects the check's moves into the toolpath, reporting progress and honouring cancel.
// The moves come in the interpreter's units (VD's); the path is kept in the file's
// (DrawingState::file_units), converted as they come.
class ToolpathSink : public MotionSink {
 public:
  ToolpathSink(Toolpath& path, const Settings& settings, const ToolpathOptions& opts)
      : path_(path),
        tolerance_(settings.planner.chord_tolerance),
        moves_in_(settings.units),
        opts_(opts) {
    path_.cutter_diameter = settings.cutter.diameter;
  }
  void move(const CanonMove& m) override {
    if (opts_.cancel && opts_.cancel->load(std::memory_order_relaxed)) throw Cancelled{};
    const std::size_t before = path_.segments.size();
    const double k = units_factor(moves_in_, path_.units);
    if (k == 1) {
      path_.add(m, tolerance_);
    } else {  // X, Y, Z and the arc's centre in the path's units (A and B turn in degrees)
      CanonMove c = m;
      for (Vec6* v : {&c.from, &c.to}) v->head<3>() *= k;
      c.center_x *= k;
      c.center_y *= k;
      path_.add(c, tolerance_ * k);
    }
    for (std::size_t i = before; i < path_.segments.size(); ++i) {
      path_.segments[i].tool = tool_;
      path_.segments[i].units = static_cast<std::uint8_t>(path_.units);
    }
    if (path_.segments.size() > before) ends_.push_back({m.count.moves, path_.segments.size()});
    if (opts_.progress && path_.segments.size() >= next_report_) {
      opts_.progress(path_);
      next_report_ = path_.segments.size() + kReportEvery;
    }
  }
  void flush() override {}
  // VP or a VU may change the chord tolerance part-way (it comes at rest, like the planner's).
  void settings_changed(const Settings& s) override {
    tolerance_ = s.planner.chord_tolerance;
    path_.wrap_a = s.display.rotary_units[0] == AxisUnit::Degrees;
    path_.wrap_b = s.display.rotary_units[1] == AxisUnit::Degrees;
  }
  // A tool change (VC, &Tool + C9, M6), a spindle speed (TR) or new units (VD, G20/G21).
  void drawing_changed(const DrawingState& d) override {
    if (d.file_units != path_.units) convert(d.file_units);
    moves_in_ = d.units;
    const auto line = static_cast<std::uint32_t>(std::max(d.line, 0));
    const double diameter = d.cutter_diameter * units_factor(d.units, path_.units);
    const bool first = path_.cutter_changes.empty();
    const double now = first ? path_.cutter_diameter : path_.cutter_changes.back().diameter;
    const int tool = first ? path_.tool : path_.cutter_changes.back().tool;
    if (path_.segments.empty() && first) {
      path_.cutter_diameter = diameter;  // set before the first cut: the cutter at the start
      path_.tool = d.tool;
    } else if (d.tool != tool ||
               std::abs(diameter - now) > 1e-9 * std::max(1.0, std::abs(now))) {
      // A tool change with the same diameter is a change too: the cuts after it are another
      // tool's (the material map and the SVG say which). Changes with no segment between
      // them (C9 names the tool, then its macro sets VC) are one: the last.
      const Toolpath::CutterChange c{path_.segments.size(), diameter, line, d.tool};
      if (!first && path_.cutter_changes.back().first == c.first)
        path_.cutter_changes.back() = c;
      else
        path_.cutter_changes.push_back(c);
      tool_ = static_cast<std::uint8_t>(std::min<std::size_t>(path_.cutter_changes.size(), 255));
    }
    if (d.spindle_rpm != rpm_)
      path_.spindle_changes.push_back({path_.segments.size(), rpm_ = d.spindle_rpm, line});
  }
  // Each move that made segments: its RunCount::moves and the segment after its last.
  std::vector<std::pair<std::size_t, std::size_t>> ends_;

 private:
  // The path so far into `to`: its points, bounds and cutters.
  void convert(Units to) {
    const auto k = static_cast<float>(units_factor(path_.units, to));
    path_.start *= k;
    for (ToolpathSegment& g : path_.segments) g.x *= k, g.y *= k, g.z *= k;
    if (!path_.bounds.isEmpty()) path_.bounds = Eigen::AlignedBox3f(path_.bounds.min() * k, path_.bounds.max() * k);
    path_.cutter_diameter *= k;
    for (Toolpath::CutterChange& c : path_.cutter_changes) c.diameter *= k;
    path_.units = to;
  }

  static constexpr std::size_t kReportEvery = 1 << 16;
  Toolpath& path_;
  double tolerance_;  // in the moves' units
  Units moves_in_;    // the units the interpreter's moves are in
  double rpm_ = 0;
  std::uint8_t tool_ = 0;
  const ToolpathOptions& opts_;
  std::size_t next_report_ = kReportEvery;
};

// The planner's segments' end times, by their move's RunCount::moves.
class TimelineSink : public SegmentSink {
 public:
  void segment(const PlannedSegment& s) override {
    if (s.count.moves >= end_s.size()) end_s.resize(s.count.moves + 1, -1);
    end_s[s.count.moves] = planner->planned_time();
  }
  void flush() override {}
  const LookAheadPlanner* planner = nullptr;
  std::vector<double> end_s;  // -1: no segment
};

// Plans every move (the cycle time, as CycleTimer does) and passes it on to the preview.
class TimedSink : public MotionSink {
 public:
  TimedSink(const Settings& settings, double feed_override, MotionSink& also)
      : planner_(settings, timeline_), also_(also) {
    timeline_.planner = &planner_;
    planner_.feed_override(feed_override);
  }
  void move(const CanonMove& m) override {
    planner_.move(m);
    also_.move(m);
  }
  void flush() override {
    planner_.flush();
    also_.flush();
  }
  void settings_changed(const Settings& s) override {
    planner_.settings_changed(s);
    also_.settings_changed(s);
  }
  void drawing_changed(const DrawingState& d) override { also_.drawing_changed(d); }
  double seconds() const { return planner_.planned_time(); }
  const std::vector<double>& end_s() const { return timeline_.end_s; }

 private:
  TimelineSink timeline_;
  LookAheadPlanner planner_;
  MotionSink& also_;
};

}  // namespace

Eigen::Vector3f Toolpath::drawn(const Vec6& p) const {
  Eigen::Vector3d q = p.head<3>();
  constexpr double kRad = 3.14159265358979323846 / 180;
  if (wrap_a && p[3] != 0) {  // turned back by -A about X
    const double c = std::cos(p[3] * kRad), s = std::sin(p[3] * kRad);
    q = Eigen::Vector3d(q.x(), c * q.y() + s * q.z(), -s * q.y() + c * q.z());
  }
  if (wrap_b && p[4] != 0) {  // turned back by -B about Y
    const double c = std::cos(p[4] * kRad), s = std::sin(p[4] * kRad);
    q = Eigen::Vector3d(c * q.x() - s * q.z(), q.y(), s * q.x() + c * q.z());
  }
  return q.cast<float>();
}

void Toolpath::add(const CanonMove& m, double chord_tolerance) {
  ++moves;
  if (m.kind != MoveKind::Line && m.kind != MoveKind::Arc) return;
  const Eigen::Vector3f from = drawn(m.from);
  const auto line = static_cast<std::uint32_t>(std::max(m.loc.line, 0));
  if (segments.empty()) {
    start = from;
    bounds.extend(start);
  } else if (const ToolpathSegment& e = segments.back();
             (Eigen::Vector3f(e.x, e.y, e.z) - from).norm() > 1e-5f) {
    // The tool was moved outside the moves (a keypad jog on the live machine): a jog joins
    // the two ends, so each segment still starts where the previous ended.
    segments.push_back({from.x(), from.y(), from.z(), line, PathKind::Jog, 0, 0});
    bounds.extend(from);
  }
  const PathKind kind = path_kind(m);
  auto push = [&](const Vec6& p) {
    const Eigen::Vector3f q = drawn(p);
    segments.push_back({q.x(), q.y(), q.z(), line, kind, 0, 0});
    bounds.extend(q);
  };
  // A line that turns a wrapped axis is a helix on the work: pieces of 2 degrees at most.
  const double turn = std::max(wrap_a ? std::abs(m.to[3] - m.from[3]) : 0.0,
                               wrap_b ? std::abs(m.to[4] - m.from[4]) : 0.0);
  if (m.kind == MoveKind::Line && turn > 2) {
    const int pieces = static_cast<int>(std::ceil(turn / 2));
    for (int k = 1; k <= pieces; ++k)
      push(m.from + (m.to - m.from) * (static_cast<double>(k) / pieces));
  } else if (m.kind == MoveKind::Line) {
    push(m.to);
  } else {
    for (const Vec6& p : arc_chords(m, chord_tolerance)) push(p);
  }
}

bool Toolpath::has_errors() const {
  return std::any_of(violations.begin(), violations.end(),
                     [](const Diagnostic& d) { return d.severity == Severity::Error; });
}

Toolpath load_toolpath(const std::string& path, const Settings& settings,
                       const ToolpathOptions& opts) {
  Toolpath out;
  out.units = settings.units;
  out.wrap_a = settings.display.rotary_units[0] == AxisUnit::Degrees;
  out.wrap_b = settings.display.rotary_units[1] == AxisUnit::Degrees;
  ToolpathSink sink(out, settings, opts);
  JobOptions job = opts.job;
  std::optional<TimedSink> timer;
  if (opts.estimate) timer.emplace(settings, job.feed_override, sink);
  job.check_moves = timer ? static_cast<MotionSink*>(&*timer) : &sink;
  const PersistentStore none;
  try {
    std::shared_ptr<const Script> script =
        Script::load(path, CommandTable::standard().is_command(), job.interpreter.language);
    out.violations = std::move(
        check_program(std::move(script), settings, opts.store ? *opts.store : none, job).kept());
    if (timer) {
      out.estimated_time_s = timer->seconds();
      // A move the planner made nothing of (too short) ends when the one before it did.
      double t = 0;
      for (const auto& [count, end] : sink.ends_) {
        if (count < timer->end_s().size() && timer->end_s()[count] >= 0)
          t = std::max(t, timer->end_s()[count]);
        out.timeline.push_back({end, t});
      }
    }
  } catch (const GantryError& e) {
    out.violations.push_back(e.diagnostic());
  } catch (const Cancelled&) {
    out.cancelled = true;
  }
  return out;
}

namespace {

// The first `n` segments of `path`, with the changes, timeline and bounds that go with them.
Toolpath first_segments(const Toolpath& path, std::size_t n) {
  Toolpath out;
  out.start = path.start;
  out.moves = path.moves;
  out.estimated_time_s = path.estimated_time_s;
  out.violations = path.violations;
  out.units = path.units;
  out.cutter_diameter = path.cutter_diameter;
  out.wrap_a = path.wrap_a;
  out.wrap_b = path.wrap_b;
  out.segments.assign(path.segments.begin(),
                      path.segments.begin() + static_cast<std::ptrdiff_t>(n));
  if (!out.segments.empty()) out.bounds.extend(out.start);
  for (const ToolpathSegment& s : out.segments) out.bounds.extend(Eigen::Vector3f(s.x, s.y, s.z));
  for (const auto& c : path.cutter_changes)
    if (c.first <= n) out.cutter_changes.push_back(c);
  for (const auto& c : path.spindle_changes)
    if (c.first <= n) out.spindle_changes.push_back(c);
  for (const auto& m : path.timeline)
    if (m.end <= n) out.timeline.push_back(m);
  return out;
}

}  // namespace

Toolpath played_to_time(const Toolpath& path, double seconds) {
  std::size_t begin = 0;
  double begin_s = 0;
  for (const Toolpath::TimeMark& m : path.timeline) {
    if (m.end_s > seconds) {
      // Part-way through this move: its segments share its time evenly.
      const double share = m.end_s > begin_s ? (seconds - begin_s) / (m.end_s - begin_s) : 1;
      const auto n = static_cast<std::size_t>(share * static_cast<double>(m.end - begin));
      return first_segments(path, begin + n);
    }
    begin = m.end;
    begin_s = m.end_s;
  }
  return first_segments(path, path.timeline.empty() ? path.segments.size() : begin);
}

Toolpath played_to_line(const Toolpath& path, std::uint32_t line) {
  const std::vector<ToolpathSegment>& seg = path.segments;
  std::size_t i = 0;
  while (i < seg.size() && seg[i].line != line && seg[i].line < line) ++i;
  while (i < seg.size() && seg[i].line == line) ++i;
  return first_segments(path, i);
}

}  // namespace gantry
