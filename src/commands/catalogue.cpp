// Every other code of the SB3 and FabMo references (shared/spec/commands.md §1), so that a
// part file using one is told by name that Gantry cannot honour it yet, and nothing runs.
#include <fmt/format.h>  // messages

#include <algorithm>  // find
#include <cctype>     // tolower
#include <deque>
#include <string>

#include "gantry/commands/command_table.hpp"
#include "gantry/interp/interpreter.hpp"

namespace gantry {
namespace {

// A catalogued code: what the references say it is, and what to do instead in Gantry.
struct Entry {
  std::string_view code;
  std::string_view name;
  CommandGroup group;
  std::string_view help;
  std::vector<ParamSpec> params;
  std::string_view instead;  // appended to the message; "" when there is nothing to suggest
};

ParamSpec num(std::string_view name, std::string_view unit, std::optional<double> def,
              std::string_view help) {
  return {name, unit, false, def, help};
}
ParamSpec text(std::string_view name, std::string_view help) {
  return {name, "", false, std::nullopt, help, ParamKind::Text};
}

// A probe: switch, speed, then a target per axis.
std::vector<ParamSpec> probe(std::string_view letters) {
  static const std::string names[] = {"target X", "target Y", "target Z",
                                      "target A", "target B", "target C"};
  std::vector<ParamSpec> out = {num("switch", "", std::nullopt, "Input switch that stops it."),
                                num("speed", "units/s", std::nullopt, "Probing speed.")};
  for (char a : letters)
    out.push_back(num(names[std::string_view("XYZABC").find(a)], "units", std::nullopt,
                      "Where the move stops if the switch never triggers."));
  return out;
}

// `count` free-form parameters, for codes whose references give no fixed list.
std::vector<ParamSpec> free_params(std::string_view name, int count, std::string_view help) {
  static const std::string names[] = {" 1", " 2", " 3", " 4", " 5", " 6", " 7", " 8"};
  static std::deque<std::string> store;  // the names must outlive the table (deque: stable)
  std::vector<ParamSpec> out;
  for (int i = 0; i < count; ++i) {
    store.push_back(std::string(name) + names[i]);
    out.push_back(text(store.back(), help));
  }
  return out;
}

// The two parameters that follow the size in CA, CC, CP and CR.
std::vector<ParamSpec> cut_tail() {
  return {text("O/I/T", "O: size is the outside of the cut, I: the inside, T (default): the path."),
          num("direction", "", 1.0, "1 clockwise, -1 counter-clockwise.")};
}

std::vector<ParamSpec> plus(std::vector<ParamSpec> a, const std::vector<ParamSpec>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

const ParamSpec kPlunge = num("plunge", "units", 0.0, "Depth per repetition; negative is down.");
const ParamSpec kReps = num("repetitions", "", 1.0, "Number of passes.");
const ParamSpec kPropX = num("proportion X", "", 1.0, "Scale in X (an ellipse).");
const ParamSpec kPropY = num("proportion Y", "", 1.0, "Scale in Y.");
const ParamSpec kFeature =
    num("feature", "", 0.0, "1 tabs (SB3), 2 pocket, 3 spiral plunge, 4 spiral and bottom pass.");
const ParamSpec kNoPullUp = num("no pull up", "", 0.0, "1 leaves the tool down at the end.");
const ParamSpec kFromZero = num("plunge from Z 0", "", 0.0, "1 plunges from Z 0.");

// SB3's file parameters, shared by FG (and FP).
std::vector<ParamSpec> file_params() {
  return {text("file name", "The part file."),
          num("proportion X", "", 1.0, "Scale of X."),
          num("proportion Y", "", 1.0, "Scale of Y."),
          num("proportion Z", "", 1.0, "Scale of Z."),
          kReps,
          num("offset", "", 0.0, "0 none, 1 3D offset, 2 2D offset."),
          kPlunge,
          num("tab feature", "", 0.0, "1 adds tabs on the last pass."),
          kFromZero};
}

const std::vector<Entry>& catalogue() {
  using G = CommandGroup;
  static const std::vector<Entry> entries = [] {
    const std::string_view ui = "A screen of the ShopBot console; Gantry has no console screens.";
    std::vector<Entry> e;
    // Cuts
    e.push_back({"CA", "Cut arch", G::Cuts,
                 "Cuts a circular arch of a given span and height from the current position.",
                 plus({num("arch length", "units", std::nullopt, "Span of the arch (required)."),
                       num("arch height", "units", std::nullopt, "Height of the arch (required).")},
                      plus(cut_tail(),
                           {num("alignment angle", "degrees", 0.0, "Clockwise from horizontal."),
                            kPlunge, kReps, kPropX, kPropY,
                            num("tab feature", "", 0.0, "1 adds tabs (SB3; FabMo skips it)."),
                            kNoPullUp, kFromZero})),
                 "cut the arch with M2/M3 moves, or CG arcs once they exist"});
    e.push_back(
        {"CC", "Cut circle", G::Cuts,
         "Cuts a circle, arc or ellipse that begins at the current position.",
         plus({num("diameter", "units", std::nullopt, "Circle diameter (required).")},
              plus(cut_tail(),
                   {num("begin angle", "degrees", std::nullopt, "From 12 o'clock, clockwise."),
                    num("end angle", "degrees", std::nullopt, "From 12 o'clock, clockwise."),
                    kPlunge, kReps, kPropX, kPropY, kFeature, kNoPullUp, kFromZero})),
         "approximate the circle with M2 moves"});
    e.push_back(
        {"CG",
         "Cut G-code circle",
         G::Cuts,
         "Cuts a G2/G3-style arc from the current position to an end point.",
         {num("diameter", "units", std::nullopt, "Arcs under 180 degrees (FabMo: obsolete)."),
          num("X end", "units", std::nullopt, "End point X (blank: the start)."),
          num("Y end", "units", std::nullopt, "End point Y (blank: the start)."),
          num("X center offset", "units", std::nullopt, "I, from the start; modal."),
          num("Y center offset", "units", std::nullopt, "J, from the start; modal."),
          text("O/I/T", "O outside, I inside, T (default) on the path."),
          num("direction", "", 1.0, "1 clockwise, -1 counter-clockwise."), kPlunge, kReps, kPropX,
          kPropY, kFeature, kNoPullUp, kFromZero},
         "approximate the arc with M2 moves"});
    e.push_back(
        {"CP", "Cut circle from center point", G::Cuts,
         "Cuts a circle given its centre; the tool first moves to the start point.",
         plus({num("diameter", "units", std::nullopt, "Circle diameter (required)."),
               num("X center", "units", std::nullopt, "Centre X (required)."),
               num("Y center", "units", std::nullopt, "Centre Y (required).")},
              plus(cut_tail(), {num("start angle", "degrees", 0.0, "From 12 o'clock, clockwise."),
                                num("end angle", "degrees", 0.0, "From 12 o'clock, clockwise."),
                                kPlunge, kReps, kPropX, kPropY, kFeature, kNoPullUp, kFromZero})),
         "approximate the circle with M2 moves"});
    e.push_back({"CR", "Cut rectangle", G::Cuts,
                 "Cuts a rectangle whose start corner is the current position.",
                 plus({num("length X", "units", std::nullopt, "Width (required)."),
                       num("length Y", "units", std::nullopt, "Height (blank: a square).")},
                      plus(cut_tail(),
                           {num("start corner", "", 4.0,
                                "1 upper left, 2 upper right, 3 bottom right, 4 bottom left."),
                            kPlunge, kReps,
                            num("feature", "", 0.0, "SB3: 1 tabs, 2 pocket; FabMo: 2 or 3 pocket."),
                            kFromZero})),
                 "cut the sides with MX and MY moves"});
    e.push_back({"C3",
                 "Homing macro (FabMo)",
                 G::Cuts,
                 "FabMo's shortcut for macro 3, the homing macro. Gantry reads C3 as custom cut 3: "
                 "it runs C3.sbp or macro_3.sbp, so this entry is never dispatched.",
                 {},
                 "write the homing routine as C3.sbp (custom cut 3)"});
    // File
    e.push_back({"FC",
                 "File conversion",
                 G::File,
                 "Converts a DXF, HP-GL, G-code or image file into a part file.",
                 {text("file name", "The file to convert.")},
                 "convert the file with CAM software and run the part file with FP"});
    e.push_back({"FE",
                 "File edit",
                 G::File,
                 "Opens a part file in the editor.",
                 {text("file name", "The file (blank: the last one).")},
                 "edit part files with any text editor"});
    e.push_back({"FG", "File: run a part file step by step", G::File,
                 "Loads a part file to step through it line by line, or run from a line.",
                 file_params(), "run the file with FP; `gantry moves` lists what each line does"});
    e.push_back({"FS",
                 "File: set the parts folder",
                 G::File,
                 "Sets the folder part files are found in, and the file mask.",
                 {text("folder", "Path (blank: the program folder)."),
                  text("mask", "File selector mask (default *.sb?).")},
                 "FP finds relative names beside the top-level file; give FP a path instead"});
    // Jog and move
    e.push_back(
        {"MI",
         "Move indexer or oscillate",
         G::Move,
         "Starts continuous rotation or oscillation of one axis alongside other moves.",
         {text("axis", "Axis letter (default B)."), num("direction", "", 1.0, "1 clockwise."),
          num("rotary speed", "units/s", std::nullopt, "Speed of rotation."),
          num("frequency", "Hz", std::nullopt, "Oscillation cycles per second."),
          num("distance", "units", std::nullopt, "Oscillation distance.")},
         ""});
    e.push_back({"MN",
                 "Move nudge",
                 G::Move,
                 "A panel of small adjustments of the current location.",
                 {},
                 "make a short relative move (SR), or zero an axis with ZX, ZY or ZZ"});
    // Probe
    const std::tuple<std::string_view, std::string_view, std::string_view> probes[] = {
        {"PX", "Probe in X", "X"},
        {"PY", "Probe in Y", "Y"},
        {"PZ", "Probe in Z", "Z"},
        {"PA", "Probe in A", "A"},
        {"PB", "Probe in B", "B"},
        {"PC", "Probe in C", "C"},
        {"P2", "Probe in 2 dimensions", "XY"},
        {"P3", "Probe in 3 dimensions", "XYZ"},
        {"P4", "Probe in 4 dimensions", "XYZA"},
        {"P5", "Probe in 5 dimensions", "XYZAB"},
        {"P6", "Probe in 6 dimensions", "XYZABC"}};
    for (const auto& [code, name, letters] : probes)
      e.push_back({code, name, G::Probe,
                   "Moves toward the target until the input switch triggers (FabMo).",
                   probe(letters), "probing needs live inputs, which arrive with issue 8"});
    // Record
    const std::string_view record = "the session record is not kept; keep the lines in a part file";
    e.push_back({"RA", "Record: activate", G::Record, "Turns command recording on.", {}, record});
    e.push_back(
        {"RI", "Record: inactivate", G::Record, "Turns command recording off.", {}, record});
    e.push_back(
        {"RP", "Record: play all", G::Record, "Replays every recorded command.", {}, record});
    e.push_back({"RR",
                 "Record: replay last commands",
                 G::Record,
                 "Replays the last commands, repeated.",
                 {text("commands back", "How many (1; A for all)."),
                  num("repetitions", "", 1.0, "How many times.")},
                 record});
    e.push_back({"RS",
                 "Record: save to a file",
                 G::Record,
                 "Saves the recorded commands to a file and opens it.",
                 {text("file name", "Blank: SBTEMP.SBP."),
                  num("commands back", "", std::nullopt, "Blank: all.")},
                 record});
    e.push_back({"RZ", "Record: zero the memory", G::Record, "Clears the record.", {}, record});
    // Settings
    e.push_back({"SC",
                 "Set coordinate system",
                 G::Settings,
                 "Selects the working coordinate system: 0 table base, 1 user (FabMo).",
                 {num("system", "", std::nullopt, "0 table base, 1 user.")},
                 "Gantry has one working system over table base; zero it with Z2, Z3 and ZX"});
    e.push_back(
        {"SI", "Send command lines", G::Settings, "A scratch pad to type lines and send them.",
         free_params("line", 8, "A line to send."), "write the lines in a part file and run it"});
    e.push_back({"SK",
                 "Set to keypad mode",
                 G::Settings,
                 "Manual jogging from the keypad; a file resumes when it is closed.",
                 {text("message", "Shown on the keypad (FabMo).")},
                 "Gantry has no keypad; jog with J commands"});
    // Utilities
    e.push_back({"UD",
                 "Utilities: diagnostic display",
                 G::Utilities,
                 ui,
                 {},
                 "`gantry run` reports the card's counts and timing"});
    e.push_back({"UI", "Utilities: install firmware", G::Utilities, ui, {}, ""});
    e.push_back({"UL",
                 "Utilities: list variables",
                 G::Utilities,
                 "Lists the variables in the editor as &name = value.",
                 {},
                 "PRINT a variable to see its value"});
    e.push_back({"UN",
                 "Utilities: name of editor",
                 G::Utilities,
                 "Sets the editor FE uses.",
                 {text("program", "Path of the editor.")},
                 "edit part files with any text editor"});
    e.push_back({"UR",
                 "Utilities: reset settings",
                 G::Utilities,
                 "Loads default or saved settings, or clears the system log.",
                 {},
                 "choose the machine profile with --settings (docs/settings.md)"});
    e.push_back({"US",
                 "Utilities: save settings",
                 G::Utilities,
                 "Saves the current settings to a file.",
                 {},
                 "settings live in the machine profile (docs/settings.md)"});
    e.push_back({"UU",
                 "Utilities: calculator",
                 G::Utilities,
                 ui,
                 {},
                 "any parameter may be an expression, such as 12+11/16"});
    e.push_back({"UV",
                 "Utilities: values display",
                 G::Utilities,
                 ui,
                 {},
                 "system variables %(n) give the values (docs/system_variables.md)"});
    // Values
    e.push_back({"VK",
                 "Values (undocumented)",
                 G::Values,
                 "Named only in SB3's UV entry; neither reference describes it.",
                 {},
                 ""});
    {
      std::vector<ParamSpec> vn = {
          num("limits on", "", 1.0, "1 limit switches stop the tool."),
          num("stop switch 4 mode", "", 0.0, "0 normally closed."),
          num("accessory enable", "", 0.0, "Enables VH (torch, laser, analog).")};
      for (ParamSpec& p : free_params("input mode", 8, "Mode of an input (SB3 positions unclear)."))
        vn.push_back(p);
      for (ParamSpec& p :
           free_params("output mode", 8, "Mode of an output (SB3 positions unclear)."))
        vn.push_back(p);
    }
    {
      std::vector<ParamSpec> vr;
      for (const char* n :
           {"XY move ramp speed", "Z move ramp speed", "A move ramp speed", "B move ramp speed",
            "XY jog ramp speed", "Z jog ramp speed", "A jog ramp speed", "B jog ramp speed"})
        vr.push_back(num(n, "units/s", 0.4, "Start and end speed of a ramp."));
      vr.push_back(num("move ramp rate", "units", 0.2, "Distance to change move speed by 2."));
      vr.push_back(num("jog ramp rate", "units", 0.2, "Distance to change jog speed by 2."));
      vr.push_back(num("3D threshold", "%", 100.0, "3D ramping sensitivity."));
      vr.push_back(num("minimum distance", "units", 0.15, "Shortest move considered."));
      vr.push_back(num("slow corner", "%", 65.0, "Speed cut at a slight corner."));
      vr.push_back(num("obsolete", "", std::nullopt, "Leave blank."));
      vr.push_back(num("obsolete", "", std::nullopt, "Leave blank."));
      vr.push_back(num("keypad ramp rate", "units", 0.2, "Ramp rate of the keypad."));
      vr.push_back(num("small circle", "units", 0.25, "Circles below this run at ramp speed."));
    }
    e.push_back({"VV",
                 "Values for variables",
                 G::Values,
                 "Defines variables; named by SB3's SL and UL entries, described by neither.",
                 {},
                 "set a variable with &name = value"});
    // Zero
    return e;
  }();
  return entries;
}

// Says which code cannot run, by name, and what to do instead; nothing else happens.
void not_implemented(CommandContext&, const CommandCall& call) {
  const Entry* entry = nullptr;
  for (const Entry& e : catalogue())
    if (e.code == call.spec.code) entry = &e;
  std::string name(call.spec.name);
  if (!name.empty()) name[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(name[0])));
  std::string message =
      fmt::format("{} ({}) is not implemented yet in Gantry", call.spec.code, name);
  if (entry && !entry->instead.empty()) message += fmt::format("; {}", entry->instead);
  fail(call.loc, message);
}

}  // namespace

void add_catalogue_commands(std::vector<CommandSpec>& out,
                            const std::vector<CommandSpec>& implemented) {
  // Copied first: `implemented` may be `out` itself, which push_back may reallocate.
  std::vector<std::string_view> have;
  for (const CommandSpec& s : implemented) have.push_back(s.code);
  for (const Entry& e : catalogue()) {
    if (std::find(have.begin(), have.end(), e.code) != have.end()) continue;
    out.push_back({e.code, e.name, e.group, e.help, e.params, not_implemented, "not implemented"});
  }
}

}  // namespace gantry
