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

const ParamSpec kPlunge = num("plunge", "units", 0.0, "Depth per repetition; negative is down.");
const ParamSpec kReps = num("repetitions", "", 1.0, "Number of passes.");
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
    std::vector<Entry> e;
    // Cuts
    e.push_back({"C3",
                 "Homing macro (FabMo)",
                 G::Cuts,
                 "FabMo's shortcut for macro 3, the homing macro. Gantry reads C3 as custom cut 3: "
                 "it runs C3.sbp or macro_3.sbp, so this entry is never dispatched.",
                 {},
                 "write the homing routine as C3.sbp (custom cut 3)"});
    // File
    e.push_back({"FG", "File: run a part file step by step", G::File,
                 "Loads a part file to step through it line by line, or run from a line.",
                 file_params(), "run the file with FP; `gantry moves` lists what each line does"});
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
    e.push_back(
        {"SI", "Send command lines", G::Settings, "A scratch pad to type lines and send them.",
         free_params("line", 8, "A line to send."), "write the lines in a part file and run it"});
    e.push_back({"SK",
                 "Set to keypad mode",
                 G::Settings,
                 "Manual jogging from the keypad; a file resumes when it is closed.",
                 {text("message", "Shown on the keypad (FabMo).")},
                 "Gantry has no keypad; jog with J commands"});
    // Values
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
