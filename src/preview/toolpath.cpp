// The toolpath of a part file: the check's canonical moves, arcs cut into chords.
#include "gantry/preview/toolpath.hpp"

#include <algorithm>  // any_of
#include <optional>

#include "gantry/commands/command_table.hpp"  // CommandTable::is_command
#include "gantry/lang/script.hpp"             // Script
#include "gantry/canon/arc_geometry.hpp"      // arc_chords
#include "gantry/motion/cycle_timer.hpp"      // the estimate

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
class ToolpathSink : public MotionSink {
 public:
  ToolpathSink(Toolpath& path, const Settings& settings, const ToolpathOptions& opts)
      : path_(path),
        tolerance_(settings.planner.chord_tolerance),
        cutter_(settings.cutter.diameter),
        opts_(opts) {}
  void move(const CanonMove& m) override {
    if (opts_.cancel && opts_.cancel->load(std::memory_order_relaxed)) throw Cancelled{};
    path_.add(m, tolerance_);
    if (opts_.progress && path_.segments.size() >= next_report_) {
      opts_.progress(path_);
      next_report_ = path_.segments.size() + kReportEvery;
    }
  }
  void flush() override {}
  // VP or a VU may change the chord tolerance part-way (it comes at rest, like the planner's),
  // and a tool change the cutter (VC's diameter).
  void settings_changed(const Settings& s) override {
    tolerance_ = s.planner.chord_tolerance;
    if (s.cutter.diameter != cutter_)
      path_.cutter_changes.push_back({path_.segments.size(), cutter_ = s.cutter.diameter});
  }

 private:
  static constexpr std::size_t kReportEvery = 1 << 16;
  Toolpath& path_;
  double tolerance_;
  double cutter_;
  const ToolpathOptions& opts_;
  std::size_t next_report_ = kReportEvery;
};

}  // namespace

void Toolpath::add(const CanonMove& m, double chord_tolerance) {
  ++moves;
  if (m.kind != MoveKind::Line && m.kind != MoveKind::Arc) return;
  const Eigen::Vector3f from = m.from.head<3>().cast<float>();
  const auto line = static_cast<std::uint32_t>(std::max(m.loc.line, 0));
  if (segments.empty()) {
    start = from;
    bounds.extend(start);
  } else if (const ToolpathSegment& e = segments.back(); Eigen::Vector3f(e.x, e.y, e.z) != from) {
    // The tool was moved outside the moves (a keypad jog on the live machine): a jog joins
    // the two ends, so each segment still starts where the previous ended.
    segments.push_back({from.x(), from.y(), from.z(), line, PathKind::Jog});
    bounds.extend(from);
  }
  const PathKind kind = path_kind(m);
  auto push = [&](const Vec6& p) {
    const Eigen::Vector3f q = p.head<3>().cast<float>();
    segments.push_back({q.x(), q.y(), q.z(), line, kind});
    bounds.extend(q);
  };
  if (m.kind == MoveKind::Line)
    push(m.to);
  else
    for (const Vec6& p : arc_chords(m, chord_tolerance)) push(p);
}

bool Toolpath::has_errors() const {
  return std::any_of(violations.begin(), violations.end(),
                     [](const Diagnostic& d) { return d.severity == Severity::Error; });
}

Toolpath load_toolpath(const std::string& path, const Settings& settings,
                       const ToolpathOptions& opts) {
  Toolpath out;
  ToolpathSink sink(out, settings, opts);
  JobOptions job = opts.job;
  std::optional<CycleTimer> timer;
  if (opts.estimate) timer.emplace(settings, job.feed_override, &sink);
  job.check_moves = timer ? static_cast<MotionSink*>(&*timer) : &sink;
  const PersistentStore none;
  try {
    std::shared_ptr<const Script> script =
        Script::load(path, CommandTable::standard().is_command());
    out.violations =
        std::move(check_program(std::move(script), settings, opts.store ? *opts.store : none, job)
                      .kept());
    if (timer) out.estimated_time_s = timer->seconds();
  } catch (const GantryError& e) {
    out.violations.push_back(e.diagnostic());
  } catch (const Cancelled&) {
    out.cancelled = true;
  }
  return out;
}

}  // namespace gantry
