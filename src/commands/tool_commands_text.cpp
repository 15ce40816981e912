// The typesetter (TT): a part file that engraves text in Gantry's own single-stroke font.
#include <fmt/format.h>  // the part files' text, messages

#include <cmath>    // sin, cos
#include <numbers>  // pi
#include <string>
#include <vector>

#include "gantry/commands/command_table.hpp"
#include "gantry/commands/stroke_font.hpp"  // TT's letters
#include "gantry/interp/command_context.hpp"
#include "tool_commands.hpp"  // the tools' parameters, PartFile

namespace gantry::tools {
namespace {

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

}  // namespace

void add_text_tools(std::vector<CommandSpec>& out) {
  const auto T = CommandGroup::Tools;
  const ParamSpec safe = safe_z_param();
  const ParamSpec passes = passes_param();
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
}

}  // namespace gantry::tools
