// The differential test of the G-code front end (docs/gcode.md, "Tested against LinuxCNC"):
// every program of tests/data/gcode/ runs through LinuxCNC's own stand-alone interpreter
// (rs274, unpacked by scripts/setup.sh) and through Gantry's, and their motions are compared
// call by call: end points, arc centres, directions, turns and planes, feed rates, traverse
// or feed, dwells, exact stops, and the spindle and coolant in force at each motion. A program
// LinuxCNC refuses must be refused by Gantry with a located error on the same line and
// nothing moved. The listed deliberate differences (tests/data/gcode/differences.txt) are
// expected to differ; an unlisted difference fails the test, and so does a listed program
// that now agrees (a stale entry).
//
// Usage: gantry_gcode_differential [--verbose] [--only NAME] [CORPUS_DIR]
#include <fcntl.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "gantry/commands/command_table.hpp"
#include "gantry/interp/operator_io.hpp"
#include "gantry/interp/persistent_store.hpp"
#include "gantry/lang/script.hpp"
#include "gantry/machine/job.hpp"
#include "gantry/motion/path_limits.hpp"
#include "gantry/settings/settings.hpp"
#include "gantry/settings/values_file.hpp"
#include "../support/recording_sink.hpp"

namespace fs = std::filesystem;
using namespace gantry;

extern char** environ;

namespace {

constexpr double kMm = 1 / 25.4;  // inches per millimetre

// ---- one motion, as either interpreter gives it, in inches (degrees for A B C) ----------

enum class Kind { Traverse, Feed, Arc, Dwell };

struct Motion {
  Kind kind = Kind::Traverse;
  double to[6] = {0, 0, 0, 0, 0, 0};   // machine coordinates
  double tol[6] = {0, 0, 0, 0, 0, 0};  // rs274: the rounding its printed numbers allow
  // Arcs: the plane (0 XY, 1 ZX, 2 YZ), the centre along its first and second axes, the
  // direction (+1 counter-clockwise) and the number of turns begun (LinuxCNC's rotation).
  int plane = 0;
  double centre[2] = {0, 0};
  double centre_tol[2] = {0, 0};
  int direction = 0, turns = 0;
  double feed = 0, feed_tol = 0;  // in/s along the path
  double dwell = 0;               // s
  bool stop_after = false;        // comes to rest after it (exact stop G61)
  bool stop_known = true;         // rs274: whether the mode decides stop_after
  int outputs = 0;                // bits: 1 spindle, 2 flood, 4 mist
  int line = 0;                   // Gantry: its source line
  std::string call;               // rs274: the printed call
};

const char* kind_name(Kind k) {
  switch (k) {
    case Kind::Traverse:
      return "traverse";
    case Kind::Feed:
      return "feed";
    case Kind::Arc:
      return "arc";
    case Kind::Dwell:
      return "dwell";
  }
  return "?";
}

struct Outcome {
  bool refused = false;
  std::string error;                     // the message (rs274's, or Gantry's formatted diagnostic)
  std::vector<int> error_lines;          // rs274: the lines whose text is the refused block
  int error_line = 0, error_column = 0;  // Gantry
  std::string error_file;                // Gantry: the file its error names
  std::vector<Motion> motions;
  int final_outputs = 0;
  std::string trouble;  // the harness could not read this side (a crash, an unknown call)
};

// ---- rs274 ---------------------------------------------------------------------------------

struct Rs274 {
  fs::path root;  // the unpacked package
  fs::path bin() const { return root / "usr/bin/rs274"; }
};

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string trim(const std::string& s) {
  const size_t b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  const size_t e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> out;
  std::string line;
  std::istringstream in(text);
  while (std::getline(in, line)) out.push_back(line);
  return out;
}

// Runs rs274 on `program`; its stdout and stderr. `home`: a folder of its own (rs274 keeps a
// tool file in $HOME, so parallel runs must not share one).
bool run_rs274(const Rs274& r, const fs::path& program, const fs::path& tool_table,
               const fs::path& home, std::string& out, std::string& err, int& status) {
  fs::create_directories(home);
  const fs::path out_file = home / "out.txt", err_file = home / "err.txt";
  std::vector<std::string> env = {"LD_LIBRARY_PATH=" + (r.root / "usr/lib").string() + ":" +
                                      (r.root / "usr/lib/x86_64-linux-gnu").string(),
                                  "HOME=" + home.string(), "PATH=/usr/bin:/bin", "LANG=C"};
  if (fs::exists(r.root / "usr/lib/python3.11/encodings/__init__.py"))
    env.push_back("PYTHONHOME=" + (r.root / "usr").string());
  std::vector<std::string> args = {r.bin().string(), "-t", tool_table.string(), "-g",
                                   program.string()};
  std::vector<char*> argv, envp;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  for (std::string& e : env) envp.push_back(e.data());
  envp.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&fa, 1, out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&fa, 2, err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addchdir_np(&fa, home.c_str());
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, argv[0], &fa, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0) return false;
  int ws = 0;
  if (waitpid(pid, &ws, 0) < 0) return false;
  status = WIFEXITED(ws) ? WEXITSTATUS(ws) : 128 + WTERMSIG(ws);
  out = read_text(out_file);
  err = read_text(err_file);
  return true;
}

