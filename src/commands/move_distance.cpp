// MD: a move of a given length in a given direction from where the tool is.
#include "gantry/commands/move_distance.hpp"

#include <fmt/format.h>  // messages

#include <array>
#include <charconv>  // from_chars
#include <cmath>     // sin, cos, atan2, fmod
#include <string>

#include "gantry/commands/command_table.hpp"
#include "gantry/interp/command_context.hpp"

namespace gantry {
namespace {

std::optional<double> number(std::string_view t) {
  double v = 0;
  const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
  if (t.empty() || r.ec != std::errc{} || r.ptr != t.data() + t.size()) return std::nullopt;
  return v;
}

// The 16 points of the compass, clockwise from N, 22.5 degrees apart.
constexpr std::array<std::string_view, 16> kCompass = {"N",  "NNE", "NE", "ENE", "E",  "ESE",
                                                       "SE", "SSE", "S",  "SSW", "SW", "WSW",
                                                       "W",  "WNW", "NW", "NNW"};

// MD, length, angle, z change: at move speed, from the current location.
void move_distance(CommandContext& ctx, const CommandCall& call) {
  const double length = *call.number(0);
  const std::string angle = call.text(1).value_or("");
  std::optional<double> last;  // the last XY move's heading, clockwise from +Y
  if (const auto& d = ctx.state().last_xy_move) last = std::atan2((*d)[0], (*d)[1]) * 180 / M_PI;
  const std::optional<double> heading = md_heading(angle, last);
  if (!heading)
    fail(call.param_loc(1),
         fmt::format("MD angle '{}' is not degrees (90), degrees right or left of the last move "
                     "(30R, 45L), a clock time (3:00) or a compass point (N, NE, SSW)",
                     angle));
  const double rad = *heading * M_PI / 180;
  Vec6 target = ctx.position();
  target[0] += length * std::sin(rad);
  target[1] += length * std::cos(rad);
  if (const std::optional<std::string> z = call.text(2)) {
    // A number is where Z goes; a number then U or D moves it up or down by that much.
    const char last = z->empty() ? ' ' : static_cast<char>(std::toupper(z->back()));
    const bool by = last == 'U' || last == 'D';
    const std::optional<double> v = number(by ? std::string_view(*z).substr(0, z->size() - 1) : *z);
    if (!v)
      fail(call.param_loc(2), fmt::format("MD Z change '{}' is not a Z location (0.5) or an "
                                          "amount up or down (0.25U, 0.1D)",
                                          *z));
    target[2] = by ? target[2] + (last == 'U' ? *v : -*v) : *v;
  }
  ctx.line_to(target, SpeedClass::Move, call.loc);
}

}  // namespace

std::optional<double> md_heading(std::string_view text, std::optional<double> last) {
  std::string t;
  for (char c : text)
    if (c != ' ') t += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  if (t.empty()) return std::nullopt;
  if (const size_t colon = t.find(':'); colon != std::string::npos) {  // clock time
    const std::optional<double> h = number(std::string_view(t).substr(0, colon));
    const std::optional<double> m = number(std::string_view(t).substr(colon + 1));
    if (!h || !m || *m < 0 || *m >= 60) return std::nullopt;
    return std::fmod(30 * *h + 0.5 * *m, 360);
  }
  for (size_t k = 0; k < kCompass.size(); ++k)
    if (t == kCompass[k]) return 22.5 * static_cast<double>(k);
  if (t.back() == 'R' || t.back() == 'L') {  // relative to the last move
    const std::optional<double> d = number(std::string_view(t).substr(0, t.size() - 1));
    if (!d) return std::nullopt;
    if (!last) return *d;  // no previous segment: SB3 ignores the R or L
    return std::fmod(*last + (t.back() == 'R' ? *d : -*d) + 720, 360);
  }
  return number(t);
}

void add_move_distance(std::vector<CommandSpec>& out) {
  out.push_back(
      {"MD",
       "Move distance",
       CommandGroup::Move,
       "Moves the given length in the given direction from where the tool is, at move speed.",
       {{"length", "units", true, std::nullopt, "How far to move."},
        {"angle", "", true, std::nullopt,
         "Degrees clockwise from +Y (90 is +X), or 30R / 45L from the last move, a clock time "
         "(3:00), or a compass point (N, SSW).",
         ParamKind::Text},
        {"z change", "", false, std::nullopt, "A Z location, or an amount up or down: 0.25U, 0.1D.",
         ParamKind::Text}},
       move_distance});
}

}  // namespace gantry
