// Probes (PX ... P6) and homing on proximity switches (C3 without a custom file).
#include <fmt/format.h>  // messages

#include <array>    // the two motors
#include <cmath>    // round
#include <utility>  // pair

#include "gantry/commands/command_table.hpp"
#include "gantry/interp/command_context.hpp"

namespace gantry {
namespace {

// The targets first, then the speed and the input switch: the order FabMo's runtime reads and
// its stock macros write (`PZ, -0.5, 1.0, 1`), not the reverse order its reference lists
// (docs/controller.md, Inputs).
template <Axis... Axes>
void probe_axes(CommandContext& ctx, const CommandCall& call) {
  constexpr size_t n = sizeof...(Axes);
  const Vec6 here = ctx.position();
  const bool absolute = ctx.state().absolute;
  Vec6 target = here;
  size_t i = 0;
  for (Axis a : {Axes...})
    if (const std::optional<double> v = call.number(i++))
      target[index(a)] = absolute ? *v : here[index(a)] + *v;
  const double speed = *call.number(n);
  const double input = *call.number(n + 1);
  if (input != std::round(input))
    fail(call.param_loc(n + 1), fmt::format("input switch {} is not a whole number", input));
  ctx.probe(target, speed, static_cast<int>(input), call.loc);
}

std::vector<ParamSpec> probe_params(std::string_view axes) {
  static const std::string names[] = {"target X", "target Y", "target Z",
                                      "target A", "target B", "target C"};
  static constexpr std::string_view letters = "XYZABC";
  std::vector<ParamSpec> out;
  for (char a : axes)
    out.push_back({names[letters.find(a)], "units", false, std::nullopt,
                   "Where the move ends if the switch never closes (SA), or how far (SR); blank: "
                   "the axis stays."});
  out.push_back({"speed", "units/s", true, std::nullopt, "How fast the probe moves."});
  out.push_back({"input", "", true, std::nullopt,
                 "The input switch (1-12) whose closing stops it; 1 is the Z zero plate."});
  return out;
}

// One axis's homing values: its own (homing.<axis>.*, WinCNC's g28move per axis) or the
// [homing] ones.
struct AxisHoming {
  double fast, slow;  // the approaches' speeds
  double retract;     // off the switch between the approaches
  double offset;      // off the switch at the end
  double search;      // the longest run towards the switch
};

AxisHoming axis_homing(const Settings& s, int i) {
  const HomingSettings& h = s.homing;
  const double retract = h.retract[i].value_or(h.back_off);
  return {h.fast[i].value_or(h.fast_speed), h.slow[i].value_or(h.slow_speed), retract,
          h.offset[i].value_or(h.back_off),
          h.search[i].value_or(s.axes[i].max - s.axes[i].min + 2 * h.back_off)};
}

// The moves while it lives rest the given driver channels' motors (squaring a slaved axis);
// every channel steps again when it ends, an error's unwinding included.
class RestingChannels {
 public:
  RestingChannels(CommandContext& ctx, unsigned channels) : ctx_(ctx) {
    ctx_.input_switches();  // at rest first: a channel stops or starts only between moves
    ctx_.rest_channels(channels);
  }
  ~RestingChannels() { ctx_.rest_channels(0); }
  RestingChannels(const RestingChannels&) = delete;
  RestingChannels& operator=(const RestingChannels&) = delete;

