// The cut commands CA, CC, CG, CP and CR: each reads its parameters, asks its generator in
// src/cuts for the tool path, checks the whole path against the soft limits, then sends it.
#include <fmt/format.h>  // messages

#include <cctype>  // toupper
#include <cmath>   // lround

#include "gantry/commands/command_table.hpp"
#include "gantry/cuts/cuts.hpp"
#include "gantry/interp/command_context.hpp"

namespace gantry {
namespace {

using cuts::CutPath;
using cuts::V2;
using cuts::V3;

ParamSpec num(std::string_view name, std::string_view unit, std::optional<double> def,
              std::string_view help) {
  return {name, unit, false, def, help};
}
ParamSpec required(std::string_view name, std::string_view help) {
  return {name, "units", true, std::nullopt, help};
}
ParamSpec flag(std::string_view name, std::string_view help) {
  return num(name, "", 0.0, help).integer(0, 1);
}

ParamSpec side() {
  return ParamSpec{"O/I/T",
                   "",
                   false,
                   std::nullopt,
                   "Where the cutter runs: O outside the size given (a part of that size), I "
                   "inside it (a hole of that size), T (default) on it.",
                   ParamKind::Text}
      .one_of("O I T");
}
ParamSpec direction() {
  return num("direction", "", 1.0, "1 clockwise, -1 counter-clockwise.").integer(-1, 1);
}
ParamSpec plunge() {
  return num("plunge", "units", 0.0, "Z change before each pass; negative goes down.");
}
ParamSpec repetitions() {
  return num("repetitions", "", 1.0, "Passes, each one plunge deeper.").integer(1, 1e6);
}
ParamSpec proportion(std::string_view axis) {
  return num(axis == "X" ? "proportion X" : "proportion Y", "", 1.0,
             axis == "X" ? "Scale in X: with proportion Y, makes an ellipse." : "Scale in Y.")
      .at_least(0);
}
ParamSpec feature() {
  return num("feature", "", 0.0,
             "1 tabs on the last pass (VB), 2 pocket, 3 spiral plunge, 4 spiral plunge and a "
             "bottom pass.")
      .integer(0, 4);
}
ParamSpec no_pull_up() {
  return flag("no pull up",
              "0 (default): at the end Z goes back to where the command started, if the cut "
              "changed it; 1 leaves the tool at its last depth.");
}
ParamSpec from_zero() {
  return flag("plunge from Z 0", "1 moves Z to 0 first and measures the plunges from there.");
}

// A circle-like command's options after its shape, from parameter `first` on.
cuts::PassOptions pass_options(const CommandCall& call, size_t first) {
  cuts::PassOptions o;
  o.plunge = *call.number(first);
  o.repetitions = static_cast<int>(std::lround(*call.number(first + 1)));
  o.feature = static_cast<int>(std::lround(*call.number(first + 4)));
  o.no_pull_up = *call.number(first + 5) != 0;
  o.from_zero = *call.number(first + 6) != 0;
  return o;
}

cuts::Side side_of(const CommandCall& call, size_t i) {
  const std::string t = call.text(i).value_or("T");
  const char c =
      t.empty() ? 'T' : static_cast<char>(std::toupper(static_cast<unsigned char>(t[0])));
  return c == 'O' ? cuts::Side::Out : c == 'I' ? cuts::Side::In : cuts::Side::True;
}

int whole(const CommandCall& call, size_t i) {
  return static_cast<int>(std::lround(*call.number(i)));
}

cuts::CutSetup setup_for(CommandContext& ctx) {
  const Vec6 at = ctx.position();
  cuts::CutSetup s = cuts::CutSetup::from(ctx.settings(), V3(at[0], at[1], at[2]));
  // VB's tabbing in the file, or FP's tab feature (its last repetition): tabs on every cut.
  const ModalState& st = ctx.state();
  s.file_tabs = st.tabs_on || ctx.file_tabs();
  s.first_tab = st.tabs_on ? st.first_tab : 0;  // FP's: one spacing from the start
  s.tabs_left = st.tabs_on ? st.tab_count : 0;
  return s;
}

// Runs a generator; a parameter it cannot use is an error located at that parameter.
template <class Generate>
CutPath generate(const CommandCall& call, Generate&& g) {
  try {
    return g();
  } catch (const cuts::CutError& e) {
    const auto& params = call.spec.params;
    const std::string_view name = e.param < params.size() ? params[e.param].name : "";
    fail(call.param_loc(e.param), fmt::format("{} parameter {} ({}): {}; nothing was moved",
                                              call.spec.code, e.param + 1, name, e.what()));
  }
}

// Sends the path. Every point it reaches (arcs' extreme points included) is checked first,
// so a path that leaves the soft limits anywhere moves nothing.
void emit(CommandContext& ctx, const CutPath& path, const CommandCall& call) {
  const Vec6 base = ctx.position();
  auto point = [&](const V3& p) {
    Vec6 v = base;
    v.head<3>() = p;
    return v;
  };
  V3 at = path.start;
  for (const cuts::CutMove& m : path.moves) {
    ctx.check_reach(point(m.to), call.loc);
    if (m.arc)
      for (const V2& e : cuts::arc_extremes(at.head<2>(), m.centre, m.sweep))
        ctx.check_reach(point(V3(e.x(), e.y(), at.z())), call.loc);
    at = m.to;
  }
  const CommandContext::OwnTabs own(ctx);  // the path's tabs are in it already
  for (const cuts::CutMove& m : path.moves) {
    if (m.arc)
      ctx.arc_to(point(m.to), m.centre.x(), m.centre.y(), m.sweep, m.speed(), call.loc);
    else
      ctx.line_to(point(m.to), m.speed(), call.loc);
  }
  // VB's tab count is a number of tabs after an ON: once used up, tabbing is off.
  ModalState& st = ctx.state();
  if (st.tabs_on && st.tab_count > 0 && path.tabs > 0) {
    st.tab_count = std::max(0, st.tab_count - path.tabs);
    if (st.tab_count == 0) st.tabs_on = false;
  }
}

void cut_circle(CommandContext& ctx, const CommandCall& call) {
  cuts::CircleParams p;
  p.diameter = *call.number(0);
  p.side = side_of(call, 1);
  p.direction = whole(call, 2);
  p.begin = call.number(3);
  p.end = call.number(4);
  p.proportion_x = *call.number(7);
  p.proportion_y = *call.number(8);
  p.pass = pass_options(call, 5);
  const cuts::CutSetup setup = setup_for(ctx);
  emit(ctx, generate(call, [&] { return cuts::cut_circle(setup, p); }), call);
}

void cut_center_circle(CommandContext& ctx, const CommandCall& call) {
  cuts::CenterCircleParams p;
  p.diameter = *call.number(0);
  p.center = V2(*call.number(1), *call.number(2));
  if (!ctx.state().absolute) p.center += ctx.position().head<2>();  // SR: from here
  p.side = side_of(call, 3);
  p.direction = whole(call, 4);
  p.begin = *call.number(5);
  p.end = *call.number(6);
  p.proportion_x = *call.number(9);
  p.proportion_y = *call.number(10);
  p.pass = pass_options(call, 7);
  const cuts::CutSetup setup = setup_for(ctx);
  emit(ctx, generate(call, [&] { return cuts::cut_center_circle(setup, p); }), call);
}

void cut_gcode_arc(CommandContext& ctx, const CommandCall& call) {
  cuts::GcodeArcParams p;
  const Vec6 here = ctx.position();
  p.diameter = call.number(0);
  // A blank end coordinate is the start's; SR makes the end relative to the start.
  for (int i = 0; i < 2; ++i) {
    const std::optional<double> v = call.number(1 + i);
    p.end[i] = !v ? here[i] : ctx.state().absolute ? *v : here[i] + *v;
  }
  std::array<double, 2>& modal = ctx.state().cg_center_offset;
  if (!p.diameter)  // I and J are modal; with a diameter they are ignored
    for (int i = 0; i < 2; ++i)
      if (const std::optional<double> v = call.number(3 + i)) modal[i] = *v;
  p.center_offset = V2(modal[0], modal[1]);
  p.side = side_of(call, 5);
  p.direction = whole(call, 6);
  p.proportion_x = *call.number(9);
  p.proportion_y = *call.number(10);
  p.pass = pass_options(call, 7);
  const cuts::CutSetup setup = setup_for(ctx);
  emit(ctx, generate(call, [&] { return cuts::cut_gcode_arc(setup, p); }), call);
}

void cut_arch(CommandContext& ctx, const CommandCall& call) {
  cuts::ArchParams p;
  p.length = *call.number(0);
  p.height = *call.number(1);
  p.side = side_of(call, 2);
  p.direction = whole(call, 3);
  p.alignment = *call.number(4);
  p.proportion_x = *call.number(7);
  p.proportion_y = *call.number(8);
  // FabMo skips parameter 10 (it has no tabs); SB3's is the tab switch.
  p.tabs = ctx.settings().dialect == Dialect::SB3 && call.number(9).value_or(0) != 0;
  p.pass.plunge = *call.number(5);
  p.pass.repetitions = whole(call, 6);
  p.pass.no_pull_up = *call.number(10) != 0;
  p.pass.from_zero = *call.number(11) != 0;
  const cuts::CutSetup setup = setup_for(ctx);
  emit(ctx, generate(call, [&] { return cuts::cut_arch(setup, p); }), call);
}

void cut_rectangle(CommandContext& ctx, const CommandCall& call) {
  cuts::RectParams p;
  p.length_x = *call.number(0);
  p.length_y = call.number(1);
  p.side = side_of(call, 2);
  p.direction = whole(call, 3);
  p.corner = whole(call, 4);
  p.plunge = *call.number(5);
  p.repetitions = whole(call, 6);
  p.feature = whole(call, 7);
  p.from_zero = *call.number(8) != 0;
  const cuts::CutSetup setup = setup_for(ctx);
  emit(ctx, generate(call, [&] { return cuts::cut_rectangle(setup, p); }), call);
}

std::vector<ParamSpec> arch_params(bool fabmo) {
  return {required("arch length", "Span from the start to the other end of the arch.").at_least(0),
          required("arch height",
                   "Rise of the arch above its span: at most half the length (a half "
                   "circle).")
              .at_least(0),
          side(),
          direction(),
          num("alignment angle", "deg", 0.0,
              "Direction of the span, clockwise from +X: 0 runs right, 90 runs down."),
          plunge(),
          repetitions(),
          proportion("X"),
          proportion("Y"),
          fabmo ? num("skip", "", std::nullopt, "Unused in FabMo's order (it has no tabs).")
                : flag("tabs", "1 leaves tabs (VB) on the last pass."),
          no_pull_up(),
          from_zero()};
}

}  // namespace

void add_cut_commands(std::vector<CommandSpec>& out) {
  const auto C = CommandGroup::Cuts;
  out.push_back({"CA", "Cut arch", C,
                 "Cuts an arch of a given span and height from where the tool is: the arc of the "
                 "circle through both ends of the span and the top of the arch.",
                 arch_params(false), cut_arch, "", arch_params(true)});
  out.push_back(
      {"CC",
       "Cut circle",
       C,
       "Cuts a circle, an arc or (with proportions) an ellipse whose path starts where the tool "
       "is, at the begin angle (degrees clockwise from 12 o'clock).",
       {required("diameter", "Diameter of the circle.").at_least(0), side(), direction(),
        num("begin angle", "deg", std::nullopt,
            "Where on the circle the tool is; blank: 0 clockwise, 360 counter-clockwise."),
        num("end angle", "deg", std::nullopt, "Where the cut ends; blank: a full circle."),
        plunge(), repetitions(), proportion("X"), proportion("Y"), feature(), no_pull_up(),
        from_zero()},
       cut_circle});
  out.push_back(
      {"CG",
       "Cut G-code circle",
       C,
       "Cuts an arc (a G2/G3) from where the tool is to an end point, about a centre given by "
       "its offset from the start, or by a diameter (then the arc under 180 degrees).",
       {num("diameter", "units", std::nullopt,
            "Blank: use I and J. Given: the arc of this diameter under 180 degrees.")
            .at_least(0),
        num("X end", "units", std::nullopt,
            "End point X (SR: from the start); blank: the start's."),
        num("Y end", "units", std::nullopt,
            "End point Y (SR: from the start); blank: the start's."),
        num("X center offset", "units", std::nullopt,
            "I: centre X from the start; blank: the last."),
        num("Y center offset", "units", std::nullopt,
            "J: centre Y from the start; blank: the last."),
        side(), direction(), plunge(), repetitions(), proportion("X"), proportion("Y"), feature(),
        no_pull_up(), from_zero()},
       cut_gcode_arc});
  out.push_back(
      {"CP",
       "Cut circle from center point",
       C,
       "Cuts a circle or arc about a given centre: the tool first moves, at its "
       "current height, to the point of the path at the start angle.",
       {required("diameter", "Diameter of the circle.").at_least(0),
        required("X center", "Centre X (SR: from here)."),
        required("Y center", "Centre Y (SR: from here)."), side(), direction(),
        num("start angle", "deg", 0.0, "Where the cut starts, clockwise from 12 o'clock."),
        num("end angle", "deg", 0.0, "Where it ends; equal to the start: a full circle."), plunge(),
        repetitions(), proportion("X"), proportion("Y"), feature(), no_pull_up(), from_zero()},
       cut_center_circle});
  out.push_back(
      {"CR",
       "Cut rectangle",
       C,
       "Cuts a rectangle whose start corner is where the tool is; Z then goes back to where it "
       "started, if the cut changed it.",
       {required("length X", "Width.").at_least(0),
        num("length Y", "units", std::nullopt, "Height; blank: a square.").at_least(0), side(),
        direction(),
        num("start corner", "", 4.0,
            "Corner the tool is at: 1 upper left, 2 upper right, 3 lower right, 4 lower left.")
            .integer(1, 4),
        plunge(), repetitions(),
        num("feature", "", 0.0,
            "1 tabs on the last pass (VB), 2 pocket from the outside in, 3 pocket from the "
            "inside out.")
            .integer(0, 3),
        from_zero()},
       cut_rectangle});
}

}  // namespace gantry