std::vector<double> numbers(const std::string& args) {
  std::vector<double> out;
  std::string token;
  for (char c : args + ",") {
    if (c == ',' || c == ' ') {
      if (!token.empty()) out.push_back(std::strtod(token.c_str(), nullptr));
      token.clear();
    } else {
      token += c;
    }
  }
  return out;
}

// rs274's canonical calls -> motions. Derivation of the coordinates (checked by experiment,
// docs/gcode.md): rs274 prints every length in the program's units in force (it says which
// with USE_LENGTH_UNITS), and a motion's coordinates in the program's frame without the
// offsets, which it prints apart (SET_G5X_OFFSET, SET_G92_OFFSET, USE_TOOL_LENGTH_OFFSET); the
// machine position is their sum. A printed feed (SET_FEED_RATE) is in the units in force when
// it is printed, and keeps its speed across a later change of units, as LinuxCNC's motion
// layer converts it then. It prints 4 decimals, so each printed number may be 0.00005 units
// off: the tolerance of a machine coordinate is the sum of those half units over the numbers
// summed (a printed zero offset counts as exact).
Outcome parse_rs274(const std::string& out, const std::string& err, int status,
                    const std::vector<std::string>& program_lines) {
  Outcome o;
  double unit = kMm;  // rs274 starts in millimetres (no INI file)
  struct Offset {
    double v[6] = {0, 0, 0, 0, 0, 0};
    double tol[6] = {0, 0, 0, 0, 0, 0};
  };
  Offset g5x, g92, tlo;
  auto set_offset = [&](Offset& off, const std::vector<double>& n, size_t first) {
    for (int a = 0; a < 6; ++a) {
      const double scale = a < 3 ? unit : 1;
      off.v[a] = n.at(first + static_cast<size_t>(a)) * scale;
      off.tol[a] = off.v[a] != 0 ? 0.5e-4 * scale : 0;
    }
  };
  double feed = 0, feed_tol = 0;
  int plane = 0;
  std::string control = "CANON_CONTINUOUS";
  int outputs = 0;
  double last[6] = {0, 0, 0, 0, 0, 0};  // where the last motion ended (both start at 0)
  double last_tol[6] = {0, 0, 0, 0, 0, 0};
  static const std::regex call_re(R"(^\s*\d+\s+N\S*\s+([A-Z_0-9]+)\((.*)\)\s*$)");
  std::vector<std::string> calls;
  for (const std::string& line : split_lines(out)) {
    std::smatch m;
    if (!std::regex_match(line, m, call_re)) continue;
    calls.push_back(line);
    const std::string name = m[1], args = m[2];
    const std::vector<double> n = numbers(args);
    auto machine = [&](int axis, double printed) {
      const double scale = axis < 3 ? unit : 1;
      return printed * scale + g5x.v[axis] + g92.v[axis] + tlo.v[axis];
    };
    auto machine_tol = [&](int axis) {
      const double scale = axis < 3 ? unit : 1;
      return 0.5e-4 * scale + g5x.tol[axis] + g92.tol[axis] + tlo.tol[axis];
    };
    auto add = [&](Motion mo) {
      // A straight move to where the tool is moves nothing: Gantry issues none. "Where the
      // tool is" within the rounding of both printed positions (a change of units reprints
      // the same point rounded otherwise).
      if (mo.kind == Kind::Traverse || mo.kind == Kind::Feed) {
        bool moves = false;
        for (int a = 0; a < 6; ++a)
          moves = moves || std::abs(mo.to[a] - last[a]) > mo.tol[a] + last_tol[a] + 1e-12;
        if (!moves) return;
      }
      if (mo.kind != Kind::Dwell) {
        std::copy(mo.to, mo.to + 6, last);
        std::copy(mo.tol, mo.tol + 6, last_tol);
      }
      mo.call = trim(line);
      mo.outputs = outputs;
      mo.stop_after = control == "CANON_EXACT_STOP";
      mo.stop_known = control != "CANON_EXACT_PATH";
      o.motions.push_back(mo);
    };
    try {
      // The machine waits here whatever the path mode (Gantry comes to rest before an output
      // switch or a pause): whether the motion before it stops is not compared.
      static const std::set<std::string> waits = {"PROGRAM_STOP",
                                                  "OPTIONAL_PROGRAM_STOP",
                                                  "PROGRAM_END",
                                                  "CHANGE_TOOL",
                                                  "START_SPINDLE_CLOCKWISE",
                                                  "START_SPINDLE_COUNTERCLOCKWISE",
                                                  "STOP_SPINDLE_TURNING",
                                                  "FLOOD_ON",
                                                  "FLOOD_OFF",
                                                  "MIST_ON",
                                                  "MIST_OFF",
                                                  "SET_MOTION_OUTPUT_BIT",
                                                  "CLEAR_MOTION_OUTPUT_BIT",
                                                  "SET_AUX_OUTPUT_BIT",
                                                  "CLEAR_AUX_OUTPUT_BIT",
                                                  "DWELL",
                                                  "TURN_PROBE_ON",
                                                  "TURN_PROBE_OFF",
                                                  "SET_SPINDLE_SPEED",
                                                  "SELECT_TOOL"};
      if (waits.count(name) && !o.motions.empty()) o.motions.back().stop_known = false;
      if (name == "USE_LENGTH_UNITS") {
        if (args.find("INCHES") != std::string::npos)
          unit = 1;
        else if (args.find("MM") != std::string::npos)
          unit = kMm;
        else
          unit = 10 * kMm;  // CANON_UNITS_CM
      } else if (name == "SET_G5X_OFFSET") {
        set_offset(g5x, n, 1);
      } else if (name == "SET_G92_OFFSET") {
        set_offset(g92, n, 0);
      } else if (name == "USE_TOOL_LENGTH_OFFSET") {
        set_offset(tlo, n, 0);
      } else if (name == "SET_XY_ROTATION") {
        if (n.at(0) != 0) o.trouble = "a rotated coordinate system (G10 L2 R): not compared";
      } else if (name == "SET_FEED_RATE") {
        feed = n.at(0) * unit / 60;
        feed_tol = 0.5e-4 * unit / 60;
      } else if (name == "SELECT_PLANE") {
        plane = args.find("XZ") != std::string::npos   ? 1
                : args.find("YZ") != std::string::npos ? 2
                                                       : 0;
      } else if (name == "SET_MOTION_CONTROL_MODE") {
        control = trim(args.substr(0, args.find(',')));
      } else if (name == "STRAIGHT_TRAVERSE" || name == "STRAIGHT_FEED" ||
                 name == "STRAIGHT_PROBE") {
        Motion mo;
        mo.kind = name == "STRAIGHT_TRAVERSE" ? Kind::Traverse : Kind::Feed;
        for (int a = 0; a < 6; ++a) {
          mo.to[a] = machine(a, n.at(static_cast<size_t>(a)));
          mo.tol[a] = machine_tol(a);
        }
        if (mo.kind == Kind::Feed) {
          mo.feed = feed;
          mo.feed_tol = feed_tol;
        }
        add(mo);
      } else if (name == "ARC_FEED") {
        // ARC_FEED(first end, second end, first centre, second centre, rotation, third
        // end, a, b, c); the plane's axes: XY: X Y (Z), XZ: Z X (Y), YZ: Y Z (X).
        static const int axes[3][3] = {{0, 1, 2}, {2, 0, 1}, {1, 2, 0}};
        const int* ax = axes[plane];
        Motion mo;
        mo.kind = Kind::Arc;
        mo.plane = plane;
        mo.to[ax[0]] = machine(ax[0], n.at(0));
        mo.to[ax[1]] = machine(ax[1], n.at(1));
        mo.to[ax[2]] = machine(ax[2], n.at(5));
        for (int a = 0; a < 3; ++a) mo.tol[a] = machine_tol(a);
        for (int a = 3; a < 6; ++a) {
          mo.to[a] = machine(a, n.at(static_cast<size_t>(a + 3)));
          mo.tol[a] = machine_tol(a);
        }
        mo.centre[0] = machine(ax[0], n.at(2));
        mo.centre[1] = machine(ax[1], n.at(3));
        mo.centre_tol[0] = machine_tol(ax[0]);
        mo.centre_tol[1] = machine_tol(ax[1]);
        const int rotation = static_cast<int>(n.at(4));
        mo.direction = rotation > 0 ? 1 : -1;
        mo.turns = std::abs(rotation);
        mo.feed = feed;
        mo.feed_tol = feed_tol;
        add(mo);
      } else if (name == "DWELL") {
        if (n.at(0) == 0) continue;  // G4 P0: a stop (Gantry's Stop move), compared as one
        Motion mo;
        mo.kind = Kind::Dwell;
        mo.dwell = n.at(0);
        add(mo);
      } else if (name == "START_SPINDLE_CLOCKWISE" || name == "START_SPINDLE_COUNTERCLOCKWISE") {
        outputs |= 1;
      } else if (name == "STOP_SPINDLE_TURNING") {
        outputs &= ~1;
      } else if (name == "FLOOD_ON") {
        outputs |= 2;
      } else if (name == "FLOOD_OFF") {
        outputs &= ~2;
      } else if (name == "MIST_ON") {
        outputs |= 4;
      } else if (name == "MIST_OFF") {
        outputs &= ~4;
      }
    } catch (const std::out_of_range&) {
      o.trouble = "cannot read rs274's call: " + trim(line);
    }
  }
  o.final_outputs = outputs;
  // An error: rs274 prints "executing", then the message and the refused block's text.
  std::vector<std::string> e;
  for (const std::string& l : split_lines(err))
    if (trim(l) != "executing" && !trim(l).empty()) e.push_back(l);
  if (status != 0 || !e.empty()) {
    o.refused = true;
    o.error = e.empty() ? "rs274 exited with status " + std::to_string(status) : trim(e[0]);
    if (e.size() >= 2) {
      const std::string block = trim(e.back());
      for (size_t i = 0; i < program_lines.size(); ++i)
        if (trim(program_lines[i]) == block) o.error_lines.push_back(static_cast<int>(i + 1));
    }
  }
  return o;
}