 private:
  CommandContext& ctx_;
};

// Squares a slaved axis (two driver channels, homing.<axis>.square_input): both motors fast
// to the first motor's switch and back off; then each motor on its own, the other resting,
// slowly to its own switch (homing.input for the first channel, square_input for the
// second), which sets the table base; the second motor moves on by square_offset; both back
// off together (docs/hardware.md, "Slaved axes").
void home_squared(CommandContext& ctx, const SourceLoc& loc, int i) {
  const Settings& s = ctx.settings();
  const HomingSettings& h = s.homing;
  const double dir = h.direction[i];
  const AxisHoming a = axis_homing(s, i);
  const double reach = a.search;
  const char L = axis_name(s, i);
  const int first_input = h.axis_input[i] != 0 ? h.axis_input[i] : h.input;
  const int second_input = h.square_input[i];
  int first = -1, second = -1;  // the axis's two channels, in channel order
  for (int k = 0; k < kAxisCount; ++k)
    if (s.drivers.channel_axis[k] == i) (first < 0 ? first : second) = k;
  auto toward = [&](double distance) {
    Vec6 t = ctx.position();
    t[i] += dir * distance;
    return t;
  };
  auto closed = [&](int input) {
    const auto in = ctx.input_switches();
    return in && (*in)[input - 1];
  };
  const bool live = ctx.input_switches().has_value();
  auto back_off = [&](double by) { ctx.homing_line(toward(-by), a.fast, loc); };
  auto stuck = [&](int input, const char* motor) {
    if (closed(input))
      fail(loc, fmt::format("homing {}: the {} motor's switch (input {}) stays closed after "
                            "backing off {}: check the switch, or the gantry is out of square "
                            "by more than that",
                            L, motor, input, a.retract));
  };
  if (closed(first_input) || closed(second_input)) {
    back_off(a.retract);  // resting on a switch: off it first
    stuck(first_input, "first");
    stuck(second_input, "second");
  }
  // Both motors, fast, until the first one's switch closes; the second may have passed its
  // own by the gantry's error: backing off must clear it.
  if (!ctx.probe(toward(reach), a.fast, first_input, loc, MachineLink::Watching::Home) && live)
    fail(loc, fmt::format("homing {}: input {} never closed within {} (the search length): "
                          "check the switch and its wiring",
                          L, first_input, reach));
  back_off(a.retract);
  stuck(first_input, "first");
  stuck(second_input, "second");
  // Each motor on its own, slowly, to its own switch.
  const std::array<std::pair<int, int>, 2> motors{{{first_input, second}, {second_input, first}}};
  for (const auto& [input, resting] : motors) {
    const RestingChannels rest(ctx, 1u << resting);
    if (!ctx.probe(toward(reach), a.slow, input, loc, MachineLink::Watching::Home) && live)
      fail(loc, fmt::format("homing {}: input {} never closed on the slow approach of the {} "
                            "motor",
                            L, input, input == first_input ? "first" : "second"));
  }
  ctx.home_axis(i, h.at[i]);  // each motor on its own switch: the table base of both
  if (h.square_offset[i] != 0) {
    const RestingChannels rest(ctx, 1u << first);
    ctx.homing_line(toward(h.square_offset[i]), a.slow, loc);
    ctx.input_switches();
    ctx.home_axis(i, h.at[i]);  // the first motor has not moved: it still stands at `at`
  }
  back_off(a.offset);
}

// WinCNC's g28coord: the axes just homed that have a park position (homing.<axis>.park, table
// base) go there at jog speed, the soft limits checked as for any move: the axes that home
// down (X and Y, mostly) first, together, then those that home up (the vertical heads), so a
// head parked lower comes down last, over its place.
void park_after_homing(CommandContext& ctx, const SourceLoc& loc, unsigned homed) {
  const HomingSettings& h = ctx.settings().homing;
  for (const int up : {-1, 1}) {
    Vec6 working = ctx.state().position;
    bool any = false;
    for (int i = 0; i < kAxisCount; ++i)
      if ((homed >> i & 1u) && h.park[i] && h.direction[i] == up) {
        working[i] = *h.park[i] - ctx.state().zero[i];
        any = true;
      }
    if (any) ctx.line_to(ctx.transform().to_file(working), SpeedClass::Jog, loc);
  }
}

}  // namespace

// Each axis of the profile's order: fast to its switch, back off, slowly to it again (the
// measured approach), set the table base there, back off the switch. Without a switch
// within a table's length and a bit, it stops with an error.
void home_on_switches(CommandContext& ctx, const SourceLoc& loc, std::string_view only) {
  const Settings& s = ctx.settings();
  const HomingSettings& h = s.homing;
  unsigned homed = 0;
  for (const char letter : h.order) {
    if (!only.empty() && only.find(letter) == std::string_view::npos) continue;
    const int i = static_cast<int>(std::string_view("xyzabc").find(letter));
    homed |= 1u << i;
    if (h.square_input[i] != 0) {
      home_squared(ctx, loc, i);
      continue;
    }
    const int input = h.axis_input[i] != 0 ? h.axis_input[i] : h.input;
    const double dir = h.direction[i];
    const AxisHoming a = axis_homing(s, i);
    const char L = static_cast<char>(letter - 'a' + 'A');
    auto toward = [&](double distance) {
      Vec6 t = ctx.position();
      t[i] += dir * distance;
      return t;
    };
    auto back_off = [&](double by) { ctx.homing_line(toward(-by), a.fast, loc); };
    if (const auto in = ctx.input_switches(); in && (*in)[input - 1]) {
      back_off(a.retract);  // resting on the switch: off it first
      if (const auto again = ctx.input_switches(); again && (*again)[input - 1])
        fail(loc, fmt::format("homing {}: input {} stays closed after backing off {}: check the "
                              "switch and its wiring",
                              L, input, a.retract));
    }
    const bool live = ctx.probe(toward(a.search), a.fast, input, loc, MachineLink::Watching::Home);
    if (!live && ctx.input_switches())
      fail(loc, fmt::format("homing {}: input {} never closed within {} (the search length, "
                            "homing.{}.search or the table's length): check the switch and its "
                            "wiring",
                            L, input, a.search, letter));
    back_off(a.retract);
    if (!ctx.probe(toward(2 * a.retract), a.slow, input, loc, MachineLink::Watching::Home) &&
        ctx.input_switches())
      fail(loc,
           fmt::format("homing {}: input {} did not close again on the slow approach", L, input));
    ctx.home_axis(i, h.at[i]);
    back_off(a.offset);
  }
  park_after_homing(ctx, loc, homed);
}

void add_probe_commands(std::vector<CommandSpec>& out) {
  using enum Axis;
  const auto P = CommandGroup::Probe;
  const char* one =
      "Moves one axis at the given speed until the input switch closes, and stops exactly where "
      "it closed; if it never closes, the move ends at the target.";
  const char* many =
      "Moves several axes together in a straight line at the given speed until the input "
      "switch closes, and stops exactly where it closed; if it never closes, the move ends at "
      "the target.";
  out.push_back({"PX", "Probe in X", P, one, probe_params("X"), probe_axes<X>});
  out.push_back({"PY", "Probe in Y", P, one, probe_params("Y"), probe_axes<Y>});
  out.push_back({"PZ", "Probe in Z", P, one, probe_params("Z"), probe_axes<Z>});
  out.push_back({"PA", "Probe in A", P, one, probe_params("A"), probe_axes<A>});
  out.push_back({"PB", "Probe in B", P, one, probe_params("B"), probe_axes<B>});
  out.push_back({"PC", "Probe in C", P, one, probe_params("C"), probe_axes<C>});
  out.push_back({"P2", "Probe in 2 dimensions", P, many, probe_params("XY"), probe_axes<X, Y>});
  out.push_back({"P3", "Probe in 3 dimensions", P, many, probe_params("XYZ"), probe_axes<X, Y, Z>});
  out.push_back(
      {"P4", "Probe in 4 dimensions", P, many, probe_params("XYZA"), probe_axes<X, Y, Z, A>});
  out.push_back(
      {"P5", "Probe in 5 dimensions", P, many, probe_params("XYZAB"), probe_axes<X, Y, Z, A, B>});
  out.push_back({"P6", "Probe in 6 dimensions", P, many, probe_params("XYZABC"),
                 probe_axes<X, Y, Z, A, B, C>});
}

}  // namespace gantry
