// Friendly Motion's command table: the one list `gantry help fm`, the parser's code lists and
// docs/friendlymotion.md's command table come from.
#include "gantry/lang/fm.hpp"

#include <fmt/format.h>  // the listings

namespace gantry {

const std::vector<FmCommandInfo>& fm_commands() {
  static const std::vector<FmCommandInfo> table = {
      {"!", "Comment", "X1 !text", "The rest of the line is ignored (a ! inside quotes is text)."},
      {"N", "Sequence number", "N#", "A target of J and K, 1 to 99999; first on its line."},
      {"X Y", "Linear motion", "X# Y#  X#Y#",
       "X1 Y1 moves X, then Y; X1Y1 is one interpolated move. G90 absolute, G91 incremental; "
       "the table stops after each move outside G9...G0."},
      {"Z A B", "Linear motion (other axes)", "Z#  A#.#  B#",
       "Single-axis moves as X and Y (named in the quick reference only); A with one digit "
       "alone is refused as ambiguous with string An."},
      {"C", "Rotary motion", "C#", "The rotary axis, in degrees; at the C feed (FC)."},
      {"XYIJ", "Circular motion", "X#Y#I#J#[R#]",
       "An arc to X,Y about centre I,J (absolute under G90, relative to the start under G91), "
       "direction from G2/G3; end = start is a full circle; R# runs it # times."},
      {"F", "Set feed rate", "F#  FX#  FY#  FC#",
       "Feed in units per second: F, FX and FY set the X-Y feed (0.005-6 in/s, or the "
       "profile's [friendly_motion] range; outside it an error), FC the C axis (deg/s)."},
      {"G0", "End profile", "G0",
       "Ends continuous velocity (G9): the table stops after each "
       "move again. G0R# is refused (undocumented)."},
      {"G2", "Clockwise", "G2", "Arcs that follow run clockwise (the default)."},
      {"G3", "Counter-clockwise", "G3", "Arcs that follow run counter-clockwise."},
      {"G4", "Timed delay", "G4X#[Q]",
       "Waits # seconds (at least 0.001) with the table at rest; Q inside a profile (a delay "
       "while the axes move) is refused."},
      {"G7", "Direct communication", "G7...", "Refused: there is no U.S. Laser controller.", false},
      {"G9", "Begin profile", "G9", "Continuous velocity: moves blend until G0."},
      {"G10", "Select font file", "G10\"file\"",
       "Only the default fontfile.txt (Gantry's own stroke font); other font files are refused "
       "(their format is not documented)."},
      {"G16", "Scribe characters", "G16\"text\"  G16",
       "Scribes the text in Gantry's stroke font from the lower left corner, laser on along "
       "the strokes; _ is a space, ) a new line, %s %i %f %c insert @0 or V73."},
      {"G19", "Character size", "G19#", "Characters # inches (or mm) high (1 at start)."},
      {"G20", "Create output file", "G20name  G20@n  G20",
       "Creates a data file (deleted first); .dat added, the data folder when no path."},
      {"G21", "Open output file (append)", "G21name  G21@n  G21", "Appends to a data file."},
      {"G22", "Close output file", "G22", "Closes the output file."},
      {"G23", "Open input file", "G23name  G23@n  G23", "Opens a data file to read."},
      {"G24", "Close input file", "G24", "Closes the input file."},
      {"G25", "Write text to output file", "G25\"text\"V#@#", "Writes a line as G58 shows it."},
      {"G26", "Write values to output file", "G26e1,e2,...,e5",
       "Writes up to 5 values, comma-separated, then a new line."},
      {"G27", "Read values from input file", "G27[R#,]V#,...",
       "Reads up to 5 values (from record R#), into variables whose index is an expression."},
      {"G43", "Dry run", "G43",
       "Moves run; outputs (M100-M131, P's relays, the laser) stay as they are."},
      {"G44", "Normal run", "G44", "Outputs switch again."},
      {"G58", "Display data", "G58\"text\"V#@#",
       "Shows text, values (4 decimals) and strings, upper case, one space apart."},
      {"G60", "User coordinate system", "G60X  G60A  G60C",
       "G60X: origin V81,V82 and a point on +X V83,V84; G60A: origin and angle V85; G60C: off."},
      {"G68", "Scaling", "G68#  G68X#  G68Y#", "Multiplies later X/Y moves; negative mirrors."},
      {"G70", "Inch mode", "G70", "Program values in inches (and in/s)."},
      {"G71", "Metric mode", "G71", "Program values in millimetres (and mm/s)."},
      {"G90", "Absolute mode", "G90", "Targets from ZERO."},
      {"G91", "Incremental mode", "G91", "Targets from the current point (the default)."},
      {"J", "Jump", "JN#  JM2##N#  JV#N#",
       "Jumps to N#; with M2## when that input is active, with V# when the variable is > 0."},
      {"K", "Subroutine call", "KN#[R#]  KM2##N#  KV#N#",
       "Calls N# until M6 (10 deep); R# calls it # more times."},
      {"L", "(undocumented)", "L...", "Refused: the manual never describes it.", false},
      {"M0", "Program stop", "M0",
       "Stops for the operator, who continues line by line (STEP) or runs on (AUTO)."},
      {"M1", "Reset motion controller", "M1", "The motion comes to rest; the profile ends."},
      {"M2", "Repeat program", "M2",
       "Back to the first line (AUTO repeats until the operator stops it; a check, or a run "
       "nobody attends, passes once)."},
      {"M3", "Manual positioning", "M3", "The operator jogs (keypad); V91-V94 follow."},
      {"M6", "Return from subroutine", "M6", "Ends a subroutine; alone on its line."},
      {"M94", "C free run (+)", "M94", "The C axis turns on its own, positive."},
      {"M95", "C free run (-)", "M95", "The C axis turns on its own, negative."},
      {"M96", "End C free run", "M96", "C stops; its position becomes ZERO."},
      {"M97", "C quick zero", "M97", "C moves to the nearest multiple of 360 and becomes ZERO."},
      {"M98", "Axis zero", "M98  M98X  M98Y", "The current position becomes ZERO (not under G60)."},
      {"M99", "Machine home", "M99  M99X  M99Y", "Homes the axes; ends the user coordinates."},
      {"M100-M131", "Output M-functions", "M1##  MV#",
       "Even codes switch output (code-100)/2+1 on, odd off, at rest between moves; M100/M101 "
       "the laser's ([friendly_motion] laser_output, with its on/off waits)."},
      {"M200-M231", "Input M-functions", "M2##", "Waits until input (code-200)+1 is active."},
      {"V", "Variables", "V#=expr  V#=?  V#=?(text)  V#",
       "V0-V90 assigned; + - * / ^ ( ), SIN COS TAN ASIN ACOS ATAN (degrees) right after =; "
       "=? asks the operator; V# alone shows it. V91-V98 read the machine."},
      {"@", "Strings", "@#=text  A#=text  @#=?  @#", "Strings @0-@9: set, ask, show."},
      {"P", "Relay matrix", "PA#  PB#  PD",
       "Connects test probe # to bus A or B (and lets it go from the other), or disconnects "
       "all, through the output switches [friendly_motion] relay_a and relay_b name; refused "
       "when the profile wires none."},
      {"S", "Analog I/O", "Sf#  SC#",
       "Q-switch frequency (kHz) and lamp current: recorded (no analog output is wired)."},
      {"T", "Trimming", "T...", "Refused: the T line's format is not documented.", false},
  };
  return table;
}

std::string fm_command_list() {
  std::string out =
      "Friendly Motion (U.S. Laser) commands, as Gantry reads .fm files "
      "(docs/friendlymotion.md).\nSeveral commands on a line, separated by spaces, run left "
      "to right; # is a number, a variable V0-V99 or an expression.\n\n";
  for (const FmCommandInfo& c : fm_commands())
    out += fmt::format("  {:<10} {:<28} {}{}\n               {}\n", c.code, c.name, c.form,
                       c.runs ? "" : "   [refused]", c.summary);
  return out;
}

std::string fm_commands_markdown() {
  std::string out = "| Command | Name | Written | What Gantry does |\n|---|---|---|---|\n";
  auto cell = [](std::string_view t) {
    std::string r;
    for (char ch : t) {
      if (ch == '|') r += "\\";
      r += ch;
    }
    return r;
  };
  for (const FmCommandInfo& c : fm_commands())
    out += fmt::format("| `{}` | {} | `{}` | {}{} |\n", cell(c.code), cell(c.name), cell(c.form),
                       c.runs ? "" : "**Refused.** ", cell(c.summary));
  return out;
}

bool fm_is_g_code(int code) {
  switch (code) {
    case 0:
    case 2:
    case 3:
    case 4:
    case 7:
    case 9:
    case 10:
    case 16:
    case 19:
    case 20:
    case 21:
    case 22:
    case 23:
    case 24:
    case 25:
    case 26:
    case 27:
    case 43:
    case 44:
    case 58:
    case 60:
    case 68:
    case 70:
    case 71:
    case 90:
    case 91:
      return true;
    default:
      return false;
  }
}

bool fm_is_m_code(int code) {
  return code == 0 || code == 1 || code == 2 || code == 3 || code == 6 ||
         (code >= 94 && code <= 99) || (code >= 100 && code <= 131) || (code >= 200 && code <= 231);
}

}  // namespace gantry