// ---- Gantry --------------------------------------------------------------------------------

// The machine the programs run on: the default profile in `units`, with a table so large
// that no soft limit is in the way.
Settings test_settings(Units units, const fs::path& tool_table, bool& tool_table_loaded) {
  Settings s = default_settings();
  if (units != s.units) convert_units(s, units);
  for (AxisSettings& a : s.axes) {
    a.min = -1e6;
    a.max = 1e6;
  }
  s.machine.limit_checking = false;
  tool_table_loaded = false;
  // The tool table: a profile key `tool_table` where Gantry has one (LinuxCNC's format).
  std::string text = settings_text(s);
  const std::string key = "tool_table = \"" + tool_table.string() + "\"\n";
  const std::regex existing(R"((^|\n)tool_table\s*=[^\n]*\n)");
  if (std::regex_search(text, existing))
    text = std::regex_replace(text, existing, "$1" + key);
  else
    text = key + text;
  SettingsLoad load = parse_settings(text, "differential.toml");
  if (load.ok()) {
    tool_table_loaded = true;
    return load.settings;
  }
  return s;
}

Outcome run_gantry(const fs::path& program, const Settings& settings) {
  Outcome o;
  const double to_in = settings.units == Units::Inches ? 1 : kMm;
  std::shared_ptr<const Script> script;
  JobOptions opt;
  opt.yes = true;
  opt.operator_present = false;
  try {
    script = Script::load(program.string(), CommandTable::standard().is_command());
    const PersistentStore store;
    const DiagnosticLog found = check_program(script, settings, store, opt);
    for (const Diagnostic& d : found.kept())
      if (d.severity == Severity::Error) {
        o.refused = true;
        o.error = format(d);
        const SourceLoc& at = d.via.empty() ? d.loc : d.via.front();
        o.error_line = at.line;
        o.error_column = at.column;
        o.error_file = at.file ? *at.file : "";
        return o;
      }
    RecordingSink sink;
    std::string printed;
    ScriptedIO io(true, {}, &printed);
    opt.interpreter.dry_run = true;
    PersistentStore scratch;
    interpret(script, settings, sink, io, scratch, opt);
    int outputs = 0;
    for (const CanonMove& m : sink.moves) {
      if (m.kind == MoveKind::Output) {
        const int bit = m.output == 1 ? 1 : m.output == 2 ? 2 : m.output == 3 ? 4 : 0;
        outputs = m.output_on ? outputs | bit : outputs & ~bit;
        continue;
      }
      if (m.kind == MoveKind::Stop) {
        if (!o.motions.empty()) o.motions.back().stop_after = true;
        continue;
      }
      if (m.kind != MoveKind::Line && m.kind != MoveKind::Arc && m.kind != MoveKind::Dwell)
        continue;
      Motion mo;
      mo.line = m.loc.line;
      mo.outputs = outputs;
      if (m.kind == MoveKind::Dwell) {
        mo.kind = Kind::Dwell;
        mo.dwell = m.dwell_s;
        o.motions.push_back(mo);
        continue;
      }
      // A move shorter than Gantry's slack moves nothing (rs274 prints it as one to where the
      // tool is, which is not compared).
      if (m.kind == MoveKind::Line && (m.to - m.from).cwiseAbs().maxCoeff() * to_in < 1e-6)
        continue;
      for (int a = 0; a < 6; ++a) mo.to[a] = m.to[a] * (a < 3 ? to_in : 1);
      if (m.kind == MoveKind::Arc) {
        mo.kind = Kind::Arc;
        mo.plane = m.plane == ArcPlane::XY ? 0 : m.plane == ArcPlane::ZX ? 1 : 2;
        mo.centre[0] = m.center_x * to_in;
        mo.centre[1] = m.center_y * to_in;
        mo.direction = m.sweep > 0 ? 1 : -1;
        // LinuxCNC's rotation counts the turns begun: a sweep of up to one turn is 1.
        mo.turns = std::max(1, static_cast<int>(std::ceil(std::abs(m.sweep) / (2 * M_PI) - 1e-9)));
        mo.feed = m.speeds.xy * to_in;
      } else {
        mo.kind = m.speed_class == SpeedClass::Jog ? Kind::Traverse : Kind::Feed;
        if (mo.kind == Kind::Feed) mo.feed = nominal_path_speed(m.to - m.from, m.speeds) * to_in;
      }
      o.motions.push_back(mo);
    }
    o.final_outputs = outputs;
  } catch (const GantryError& e) {
    // The check passed, so a real run would have moved before this: never a refusal alike.
    o.trouble = "Gantry's check passed but its run stopped: " + format(e.diagnostic());
  } catch (const std::exception& e) {
    o.trouble = std::string("Gantry threw: ") + e.what();
  }
  return o;
}

