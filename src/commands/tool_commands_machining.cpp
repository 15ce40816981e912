// The part-file tools that cut: the drill press (TD), the fluter (TF) and the tabletop
// surfacer (TU) take their values as parameters and write a part file, which the operator
// checks and runs with FP.
#include <fmt/format.h>  // the part files' text, messages

#include <cmath>  // ceil
#include <string>
#include <vector>

#include "gantry/commands/command_table.hpp"
#include "gantry/interp/command_context.hpp"
#include "tool_commands.hpp"  // the tools' parameters, PartFile

namespace gantry::tools {
namespace {

// ---- TD: drill press ------------------------------------------------------------------------

enum Td {
  kTdFile,
  kTdX,
  kTdY,
  kTdCountX,
  kTdCountY,
  kTdSpacingX,
  kTdSpacingY,
  kTdDepth,
  kTdPasses,
  kTdSafeZ,
  kTdHole,
  kTdBit,
  kTdPocket,
  kTdOverlap,
  kTdZero,
  kTdThickness
};

// The spacing of a row of `count` holes (parameter i); needed only for more than one.
double spacing(const CommandCall& call, size_t i, int count) {
  if (count == 1) return 0;
  const std::optional<double> s = call.number(i);
  if (!s || *s == 0)
    fail(call.param_loc(i), fmt::format("{} holes in a row need a {} other than 0 ({})", count,
                                        call.spec.params[i].name, call.spec.code));
  return *s;
}

void drill_press(CommandContext& ctx, const CommandCall& call) {
  const Cutter c = cutter(ctx);
  const double x0 = *call.number(kTdX), y0 = *call.number(kTdY);
  const int nx = whole(call, kTdCountX, 1, 1000), ny = whole(call, kTdCountY, 1, 1000);
  const double dx = spacing(call, kTdSpacingX, nx), dy = spacing(call, kTdSpacingY, ny);
  const double depth = positive(call, kTdDepth);
  const int passes = whole(call, kTdPasses, 1, 1000);
  const bool table_zero = choice(call, kTdZero, "material surface", "table top");
  double surface = 0;
  if (table_zero) {
    if (!call.number(kTdThickness))
      fail(call.param_loc(kTdThickness),
           "TD needs the material thickness (parameter 16) when Z 0 is the table top");
    surface = positive(call, kTdThickness);
    if (depth > surface)
      ctx.warn(call.param_loc(kTdDepth),
               fmt::format("the holes go {} below the table top (Z 0); TD drills them so",
                           part_number(depth - surface)));
  }
  const double bottom = surface - depth;
  const double safe = safe_z(ctx, call, kTdSafeZ, surface);
  const double bit = positive(call, kTdBit, c.diameter);
  const double hole = *call.number(kTdHole) == 0 ? bit : positive(call, kTdHole);
  if (hole < bit)
    fail(call.param_loc(kTdHole),
         fmt::format("a hole of diameter {} is smaller than the bit ({}); use a bit no wider "
                     "than the hole",
                     part_number(hole), part_number(bit)));
  const bool pocket = choice(call, kTdPocket, "cut the outline", "pocket from the centre out");
  const double step = bit * (1 - overlap(call, kTdOverlap, c.overlap) / 100);
  const double r = (hole - bit) / 2;  // the radius the bit's centre follows
  const double tolerance = ctx.settings().planner.chord_tolerance;

  PartFile f(ctx, "TD", "Drill press",
             {fmt::format("{} x {} holes of diameter {}, the first at X {}, Y {}, {} apart in X "
                          "and {} in Y",
                          nx, ny, part_number(hole), part_number(x0), part_number(y0),
                          part_number(dx), part_number(dy)),
              fmt::format("Depth {} in {} pass{}, bit {}; Z 0 is the {}; safe Z {}",
                          part_number(depth), passes, passes == 1 ? "" : "es", part_number(bit),
                          table_zero ? "table top" : "material surface", part_number(safe))});
  f.jog_z(safe);
  const std::vector<double> levels = pass_depths(surface, bottom, passes);
  for (int j = 0; j < ny; ++j)
    for (int i0 = 0; i0 < nx; ++i0) {
      const int i = j % 2 ? nx - 1 - i0 : i0;  // back and forth along the rows
      const double cx = x0 + i * dx, cy = y0 + j * dy;
      f.comment(fmt::format("Hole {}, {}", i + 1, j + 1));
      if (r <= 0) {  // the bit's own size: plunge, back to the surface between passes
        f.jog_xy(cx, cy);
        for (int k = 0; k < passes; ++k) {
          f.move_z(levels[k]);
          if (k + 1 < passes) f.jog_z(surface);
        }
      } else if (!pocket) {  // the outline: the middle comes free on the last pass
        f.jog_xy(cx, cy + r);
        for (double z : levels) {
          f.move_z(z);
          f.circle(cx, cy, r, tolerance);
        }
      } else {  // rings from the centre out, each at most `step` beyond the last
        const int rings = static_cast<int>(std::ceil(r / step - 1e-9));
        f.jog_xy(cx, cy);
        for (int k = 0; k < passes; ++k) {
          if (k > 0) f.move_xy(cx, cy);
          f.move_z(levels[k]);
          for (int q = 1; q <= rings; ++q) {
            const double rq = r * q / rings;
            f.move_xy(cx, cy + rq);
            f.circle(cx, cy, rq, tolerance);
          }
        }
      }
      f.jog_z(safe);
    }
  f.write(ctx, call, fmt::format("{} hole{}", nx * ny, nx * ny == 1 ? "" : "s"));
}

// ---- TF: fluter ----------------------------------------------------------------------------

enum Tf {
  kTfFile,
  kTfX,
  kTfY,
  kTfCount,
  kTfSpacing,
  kTfLength,
  kTfDepth,
  kTfPasses,
  kTfAlongX,
  kTfSafeZ
};

void fluter(CommandContext& ctx, const CommandCall& call) {
  const double x0 = *call.number(kTfX), y0 = *call.number(kTfY);
  const int n = whole(call, kTfCount, 1, 1000);
  double gap = 0;
  if (n > 1) {
    const std::optional<double> s = call.number(kTfSpacing);
    if (!s || *s == 0)
      fail(call.param_loc(kTfSpacing),
           fmt::format("{} flutes need a spacing other than 0 (TF)", n));
    gap = *s;
  }
  const double len = positive(call, kTfLength);
  const double depth = positive(call, kTfDepth);
  const int passes = whole(call, kTfPasses, 1, 1000);
  const bool along_x = choice(call, kTfAlongX, "flutes along Y", "flutes along X");
  const double safe = safe_z(ctx, call, kTfSafeZ, 0);

  PartFile f(ctx, "TF", "Fluter",
             {fmt::format("{} flute{} {} long along {}, {} apart, the first from X {}, Y {}", n,
                          n == 1 ? "" : "s", part_number(len), along_x ? "X" : "Y",
                          part_number(gap), part_number(x0), part_number(y0)),
              fmt::format("Depth {} in {} pass{}; Z 0 is the material surface; safe Z {}",
                          part_number(depth), passes, passes == 1 ? "" : "es", part_number(safe))});
  // Flute i from (u, v) to (u + len, v) in its own axes; X, Y when the flutes run along X.
  auto point = [&](double u, double v, bool jog) {
    const double x = along_x ? u : v, y = along_x ? v : u;
    jog ? f.jog_xy(x, y) : f.move_xy(x, y);
  };
  const double u0 = along_x ? x0 : y0, v0 = along_x ? y0 : x0;
  f.jog_z(safe);
  const std::vector<double> levels = pass_depths(0, -depth, passes);
  for (int i = 0; i < n; ++i) {
    const double v = v0 + i * gap;
    f.comment(fmt::format("Flute {}", i + 1));
    point(u0, v, true);
    for (int k = 0; k < passes; ++k) {  // back and forth, one pass deeper each way
      f.move_z(levels[k]);
      point(k % 2 ? u0 : u0 + len, v, false);
    }
    f.jog_z(safe);
  }
  f.write(ctx, call, fmt::format("{} flute{}", n, n == 1 ? "" : "s"));
}

// ---- TU: tabletop surfacer -----------------------------------------------------------------

enum Tu {
  kTuFile,
  kTuX,
  kTuY,
  kTuSizeX,
  kTuSizeY,
  kTuDepth,
  kTuPasses,
  kTuBit,
  kTuOverlap,
  kTuAlongY,
  kTuSafeZ
};

void surfacer(CommandContext& ctx, const CommandCall& call) {
  const Cutter c = cutter(ctx);
  const double x0 = *call.number(kTuX), y0 = *call.number(kTuY);
  const double sx = positive(call, kTuSizeX), sy = positive(call, kTuSizeY);
  const double depth = positive(call, kTuDepth);
  const int passes = whole(call, kTuPasses, 1, 1000);
  const double bit = positive(call, kTuBit, c.diameter);
  const double ov = overlap(call, kTuOverlap, c.overlap);
  const bool along_y = choice(call, kTuAlongY, "rows along X", "rows along Y");
  const double safe = safe_z(ctx, call, kTuSafeZ, 0);
  for (size_t i : {size_t{kTuSizeX}, size_t{kTuSizeY}})
    if (*call.number(i) < bit)
      fail(call.param_loc(i),
           fmt::format("{} ({}) is {}, less than the bit ({}): the bit cannot stay inside the "
                       "area",
                       call.spec.params[i].name, call.spec.code, part_number(*call.number(i)),
                       part_number(bit)));
  // The bit's centre stays half a bit inside the area, so its edge reaches every side.
  const double half = bit / 2;
  const double u0 = (along_y ? y0 : x0) + half, u1 = (along_y ? y0 + sy : x0 + sx) - half;
  const double v0 = (along_y ? x0 : y0) + half, v1 = (along_y ? x0 + sx : y0 + sy) - half;
  const double step = bit * (1 - ov / 100);
  const int rows = v1 > v0 ? static_cast<int>(std::ceil((v1 - v0) / step - 1e-9)) + 1 : 1;

  PartFile f(
      ctx, "TU", "Tabletop surfacer",
      {fmt::format(
           "Area X {} to {}, Y {} to {}: {} rows along {}, then the edge; bit {}, overlap {} %",
           part_number(x0), part_number(x0 + sx), part_number(y0), part_number(y0 + sy), rows,
           along_y ? "Y" : "X", part_number(bit), part_number(ov)),
       fmt::format("Depth {} in {} pass{}; Z 0 is the surface; safe Z {}", part_number(depth),
                   passes, passes == 1 ? "" : "es", part_number(safe))});
  auto point = [&](double u, double v, bool jog) {
    const double x = along_y ? v : u, y = along_y ? u : v;
    jog ? f.jog_xy(x, y) : f.move_xy(x, y);
  };
  f.jog_z(safe);
  for (double z : pass_depths(0, -depth, passes)) {
    point(u0, v0, true);
    f.move_z(z);
    for (int i = 0; i < rows; ++i) {
      const double v = rows == 1 ? v0 : v0 + (v1 - v0) * i / (rows - 1);
      if (i > 0) point(i % 2 ? u1 : u0, v, false);  // over to the next row
      point(i % 2 ? u0 : u1, v, false);             // along the row, back and forth
    }
    // Once around the edge from the corner the last row ended at: between the rows' ends
    // the bit would leave scallops along the sides.
    const double corners[4][2] = {{u0, v0}, {u1, v0}, {u1, v1}, {u0, v1}};
    const int last = (rows - 1) % 2 ? 3 : 2;
    for (int k = 1; k <= 4; ++k)
      point(corners[(last + k) % 4][0], corners[(last + k) % 4][1], false);
    f.jog_z(safe);
  }
  f.write(ctx, call, fmt::format("{} rows in {} pass{}", rows, passes, passes == 1 ? "" : "es"));
}

}  // namespace

void add_machining_tools(std::vector<CommandSpec>& out) {
  const auto T = CommandGroup::Tools;
  const ParamSpec safe = safe_z_param();
  const ParamSpec passes = passes_param();
  const ParamSpec bit = bit_param();
  const ParamSpec over = overlap_param();
  out.push_back(
      {"TD",
       "Tools: drill press",
       T,
       "Writes a part file that drills a grid of holes: each is plunged when it is the bit's "
       "size, or cut around (or pocketed from the centre out) when larger. Run the file with "
       "FP. Nothing moves while TD runs.",
       {file_param("The part file to write; a relative name goes beside this file."),
        length("X first hole", 0.0, "Centre of the first hole."),
        length("Y first hole", 0.0, "Centre of the first hole."),
        count("holes in X", 1.0, "How many holes along X."),
        count("holes in Y", 1.0, "How many rows along Y."),
        length("X spacing", 0.0, "Centre to centre along X (needed for 2 or more)."),
        length("Y spacing", 0.0, "Centre to centre along Y (needed for 2 or more)."),
        length("depth", std::nullopt, "How deep below the surface (above 0).", true), passes, safe,
        length("hole diameter", 0.0, "0: the bit's own size (a plunge)."), bit,
        count("pocket", 0.0, "1 cuts a larger hole out from the centre; 0 its outline only."), over,
        count("Z zero", 0.0, "0 Z 0 is the material surface, 1 the table top."),
        length("material thickness", std::nullopt, "Needed when Z 0 is the table top.")},
       drill_press,
       "the blank outline and the preview of SB3's screen"});
  out.push_back(
      {"TF",
       "Tools: Forney fluter",
       T,
       "Writes a part file that cuts parallel flutes (straight grooves) with the bit's profile, "
       "back and forth one pass deeper each way. Run the file with FP.",
       {file_param("The part file to write; a relative name goes beside this file."),
        length("X start", 0.0, "Start of the first flute (bit centre)."),
        length("Y start", 0.0, "Start of the first flute (bit centre)."),
        count("flutes", 1.0, "How many flutes."),
        length("spacing", 0.0, "Centre to centre (needed for 2 or more)."),
        length("flute length", std::nullopt, "Along the flute, centre to centre of its ends.",
               true),
        length("depth", std::nullopt, "Below the surface (Z 0), above 0.", true), passes,
        count("along X", 0.0, "0 the flutes run along Y, 1 along X."), safe},
       fluter,
       "the groove width from a V-bit's angle, and placing the flutes from the blank's size and "
       "edge distance (give the first flute's start and the spacing); no preview"});
  out.push_back(
      {"TU",
       "Tools: tabletop surfacer",
       T,
       "Writes a part file that flattens a rectangle to a depth: row by row with the given "
       "overlap, then once around the edge, the bit's edge reaching every side. Run the file "
       "with FP.",
       {file_param("The part file to write; a relative name goes beside this file."),
        length("X start", 0.0, "Lower left corner of the area."),
        length("Y start", 0.0, "Lower left corner of the area."),
        length("X size", std::nullopt, "Width of the area.", true),
        length("Y size", std::nullopt, "Height of the area.", true),
        length("depth", std::nullopt, "Below the surface (Z 0), above 0.", true), passes, bit, over,
        count("along Y", 0.0, "0 rows run along X, 1 along Y."), safe},
       surfacer,
       "the preview of SB3's screen"});
}

}  // namespace gantry::tools
