// The tools that ask the machine: the copy machine (TC) probes a grid and writes what it
// found; setup (TS) prints the machine profile.
#include <fmt/format.h>  // the part files' text, messages

#include <cctype>  // toupper
#include <cmath>   // floor
#include <string>
#include <vector>

#include "gantry/commands/command_table.hpp"
#include "gantry/interp/command_context.hpp"
#include "tool_commands.hpp"  // the tools' parameters, PartFile

namespace gantry::tools {
namespace {

// ---- TC: copy machine (digitizing) --------------------------------------------------------

enum Tc {
  kTcFile,
  kTcX,
  kTcY,
  kTcSizeX,
  kTcSizeY,
  kTcSpacing,
  kTcBottom,
  kTcSafeZ,
  kTcSpeed,
  kTcInput
};

// Probes a grid over a part and writes what it found: a part file whose moves follow the
// surface row by row (a copy to cut with a ball-nose bit), or with a .csv name the points.
// Rows run along X, back and forth; each point is a probe straight down from safe Z to the
// bottom, so the part must not overhang. A point where nothing touched is at the bottom.
void copy_machine(CommandContext& ctx, const CommandCall& call) {
  const double x0 = *call.number(kTcX), y0 = *call.number(kTcY);
  const double sx = positive(call, kTcSizeX), sy = positive(call, kTcSizeY);
  const double step = positive(call, kTcSpacing);
  const double bottom = *call.number(kTcBottom);
  const double safe = safe_z(ctx, call, kTcSafeZ, bottom);
  const double speed = positive(call, kTcSpeed, ctx.state().speeds.move.z);
  const int input = whole(call, kTcInput, 1, 12);
  const int nx = static_cast<int>(std::floor(sx / step + 1e-9)) + 1;
  const int ny = static_cast<int>(std::floor(sy / step + 1e-9)) + 1;
  if (static_cast<long long>(nx) * ny > 1'000'000)
    fail(call.param_loc(kTcSpacing),
         fmt::format("a spacing of {} makes {} x {} points; TC probes at most 1,000,000 (widen "
                     "the spacing)",
                     part_number(step), nx, ny));
  const std::string name = *call.text(kTcFile);
  const bool csv = name.size() > 4 && (name.ends_with(".csv") || name.ends_with(".CSV"));
  // Every point is checked before the first probe: nothing moves for a grid off the table.
  for (const double x : {x0, x0 + (nx - 1) * step})
    for (const double y : {y0, y0 + (ny - 1) * step})
      for (const double z : {safe, bottom}) {
        Vec6 p = ctx.position();
        p[0] = x, p[1] = y, p[2] = z;
        ctx.check_reach(p, call.loc);
      }
  const bool live = ctx.input_switches().has_value();  // a check has no surface to find

  struct Point {
    double x, y, z;
  };
  std::vector<std::vector<Point>> rows(ny);
  int missed = 0;
  auto go = [&](double x, double y, double z, SpeedClass cls) {
    Vec6 p = ctx.position();
    p[0] = x, p[1] = y, p[2] = z;
    ctx.line_to(p, cls, call.loc);
  };
  go(ctx.position()[0], ctx.position()[1], safe, SpeedClass::Jog);
  for (int j = 0; j < ny; ++j)
    for (int i0 = 0; i0 < nx; ++i0) {
      const int i = j % 2 ? nx - 1 - i0 : i0;
      const double x = x0 + i * step, y = y0 + j * step;
      go(x, y, safe, SpeedClass::Jog);
      Vec6 target = ctx.position();
      target[2] = bottom;
      const bool hit = ctx.probe(target, speed, input, call.loc);
      missed += live && !hit;
      rows[j].push_back({x, y, hit ? ctx.position()[2] : bottom});
      go(x, y, safe, SpeedClass::Jog);
    }
  if (missed > 0)
    ctx.warn(call.loc, fmt::format("{} of {} points found nothing down to Z {}; TC put them "
                                   "there",
                                   missed, nx * ny, part_number(bottom)));

  std::string about = fmt::format("{} x {} points {} apart from X {}, Y {}", nx, ny,
                                  part_number(step), part_number(x0), part_number(y0));
  std::string text;
  if (csv) {
    text = "x,y,z\n";
    for (const std::vector<Point>& row : rows)
      for (const Point& p : row)
        text += fmt::format("{},{},{}\n", part_number(p.x), part_number(p.y), part_number(p.z));
  } else {
    PartFile f(ctx, "TC", "Copy of a probed surface",
               {about, fmt::format("Follows the surface row by row: cut it with a ball-nose bit; "
                                   "safe Z {}",
                                   part_number(safe))});
    f.jog_z(safe);
    f.jog_xy(rows[0][0].x, rows[0][0].y);
    for (const std::vector<Point>& row : rows)
      for (const Point& p : row)
        f.line(fmt::format("M3, {}, {}, {}", part_number(p.x), part_number(p.y), part_number(p.z)));
    f.jog_z(safe);
    text = f.text();
  }
  const std::string path = ctx.write_file(name, text, call.param_loc(kTcFile));
  ctx.print(fmt::format("TC probed {} and wrote {}{}\n", about, path,
                        csv ? "" : fmt::format("; run it with FP, {}", name)));
}

// ---- TS: setup -----------------------------------------------------------------------------

// A setting as stored, every digit kept.
std::string show(double v) {
  return fmt::format("{}", v);
}

void setup(CommandContext& ctx, const CommandCall&) {
  const Settings& s = ctx.settings();
  const char* u = units_name(s.units);
  std::string out = fmt::format(
      "Machine profile: {}\nUnits: {}\nCard: {} (pacer {} Hz, step pulse {} us, direction setup "
      "{} us)\n",
      s.name.empty() ? "(unnamed)" : s.name, u, s.card.type, show(s.card.pacer_hz()),
      show(s.card.step_pulse_us), show(s.card.dir_setup_us));
  out += fmt::format("Axis  {:>12}  {:>10}  {:>10}  {}\n", "steps/unit", "max speed", "max accel",
                     "travel (table base)");
  for (int i = 0; i < kAxisCount; ++i) {
    const AxisSettings& a = s.axes[i];
    out += fmt::format("{:<4}  {:>12}  {:>10}  {:>10}  {} to {}\n",
                       static_cast<char>(std::toupper(kAxisLetters[i])), show(a.steps_per_unit),
                       show(a.max_speed), show(a.max_accel), show(a.min), show(a.max));
  }
  const GroupSpeeds& m = ctx.state().speeds.move;
  const GroupSpeeds& j = ctx.state().speeds.jog;
  out += fmt::format("Move speeds ({}/s): XY {}, Z {}, A {}, B {}, C {}\n", u, show(m.xy),
                     show(m.z), show(m.a), show(m.b), show(m.c));
  out += fmt::format("Jog speeds ({}/s): XY {}, Z {}, A {}, B {}, C {}\n", u, show(j.xy), show(j.z),
                     show(j.a), show(j.b), show(j.c));
  const Cutter c = cutter(ctx);
  out += fmt::format("Cutter: diameter {}, safe Z {}\n", show(c.diameter), show(c.safe_z));
  out +=
      "These are the machine profile's values (docs/settings.md) as MS, JS and the V "
      "commands left them.\n";
  ctx.print(out);
}

}  // namespace

void add_machine_tools(std::vector<CommandSpec>& out) {
  const auto T = CommandGroup::Tools;
  out.push_back(
      {"TC",
       "Tools: copy machine",
       T,
       "Digitizes a part: probes a grid straight down from safe Z (a probe on an input, as PZ "
       "uses) and writes a part file that follows the surface row by row, or with a .csv "
       "name the points X, Y, Z. The part must not overhang.",
       {file_param("What to write: a part file (.sbp), or the points (.csv)."),
        length("X start", 0.0, "Corner of the grid."),
        length("Y start", 0.0, "Corner of the grid."),
        length("X size", std::nullopt, "Extent of the grid along X.", true),
        length("Y size", std::nullopt, "Extent of the grid along Y.", true),
        length("spacing", std::nullopt, "Between points, both ways.", true),
        length("bottom", std::nullopt, "How low each probe goes (below the part).", true),
        length("safe Z", std::nullopt,
               "Z above the part between points (blank: the profile's "
               "safe Z above the bottom)."),
        {"probe speed", "units/s", false, std::nullopt, "Blank: the Z move speed."},
        count("input", 1.0, "The probe's input switch (1-12).")},
       copy_machine,
       "outline (2D) tracing, and normally closed probes: it probes a grid, closing"});
  out.push_back({"TS",
                 "Tools: ShopBot setup",
                 T,
                 "Prints the machine's setup: profile, units, card, each axis's steps per unit, "
                 "speed and travel, the current speeds and the cutter.",
                 {},
                 setup,
                 "entering the setup (it is the machine profile's) and calibrating zeroing with "
                 "a zero plate or proximity switches"});
}

}  // namespace gantry::tools