// ---- comparing -----------------------------------------------------------------------------

const double kSlack = 1e-6;  // in: Gantry's own arithmetic, beyond rs274's rounding

std::string fmt_num(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%.6f", v);
  return b;
}

std::string describe(const Motion& m, bool rs274) {
  std::string s = kind_name(m.kind);
  if (m.kind == Kind::Dwell) return s + " " + fmt_num(m.dwell) + " s";
  static const char* names = "XYZABC";
  for (int a = 0; a < 6; ++a) s += std::string(" ") + names[a] + fmt_num(m.to[a]);
  if (m.kind == Kind::Arc)
    s += " plane " +
         std::string(m.plane == 0   ? "XY"
                     : m.plane == 1 ? "ZX"
                                    : "YZ") +
         " centre " + fmt_num(m.centre[0]) + "," + fmt_num(m.centre[1]) +
         (m.direction > 0 ? " ccw" : " cw") + " turns " + std::to_string(m.turns);
  if (m.kind != Kind::Traverse) s += " F" + fmt_num(m.feed * 60) + " in/min";
  if (m.stop_after) s += " then stop";
  s += " outputs " + std::to_string(m.outputs);
  if (rs274)
    s += "   <- " + m.call;
  else
    s += "   <- line " + std::to_string(m.line);
  return s;
}

