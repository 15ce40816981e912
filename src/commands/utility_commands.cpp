// Utilities, UD to UV. SB3 opens a screen for most of them; Gantry prints the console
// equivalent where the command runs: the diagnostics (UD), the values and settings the
// location readout does not show (UV), the variables (UL), a calculation (UU). UN shows the
// editor FE uses, which only the machine profile sets; US saves the settings to a file and
// UR loads them back (or the profile's). UI installs control-box firmware, and Gantry has no
// control box: it says so by name. UZ is with the zero commands.
#include <fmt/format.h>   // reports, messages

#include <cmath>       // llround
#include <cstdlib>     // getenv
#include <ctime>       // US's date
#include <filesystem>  // UN's look along PATH
#include <sstream>
#include <string>

#include "gantry/commands/command_table.hpp"
#include "gantry/core/text_file.hpp"  // read_text_file
#include "gantry/interp/command_context.hpp"
#include "gantry/interp/interpreter_options.hpp"  // InterpreterOptions
#include "gantry/settings/values_file.hpp"  // settings_text, parse_settings

namespace gantry {
namespace {

// A setting as stored, every digit kept.
std::string show(double v) {
  return fmt::format("{}", v);
}

std::string on_off(bool on) {
  return on ? "on" : "off";
}

// "XY 1, Z 0.5, A 2, B 2, C 2"
std::string groups(const GroupSpeeds& g) {
  return fmt::format("XY {}, Z {}, A {}, B {}, C {}", show(g.xy), show(g.z), show(g.a), show(g.b),
                     show(g.c));
}

// "X 1000, Y 1000, ..." for the axes in use (VD's number of axes).
template <class F>
std::string per_axis(const Settings& s, F value) {
  std::string out;
  for (int i = 0; i < std::max(3, s.display.axes); ++i)
    out += fmt::format("{}{} {}", out.empty() ? "" : ", ",
                       static_cast<char>(std::toupper(kAxisLetters[i])), value(i));
  return out;
}

const Settings& profile_of(const CommandContext& ctx) {
  static const Settings built_in = default_settings();
  return ctx.options().profile ? *ctx.options().profile : built_in;
}

std::string profile_line(const CommandContext& ctx) {
  const std::string& path = ctx.options().profile_path;
  return fmt::format("Machine profile: \"{}\" ({})\n", profile_of(ctx).name,
                     path.empty() ? "built in: settings/default.toml" : path);
}

std::string values_line(const CommandContext& ctx) {
  const std::string& path = ctx.options().values_path;
  return fmt::format("Values file: {}\n", path.empty() ? "none (this run saves no values)" : path);
}

std::string editor_line(const CommandContext& ctx) {
  const EditorChoice e = editor_choice(ctx);
  return fmt::format("Editor (FE): {} ({})\n", e.text, e.from);
}

// Saves a report when the command names a file (SB3 keeps UD's and UV's in PROBLEM.LOG).
void print_and_save(CommandContext& ctx, const CommandCall& call, const std::string& report) {
  ctx.print(report);
  if (const std::optional<std::string> name = call.text(0)) {
    const std::string path = ctx.write_file(*name, report, call.param_loc(0));
    ctx.print(fmt::format("{} saved this report to {}\n", call.spec.code, path));
  }
}

// ---- UV: values and settings -------------------------------------------------------------

std::string values_report(CommandContext& ctx) {
  const Settings& s = ctx.settings();
  const ModalState& st = ctx.state();
  const char* u = units_name(s.units);
  std::string out = "Values and settings (UV):\n";
  out += fmt::format("Parts folder (FS): {}\n",
                     ctx.parts_folder().empty() ? "the working directory" : ctx.parts_folder());
  out += fmt::format("File mask (FS): {}\n", ctx.parts_mask());
  out += fmt::format("Last file loaded (FE's blank): {}\n",
                     ctx.last_file().empty() ? "none" : ctx.last_file());
  out += editor_line(ctx);
  out += fmt::format("Units: {}; dialect: {}; axes in use: {}\n", u,
                     s.dialect == Dialect::FabMo ? "fabmo" : "sb3", s.display.axes);
  out += fmt::format("Coordinate system (SC): {}\n", st.user_zero && st.zero == Vec6::Zero()
                                                         ? "0, table base (user offsets set aside)"
                                                         : "1, user");
  out += fmt::format("Move speeds ({}/s): {}\n", u, groups(st.speeds.move));
  out += fmt::format("Jog speeds ({}/s): {}\n", u, groups(st.speeds.jog));
  const RampSettings& r = s.ramps;
  out += fmt::format("Move ramp speeds ({}/s): {}\n", u, groups(r.move_ramp_speed));
  out += fmt::format("Jog ramp speeds ({}/s): {}\n", u, groups(r.jog_ramp_speed));
  out += fmt::format(
      "Ramps: move rate {}, jog rate {}, keypad rate {} {}; 3D threshold {} %; minimum "
      "distance {}; slow corner {} %; small circle {}\n",
      show(r.move_ramp_rate), show(r.jog_ramp_rate), show(r.keypad_ramp_rate), u,
      show(r.threshold_3d), show(r.min_distance), show(r.slow_corner), show(r.small_circle));
  out += fmt::format("Steps per unit (VU): {}\n",
                     per_axis(s, [&](int i) { return show(s.axes[i].steps_per_unit); }));
  const CalibrationSettings& c = s.calibration;
  out += fmt::format(
      "Calibration: circle resolution {}; resolution multipliers {}, {}, {}, {}, {}; step "
      "divider {}; resolution shift {}\n",
      show(c.circle_resolution), show(c.resolution_multiplier[0]), show(c.resolution_multiplier[1]),
      show(c.resolution_multiplier[2]), show(c.resolution_multiplier[3]),
      show(c.resolution_multiplier[4]), c.step_divider, on_off(!c.no_resolution_shift));
  out += fmt::format(
      "Soft limits (VL, table base): {}; checking (SF) {}\n",
      per_axis(
          s,
          [&](int i) { return fmt::format("{} to {}", show(s.axes[i].min), show(s.axes[i].max)); }),
      on_off(s.machine.limit_checking));
  out += fmt::format("Cutter (VC): diameter {}, safe Z {}, safe A {}, pocket overlap {} %\n",
                     show(s.cutter.diameter), show(s.cutter.safe_z), show(s.cutter.safe_a),
                     show(s.cutter.pocket_overlap));
  out += fmt::format("Warning before moves (SW): {} s\n", show(s.machine.warning_s));
  out += profile_line(ctx);
  out += values_line(ctx);
  return out;
}

void values_display(CommandContext& ctx, const CommandCall& call) {
  print_and_save(ctx, call, values_report(ctx));
}

// ---- UD: diagnostics ---------------------------------------------------------------------

std::string diagnostic_report(CommandContext& ctx) {
  const Settings& s = ctx.settings();
  const ModalState& st = ctx.state();
  std::string out = fmt::format("Diagnostics (UD), Gantry {}:\n", GANTRY_VERSION);
  out += profile_line(ctx);
  out += values_line(ctx);
  const CardSettings& c = s.card;
  out += fmt::format("Card: {} (pacer {} Hz, step pulse {} us, direction setup {} us)\n", c.type,
                     show(c.pacer_hz()), show(c.step_pulse_us), show(c.dir_setup_us));
  out += fmt::format("Units: {}; planner: {}\n", units_name(s.units),
                     planner_mode_name(s.planner.mode));
  // Where the moves issued so far leave the tool, in the frame the step counts are in.
  const Vec6 machine = st.machine_origin + st.zero + st.position + st.applied_offset;
  out += fmt::format("Position in steps (the moves issued so far): {}\n", per_axis(s, [&](int i) {
                       return std::llround(machine[i] * s.axes[i].steps_per_unit);
                     }));
  out += fmt::format("Location: {}\n", per_axis(s, [&](int i) { return show(st.position[i]); }));
  out += fmt::format("Table base location: {}\n",
                     per_axis(s, [&](int i) { return show(st.position[i] + st.zero[i]); }));
  std::string outputs;
  for (int n = 1; n <= 32; ++n)
    if (st.outputs & (1u << (n - 1)))
      outputs += fmt::format("{}{}", outputs.empty() ? "" : ", ", n);
  out += fmt::format("Mode: {}, {}; output switches on: {}; moves issued: {}\n",
                     st.absolute ? "absolute (SA)" : "relative (SR)",
                     st.preview ? "preview (SP)" : "move/cut (SM)",
                     outputs.empty() ? "none" : outputs, ctx.moves());
  const std::vector<std::string> problems = settings_problems(s);
  out += fmt::format("Settings problems: {}\n", problems.empty() ? "none" : "");
  for (const std::string& p : problems) out += fmt::format("  - {}\n", p);
  return out;
}

void diagnostic_display(CommandContext& ctx, const CommandCall& call) {
  std::string report = diagnostic_report(ctx);
  ctx.print(report);
  if (const std::optional<std::string> name = call.text(0)) {
    report += values_report(ctx);  // both, as SB3's PROBLEM.LOG holds them
    const std::string path = ctx.write_file(*name, report, call.param_loc(0));
    ctx.print(fmt::format("UD saved this report and UV's to {}\n", path));
  }
}

// ---- UL, UU ------------------------------------------------------------------------------

void list_variables(CommandContext& ctx, const CommandCall&) {
  const auto vars = ctx.variables();
  if (vars.empty()) {
    ctx.print("No &variables are defined.\n");
    return;
  }
  std::string out;
  for (const auto& [name, v] : vars)
    out += v.is_number() ? fmt::format("&{} = {}\n", name, v.to_string())
                         : fmt::format("&{} = \"{}\"\n", name, v.str());
  ctx.print(out);
}

void calculator(CommandContext& ctx, const CommandCall& call) {
  ctx.print(format_number(*call.number(0)) + "\n");
}

// ---- UN: the editor ------------------------------------------------------------------------

// Whether `first` can be started: a path to a file, or a name on PATH.
bool startable(const std::string& first) {
  std::error_code ec;
  if (first.find('/') != std::string::npos) return std::filesystem::is_regular_file(first, ec);
  const char* path = std::getenv("PATH");
  std::string_view rest = path ? path : "";
  while (true) {
    const size_t colon = rest.find(':');
    const std::string dir(rest.substr(0, colon));
    if (std::filesystem::is_regular_file(std::filesystem::path(dir.empty() ? "." : dir) / first,
                                         ec))
      return true;
    if (colon == std::string_view::npos) return false;
    rest.remove_prefix(colon + 1);
  }
}

// UN shows the editor; it never changes it. A part file that could name the program FE
// starts could run any program (docs/security.md), and a value UN kept would live in the
// values file, which part files can write: the machine profile alone sets it.
void name_editor(CommandContext& ctx, const CommandCall& call) {
  const EditorChoice e = editor_choice(ctx);
  if (const std::optional<std::string> program = call.text(0))
    fail(call.param_loc(0),
         fmt::format("UN cannot change the editor{}: set it in the machine profile, [machine] "
                     "editor = \"{}\" (docs/security.md); FE uses {} ({})",
                     ctx.part_file_running() ? " from a part file" : "", *program, e.text, e.from));
  ctx.print(fmt::format("FE opens files in {} ({}){}\n", e.text, e.from,
                        e.words.empty() || startable(e.words.front())
                            ? ""
                            : "; no such program was found (PATH is searched for a bare name)"));
}

// ---- US, UR: settings files ----------------------------------------------------------------

// The current values: the settings, with the speeds MS and JS left in force.
Settings current(CommandContext& ctx) {
  Settings s = ctx.settings();
  s.speeds = ctx.state().speeds;
  return s;
}

void save_settings(CommandContext& ctx, const CommandCall& call) {
  const std::time_t now = std::time(nullptr);
  std::tm day{};
  localtime_r(&now, &day);
  char date[32];
  std::strftime(date, sizeof date, "%Y-%m-%d %H:%M", &day);
  const Settings s = current(ctx);
  const std::string text = fmt::format(
      "# Gantry settings saved by US on {} (profile \"{}\").\n"
      "# UR, FILE makes them the current values again; --settings FILE runs with them as the "
      "machine profile.\n\n{}",
      date, s.name, settings_text(s));
  const std::string path = ctx.write_file(*call.text(0), text, call.param_loc(0));
  ctx.print(fmt::format("US saved the current settings to {}; UR, {} loads them again\n", path,
                        *call.text(0)));
}

void reset_settings(CommandContext& ctx, const CommandCall& call) {
  const Settings& profile = profile_of(ctx);
  Settings next = profile;
  std::string from = "the machine profile's values";
  if (const std::optional<std::string> name = call.text(0)) {
    std::string path;
    const std::optional<std::string> text = ctx.read_file(*name, call.param_loc(0), &path);
    if (!text)
      fail(call.param_loc(0), fmt::format("UR: cannot read {}; nothing was changed", path));
    // Laid over the profile, as the values file is: US's complete files and values files
    // (only the keys that differ) both load.
    const SettingsLoad load =
        parse_settings(settings_text(profile), "the machine profile", *text, path);
    if (!load.ok())
      fail(call.param_loc(0),
           fmt::format("UR: {}; nothing was changed", format(load.errors.front())));
    next = load.settings;
    from = path;
  }
  Settings now = ctx.settings();
  convert_units(now, next.units);  // the machine's keys compare in the same units
  if (const std::string key = machine_key_changed(now, next); !key.empty())
    fail(call.param_loc(0),
         fmt::format("UR: {} describes another machine ({} differs from this run's); UR "
                     "loads the operator's values, not a machine: run with --settings to use "
                     "it; nothing was changed",
                     call.text(0) ? from : "the machine profile", key));
  if (const std::vector<std::string> problems = settings_problems(next); !problems.empty())
    fail(call.param_loc(0), fmt::format("UR: {} would break a rule of the machine profile: {}; "
                                        "nothing was changed",
                                        from, problems.front()));
  // For good: what a running file changed is not undone over UR's values when it ends.
  ctx.make_values_permanent();
  ctx.change_units(next.units, ValueScope::Permanent, call.loc);  // the location follows
  ctx.change_values(ValueScope::Permanent) = next;
  ctx.state().speeds = next.speeds;
  ctx.values_reach_motion(call.loc);
  ctx.print(fmt::format("UR loaded {} as the current values\n", from));
}

// ---- UI ------------------------------------------------------------------------------------

void install_firmware(CommandContext&, const CommandCall& call) {
  fail(call.loc,
       "UI (install control box firmware) cannot run on this machine: Gantry drives the step "
       "card directly, and there is no control box whose firmware could be installed; nothing "
       "was done");
}

ParamSpec text(std::string_view name, std::string_view help, bool required = false) {
  return {name, "", required, std::nullopt, help, ParamKind::Text};
}

}  // namespace

EditorChoice editor_choice(const CommandContext& ctx) {
  EditorChoice e{{}, profile_of(ctx).machine.editor, "the machine profile's [machine] editor"};
  for (const char* var : {"VISUAL", "EDITOR"})
    if (const char* set = std::getenv(var); e.text.empty() && set && *set)
      e = {{}, set, fmt::format("${}", var)};
  if (e.text.empty()) e = {{}, "vi", "neither the machine profile, $VISUAL nor $EDITOR names one"};
  std::istringstream words(e.text);
  for (std::string w; words >> w;) e.words.push_back(w);
  return e;
}

void add_utility_commands(std::vector<CommandSpec>& out) {
  const auto U = CommandGroup::Utilities;
  out.push_back({"UD",
                 "Utilities: diagnostic display",
                 U,
                 "Prints a diagnostic report: the version, the machine profile and values file, "
                 "the card and its timing, the position in motor steps, the location, the modes, "
                 "and any broken rule of the settings. Given a file, saves it there with UV's "
                 "report (SB3's PROBLEM.LOG).",
                 {text("save to", "A file for the report (blank: printed only).")},
                 diagnostic_display});
  out.push_back({"UI",
                 "Utilities: install control box firmware",
                 U,
                 "Installs firmware in a ShopBot control box. Gantry drives the step card "
                 "directly and has no control box: UI says so and does nothing.",
                 {},
                 install_firmware,
                 "refused by name: Gantry drives the step card directly; there is no control "
                 "box whose firmware could be installed"});
  out.push_back({"UL",
                 "Utilities: list variables",
                 U,
                 "Prints every &variable as `&NAME = value`, sorted by name; text values in "
                 "double quotes. Define variables with VV or `&name = value`.",
                 {},
                 list_variables,
                 "editing the list in an editor (SB3); set variables with VV or &name = value"});
  out.push_back({"UN",
                 "Utilities: name of editor program",
                 U,
                 "Shows the program FE opens files in and where it is set: the machine "
                 "profile's [machine] editor, else $VISUAL, $EDITOR, vi. Only the profile "
                 "changes it: UN with a program is refused, from a part file and from the "
                 "console alike (docs/security.md).",
                 {text("program", "Refused: set [machine] editor in the machine profile instead.")},
                 name_editor,
                 "naming the editor: the machine profile sets it (docs/security.md)",
                 {},
                 false});
  out.push_back({"UR",
                 "Utilities: reset settings",
                 U,
                 "Makes a settings file (saved by US, or a values file) the current values, or "
                 "the machine profile's own values when blank. The values last, and the run "
                 "saves them to the values file. A file for another machine (card, wiring, "
                 "axis hardware limits, planner) is refused.",
                 {text("settings file", "Saved by US (blank: the machine profile's values).")},
                 reset_settings,
                 "clearing the system log (Gantry keeps none)",
                 {},
                 false});
  out.push_back({"US",
                 "Utilities: save settings",
                 U,
                 "Saves every current setting (with the speeds in force) to a file as a complete "
                 "machine profile; UR loads it back, --settings runs with it.",
                 {text("file name",
                       "The settings file to write; a relative name goes in the "
                       "parts folder.",
                       true)},
                 save_settings});
  out.push_back(
      {"UU",
       "Utilities: calculator",
       U,
       "Prints the value of an expression, e.g. `UU, 12+11/16` prints 12.6875. Any "
       "parameter of any command may be such an expression; trigonometry is in "
       "radians (degrees in the FabMo dialect).",
       {{"expression", "", true, std::nullopt, "The calculation; &variables may be used."}},
       calculator});
  out.push_back({"UV",
                 "Utilities: values display",
                 U,
                 "Prints the values and settings the location readout does not show: the parts "
                 "folder and mask, the editor, units, speeds, ramps, calibration, limits, the "
                 "cutter, and where the profile and values file are. Given a file, saves it "
                 "there.",
                 {text("save to", "A file for the report (blank: printed only).")},
                 values_display});
}

}  // namespace gantry
