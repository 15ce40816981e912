// Settings commands that set modes of a run: SF, SV, SW, SL, SM, SP, SK and FabMo's SU; and
// FabMo's CN (call a macro) and C3 (its homing macro).
#include <fmt/format.h>  // messages

#include "gantry/commands/command_table.hpp"
#include "gantry/interp/command_context.hpp"

namespace gantry {
namespace {

// SF: soft-limit checking on or off. In a part file it lasts until the file ends (SV keeps
// it); typed at the console it stays.
void set_limit_checking(CommandContext& ctx, const CommandCall& call) {
  ctx.change_values(ValueScope::File).machine.limit_checking = *call.number(0) != 0;
}

void make_permanent(CommandContext& ctx, const CommandCall&) {
  ctx.make_values_permanent();
}

void set_warning(CommandContext& ctx, const CommandCall& call) {
  ctx.change_values(ValueScope::Permanent).machine.warning_s = *call.number(0);
}

void clear_variables(CommandContext& ctx, const CommandCall&) {
  ctx.clear_variables();
}

// SP: what follows is previewed, not cut: moves change the location but reach no motor.
// SM returns to the machine: the location is the tool's again, as it was at SP.
void set_preview(CommandContext& ctx, const CommandCall& call) {
  ModalState& st = ctx.state();
  if (st.preview) return;  // SP while previewing restarts the preview: nothing to keep
  ctx.come_to_rest(call.loc);
  st.preview =
      PreviewReturn{st.position, st.zero, st.machine_origin, st.applied_offset, st.tool_offset};
}

// SK: the operator jogs with the keypad; the file goes on from where the tool is when they
// close it. A preview (SP) has no machine to jog.
void keypad(CommandContext& ctx, const CommandCall& call) {
  if (ctx.state().preview) return;
  ctx.keypad(call.text(0).value_or(""), call.loc);
}

void set_move_mode(CommandContext& ctx, const CommandCall&) {
  ctx.end_preview();
}

// SU (FabMo, in its stock macros): units for the rest of the file; they revert at its end.
void set_units(CommandContext& ctx, const CommandCall& call) {
  const std::string u = call.text(0).value_or("");
  const bool mm = u == "1" || u == "mm" || u == "MM";
  ctx.change_units(mm ? Units::Millimetres : Units::Inches, ValueScope::File, call.loc);
}

// CN (FabMo, in its stock macros): runs macro n, as C<n> does.
void call_macro(CommandContext& ctx, const CommandCall& call) {
  ctx.call_macro(static_cast<int>(*call.number(0)), call.loc);
}

// C3 (FabMo's homing macro). A part file's C3 line is read as custom cut 3, which does the
// same; this entry gives it its name and help.
void homing_macro(CommandContext& ctx, const CommandCall& call) {
  ctx.call_macro(3, call.loc);
}

// SC (FabMo): 0 reads and moves in table base coordinates, the user system's offsets (the
// zero commands') set aside; 1 brings them back. Offsets set while 0 is in force (ZX, VA,
// ZT...) make a new user system, which stays: the ones set aside are dropped.
void set_coordinate_system(CommandContext& ctx, const CommandCall& call) {
  ModalState& st = ctx.state();
  const bool table_base = st.user_zero && st.zero == Vec6::Zero();
  if (*call.number(0) == 0) {
    if (table_base) return;
    st.user_zero = st.zero;
    st.position += st.zero;
    st.zero = Vec6::Zero();
    return;
  }
  if (table_base) {
    st.zero = *st.user_zero;
    st.position -= st.zero;
  }
  st.user_zero.reset();
}

}  // namespace

void add_settings_commands(std::vector<CommandSpec>& out) {
  const auto S = CommandGroup::Settings;
  out.push_back({"SF",
                 "Set limit checking",
                 S,
                 "Turns checking of every move against the soft limits (VL) on or off. In a "
                 "part file the change lasts until the file ends, unless SV.",
                 {ParamSpec{"checking", "", true, std::nullopt, "1 on, 0 off."}.integer(0, 1)},
                 set_limit_checking,
                 "",
                 {},
                 false,
                 "%(30)"});
  out.push_back({"SV",
                 "Set values permanent",
                 S,
                 "Keeps the values that VS, VU, VI, VL and SF changed in this part file (and in "
                 "the files that called it) when the files end.",
                 {},
                 make_permanent,
                 "",
                 {},
                 true});
  out.push_back(
      {"SW",
       "Set warning duration",
       S,
       "Seconds of warning before a run moves the tool: the machine waits, the console "
       "beeps and output switch 4 comes on (SO). 0 turns the wait off.",
       {ParamSpec{"duration", "s", false, 2.0, "Warning time, 0 to 3600."}.range(0, 3600)},
       set_warning,
       "",
       {},
       false,
       "%(21)"});
  out.push_back({"SL",
                 "Set: clear all variables",
                 S,
                 "Deletes every &variable and its value ($variables are kept).",
                 {},
                 clear_variables,
                 "",
                 {},
                 true});
  out.push_back({"SM",
                 "Set to move/cut mode",
                 S,
                 "Commands move the machine again; after SP, the location is the tool's as it "
                 "was when SP ran.",
                 {},
                 set_move_mode,
                 "",
                 {},
                 true,
                 "%(22)"});
  out.push_back(
      {"SU",
       "Set units for this file",
       S,
       "FabMo: inches or millimetres until the part file ends (every value and the "
       "location are converted, and converted back at the end).",
       {ParamSpec{"units", "", true, std::nullopt, "0 or in: inches; 1 or mm: mm.", ParamKind::Text}
            .one_of("0 1 in mm IN MM")},
       set_units,
       "",
       {},
       false,
       "%(25)"});
  out.push_back(
      {"CN",
       "Call macro",
       CommandGroup::Cuts,
       "FabMo: runs macro number n (C<n>.sbp or macro_<n>.sbp), as C<n> does.",
       {ParamSpec{"macro", "", true, std::nullopt, "The macro's number."}.integer(0, 1e6)},
       call_macro});
  out.push_back({"C3",
                 "Homing macro (FabMo)",
                 CommandGroup::Cuts,
                 "FabMo's shortcut for macro 3, the homing macro: runs C3.sbp or macro_3.sbp, "
                 "or without them the built-in homing on the proximity switches.",
                 {},
                 homing_macro});
  out.push_back({"SK",
                 "Set to keypad mode",
                 S,
                 "Hands the machine to the keypad: the operator jogs (arrows X and Y, "
                 "PageUp/PageDown Z) and closes the keypad to go on; a part file waits, then "
                 "continues from where the tool is. Typed at the console it opens the keypad.",
                 {ParamSpec{"message", "", false, std::nullopt,
                            "Shown with the keypad, e.g. what to do before going on (FabMo).",
                            ParamKind::Text}},
                 keypad,
                 {},
                 {},
                 true,
                 "%(1)-%(10)"});
  out.push_back({"SP",
                 "Set to preview mode",
                 S,
                 "Moves that follow change the location without moving the machine, until SM.",
                 {},
                 set_preview,
                 "the moves are not drawn as they are previewed: `gantry preview` and the "
                 "window's 3D view draw a file before it runs",
                 {},
                 true,
                 "%(22)"});
  out.push_back(
      {"SC",
       "Set coordinate system",
       S,
       "FabMo: 0 selects the table base system (locations and moves in table base "
       "coordinates; the zero commands' offsets are set aside), 1 the user system (the "
       "offsets back). Zeroing while 0 is in force makes a new user system.",
       {ParamSpec{"system", "", true, std::nullopt, "0 table base, 1 user."}.integer(0, 1)},
       set_coordinate_system,
       "",
       {},
       false,
       "%(1)-%(5)"});
}

}  // namespace gantry