// The first difference between the two motions, or "".
std::string differs(const Motion& g, const Motion& r) {
  if (g.kind != r.kind)
    return std::string(kind_name(g.kind)) + " where LinuxCNC has a " + kind_name(r.kind);
  if (g.kind == Kind::Dwell) return std::abs(g.dwell - r.dwell) > 0.5e-4 + 1e-9 ? "dwell time" : "";
  static const char* names = "XYZABC";
  for (int a = 0; a < 6; ++a)
    if (!(std::abs(g.to[a] - r.to[a]) <= r.tol[a] + kSlack))
      return std::string("end point ") + names[a] + " off by " + fmt_num(g.to[a] - r.to[a]);
  if (g.kind == Kind::Arc) {
    if (g.plane != r.plane) return "arc plane";
    for (int i = 0; i < 2; ++i)
      if (!(std::abs(g.centre[i] - r.centre[i]) <= r.centre_tol[i] + kSlack))
        return "arc centre off by " + fmt_num(g.centre[i] - r.centre[i]);
    if (g.direction != r.direction) return "arc direction";
    if (g.turns != r.turns) return "arc turns";
  }
  if (g.kind != Kind::Traverse) {
    // Relative slack as well: an inverse-time feed is a quotient of rounded numbers.
    if (!(std::abs(g.feed - r.feed) <= r.feed_tol + 1e-9 + 1e-7 * std::abs(r.feed)))
      return "feed rate off by " + fmt_num((g.feed - r.feed) * 60) + " in/min";
  }
  if (r.stop_known && g.stop_after != r.stop_after)
    return g.stop_after ? "stops after the move where LinuxCNC blends (G64)"
                        : "blends where LinuxCNC stops (G61 exact stop)";
  if (g.outputs != r.outputs) return "spindle/coolant state";
  return "";
}

