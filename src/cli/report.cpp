// Report and move formatting for the command line.
#include "report.hpp"

#include <fmt/format.h>  // text layout

#include <cmath>  // M_PI

#include "gantry/motion/path_limits.hpp"  // nominal_path_speed
#include "sim/sim_card.hpp"               // SimCard

namespace gantry {
namespace {

template <class V>
nlohmann::ordered_json axis_object(const V& v) {
  nlohmann::ordered_json o = nlohmann::ordered_json::object();
  for (int i = 0; i < kAxisCount; ++i) o[std::string(1, kAxisLetters[i])] = v[i];
  return o;
}

nlohmann::ordered_json vec_array(const Vec6& v) {
  nlohmann::ordered_json a = nlohmann::ordered_json::array();
  for (int i = 0; i < kAxisCount; ++i) a.push_back(v[i]);
  return a;
}

char axis_name(int axis) {
  return static_cast<char>(kAxisLetters[axis] - 'a' + 'A');
}

bool limits_exceeded(const RunReport& r) {
  return r.timing_violations + r.kinematic_violations > 0;
}

// The status line: run_status with why, and never "done" alone when the check did not cover
// the whole file.
std::string status_text(const RunReport& r) {
  std::string out = run_status(r);
  if (r.stopped_by != "none")
    out += r.stopped_by == "stop" ? ": stopped by the operator" : ": E-stop by the operator";
  if (r.errors.empty() && limits_exceeded(r)) out += ": the card saw the machine's limits exceeded";
  if (r.errors.empty() && r.check_stopped)
    out += fmt::format(
        ", but the check before the run stopped at {}:{} and the lines after it ran unchecked",
        r.check_stopped->loc.file ? *r.check_stopped->loc.file : "", r.check_stopped->loc.line);
  return out;
}

}  // namespace

void add_card_checks(RunReport& r, SimCard& card) {
  r.timing_violations = card.timing_violations();
  for (const TimingViolation& v : card.first_violations())
    r.violation_notes.push_back(
        fmt::format("tick {} axis {}: {}", v.tick, axis_name(v.axis), rule_name(v.rule)));
  const KinematicsMonitor& k = card.kinematics();
  r.max_velocity_ratio = k.max_velocity_ratio();
  r.max_accel_ratio = k.max_accel_ratio();
  r.kinematic_violations = k.violations();
  for (const KinematicsMonitor::Violation& v : k.first_violations())
    r.violation_notes.push_back(fmt::format("tick {} axis {}: {} {:.1f} % of its limit", v.tick,
                                            axis_name(v.axis),
                                            v.accel ? "acceleration" : "velocity", v.ratio * 100));
}

const char* run_status(const RunReport& r) {
  return !r.errors.empty() ? "error" : limits_exceeded(r) ? "violation" : "done";
}

int exit_code(const RunReport& r) {
  return r.errors.empty() && !limits_exceeded(r) ? 0 : 1;
}

nlohmann::ordered_json to_json(const Diagnostic& d) {
  return {{"file", d.loc.file ? *d.loc.file : ""},
          {"line", d.loc.line},
          {"column", d.loc.column},
          {"severity", d.severity == Severity::Error ? "error" : "warning"},
          {"message", d.message}};
}

nlohmann::ordered_json to_json(const RunReport& r) {
  nlohmann::ordered_json j;
  j["status"] = run_status(r);
  j["units"] = units_name(r.units);
  j["position"] = axis_object(r.position);
  j["steps"] = axis_object(r.steps);
  j["commanded_steps"] = axis_object(r.commanded_steps);
  j["played_steps"] = axis_object(r.played_steps);
  j["fault"] = r.fault;
  j["time_s"] = r.time_s;
  j["planned_time_s"] = r.planned_time_s;
  j["estimated_time_s"] = r.estimated_time_s;
  j["lines"] = r.lines;
  j["moves"] = r.moves;
  j["cut"] = r.cut;
  j["stopped_by"] = r.stopped_by;
  j["timing_violations"] = r.timing_violations;
  j["kinematic_violations"] = r.kinematic_violations;
  j["max_velocity_ratio"] = r.max_velocity_ratio;
  j["max_accel_ratio"] = r.max_accel_ratio;
  j["errors"] = nlohmann::ordered_json::array();
  for (const Diagnostic& d : r.errors) j["errors"].push_back(to_json(d));
  if (!r.error_summary.empty()) j["errors_not_shown"] = r.error_summary;
  // "complete": the check before the run covered the whole file; "partial": it stopped at
  // `check_stopped` (why: its message), and the run went past that line unchecked.
  j["check"] = r.check_stopped ? "partial" : "complete";
  if (r.check_stopped) j["check_stopped"] = to_json(*r.check_stopped);
  return j;
}

std::string to_text(const RunReport& r) {
  std::string out = fmt::format("status     {}\n", status_text(r));
  out += "position  ";
  for (int i = 0; i < kAxisCount; ++i)
    out += fmt::format(" {}={:.4f}", r.axis_names[static_cast<size_t>(i)], r.position[i]);
  out += fmt::format(" ({})\nsteps     ", units_name(r.units));
  for (int i = 0; i < kAxisCount; ++i)
    out += fmt::format(" {}={}", static_cast<char>(kAxisLetters[i] - 'a' + 'A'), r.steps[i]);
  if (r.fault != "none") {
    out += fmt::format(
        "\nfault      {}: the card stopped; the tool is where the pulses played put "
        "it ({} the step generator's count of them)\n",
        r.fault, r.steps == r.played_steps ? "equal to" : "DIFFERENT FROM");
  } else {
    out += fmt::format("\n           {} the planner's commanded steps\n",
                       r.steps == r.commanded_steps ? "equal to" : "DIFFERENT FROM");
  }
  out += fmt::format("time       {:.3f} s on the card ({:.3f} s planned, {:.3f} s estimated)\n",
                     r.time_s, r.planned_time_s, r.estimated_time_s);
  out += fmt::format("executed   {} statements, {} moves{}\n", r.lines, r.moves,
                     r.cut ? " before the motion was cut; the rest did not run" : "");
  out += fmt::format("timing     {} violations\n", r.timing_violations);
  out += fmt::format(
      "limits     peak velocity {:.1f} %, peak acceleration {:.1f} % of the "
      "axis limits; {} violations\n",
      r.max_velocity_ratio * 100, r.max_accel_ratio * 100, r.kinematic_violations);
  for (const std::string& n : r.violation_notes) out += fmt::format("           {}\n", n);
  return out;
}

nlohmann::ordered_json to_json(const CanonMove& m) {
  nlohmann::ordered_json j = {
      {"file", m.loc.file ? *m.loc.file : ""},
      {"line", m.loc.line},
      {"kind", kind_name(m.kind)},
      {"speed_class", speed_class_name(m.speed_class)},
      {"from", vec_array(m.from)},
      {"to", vec_array(m.to)},
      {"speed",
       m.kind == MoveKind::Arc ? m.speeds.xy : nominal_path_speed(m.to - m.from, m.speeds)}};
  if (m.kind == MoveKind::Arc) {  // centre and signed sweep (radians, counter-clockwise +)
    j["center"] = {m.center_x, m.center_y};
    j["sweep"] = m.sweep;
    if (m.plane != ArcPlane::XY) j["plane"] = m.plane == ArcPlane::ZX ? "ZX" : "YZ";
  }
  if (m.kind == MoveKind::Dwell) j["dwell_s"] = m.dwell_s;
  if (m.kind == MoveKind::Output) {
    j["output"] = m.output;
    j["on"] = m.output_on;
  }
  if (m.kind == MoveKind::SpindleSpeed) j["rpm"] = m.spindle_rpm;
  return j;
}

nlohmann::ordered_json to_json(const CommandSpec& s) {
  nlohmann::ordered_json params = nlohmann::ordered_json::array();
  for (const ParamSpec& p : s.params) {
    nlohmann::ordered_json j = {{"name", p.name},
                                {"unit", p.unit},
                                {"kind", p.kind == ParamKind::Number ? "number" : "text"},
                                {"required", p.required}};
    j["default"] = p.default_value ? nlohmann::ordered_json(*p.default_value) : nullptr;
    j["help"] = p.help;
    params.push_back(std::move(j));
  }
  return {{"code", s.code},
          {"name", s.name},
          {"group", group_name(s.group)},
          {"coverage", s.coverage.empty() ? std::string_view("complete") : s.coverage},
          {"help", s.help},
          {"parameters", std::move(params)}};
}

std::string to_text(const CanonMove& m) {
  auto v = [](const Vec6& p) {
    return fmt::format("{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f}", p[0], p[1], p[2], p[3], p[4],
                       p[5]);
  };
  if (m.kind == MoveKind::Arc)  // the XY speed runs along the arc
    return fmt::format(
        "{}:{}  {} {}  {} -> {}  centre {:.4f},{:.4f}{} sweep {:.4f} deg  at {:.4f}/s",
        m.loc.file ? *m.loc.file : "", m.loc.line, kind_name(m.kind),
        speed_class_name(m.speed_class), v(m.from), v(m.to), m.center_x, m.center_y,
        m.plane == ArcPlane::XY   ? ""
        : m.plane == ArcPlane::ZX ? " (ZX plane)"
                                  : " (YZ plane)",
        m.sweep * 180 / M_PI, m.speeds.xy);
  return fmt::format("{}:{}  {} {}  {} -> {}  at {:.4f}/s", m.loc.file ? *m.loc.file : "",
                     m.loc.line, kind_name(m.kind), speed_class_name(m.speed_class), v(m.from),
                     v(m.to), nominal_path_speed(m.to - m.from, m.speeds));
}

}  // namespace gantry
