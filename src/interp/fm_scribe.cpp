// G10 / G16 / G19, Friendly Motion's character scribing (docs/friendlymotion.md, "Data files,
// scribed text and the display").
#include "gantry/interp/fm_scribe.hpp"

#include <fmt/format.h>

#include <cmath>    // isfinite, trunc
#include <cstdio>   // snprintf
#include <utility>  // pair

#include "gantry/commands/stroke_font.hpp"
#include "gantry/core/text.hpp"  // ascii::upper, ascii::lower

namespace gantry {
namespace {

constexpr double kLineSpacing = 1.5;  // between two lines' baselines, in character heights
constexpr std::string_view kPunctuation = "!#'*+,-./:;<=>[\\]^";

SourceLoc at_column(const SourceLoc& text_loc, std::size_t index) {
  SourceLoc l = text_loc;
  if (l.column > 0) l.column += static_cast<int>(index);
  return l;
}

// printf with one value through a format built from checked parts.
template <typename T>
std::string printf_one(const std::string& format, T value) {
  const int n = std::snprintf(nullptr, 0, format.c_str(), value);
  std::string out(static_cast<std::size_t>(n > 0 ? n : 0), '\0');
  std::snprintf(out.data(), out.size() + 1, format.c_str(), value);
  return out;
}

// The text with its variable put in, and for each character of it the index in `text` it
// came from (an inserted character: the %'s), so an error can point at the right column.
struct Expanded {
  std::string text;
  std::vector<std::size_t> from;
  std::size_t insert_begin = 0, insert_end = 0;  // the inserted characters, [begin, end)
  char conversion = 0;
};

Expanded expand(std::string_view text, double v73, std::string_view s0, const SourceLoc& loc) {
  Expanded e;
  const std::size_t pct = text.find('%');
  auto copy = [&](std::size_t from, std::size_t to) {
    for (std::size_t i = from; i < to; ++i) {
      e.text += text[i];
      e.from.push_back(i);
    }
  };
  if (pct == std::string_view::npos) {
    copy(0, text.size());
    e.insert_begin = e.insert_end = e.text.size();
    return e;
  }
  std::size_t k = pct + 1;
  const std::size_t flags_at = k;
  while (k < text.size() && std::string_view("-+ 0#").find(text[k]) != std::string_view::npos) ++k;
  const std::string flags(text.substr(flags_at, k - flags_at));
  const std::size_t width_at = k;
  while (k < text.size() && text[k] >= '0' && text[k] <= '9') ++k;
  const std::string width(text.substr(width_at, k - width_at));
  std::string precision;
  bool has_precision = false;
  if (k < text.size() && text[k] == '.') {
    has_precision = true;
    const std::size_t p = ++k;
    while (k < text.size() && text[k] >= '0' && text[k] <= '9') ++k;
    precision = std::string(text.substr(p, k - p));
  }
  if (width.size() > 2 || precision.size() > 2)
    fail(at_column(loc, pct), "G16: a width or precision in a % has at most two digits");
  if (k >= text.size())
    fail(at_column(loc, pct),
         "G16: a % is followed by s (the string @0), i, f or c (V73), with printf's flags, "
         "width and precision between them");
  const char conv = ascii::lower(text[k]);
  if (std::string_view("sifc").find(conv) == std::string_view::npos)
    fail(at_column(loc, k),
         fmt::format("G16: %{} puts in nothing: %s puts in the string @0, %i, %f and %c V73",
                     text[k]));
  const std::string_view allowed = conv == 'f' ? "-+ 0#" : conv == 'i' ? "-+ 0" : "-";
  for (char f : flags)
    if (allowed.find(f) == std::string_view::npos)
      fail(at_column(loc, pct),
           fmt::format("G16: printf's flag '{}' does not apply to %{}", f, text[k]));
  if (has_precision && conv == 'c') fail(at_column(loc, pct), "G16: %c takes no precision");
  const std::string spec = "%" + flags + width + (has_precision ? "." + precision : "");
  if (conv != 's' && !std::isfinite(v73))
    fail(at_column(loc, pct), fmt::format("G16: V73 is {}, not a number to put in", v73));

  std::string value;
  switch (conv) {
    case 's':
      value = printf_one(spec + "s", std::string(s0).c_str());
      break;
    case 'i': {
      const double whole = std::trunc(v73);  // the manual: 66.55 is 66
      if (std::fabs(whole) > 1e15)
        fail(at_column(loc, pct), fmt::format("G16: V73 = {} is too large for %i", v73));
      value = printf_one(spec + "lld", static_cast<long long>(whole));
      break;
    }
    case 'f':
      // The manual's bare %f shows 66.55 where C would print 66.550000: its shortest form.
      value = flags.empty() && width.empty() && !has_precision ? fmt::format("{}", v73)
                                                               : printf_one(spec + "f", v73);
      break;
    default: {  // 'c'
      const double code = std::trunc(v73);
      if (code < 32 || code > 126)
        fail(at_column(loc, pct),
             fmt::format("G16: %c puts in the character whose code V73 holds, and {} is not a "
                         "printable character's (32 to 126)",
                         code));
      value = printf_one(spec + "c", static_cast<int>(code));
      break;
    }
  }
  if (const std::size_t second = text.find('%', k + 1); second != std::string_view::npos)
    fail(at_column(loc, second),
         "G16 puts in one variable only (the manual); use one G16 for each variable");
  copy(0, pct);
  e.insert_begin = e.text.size();
  for (char c : value) {
    e.text += c;
    e.from.push_back(pct);
  }
  e.insert_end = e.text.size();
  e.conversion = text[k];
  copy(k + 1, text.size());
  return e;
}

}  // namespace

double fm_character_height(double g19, bool metric, const SourceLoc& loc) {
  if (!std::isfinite(g19) || !(g19 > 0))
    fail(loc, fmt::format("G19{}: the characters' size must be above 0 (1 is 1 inch high)", g19));
  return g19 * (metric ? 25.4 : 1.0);
}

void fm_select_font(std::string_view name, const SourceLoc& loc) {
  const std::size_t slash = name.find_last_of("/\\");
  const std::string base =
      ascii::lower(slash == std::string_view::npos ? name : name.substr(slash + 1));
  if (base == "fontfile.txt" || base == "fontfile") return;
  fail(loc, fmt::format("G10\"{}\": Gantry cannot read another font file: the manual does not "
                        "give the font file's format (U.S. Laser gave it on request), so G16 "
                        "scribes with Gantry's own stroke font, its stand-in for the default "
                        "fontfile.txt",
                        name));
}

bool fm_scribable(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == ' ' ||
         kPunctuation.find(c) != std::string_view::npos;
}

std::string fm_scribe_insert(std::string_view text, double v73, std::string_view s0,
                             const SourceLoc& text_loc) {
  return expand(text, v73, s0, text_loc).text;
}

FmScribePath fm_scribe(std::string_view text, double v73, std::string_view s0,
                       const FmScribeStyle& style, const SourceLoc& text_loc) {
  if (!std::isfinite(style.height) || !(style.height > 0) || !std::isfinite(style.width_ratio) ||
      !(style.width_ratio > 0))
    fail(text_loc, fmt::format("G16: the characters' height ({}) and width ratio ({}) must be "
                               "above 0",
                               style.height, style.width_ratio));
  if (text.empty()) fail(text_loc, "G16 has no text to scribe");
  const Expanded e = expand(text, v73, s0, text_loc);
  // Font units to program units: capitals are kCapHeight tall, and a standard character (the
  // H) is width_ratio of the height wide, so the font's own 6:4 becomes the manual's 2:1.
  const double ky = style.height / StrokeFont::kCapHeight;
  const double kx = style.height * style.width_ratio / StrokeFont::glyph('H')->width;
  FmScribePath path;
  double pen = 0, baseline = 0;  // pen in font units along the line; baseline in program units
  for (std::size_t i = 0; i < e.text.size(); ++i) {
    char c = e.text[i];
    if (c == ')') {
      pen = 0;
      baseline -= kLineSpacing * style.height;
      continue;
    }
    if (c == '_') c = ' ';
    if (c >= 'a' && c <= 'z') c = ascii::upper(c);
    if (!fm_scribable(c)) {
      const bool inserted = i >= e.insert_begin && i < e.insert_end;
      const std::string shown =
          c >= ' ' && c <= '~'
              ? fmt::format("'{}'", c)
              : fmt::format("the byte {}", static_cast<int>(static_cast<unsigned char>(c)));
      fail(at_column(text_loc, e.from[i]),
           fmt::format("G16 cannot scribe {}{}: the character set is A-Z, 0-9 and {} (_ is a "
                       "space, ) a new line, % puts in a variable)",
                       shown, inserted ? fmt::format(" (put in by %{})", e.conversion) : "",
                       kPunctuation));
    }
    const StrokeGlyph& g = *StrokeFont::glyph(c);
    for (const auto& stroke : g.strokes) {
      std::vector<FmPoint>& out = path.strokes.emplace_back();
      for (const auto& p : stroke) out.push_back({(pen + p[0]) * kx, baseline + p[1] * ky});
    }
    pen += StrokeFont::advance(c);
  }
  path.end = {pen * kx, baseline};
  return path;
}

}  // namespace gantry