struct Verdict {
  enum What { Matched, RefusedAlike, Mismatch } what = Matched;
  std::string detail;
};

Verdict compare(const Outcome& g, const Outcome& r, const fs::path& program) {
  Verdict v;
  if (!r.trouble.empty() || !g.trouble.empty()) {
    v.what = Verdict::Mismatch;
    v.detail = "  " + (r.trouble.empty() ? g.trouble : r.trouble) + "\n";
    return v;
  }
  if (r.refused) {
    if (!g.refused) {
      v.what = Verdict::Mismatch;
      v.detail = "  LinuxCNC refuses it: " + r.error + " (line " +
                 (r.error_lines.empty() ? std::string("?") : std::to_string(r.error_lines[0])) +
                 ")\n  Gantry runs it (" + std::to_string(g.motions.size()) + " motions)\n";
      return v;
    }
    const bool located = g.error_line > 0 && g.error_column > 0 &&
                         fs::path(g.error_file).filename() == program.filename();
    const bool same_line =
        r.error_lines.empty() ||
        std::find(r.error_lines.begin(), r.error_lines.end(), g.error_line) != r.error_lines.end();
    if (located && same_line && g.motions.empty()) {
      v.what = Verdict::RefusedAlike;
      return v;
    }
    v.what = Verdict::Mismatch;
    v.detail =
        "  LinuxCNC refuses line " +
        (r.error_lines.empty() ? std::string("?") : std::to_string(r.error_lines[0])) + ": " +
        r.error + "\n  Gantry refuses " +
        (located ? "line " + std::to_string(g.error_line) : std::string("without a location")) +
        ": " + g.error + "\n";
    return v;
  }
  if (g.refused) {
    v.what = Verdict::Mismatch;
    v.detail = "  LinuxCNC runs it (" + std::to_string(r.motions.size()) +
               " motions)\n  Gantry refuses it: " + g.error + "\n";
    return v;
  }
  const size_t n = std::min(g.motions.size(), r.motions.size());
  for (size_t i = 0; i < n; ++i) {
    const std::string d = differs(g.motions[i], r.motions[i]);
    if (!d.empty()) {
      v.what = Verdict::Mismatch;
      v.detail = "  motion " + std::to_string(i + 1) + ", line " +
                 std::to_string(g.motions[i].line) + ": " + d +
                 "\n    Gantry:   " + describe(g.motions[i], false) +
                 "\n    LinuxCNC: " + describe(r.motions[i], true) + "\n";
      return v;
    }
  }
  if (g.motions.size() != r.motions.size()) {
    v.what = Verdict::Mismatch;
    v.detail = "  Gantry has " + std::to_string(g.motions.size()) + " motions, LinuxCNC " +
               std::to_string(r.motions.size()) + "\n";
    const auto& longer = g.motions.size() > n ? g.motions : r.motions;
    v.detail += std::string("    first extra (") + (&longer == &g.motions ? "Gantry" : "LinuxCNC") +
                "): " + describe(longer[n], &longer == &r.motions) + "\n";
    return v;
  }
  if (g.final_outputs != r.final_outputs) {
    v.what = Verdict::Mismatch;
    v.detail = "  spindle/coolant at the end: Gantry " + std::to_string(g.final_outputs) +
               ", LinuxCNC " + std::to_string(r.final_outputs) + "\n";
  }
  return v;
}

// The listed deliberate differences: "NAME  reason", # comments.
std::map<std::string, std::string> read_differences(const fs::path& p) {
  std::map<std::string, std::string> out;
  for (const std::string& raw : split_lines(read_text(p))) {
    const std::string line = trim(raw);
    if (line.empty() || line[0] == '#') continue;
    const size_t sp = line.find_first_of(" \t");
    out[line.substr(0, sp)] = sp == std::string::npos ? "" : trim(line.substr(sp));
  }
  return out;
}

// The corpus's programs: the names Gantry reads as G-code.
bool is_program(const fs::path& p) {
  const std::string e = p.extension().string();
  return e == ".ngc" || e == ".nc" || e == ".tap" || e == ".gcode";
}

bool uses_tool_table(const std::string& text) {
  static const std::regex re(R"([Mm]\s*0*6(?![0-9.])|[Hh]\s*[0-9#\[])");
  return std::regex_search(text, re);
}

}  // namespace

