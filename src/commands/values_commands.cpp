// The V commands: the operator's values (docs/values.md). Each parameter is a field of the
// settings; its table entry below names it, once, for the parser, the sheets and the docs.
#include <fmt/format.h>  // messages

#include <cmath>       // lround
#include <deque>       // stable storage for generated names
#include <functional>  // a field's setter

#include "gantry/commands/command_table.hpp"
#include "gantry/commands/values_sheets.hpp"
#include "gantry/interp/command_context.hpp"
#include "gantry/interp/tool_table.hpp"  // cutter_to_tool_table
#include "gantry/lang/expression.hpp"    // parse_lvalue: VV's names
#include "gantry/settings/settings_schema.hpp"  // ranges and members of schema settings
#include "values_display.hpp"                   // a bare command's values

namespace gantry {
namespace {

// One parameter of a V command and the field it sets. `set` is null for a parameter the
// references mark obsolete (accepted and ignored, as SB3 does) and for those with no
// meaning on this machine, which `ignored` explains in a warning.
// `row` (with `index`: a family's index or a list's item) is the schema setting the
// parameter sets, which a bare command shows; null for one that sets none.
struct Field {
  ParamSpec param;
  std::function<void(Settings&, const Value&)> set = nullptr;
  std::string_view ignored = {};
  const SettingRow* row = nullptr;
  int index = 0;
};

// `f`, shown as schema setting `path`'s value (item `i`).
Field showing(Field f, std::string_view path, int i = 0) {
  f.row = &setting_row(path);
  f.index = i;
  return f;
}

ParamSpec num(std::string_view name, std::string_view unit, std::string_view help) {
  return {name, unit, false, std::nullopt, help};
}
ParamSpec flag(std::string_view name, std::string_view help) {
  return num(name, "", help).integer(0, 1);
}
ParamSpec word(std::string_view name, std::string_view choices, std::string_view help) {
  return ParamSpec{name, "", false, std::nullopt, help, ParamKind::Text}.one_of(choices);
}
Field obsolete(int n) {
  static const std::string names[] = {"obsolete 1", "obsolete 2", "obsolete 3", "obsolete 4"};
  return {num(names[n], "", "No longer used; leave it blank."), nullptr};
}

bool on(const Value& v) {
  return v.num() != 0;
}
int whole(const Value& v) {
  return static_cast<int>(std::lround(v.num()));
}

// A parameter that sets a schema setting (settings_schema.hpp; `i`: a family's index, the
// axis): the schema gives its range (checked before the handler runs, so the schema's own
// check in set_setting always passes) and its member; the sheet's name, unit and help stay
// the command's. The table's ranges are inclusive: a range open at 0 starts at 1e-6 here.
Field schema_field(std::string_view path, ParamSpec spec, int i = 0) {
  const SettingRow& row = setting_row(path);
  const double lo = row.range.lo_open ? row.range.lo + 1e-6 : row.range.lo;
  switch (row.kind) {
    case SettingKind::Integer:
      return {spec.integer(row.range.lo, row.range.hi),
              [&row, i](Settings& s, const Value& v) {
                *static_cast<int*>(row.field(s, i)) = whole(v);
              },
              {}, &row, i};
    case SettingKind::Bool:
      return {spec.integer(0, 1),
              [&row, i](Settings& s, const Value& v) {
                *static_cast<bool*>(row.field(s, i)) = on(v);
              },
              {}, &row, i};
    default:
      return {spec.range(lo, row.range.hi),
              [&row, i](Settings& s, const Value& v) { set_setting(s, row, v.num(), i); }, {},
              &row, i};
  }
}

// A bare command: the value of each parameter that sets a setting.
void show(CommandContext& ctx, const CommandCall& call, const std::vector<Field>& fields) {
  std::vector<ShownValue> shown;
  for (size_t i = 0; i < fields.size(); ++i)
    if (fields[i].row)
      shown.push_back({i + 1, &fields[i].param,
                       setting_value_text(*fields[i].row, ctx.settings(), fields[i].index)});
  ctx.print(values_listing(call.spec, shown, ctx.settings()));
}

std::vector<ParamSpec> params_of(const std::vector<Field>& fields) {
  std::vector<ParamSpec> out;
  for (const Field& f : fields) out.push_back(f.param);
  return out;
}

// Applies the call's values to a copy of the settings, checks the rules that tie keys
// together, then commits: a bad value changes nothing.
void apply(CommandContext& ctx, const CommandCall& call, const std::vector<Field>& fields,
           ValueScope scope,
           void (*extra)(CommandContext&, const CommandCall&, Settings&) = nullptr) {
  Settings next = ctx.settings();
  for (size_t i = 0; i < fields.size(); ++i) {
    if (!call.values[i] || i >= call.args.size() || call.args[i].blank()) continue;
    if (fields[i].set) fields[i].set(next, *call.values[i]);
    if (!fields[i].ignored.empty())
      ctx.warn(call.param_loc(i), fmt::format("{} parameter {} ({}): {}", call.spec.code, i + 1,
                                              fields[i].param.name, fields[i].ignored));
  }
  if (extra) extra(ctx, call, next);
  const std::vector<std::string> problems = settings_problems(next);
  if (!problems.empty())
    fail(call.loc, fmt::format("{} would break a rule of the machine profile: {}; nothing was "
                               "changed",
                               call.spec.code, problems.front()));
  ctx.change_values(scope) = next;
}

// ---- VC: cutter -----------------------------------------------------------------------

Field diameter() {
  return schema_field("cutter.diameter", num("cutter diameter", "units",
                                              "Used by the O and I offsets of the cut commands."));
}
Field safe_z() {
  return schema_field("cutter.safe_z", num("safe Z pull-up", "units",
                                            "Working Z that MH and JH raise the tool to first."));
}
Field pocket_overlap() {
  return schema_field(
      "cutter.pocket_overlap",
      num("pocket overlap", "%", "Overlap of pocketing passes, % of the cutter diameter."));
}
Field safe_a() {
  return schema_field(
      "cutter.safe_a",
      num("safe A pull-up", "A units", "The same height for an A axis used as a second Z."));
}

const std::vector<Field>& vc_sb3() {
  static const std::vector<Field> f = {
      diameter(),
      obsolete(0),
      obsolete(1),
      safe_z(),
      // SB3 files in the corpus write 0 here: read as the default, "-" (0 and -1 negative,
      // 1 positive).
      showing({word("plunge direction", "- + 0 1 -1", "-: a negative Z goes into the material."),
               [](Settings& s, const Value& v) {
                 s.cutter.plunge_negative = v.to_string() != "+" && v.to_string() != "1";
               }},
              "cutter.plunge_direction"),
      pocket_overlap(),
      safe_a(),
      {flag("triggered output", "1 turns the Z/A-triggered output switch on for this file."),
       nullptr, "the Z/A-triggered output switch is stored, not switched by Gantry"},
      schema_field("cutter.trigger_on",
                   num("trigger ON level", "units", "Z or A level at which the switch comes on.")),
      schema_field("cutter.trigger_off",
                   num("trigger OFF level", "units", "Z or A level at which the switch goes off.")),
      showing({word("trigger axis", "Z A", "The axis watched: Z or A."),
               [](Settings& s, const Value& v) {
                 s.cutter.trigger_axis = (v.to_string() == "A" || v.to_string() == "a") ? 3 : 2;
               }},
              "cutter.trigger_axis"),
      schema_field("cutter.trigger_output", num("triggered switch", "", "Output switch 3-12 (not 4)."))};
  return f;
}
const std::vector<Field>& vc_fabmo() {
  static const std::vector<Field> f = {diameter(),  obsolete(0),      obsolete(1), safe_z(),
                                       obsolete(2), pocket_overlap(), safe_a()};
  return f;
}

void values_cutter(CommandContext& ctx, const CommandCall& call) {
  const bool fabmo = ctx.settings().dialect == Dialect::FabMo;
  if (shows_values(ctx, call)) return show(ctx, call, fabmo ? vc_fabmo() : vc_sb3());
  const double before = ctx.settings().cutter.diameter;
  apply(ctx, call, fabmo ? vc_fabmo() : vc_sb3(), ValueScope::Permanent,
        [](CommandContext&, const CommandCall& call, Settings& s) {
          if (s.cutter.trigger_output == 4)
            fail(call.param_loc(11),
                 "VC: the triggered switch cannot be output 4 (the "
                 "tool-in-motion switch); use 3 or 5-12");
        });
  // The tool in the spindle keeps VC's diameter in G-code's tool table (docs/gcode.md).
  if (const double d = ctx.settings().cutter.diameter; d != before)
    cutter_to_tool_table(ctx, d, call.param_loc(0));
}

// ---- VB: tabs -------------------------------------------------------------------------

const std::vector<Field>& vb_fields() {
  static const std::vector<Field> f = {
      schema_field("tabs.pull_up", num("tab height", "units", "How far the cutter lifts for a tab.")),
      schema_field("tabs.spacing", num("tab spacing", "units", "Distance from one tab to the next.")),
      schema_field("tabs.size", num("tab size", "units", "Tab length along the path.")),
      schema_field("tabs.leads",
                   num("lead length", "units", "Length of the incline up to and down from a tab.")),
      {flag("tabs on", "1 starts tab insertion in this file, 0 ends it."), nullptr},
      {num("tab count", "", "How many tabs after an ON (then no OFF is needed).").integer(0, 1e6),
       nullptr},
      {num("first tab", "units", "Distance to the first tab of a series.").at_least(0), nullptr}};
  return f;
}

void values_tabs(CommandContext& ctx, const CommandCall& call) {
  if (shows_values(ctx, call)) return show(ctx, call, vb_fields());
  apply(ctx, call, vb_fields(), ValueScope::Permanent);
  ModalState& st = ctx.state();
  if (const auto v = call.number(4)) st.tabs_on = *v != 0;
  if (const auto v = call.number(5)) {
    st.tab_count = static_cast<int>(*v);
    if (*v > 0) st.tabs_on = true;
  }
  if (const auto v = call.number(6)) st.first_tab = *v;
  if (call.number(4) || call.number(5) || call.number(6)) {  // a series of tabs starts here
    st.tab_travel = 0;
    st.tabs_passed = 0;
  }
}

// ---- VD: display and units ------------------------------------------------------------

AxisUnit axis_unit(const Value& v) {
  const int n = whole(v);
  return n == 0 ? AxisUnit::Inches : n == 1 ? AxisUnit::Millimetres : AxisUnit::Degrees;
}
ParamSpec unit_code(std::string_view name) {
  return num(name, "", "0 inches, 1 millimetres, 2 degrees.").integer(0, 2);
}
Field linear_units() {
  return showing(
      {num("linear units", "", "0 inches, 1 millimetres: every value is converted.").integer(0, 1),
       nullptr},  // applied by values_display: it converts everything
      "units");
}
Field units_of(int axis) {
  static const std::string names[] = {"A units", "B units", "C units"};
  static const std::string_view rows[] = {"display.units_a", "display.units_b", "display.units_c"};
  return showing({unit_code(names[axis]),
                  [axis](Settings& s, const Value& v) { s.display.rotary_units[axis] = axis_unit(v); }},
                 rows[axis]);
}
constexpr std::string_view kScreen =
    "Windows message-screen placement has no meaning in Gantry's "
    "console; ignored";

const std::vector<Field>& vd_sb3() {
  static const std::vector<Field> f = {
      obsolete(0),
      schema_field("display.axes",
                   num("number of axes", "", "Axes in use: 3 XYZ, 4 adds A, 5 adds B, 6 adds C.")),
      linear_units(),
      units_of(0),
      units_of(1),
      obsolete(1),
      schema_field("display.show_comments",
                   flag("show comments", "1 shows part-file comments as the file runs.")),
      schema_field("display.keypad_step", num("keypad step", "units", "Fixed-distance keypad step.")),
      schema_field("display.keypad_remote",
                   num("keypad remote", "", "0 keyboard, 1 pendant on the inputs, 2 other.")),
      schema_field("display.part_file_log", flag("part file log", "1 logs each part file run.")),
      schema_field("display.system_log", flag("system log", "1 keeps a system log.")),
      {num("message X", "twips", "Message screen left."), nullptr, kScreen},
      {num("message Y", "twips", "Message screen top."), nullptr, kScreen},
      {num("message width", "twips", "Message screen width."), nullptr, kScreen},
      {num("message height", "twips", "Message screen height."), nullptr, kScreen},
      schema_field("display.show_progress",
                   flag("show progress", "1 shows a progress bar while a file runs.")),
      schema_field("display.keypad_outputs_off",
                   flag("keypad outputs off",
                        "1 turns the output switches off when the keypad closes.")),
      schema_field("display.show_progress",
                   flag("show progress (again)", "The same as parameter 16 (SB3 lists it twice).")),
      {num("display type", "", "SB3's EASY or full screen."), nullptr,
       "Gantry has one console; ignored"}};
  return f;
}
const std::vector<Field>& vd_fabmo() {
  static const std::vector<Field> f = {obsolete(0), linear_units(), units_of(0), units_of(1),
                                       units_of(2)};
  return f;
}

void values_display(CommandContext& ctx, const CommandCall& call) {
  const bool fabmo = ctx.settings().dialect == Dialect::FabMo;
  if (shows_values(ctx, call)) return show(ctx, call, fabmo ? vd_fabmo() : vd_sb3());
  const size_t units_param = fabmo ? 1 : 2;
  apply(ctx, call, fabmo ? vd_fabmo() : vd_sb3(), ValueScope::Permanent);
  if (const std::optional<double> units = call.number(units_param))
    ctx.change_units(*units == 1 ? Units::Millimetres : Units::Inches, ValueScope::Permanent,
                     call.loc);
}

// ---- VH: height control, laser, heater --------------------------------------------------

const std::vector<Field>& vh_fields() {
  static const std::vector<Field> f = {
      schema_field("accessories.mode",
                   num("control mode", "",
                       "1 turns the accessory on, 0 off (VN parameter 3 enables it).")),
      schema_field("accessories.plasma_rate",
                   num("plasma height rate", "", "Pull-up rate as a share of the XY speed.")),
      schema_field("accessories.pwm_low", num("laser PWM low", "%", "Background PWM level.")),
      schema_field("accessories.pwm_high",
                   num("laser PWM high", "%", "Peak PWM level, reached at full speed.")),
      schema_field("accessories.pulse_khz", num("laser pulse frequency", "kHz", "PWM frequency.")),
      schema_field("accessories.low_cycle",
                   num("low cycle time", "", "Share of time at low PWM for heater control, 1-10.")),
      schema_field("accessories.temperature",
                   num("set temperature", "", "Heater target on analog input 1."))};
  return f;
}

void values_accessories(CommandContext& ctx, const CommandCall& call) {
  if (shows_values(ctx, call)) return show(ctx, call, vh_fields());
  apply(ctx, call, vh_fields(), ValueScope::Permanent,
        [](CommandContext&, const CommandCall& call, Settings& s) {
          if (s.accessories.mode != 1) return;
          if (s.switches.accessory == 0)
            fail(call.param_loc(0),
                 "VH mode 1 needs an accessory enabled first: VN parameter "
                 "3 (1 torch height, 2 laser, 3 analog); nothing was changed");
          fail(call.param_loc(0),
               "VH mode 1: Gantry has no torch-height, laser-PWM or heater "
               "output on this machine; the values can be set with mode 0, "
               "nothing was changed");
        });
}

// ---- VI: driver channels --------------------------------------------------------------

int axis_of(const Value& v) {
  const std::string t = v.to_string();
  const size_t letter = std::string_view("XYZABCxyzabc").find(t.empty() ? '?' : t[0]);
  if (letter != std::string_view::npos) return static_cast<int>(letter % 6);
  return t[0] - '1';  // 1-6, checked by the choices
}

Field channel(int k) {
  static const std::string names[] = {"channel 1 axis", "channel 2 axis", "channel 3 axis",
                                      "channel 4 axis", "channel 5 axis", "channel 6 axis"};
  return showing({word(names[k], "X Y Z A B C 1 2 3 4 5 6", "The axis this driver channel drives."),
                  [k](Settings& s, const Value& v) { s.drivers.channel_axis[k] = axis_of(v); }},
                 "drivers.channels", k);
}
Field comm_speed() {
  return {num("comm speed", "", "SB3's serial link speed code."), nullptr,
          "Gantry's cards have no serial link; ignored"};
}

const std::vector<Field>& vi_sb3() {
  static const std::vector<Field> f = {
      {num("comm port", "", "SB3's serial port."), nullptr,
       "Gantry's cards have no serial port; ignored"},
      obsolete(0),
      obsolete(1),
      obsolete(2),
      channel(0),
      channel(1),
      channel(2),
      channel(3),
      comm_speed(),
      channel(4),
      channel(5),
      {flag("enable outputs", "0 disables all step output (not supported: see the docs)."),
       nullptr}};
  return f;
}
const std::vector<Field>& vi_fabmo() {
  static const std::vector<Field> f = {channel(0),   channel(1), channel(2), channel(3),
                                       comm_speed(), channel(4), channel(5)};
  return f;
}

void values_drivers(CommandContext& ctx, const CommandCall& call) {
  const bool fabmo = ctx.settings().dialect == Dialect::FabMo;
  if (shows_values(ctx, call)) return show(ctx, call, fabmo ? vi_fabmo() : vi_sb3());
  if (!fabmo && call.number(11) == 0.0)
    fail(call.param_loc(11),
         "VI: running with step output disabled is not supported; "
         "`gantry check` or `gantry moves` run a file without moving");
  const Settings before = ctx.settings();
  apply(ctx, call, fabmo ? vi_fabmo() : vi_sb3(), ValueScope::File);
  if (ctx.settings().drivers.channel_axis != before.drivers.channel_axis)
    ctx.values_reach_motion(call.loc);
}

// ---- VL: soft limits ------------------------------------------------------------------

Field limit(int axis, bool high) {
  static const std::string names[2][6] = {
      {"low X", "low Y", "low Z", "low A", "low B", "low C"},
      {"high X", "high Y", "high Z", "high A", "high B", "high C"}};
  return schema_field(high ? "axes.<x..c>.max" : "axes.<x..c>.min",
                      num(names[high][axis], "units",
                          high ? "Highest location allowed, table base coordinates."
                               : "Lowest location allowed, table base coordinates."),
                      axis);
}

const std::vector<Field>& vl_sb3() {
  static const std::vector<Field> f = {
      limit(0, false),
      limit(0, true),
      limit(1, false),
      limit(1, true),
      limit(2, false),
      limit(2, true),
      limit(3, false),
      limit(3, true),
      schema_field("machine.limit_checking",
                   flag("limit checking", "1 checks moves against the limits, 0 does not (as SF).")),
      limit(4, false),
      limit(4, true)};
  return f;
}
const std::vector<Field>& vl_fabmo() {
  static const std::vector<Field> f = {limit(0, false), limit(0, true),  limit(1, false),
                                       limit(1, true),  limit(2, false), limit(2, true),
                                       limit(3, false), limit(3, true),  limit(4, false),
                                       limit(4, true),  limit(5, false), limit(5, true)};
  return f;
}

void values_limits(CommandContext& ctx, const CommandCall& call) {
  const bool fabmo = ctx.settings().dialect == Dialect::FabMo;
  if (shows_values(ctx, call)) return show(ctx, call, fabmo ? vl_fabmo() : vl_sb3());
  apply(ctx, call, fabmo ? vl_fabmo() : vl_sb3(), ValueScope::File);
}

// ---- VN: input and output switch modes ------------------------------------------------

// AMB-19: the references name the groups but not their positions. Gantry's order: 1-3 as
// SB3 numbers them, 4-14 the modes of inputs 1-3 and 5-12, 15-26 those of outputs 1-12.
const std::vector<Field>& vn_fields() {
  static const std::vector<Field> f = [] {
    std::vector<Field> v = {
        schema_field("switches.limits",
                     flag("limit switches", "1 limit switches stop the machine, 0 they do not.")),
        schema_field("switches.stop_normally_open",
                     flag("stop switch wiring",
                          "Input 4, the stop switch: 0 normally closed, 1 open.")),
        schema_field("switches.accessory",
                     num("accessory", "", "0 none, 1 torch height, 2 laser, 3 analog (VH)."))};
    static std::deque<std::string> names;
    for (int n : {1, 2, 3, 5, 6, 7, 8, 9, 10, 11, 12}) {  // input 4 is the stop switch
      names.push_back(fmt::format("input {} mode", n));
      v.push_back(showing(
          {num(names.back(), "", "0 standard, 1 NO limit, 2 NC limit, 3 NO stop, 4 NC stop.")
               .integer(0, 4),
           [n](Settings& s, const Value& x) { s.switches.input_modes[n - 1] = whole(x); }},
          "switches.input_modes", n - 1));
    }
    for (int k = 0; k < 12; ++k) {
      names.push_back(fmt::format("output {} mode", k + 1));
      v.push_back(showing({num(names.back(), "",
                               "0 off at file end, 1 stays on, 2 as 0 and off while paused, 3 on "
                               "for a file, 4 on from file start, 5 as 3 and off while paused.")
                               .integer(0, 5),
                           [k](Settings& s, const Value& x) { s.switches.output_modes[k] = whole(x); }},
                          "switches.output_modes", k));
    }
    return v;
  }();
  return f;
}

// The limit and stop switches change on the card and in the controller with the machine at
// rest, from this point of the motion stream on.
void values_switches(CommandContext& ctx, const CommandCall& call) {
  if (shows_values(ctx, call)) return show(ctx, call, vn_fields());
  const SwitchSettings before = ctx.settings().switches;
  apply(ctx, call, vn_fields(), ValueScope::Permanent);
  const Settings& s = ctx.settings();
  const SwitchSettings& now = s.switches;
  if (now.stop_normally_open != before.stop_normally_open && s.inputs.switch_bits[3] >= 0 &&
      s.inputs.switch_bits[3] == s.inputs.estop_bit)
    ctx.warn(call.param_loc(1),
             fmt::format("input 4 is the E-stop chain here (inputs.estop_bit {}), wired as the "
                         "profile says (estop_active_low); the stop switch wiring does not "
                         "change it",
                         s.inputs.estop_bit));
  if (now.limits != before.limits || now.stop_normally_open != before.stop_normally_open ||
      now.input_modes != before.input_modes)
    ctx.values_reach_motion(call.loc);
}

// ---- VO: temporary tool offset --------------------------------------------------------

const std::vector<ParamSpec>& vo_params() {
  static const std::vector<ParamSpec> p = [] {
    std::vector<ParamSpec> v = {num("offset on", "", "1 on, 2 off (0 also off)").integer(0, 2)};
    for (const char* n : {"X offset", "Y offset", "Z offset", "A offset", "B offset", "C offset"})
      v.push_back(num(n, "units", "Added to every move while the offset is on."));
    return v;
  }();
  return p;
}

void values_offset(CommandContext& ctx, const CommandCall& call) {
  ModalState& st = ctx.state();
  for (int i = 0; i < kAxisCount; ++i)
    if (const auto v = call.number(1 + i)) st.tool_offset_values[i] = *v;
  if (const auto v = call.number(0))
    st.tool_offset = *v == 1 ? st.tool_offset_values : Vec6::Zero();
  else if (st.tool_offset != Vec6::Zero())
    st.tool_offset = st.tool_offset_values;  // new values for an offset that is on
}

// ---- VP: preview ----------------------------------------------------------------------

const std::vector<Field>& vp_fields() {
  static const std::vector<Field> f = {
      schema_field("preview.grid", num("grid", "units", "Grid spacing in the preview.")),
      schema_field("preview.table_x", num("table X", "units", "Table size in X.")),
      schema_field("preview.table_y", num("table Y", "units", "Table size in Y.")),
      schema_field("preview.table_z", num("table Z", "units", "Table size in Z.")),
      schema_field("preview.simulate_cutting",
                   flag("simulate cutting", "1 runs the preview as a fast simulated cut.")),
      schema_field("preview.draw_tool", flag("draw tool", "1 draws the cutter.")),
      schema_field("preview.start_at_location",
                   flag("start at tool", "1 starts the preview where the tool is, 0 at 0,0.")),
      schema_field("preview.show_jogs", flag("show jogs", "1 draws jogs (in another colour)."))};
  return f;
}

void values_preview(CommandContext& ctx, const CommandCall& call) {
  if (shows_values(ctx, call)) return show(ctx, call, vp_fields());
  apply(ctx, call, vp_fields(), ValueScope::Permanent);
}

// ---- VR: ramps ------------------------------------------------------------------------

Field ramp_speed(bool jog, int group) {
  static const std::string names[2][4] = {
      {"XY move ramp speed", "Z move ramp speed", "A move ramp speed", "B move ramp speed"},
      {"XY jog ramp speed", "Z jog ramp speed", "A jog ramp speed", "B jog ramp speed"}};
  return schema_field(jog ? "ramps.jog_speed.<xy,z,a,b,c>" : "ramps.move_speed.<xy,z,a,b,c>",
                      num(names[jog][group], "units/s", "Speed a ramp starts from and ends at."),
                      group);
}

const std::vector<Field>& vr_sb3() {
  static const std::vector<Field> f = {
      ramp_speed(false, 0),
      ramp_speed(false, 1),
      ramp_speed(false, 2),
      ramp_speed(false, 3),
      ramp_speed(true, 0),
      ramp_speed(true, 1),
      ramp_speed(true, 2),
      ramp_speed(true, 3),
      schema_field("ramps.move_ramp_rate",
                   num("move ramp rate", "units",
                       "Distance over which move speed changes by 2 units/s.")),
      schema_field("ramps.jog_ramp_rate", num("jog ramp rate", "units", "The same for jogs.")),
      schema_field("ramps.threshold_3d",
                   num("3D threshold", "%", "Sensitivity of 3D ramping; lower is more sensitive.")),
      schema_field("ramps.min_distance",
                   num("minimum distance", "units",
                       "Shortest distance looked at for a ramp decision.")),
      schema_field("ramps.slow_corner",
                   num("slow corner speed", "%", "Share of speed kept through a slight corner.")),
      obsolete(0),
      obsolete(1),
      schema_field("ramps.keypad_ramp_rate",
                   num("keypad ramp rate", "units", "Ramp rate of keypad jogs.")),
      schema_field("ramps.small_circle",
                   num("small circle", "units",
                       "Circles of smaller diameter run at ramp speed (AMB-22)."))};
  return f;
}

// FabMo's VR sets jerk limits (AMB-24: units unstated). Gantry's planner has one jerk for
// the path; FabMo's XY value sets it, in g2core's unit (millions of mm/min^3), converted.
const std::vector<Field>& vr_fabmo() {
  static const std::vector<Field> f = [] {
    std::vector<Field> v = {
        {num("XY jerk", "Mmm/min^3", "Jerk limit of the path (S-curve ramps).").range(0, 1e6),
         [](Settings& s, const Value& x) {
           const double mm_s3 = x.num() * 1e6 / (60.0 * 60.0 * 60.0);
           s.planner.jerk = mm_s3 * units_factor(Units::Millimetres, s.units);
         }}};
    for (const char* n : {"Z jerk", "A jerk", "B jerk", "C jerk"})
      v.push_back(
          {num(n, "Mmm/min^3", "Per-axis jerk: the XY value governs the path.").range(0, 1e6),
           nullptr, "Gantry limits jerk along the path with the XY value only; ignored"});
    return v;
  }();
  return f;
}

void values_ramps(CommandContext& ctx, const CommandCall& call) {
  const bool fabmo = ctx.settings().dialect == Dialect::FabMo;
  if (shows_values(ctx, call)) return show(ctx, call, fabmo ? vr_fabmo() : vr_sb3());
  apply(ctx, call, fabmo ? vr_fabmo() : vr_sb3(), ValueScope::Permanent);
  ctx.values_reach_motion(call.loc);
}

// ---- VU: calibration ------------------------------------------------------------------

Field steps(int axis) {
  static const std::string names[] = {"X steps per unit", "Y steps per unit", "Z steps per unit",
                                      "A steps per unit", "B steps per unit", "C steps per unit"};
  return schema_field("axes.<x..c>.steps_per_unit",
                      num(names[axis], "steps/unit",
                          "Motor steps per unit of travel; negative reverses the axis."),
                      axis);
}
Field multiplier(int axis) {
  static const std::string names[] = {"X resolution multiplier", "Y resolution multiplier",
                                      "Z resolution multiplier", "A resolution multiplier",
                                      "B resolution multiplier"};
  const SettingRow& row = setting_row("calibration.resolution_multipliers");
  return {num(names[axis], "", "Jog resolution shift of SB3's alpha drives.")
              .range(row.range.lo, row.range.hi),
          [axis](Settings& s, const Value& v) { s.calibration.resolution_multiplier[axis] = v.num(); },
          {}, &row, axis};
}

const std::vector<Field>& vu_fields() {
  static const std::vector<Field> f = {
      steps(0),
      steps(1),
      steps(2),
      steps(3),
      schema_field("calibration.circle_resolution",
                   num("circle resolution", "units", "Segment length of arcs in the cut commands.")),
      obsolete(0),
      obsolete(1),
      obsolete(2),
      steps(4),
      multiplier(0),
      multiplier(1),
      multiplier(2),
      multiplier(3),
      multiplier(4),
      schema_field("calibration.step_divider",
                   num("step divider", "", "1-100: every speed runs at 1/n of its value.")),
      schema_field("calibration.no_resolution_shift",
                   flag("no resolution shift", "1 turns off the jog resolution shift."))};
  return f;
}

void values_calibration(CommandContext& ctx, const CommandCall& call) {
  if (shows_values(ctx, call)) return show(ctx, call, vu_fields());
  const Settings before = ctx.settings();
  apply(ctx, call, vu_fields(), ValueScope::File);
  for (int i = 0; i < kAxisCount; ++i)
    if (ctx.settings().axes[i].steps_per_unit != before.axes[i].steps_per_unit)
      return ctx.values_reach_motion(call.loc);
}

// ---- VA: locations --------------------------------------------------------------------

std::vector<ParamSpec> va_params(std::string_view letters) {
  static const std::string working[] = {"X location", "Y location", "Z location",
                                        "A location", "B location", "C location"};
  static const std::string base[] = {"table base X", "table base Y", "table base Z",
                                     "table base A", "table base B", "table base C"};
  std::vector<ParamSpec> out;
  for (char a : letters)
    out.push_back(num(working[std::string_view("XYZABC").find(a)], "units",
                      "The value the current location takes; nothing moves."));
  for (char a : letters)
    out.push_back(num(base[std::string_view("XYZABC").find(a)], "units",
                      "The table base value of the current location; nothing moves."));
  return out;
}

// Table base values first, then working ones (FabMo states that order; SB3 is silent).
void values_locations(CommandContext& ctx, const CommandCall& call) {
  const int n = ctx.settings().dialect == Dialect::FabMo ? 6 : 5;
  if (shows_values(ctx, call)) {  // the working location, then its table base value
    const ModalState& st = ctx.state();
    const std::vector<ParamSpec>& params = call.spec.params_for(ctx.settings().dialect);
    std::vector<ShownValue> shown;
    for (int i = 0; i < 2 * n; ++i)
      shown.push_back({static_cast<size_t>(i) + 1, &params[i],
                       format_number(i < n ? st.position[i] : st.position[i - n] + st.zero[i - n]),
                       i % n >= 3 && ctx.settings().display.rotary_units[i % n - 3] == AxisUnit::Degrees ? "deg" : ""});
    return ctx.print(values_listing(call.spec, shown, ctx.settings()));
  }
  // FabMo's `VA, 0,,,,,, 0` (X, then table base X) read in SB3's layout sets table base Y:
  // parameter 6 (C in FabMo's layout, table base X in SB3's) blank while a later one is set
  // may be either. SB3's own files write such lines (table base Z alone), so the profile's
  // dialect decides and the line says how it was read.
  if (n == 5 && !call.number(5))
    for (int i = 6; i < 10; ++i)
      if (call.number(i))
        ctx.warn(call.param_loc(i),
                 fmt::format("VA parameter {} is read as table base {} in SB3's 10-value layout "
                             "(this profile's dialect); in FabMo's 12-value one, which this "
                             "line's blank parameter 6 suggests, it is table base {}: set "
                             "dialect = \"fabmo\" if this is a FabMo file",
                             i + 1, "XYZAB"[i - 5], "XYZABC"[i - 6]));
  Vec6 base = Vec6::Zero();
  unsigned base_axes = 0;
  for (int i = 0; i < n; ++i)
    if (const auto v = call.number(n + i)) {
      base[i] = *v;
      base_axes |= 1u << i;
    }
  ctx.set_table_base(base_axes, base);
  ModalState& st = ctx.state();
  for (int i = 0; i < n; ++i)
    if (const auto v = call.number(i)) {
      st.zero[i] += st.position[i] - *v;
      st.position[i] = *v;
    }
}

// ---- VV: variables ------------------------------------------------------------------------

constexpr size_t kVvPairs = 8;

std::vector<ParamSpec> vv_params() {
  static const std::deque<std::string> names = [] {
    std::deque<std::string> n;
    for (size_t k = 1; k <= kVvPairs; ++k) {
      n.push_back(fmt::format("name {}", k));
      n.push_back(fmt::format("value {}", k));
    }
    return n;
  }();
  std::vector<ParamSpec> out;
  for (size_t k = 0; k < 2 * kVvPairs; ++k)
    out.push_back({names[k], "", false, std::nullopt,
                   k % 2 ? "Its value: a number, text, or an expression."
                         : "A variable, &NAME (the & may be left out).",
                   ParamKind::Text});
  return out;
}

// VV, &NAME, value, ...: every pair is checked before any variable is set.
void values_variables(CommandContext& ctx, const CommandCall& call) {
  std::vector<std::pair<std::string, Value>> set;
  for (size_t n = 0; n < 2 * kVvPairs; n += 2) {
    const bool named = n < call.args.size() && !call.args[n].blank();
    const std::optional<Value>& value = call.values[n + 1];
    if (!named && !value) continue;
    if (!named)
      fail(call.param_loc(n + 1), fmt::format("VV: value {} has no name; give the variable "
                                              "(&NAME) as parameter {}",
                                              n / 2 + 1, n + 1));
    std::string written = call.args[n].text;  // as written: its value, if any, is not wanted
    if (written.starts_with('$'))
      fail(call.param_loc(n),
           fmt::format("VV sets &variables; set {0} with `{0} = value`", written));
    if (!written.starts_with('&')) written = "&" + written;
    const std::optional<LValue> target = parse_lvalue(written, call.param_loc(n));
    if (!target || !target->path.empty())
      fail(call.param_loc(n), fmt::format("VV: {} is not a variable name; write &NAME (letters, "
                                          "digits and _)",
                                          call.args[n].text));
    if (!value)  // at the value when it is written (""), else at the name
      fail(call.param_loc(n + 1 < call.args.size() ? n + 1 : n),
           fmt::format("VV: &{} has no value (parameter {})", target->name, n + 2));
    set.push_back({target->name, *value});
  }
  if (set.empty()) fail(call.loc, "VV needs a variable and its value, e.g. VV, &DEPTH, 0.5");
  for (auto& [name, value] : set) ctx.set_variable(name, std::move(value));
}

// VK: named once, in SB3's "see also" of UV; neither reference says what it does.
void values_unknown(CommandContext&, const CommandCall& call) {
  fail(call.loc,
       "VK cannot run: SB3's reference names it only in UV's \"see also\" and neither "
       "reference says what it does, so Gantry has nothing to reproduce; nothing was done. "
       "UV prints the values and settings");
}

}  // namespace

std::string_view sheet_of(const SettingRow& row, bool* as_parameter) {
  if (as_parameter) *as_parameter = true;
  const std::pair<std::string_view, const std::vector<Field>*> sheets[] = {
      {"VC", &vc_sb3()},   {"VC", &vc_fabmo()},  {"VB", &vb_fields()}, {"VD", &vd_sb3()},
      {"VD", &vd_fabmo()}, {"VH", &vh_fields()}, {"VI", &vi_sb3()},    {"VI", &vi_fabmo()},
      {"VL", &vl_sb3()},   {"VL", &vl_fabmo()},  {"VN", &vn_fields()}, {"VP", &vp_fields()},
      {"VR", &vr_sb3()},   {"VR", &vr_fabmo()},  {"VU", &vu_fields()}};
  for (const auto& [code, fields] : sheets)
    for (const Field& f : *fields)
      if (f.row == &row) return code;
  if (row.section.starts_with("speeds.")) return "VS";  // VS's (mode_commands.cpp)
  if (as_parameter) *as_parameter = false;
  const std::string path = row.path();
  for (const SheetRows& r : sheet_profile_rows())
    if (path.starts_with(r.prefix)) return r.code;
  return "";
}

void add_values_commands(std::vector<CommandSpec>& out) {
  const auto V = CommandGroup::Values;
  out.push_back({"VA", "Values for axis locations", V,
                 "Gives the current location new working values, then table base values, "
                 "without moving. Blank keeps an axis's value.",
                 va_params("XYZAB"), values_locations, "", va_params("XYZABC"), false, "%(1)-%(10)",
                 "SB3's VA has 10 values (X to B, then table base X to B) and FabMo's 12 (X to "
                 "C, then table base X to C); set dialect = \"fabmo\" in the profile for "
                 "FabMo's layout"});
  out.push_back({"VB",
                 "Values for tabs",
                 V,
                 "Sets the size and spacing of tabs left on the last pass of a cut, and turns "
                 "tab insertion on or off in a file.",
                 params_of(vb_fields()),
                 values_tabs,
                 "",
                 {},
                 false,
                 "%(41)-%(44)"});
  out.push_back({"VC", "Values for the cutter", V,
                 "Sets the cutter diameter, the safe Z and A pull-up heights, the plunge "
                 "direction, the pocket overlap and the Z/A-triggered output switch.",
                 params_of(vc_sb3()), values_cutter,
                 "the triggered output switch (parameters 8-12) is stored, not switched",
                 params_of(vc_fabmo()), false, "%(20), %(28), %(29)"});
  out.push_back({"VD", "Values for display and units", V,
                 "Sets the number of axes, the linear units (every value and the position are "
                 "converted), the A/B/C units and console options.",
                 params_of(vd_sb3()), values_display, "", params_of(vd_fabmo()), false,
                 "%(25), %(27)"});
  out.push_back({"VH", "Values for height control and accessories", V,
                 "Sets torch-height, laser-PWM and heater values (VN parameter 3 enables them).",
                 params_of(vh_fields()), values_accessories,
                 "values are stored; Gantry drives no torch, laser or heater output"});
  out.push_back({"VI", "Values for driver channels", V,
                 "Assigns an axis to each driver channel 1-6 (its step and direction pins). "
                 "In a part file the change lasts until the file ends, unless SV.",
                 params_of(vi_sb3()), values_drivers,
                 "enable = 0 (run without step output) is refused", params_of(vi_fabmo()), false,
                 "%(36)-%(40)"});
  out.push_back({"VL", "Values for table limits", V,
                 "Sets the soft limits in table base coordinates, and (SB3) limit checking. In a "
                 "part file the change lasts until the file ends, unless SV.",
                 params_of(vl_sb3()), values_limits, "", params_of(vl_fabmo()), false,
                 "%(11)-%(20), %(30)"});
  out.push_back({"VN",
                 "Values for input and output switches",
                 V,
                 "Sets limit switches on or off, the stop switch wiring, the accessory, and the "
                 "mode of each input and output switch.",
                 params_of(vn_fields()),
                 values_switches,
                 "the accessory is stored only (VH drives no torch, laser or heater)",
                 {},
                 false,
                 "%(91)-%(98), %(111)-%(122), %(131)-%(134)"});
  out.push_back({"VO",
                 "Values for a temporary tool offset",
                 V,
                 "Adds an offset to every move (a second head, an air drill) until turned off or "
                 "the run ends; the location shows where the tool really is.",
                 vo_params(),
                 values_offset,
                 "",
                 {},
                 false,
                 "%(1)-%(10)"});
  out.push_back({"VP", "Values for the preview", V,
                 "Sets the preview's grid, table size and drawing options.", params_of(vp_fields()),
                 values_preview,
                 "stored and shown by UV; `gantry preview` and the window's 3D view take "
                 "their own options"});
  out.push_back({"VR", "Values for ramps", V,
                 "Sets the ramp speeds and rates of the SB3 ramp model (docs/planner.md); FabMo's "
                 "form sets jerk limits. The machine comes to rest first.",
                 params_of(vr_sb3()), values_ramps, "", params_of(vr_fabmo())});
  out.push_back({"VU",
                 "Values for calibration",
                 V,
                 "Sets steps per unit, arc resolution, resolution multipliers and the step "
                 "divider. In a part file the change lasts until the file ends, unless SV.",
                 params_of(vu_fields()),
                 values_calibration,
                 "resolution multipliers and shifting are stored (step/direction drives have no "
                 "resolution shift)",
                 {},
                 false,
                 "%(151)-%(156)"});
  out.push_back({"VV", "Values for variables", V,
                 "Defines &variables: up to 8 name and value pairs, e.g. `VV, &DEPTH, 0.5, "
                 "&MATERIAL, Oak`, as `&name = value` would. Nothing is set unless every pair "
                 "is right. UL lists them; SL deletes them.",
                 vv_params(), values_variables});
  out.push_back({"VK",
                 "Values (undocumented)",
                 V,
                 "Named only in SB3's UV entry; neither reference describes it. It stops the "
                 "file and says so.",
                 {},
                 values_unknown,
                 "refused by name: neither reference says what VK does"});
}

}  // namespace gantry
