// Tools commands, TC to TU: SB3's "virtual tools", each a separate program with its own
// screens. Gantry's drill press (TD), fluter (TF) and tabletop surfacer (TU) take their
// values as parameters and write a part file, which the operator checks and runs with FP;
// the header writer (TH) adds a comment header to a part file; setup (TS) prints the machine
// profile; the typesetter (TT) writes a part file that engraves text in Gantry's own
// single-stroke font; the copy machine (TC) probes a grid and writes what it found; the
// indexer (TI) writes a part file that runs another at each turn of a rotary axis.
#include <fmt/format.h>  // the part files' text, messages

#include <algorithm>  // clamp
#include <cctype>     // toupper
#include <cmath>      // ceil, round, sin, cos, acos
#include <ctime>      // the date in TH's header
#include <numbers>    // pi
#include <string>
#include <utility>  // pair
#include <vector>

#include "gantry/commands/command_table.hpp"
#include "gantry/commands/stroke_font.hpp"  // TT's letters
#include "gantry/convert/part_file.hpp"     // PartText, part_number
#include "gantry/core/text.hpp"             // upper
#include "gantry/interp/interpreter.hpp"

namespace gantry {
namespace {

// ---- parameters -------------------------------------------------------------------------

ParamSpec file_param(std::string_view help) {
  return {"file name", "", true, std::nullopt, help, ParamKind::Text};
}
ParamSpec length(std::string_view name, std::optional<double> def, std::string_view help,
                 bool required = false) {
  return {name, "units", required, def, help};
}
ParamSpec count(std::string_view name, std::optional<double> def, std::string_view help) {
  return {name, "", false, def, help};
}

// Parameter i as a whole number in [lo, hi].
int whole(const CommandCall& call, size_t i, int lo, int hi) {
  const double v = *call.number(i);
  if (v != std::round(v) || v < lo || v > hi)
    fail(call.param_loc(i),
         fmt::format("{} ({}) is {}; it must be a whole number from {} to {}",
                     call.spec.params[i].name, call.spec.code, part_number(v), lo, hi));
  return static_cast<int>(v);
}

// Parameter i, which must be above 0; `fallback` when blank (nullopt: it must be given).
double positive(const CommandCall& call, size_t i, std::optional<double> fallback = std::nullopt) {
  const std::optional<double> v = call.number(i) ? call.number(i) : fallback;
  if (!v)
    fail(call.param_loc(i), fmt::format("{} needs its parameter {} ({})", call.spec.code, i + 1,
                                        call.spec.params[i].name));
  if (!(*v > 0))
    fail(call.param_loc(i), fmt::format("{} ({}) is {}; it must be above 0",
                                        call.spec.params[i].name, call.spec.code, part_number(*v)));
  return *v;
}

// Parameter i as an overlap in percent, 0 up to (not including) 100.
double overlap(const CommandCall& call, size_t i, double fallback) {
  const double v = call.number(i).value_or(fallback);
  if (!(v >= 0 && v < 100))
    fail(call.param_loc(i),
         fmt::format("{} ({}) is {} %; it must be from 0 up to (not including) 100",
                     call.spec.params[i].name, call.spec.code, part_number(v)));
  return v;
}

// Parameter i as a choice between 0 and 1.
bool choice(const CommandCall& call, size_t i, std::string_view zero, std::string_view one) {
  const double v = call.number(i).value_or(0);
  if (v != 0 && v != 1)
    fail(call.param_loc(i),
         fmt::format("{} ({}) is {}; it is 0 ({}) or 1 ({})", call.spec.params[i].name,
                     call.spec.code, part_number(v), zero, one));
  return v == 1;
}

// The cutter values of the profile (VC) the tools fall back on when a parameter is blank.
struct Cutter {
  double diameter, safe_z, overlap;
};
Cutter cutter(const CommandContext& ctx) {
  const CutterSettings& c = ctx.settings().cutter;
  return {c.diameter, c.safe_z, c.pocket_overlap};
}

// Safe Z (parameter i): blank is the profile's Safe-Z above `surface`; it must clear it.
double safe_z(const CommandContext& ctx, const CommandCall& call, size_t i, double surface) {
  const double z = call.number(i).value_or(surface + cutter(ctx).safe_z);
  if (!(z > surface))
    fail(call.param_loc(i),
         fmt::format("safe Z ({}) is {}, not above the material surface (Z {}); the tool "
                     "would travel through the material",
                     call.spec.code, part_number(z), part_number(surface)));
  return z;
}

// The Z of each pass, evenly down to `bottom` from `surface`.
std::vector<double> pass_depths(double surface, double bottom, int passes) {
  std::vector<double> z;
  for (int k = 1; k <= passes; ++k) z.push_back(surface + (bottom - surface) * k / passes);
  return z;
}

// ---- the part file a tool writes -----------------------------------------------------------

// A tool's part file: its header, then what the tool writes through PartText.
class PartFile : public PartText {
 public:
  // The first lines: what wrote it, for which machine and units, and the summary `about`.
  PartFile(const CommandContext& ctx, std::string_view code, std::string_view tool,
           const std::vector<std::string>& about) {
    const Settings& s = ctx.settings();
    comment(fmt::format("{} written by Gantry {} ({}) for the machine profile \"{}\"", tool,
                        GANTRY_VERSION, code, s.name));
    comment(fmt::format("Units: {}. Absolute coordinates from working 0 (it sets SA).",
                        units_name(s.units)));
    for (const std::string& a : about) comment(a);
    line("SA");
  }
  // Writes the file through the interpreter (a check keeps it in its sandbox) and tells the
  // operator how to run it.
  void write(CommandContext& ctx, const CommandCall& call, std::string_view what) {
    const std::string name = *call.text(0);
    const std::string path = ctx.write_file(name, text(), call.param_loc(0));
    ctx.print(
        fmt::format("{} wrote {} to {}; run it with FP, {} (`gantry moves {}` lists its "
                    "moves)\n",
                    call.spec.code, what, path, name, path));
  }
};

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

// ---- TT: typesetter ------------------------------------------------------------------------

enum Tt { kTtFile, kTtText, kTtX, kTtY, kTtHeight, kTtDepth, kTtPasses, kTtSafeZ, kTtAngle };

// The text TT engraves: every character printable ASCII, and something to draw.
std::string engraved_text(const CommandCall& call) {
  const std::string text = call.text(kTtText).value_or("");
  for (size_t i = 0; i < text.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (!StrokeFont::glyph(static_cast<char>(c)))
      fail(call.param_loc(kTtText),
           fmt::format("TT: character {} of the text is {}; the font draws the printable ASCII "
                       "characters (space to ~) only",
                       i + 1,
                       c >= 0x80 ? std::string("outside ASCII")
                                 : fmt::format("a control character (code {})", c)));
  }
  if (text.find_first_not_of(' ') == std::string::npos)
    fail(call.param_loc(kTtText), "TT needs some text to engrave (parameter 2)");
  return text;
}

void typesetter(CommandContext& ctx, const CommandCall& call) {
  const std::string text = engraved_text(call);
  const double x0 = *call.number(kTtX), y0 = *call.number(kTtY);
  const double height = positive(call, kTtHeight);
  const double depth = positive(call, kTtDepth);
  const int passes = whole(call, kTtPasses, 1, 1000);
  const double safe = safe_z(ctx, call, kTtSafeZ, 0);
  const double angle = *call.number(kTtAngle);
  const double scale = height / StrokeFont::kCapHeight;
  const double a = angle * std::numbers::pi / 180, ca = std::cos(a), sa = std::sin(a);
  double width = -StrokeFont::kGap;  // the text's, in font units
  for (char c : text) width += StrokeFont::advance(c);

  PartFile f(ctx, "TT", "Typesetter",
             {fmt::format("Text \"{}\": capitals {} tall, {} wide, the baseline from X {}, Y {} "
                          "at {} degrees",
                          text, part_number(height), part_number(width * scale), part_number(x0),
                          part_number(y0), part_number(angle)),
              fmt::format("Engraved {} deep in {} pass{} along the letters' centre lines "
                          "(Gantry's single-stroke font); safe Z {}",
                          part_number(depth), passes, passes == 1 ? "" : "es", part_number(safe))});
  // Font units to working X, Y: scaled, then turned about the start of the baseline.
  auto at = [&](double pen, const std::array<double, 2>& p) {
    const double u = (pen + p[0]) * scale, v = p[1] * scale;
    return std::array<double, 2>{x0 + u * ca - v * sa, y0 + u * sa + v * ca};
  };
  const std::vector<double> levels = pass_depths(0, -depth, passes);
  f.jog_z(safe);
  double pen = 0;
  int strokes = 0;
  for (char c : text) {
    const StrokeGlyph& g = *StrokeFont::glyph(c);
    if (!g.strokes.empty()) f.comment(fmt::format("{}", c));
    for (const auto& stroke : g.strokes) {
      const std::array<double, 2> start = at(pen, stroke.front());
      f.jog_xy(start[0], start[1]);
      for (int k = 0; k < passes; ++k) {  // each pass back along the stroke, one deeper
        f.move_z(levels[k]);
        for (size_t j = 1; j < stroke.size(); ++j) {
          const auto& p = stroke[k % 2 ? stroke.size() - 1 - j : j];
          const std::array<double, 2> q = at(pen, p);
          f.move_xy(q[0], q[1]);
        }
      }
      f.jog_z(safe);
      ++strokes;
    }
    pen += StrokeFont::advance(c);
  }
  f.write(ctx, call,
          fmt::format("{} character{} ({} stroke{})", text.size(), text.size() == 1 ? "" : "s",
                      strokes, strokes == 1 ? "" : "s"));
}

// ---- TH: header writer ---------------------------------------------------------------------

enum Th {
  kThFile,
  kThTitle,
  kThContact,
  kThMaterial,
  kThBlankX,
  kThBlankY,
  kThThickness,
  kThBit,
  kThZero,
  kThNotes,
  kThFirst,
  kThLast
};

constexpr std::string_view kHeaderBegin = "'---- Header (Gantry TH) ----";
constexpr std::string_view kHeaderEnd = "'---- End of header ----";
constexpr std::string_view kLastBegin = "'---- Run last (Gantry TH) ----";

// `text` without the header and the closing FP a previous TH wrote.
std::string without_old_header(std::string text, const CommandCall& call, const std::string& path) {
  if (text.starts_with(kHeaderBegin)) {
    const size_t end = text.find(kHeaderEnd);
    if (end == std::string::npos)
      fail(call.param_loc(kThFile),
           fmt::format("{} starts with a header TH wrote but its end line ({}) is gone; remove "
                       "the old header by hand, then run TH again",
                       path, kHeaderEnd));
    const size_t next = text.find('\n', end);
    text.erase(0, next == std::string::npos ? text.size() : next + 1);
  }
  const size_t last = text.rfind(kLastBegin);
  if (last != std::string::npos && (last == 0 || text[last - 1] == '\n')) {
    const size_t fp = text.find('\n', last);  // the FP line follows, and nothing after it
    const size_t after = fp == std::string::npos ? fp : text.find('\n', fp + 1);
    if (fp != std::string::npos &&
        (after == std::string::npos || text.find_first_not_of("\r\n", after) == std::string::npos))
      text.erase(last);
  }
  return text;
}

std::string quoted_file(const CommandCall& call, size_t i) {
  const std::string name = *call.text(i);
  if (name.find('"') != std::string::npos)
    fail(call.param_loc(i), "a file name for FP cannot hold a double quote");
  return fmt::format("FP, \"{}\"", name);
}

void header_writer(CommandContext& ctx, const CommandCall& call) {
  std::string path;
  const std::optional<std::string> old =
      ctx.read_file(*call.text(kThFile), call.param_loc(kThFile), &path);
  if (!old)
    fail(call.param_loc(kThFile),
         fmt::format("cannot read {}; TH adds a header to an existing part file", path));
  constexpr std::string_view kBom = "\xEF\xBB\xBF";  // kept first, where a reader looks for it
  const bool bom = old->starts_with(kBom);
  const std::string body = without_old_header(old->substr(bom ? kBom.size() : 0), call, path);
  const std::string eol = old->find("\r\n") != std::string::npos ? "\r\n" : "\n";
  const Settings& s = ctx.settings();
  std::vector<std::string> lines = {std::string(kHeaderBegin)};
  auto field = [&](std::string_view label, size_t i) {
    if (const std::optional<std::string> v = call.text(i); v && !v->empty())
      lines.push_back(fmt::format("' {}: {}", label, *v));
  };
  field("Title", kThTitle);
  field("Contact", kThContact);
  field("Material", kThMaterial);
  std::string blank;
  const std::pair<std::string_view, size_t> sizes[] = {
      {"X", kThBlankX}, {"Y", kThBlankY}, {"thickness", kThThickness}};
  for (const auto& [label, i] : sizes)
    if (const std::optional<double> v = call.number(i))
      blank += fmt::format("{}{} {}", blank.empty() ? "" : ", ", label, part_number(*v));
  if (!blank.empty()) lines.push_back(fmt::format("' Blank: {} {}", blank, units_name(s.units)));
  field("Bit", kThBit);
  if (call.number(kThZero))
    lines.push_back(fmt::format("' Z zero: {}", choice(call, kThZero, "surface", "table top")
                                                    ? "the table top"
                                                    : "the material surface"));
  field("Notes", kThNotes);
  const std::time_t now = std::time(nullptr);
  std::tm day{};
  localtime_r(&now, &day);
  char date[16];
  std::strftime(date, sizeof date, "%Y-%m-%d", &day);
  lines.push_back(fmt::format("' Units: {}; machine profile \"{}\"", units_name(s.units), s.name));
  lines.push_back(fmt::format("' Header written {} by Gantry {} (TH)", date, GANTRY_VERSION));
  if (call.text(kThFirst) && !call.text(kThFirst)->empty())
    lines.push_back(quoted_file(call, kThFirst));
  lines.push_back(std::string(kHeaderEnd));
  std::string text(bom ? kBom : "");
  for (const std::string& l : lines) text += l + eol;
  text += body;
  if (call.text(kThLast) && !call.text(kThLast)->empty()) {
    if (!text.empty() && text.back() != '\n') text += eol;
    text += std::string(kLastBegin) + eol + quoted_file(call, kThLast) + eol;
  }
  const std::string written = ctx.write_file(*call.text(kThFile), text, call.param_loc(kThFile));
  ctx.print(fmt::format("TH wrote a header of {} lines to {}\n", lines.size(), written));
}

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

// ---- TI: indexer ----------------------------------------------------------------------------

enum Ti { kTiFile, kTiPart, kTiAxis, kTiDivisions, kTiStart, kTiSafeZ };

// Writes a part file that runs another one at each of `divisions` equal turns of a rotary
// axis (a column fluted all round, a pattern on each face): up to safe Z, index, run it.
// SB3 names TI without describing it; this is what an indexer's virtual tool is for.
void indexer(CommandContext& ctx, const CommandCall& call) {
  const std::string part = *call.text(kTiPart);
  const std::string axis = ascii::upper(call.text(kTiAxis).value_or("B"));
  const int n = whole(call, kTiDivisions, 1, 3600);
  const double start = call.number(kTiStart).value_or(0);
  const double safe = safe_z(ctx, call, kTiSafeZ, 0);
  PartFile f(ctx, "TI", "Indexer",
             {fmt::format("Runs {} at {} position{} of {}, {} degrees apart from {}", part, n,
                          n == 1 ? "" : "s", axis, part_number(360.0 / n), part_number(start)),
              fmt::format("Safe Z {} before each turn", part_number(safe))});
  for (int k = 0; k < n; ++k) {
    f.comment(fmt::format("Position {} of {}", k + 1, n));
    f.jog_z(safe);
    f.line(fmt::format("J{}, {}", axis, part_number(start + 360.0 * k / n)));
    f.line(fmt::format("FP, {}", part));
  }
  f.jog_z(safe);
  f.write(ctx, call, fmt::format("{} at {} positions of {}", part, n, axis));
}

}  // namespace

void add_tool_commands(std::vector<CommandSpec>& out) {
  const auto T = CommandGroup::Tools;
  const ParamSpec safe = length("safe Z", std::nullopt,
                                "Z of the moves between cuts (blank: the profile's safe Z above "
                                "the surface).");
  const ParamSpec passes = count("passes", 1.0, "Cuts to the full depth, evenly deeper.");
  const ParamSpec bit =
      length("bit diameter", std::nullopt, "The cutter (blank: cutter.diameter of the profile).");
  const ParamSpec over = {"overlap", "%", false, std::nullopt,
                          "Of the bit, between neighbouring paths (blank: the profile's "
                          "cutter.pocket_overlap)."};
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
      {"TH",
       "Tools: header writer",
       T,
       "Adds a comment header to a part file: the given fields, the units, the machine profile "
       "and the date, and optionally FP lines that run a file first and last. A header TH "
       "wrote before is replaced.",
       {file_param("The part file to add the header to."),
        {"title", "", false, std::nullopt, "What the file makes.", ParamKind::Text},
        {"contact", "", false, std::nullopt, "Who to ask; use restrictions.", ParamKind::Text},
        {"material", "", false, std::nullopt, "The material.", ParamKind::Text},
        length("blank X", std::nullopt, "Blank size in X."),
        length("blank Y", std::nullopt, "Blank size in Y."),
        length("thickness", std::nullopt, "Blank thickness."),
        {"bit", "", false, std::nullopt, "Bit size and type.", ParamKind::Text},
        count("Z zero", std::nullopt, "0 the material surface, 1 the table top (blank: not said)."),
        {"notes", "", false, std::nullopt, "Anything else (offsets used, ...).", ParamKind::Text},
        {"run first", "", false, std::nullopt, "A part file run (FP) before the file's own lines.",
         ParamKind::Text},
        {"run last", "", false, std::nullopt, "A part file run (FP) after them.", ParamKind::Text}},
       header_writer});
  out.push_back(
      {"TI",
       "Tools: indexer",
       T,
       "Writes a part file that runs another at equal turns of a rotary axis: up to safe Z, "
       "turn, run it, for each division. Run the file it writes with FP.",
       {file_param("The part file to write; a relative name goes beside this file."),
        {"part file", "", true, std::nullopt, "The part file to run at each position.",
         ParamKind::Text},
        ParamSpec{"axis", "", false, std::nullopt, "A or B (blank: B).", ParamKind::Text}.one_of(
            "A B"),
        count("divisions", 4.0, "Equal positions in a turn."),
        {"start angle", "deg", false, 0.0, "The first position."},
        length("safe Z", std::nullopt, "Z before each turn (blank: the profile's safe Z).")},
       indexer});
  out.push_back({"TS",
                 "Tools: ShopBot setup",
                 T,
                 "Prints the machine's setup: profile, units, card, each axis's steps per unit, "
                 "speed and travel, the current speeds and the cutter.",
                 {},
                 setup,
                 "entering the setup (it is the machine profile's) and calibrating zeroing with "
                 "a zero plate or proximity switches"});
  out.push_back(
      {"TT",
       "Tools: typesetter",
       T,
       "Writes a part file that engraves a line of text: each letter of Gantry's own "
       "single-stroke font (every printable ASCII character) followed along its centre line "
       "at the depth, one pass deeper each way, lifting to safe Z between strokes. Run the "
       "file with FP.",
       {file_param("The part file to write; a relative name goes beside this file."),
        {"text", "", true, std::nullopt,
         "What to engrave; in double quotes when it holds commas or leading blanks.",
         ParamKind::Text},
        length("X start", 0.0, "Where the baseline of the first letter starts."),
        length("Y start", 0.0, "Where the baseline of the first letter starts."),
        length("height", std::nullopt, "Of the capitals and digits (lower case: 2/3 of it).", true),
        length("depth", std::nullopt, "Below the surface (Z 0), above 0.", true),
        passes,
        safe,
        {"angle", "deg", false, 0.0,
         "Of the baseline, counter-clockwise from +X, about the start."}},
       typesetter,
       "V-carving the outlines of installed fonts (it engraves its own single-stroke font at "
       "one depth); more than one line of text per file"});
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

}  // namespace gantry