int main(int argc, char** argv) {
  bool verbose = false;
  std::string only;
  fs::path corpus = fs::path(GANTRY_SOURCE_DIR) / "tests/data/gcode";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--verbose")
      verbose = true;
    else if (a == "--only" && i + 1 < argc)
      only = argv[++i];
    else
      corpus = a;
  }
  const auto started = std::chrono::steady_clock::now();
  Rs274 rs;
  const char* env_root = std::getenv("GANTRY_LINUXCNC_ROOT");
  rs.root = env_root ? fs::path(env_root) : fs::path(GANTRY_SOURCE_DIR) / "build/linuxcnc/root";
  if (!fs::exists(rs.bin())) {
    std::fprintf(stderr,
                 "GcodeDifferential: FAILED: LinuxCNC's rs274 is not at %s; run scripts/setup.sh "
                 "(it unpacks it into build/linuxcnc), or set GANTRY_LINUXCNC_ROOT to the "
                 "unpacked package's root\n",
                 rs.bin().c_str());
    return 1;
  }
  const fs::path tool_table = corpus / "tool.tbl";
  std::vector<fs::path> programs;
  for (const auto& e : fs::directory_iterator(corpus))
    if (is_program(e.path()) && (only.empty() || e.path().filename() == only))
      programs.push_back(e.path());
  std::sort(programs.begin(), programs.end());
  if (programs.empty()) {
    std::fprintf(stderr, "GcodeDifferential: FAILED: no programs (.ngc .nc .tap .gcode) in %s\n",
                 corpus.c_str());
    return 1;
  }
  const std::map<std::string, std::string> listed = read_differences(corpus / "differences.txt");

  // LinuxCNC first, in parallel (each run is a process of its own): each program as it is
  // (rs274 starts in millimetres: a millimetre machine) and with G20 put before it (an inch
  // machine, whose programs start in G20 as LinuxCNC's do with an inch INI).
  std::vector<Outcome> ref_mm(programs.size()), ref_in(programs.size());
  std::vector<std::string> texts(programs.size());
  for (size_t i = 0; i < programs.size(); ++i) texts[i] = read_text(programs[i]);
  const fs::path scratch = fs::temp_directory_path() /
                           ("gantry-differential-" + std::to_string(static_cast<long>(getpid())));
  const fs::path cache = rs.root.parent_path() / "cache";
  // The key: the tool table and which rs274 (its size and time), besides the program.
  std::error_code stamp_error;
  const std::string tools_text =
      read_text(tool_table) + "\x1f" + std::to_string(fs::file_size(rs.bin(), stamp_error)) +
      "\x1f" +
      std::to_string(fs::last_write_time(rs.bin(), stamp_error).time_since_epoch().count());
  std::atomic<size_t> next{0};
  std::atomic<bool> spawn_failed{false};
  const unsigned workers = std::max(2u, std::min(8u, std::thread::hardware_concurrency() * 2));
  std::vector<std::thread> pool;
  for (unsigned w = 0; w < workers; ++w)
    pool.emplace_back([&, w] {
      const fs::path home = scratch / std::to_string(w);
      for (size_t job; (job = next++) < 2 * programs.size();) {
        const size_t i = job / 2;
        const bool inch = job % 2 == 1;
        std::vector<std::string> lines = split_lines(texts[i]);
        fs::path program = programs[i];
        size_t at = 0;  // the G20 line's index in the copy
        if (inch) {
          // After a first % line: a % line ends the program anywhere else.
          while (at < lines.size() && trim(lines[at]).empty()) ++at;
          at = at < lines.size() && trim(lines[at]) == "%" ? at + 1 : 0;
          lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(at), "G20");
          fs::create_directories(home);
          program = home / programs[i].filename();
          std::ofstream copy(program, std::ios::binary);
          for (const std::string& l : lines) copy << l << "\n";
        }
        std::string out, err;
        int status = 0;
        // rs274's answer depends only on the program, the variant and the tool table: kept
        // beside the unpacked package, so a second run of the test spawns only what changed.
        std::string joined;
        for (const std::string& l : lines) joined += l + "\n";
        const fs::path cached =
            cache / (std::to_string(std::hash<std::string>{}(joined + "\x1f" + tools_text)) +
                     (inch ? "-in" : "-mm"));
        if (fs::exists(cached.string() + ".rc")) {
          out = read_text(cached.string() + ".out");
          err = read_text(cached.string() + ".err");
          status = std::atoi(read_text(cached.string() + ".rc").c_str());
        } else {
          if (!run_rs274(rs, program, tool_table, home, out, err, status)) {
            spawn_failed = true;
            continue;
          }
          std::error_code ignored;
          fs::create_directories(cache, ignored);
          std::ofstream(cached.string() + ".out", std::ios::binary) << out;
          std::ofstream(cached.string() + ".err", std::ios::binary) << err;
          const fs::path rc_tmp = cached.string() + ".rc." + std::to_string(w);
          std::ofstream(rc_tmp) << status;
          fs::rename(rc_tmp, cached.string() + ".rc", ignored);  // last: marks it complete
        }
        Outcome o = parse_rs274(out, err, status, lines);
        if (inch) {
          for (int& l : o.error_lines)  // back to the program's own line numbers
            if (l > static_cast<int>(at) + 1) --l;
          ref_in[i] = std::move(o);
        } else {
          ref_mm[i] = std::move(o);
        }
      }
    });
  for (std::thread& t : pool) t.join();
  std::error_code ec;
  fs::remove_all(scratch, ec);
  if (spawn_failed) {
    std::fprintf(stderr, "GcodeDifferential: FAILED: could not start %s; run scripts/setup.sh\n",
                 rs.bin().c_str());
    return 1;
  }

  const double rs274_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  bool tools_in = false, tools_mm = false;
  const Settings inch = test_settings(Units::Inches, tool_table, tools_in);
  const Settings mm = test_settings(Units::Millimetres, tool_table, tools_mm);
  int compared = 0, matched = 0, refused = 0, expected = 0, unexpected = 0, stale = 0;
  std::vector<std::string> failures;
  std::set<std::string> seen;
  std::map<std::string, int> by_kind;  // listed differences by their reason's first word
  for (size_t i = 0; i < programs.size(); ++i) {
    const std::string name = programs[i].filename().string();
    seen.insert(name);
    ++compared;
    // Every program runs on an inch machine and, unless it uses the tool table (which rs274
    // reads in inches), on a millimetre one.
    std::vector<std::tuple<const char*, const Settings*, const Outcome*>> machines;
    machines.push_back({"inch machine", &inch, &ref_in[i]});
    if (!uses_tool_table(texts[i])) machines.push_back({"mm machine", &mm, &ref_mm[i]});
    Verdict verdict;
    std::string detail;
    for (const auto& [label, settings, reference] : machines) {
      const Verdict v = compare(run_gantry(programs[i], *settings), *reference, programs[i]);
      if (v.what == Verdict::Mismatch) {
        verdict = v;
        detail = std::string("  (") + label + ")\n" + v.detail;
        break;
      }
      verdict = v;
    }
    const auto entry = listed.find(name);
    if (verdict.what == Verdict::Mismatch) {
      if (entry != listed.end()) {
        ++expected;
        ++by_kind[entry->second.substr(0, entry->second.find(':'))];
        if (verbose)
          std::printf("listed difference %s (%s):\n%s", name.c_str(), entry->second.c_str(),
                      detail.c_str());
      } else {
        ++unexpected;
        failures.push_back("MISMATCH " + name + ":\n" + detail);
      }
    } else {
      verdict.what == Verdict::Matched ? ++matched : ++refused;
      if (entry != listed.end()) {
        ++stale;
        failures.push_back("STALE " + name + ": listed in differences.txt (" + entry->second +
                           ") but Gantry now agrees with LinuxCNC: remove the entry\n");
      }
      if (verbose)
        std::printf("%s %s\n", verdict.what == Verdict::Matched ? "matched" : "refused alike",
                    name.c_str());
    }
  }
  if (only.empty())
    for (const auto& [name, reason] : listed)
      if (!seen.count(name)) {
        ++stale;
        failures.push_back("STALE " + name + ": listed in differences.txt but not in the corpus\n");
      }
  for (const std::string& f : failures) std::printf("%s", f.c_str());
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  std::string kinds;
  for (const auto& [kind, count] : by_kind)
    kinds += (kinds.empty() ? "" : ", ") + std::to_string(count) + " " + kind;
  std::printf(
      "GcodeDifferential: %d programs compared with LinuxCNC's rs274: %d matched, %d refused "
      "alike, %d listed differences (%s), %d unexpected mismatches, %d stale entries (%.1f s, "
      "rs274 %.1f s of it; tool table %s)\n",
      compared, matched, refused, expected, kinds.empty() ? "none" : kinds.c_str(), unexpected,
      stale, seconds, rs274_seconds, tools_in ? "loaded" : "not supported by Gantry yet");
  return unexpected == 0 && stale == 0 ? 0 : 1;
}
