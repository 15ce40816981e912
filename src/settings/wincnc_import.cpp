// `gantry import-wincnc`: WINCNC.INI, CNCSCRN.INI and CNC.MAC read into a profile. Facts from
// the WinCNC Users Guide (seed 003, "System Configuration", "CNCSCRN.INI Settings", "Macro
// File Configuration"); the decisions where it is silent are in docs/hardware.md,
// "Importing a WinCNC set-up".
#include "gantry/settings/wincnc_import.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>  // join

#include <algorithm>
#include <array>
#include <cctype>  // toupper
#include <charconv>
#include <cmath>
#include <cstdlib>  // atoi
#include <map>
#include <set>
#include <tuple>

#include "gantry/core/text.hpp"             // ascii::lower, trim
#include "gantry/settings/values_file.hpp"  // settings_text: the schema's writer

namespace gantry {
namespace {

// How a keyword of WINCNC.INI is read: its parameters (letters), or a raw value; whether
// Gantry maps it (`reason` empty) or why not.
enum class Form { Letters, Raw };
struct Keyword {
  std::string_view name;
  Form form = Form::Raw;
  std::string_view letters;  // Letters: those allowed
  std::string_view reason;   // not mapped: why ("": mapped, or partly, by the code)
};

constexpr std::string_view kScreen =
    "a WinCNC screen or Windows setting; Gantry's console and window are its own";
constexpr std::string_view kProcess =
    "a process Gantry does not drive (plasma, laser, knife, saw, pump, scanning)";
constexpr std::string_view kTuning =
    "WinCNC's own motion tuning; Gantry's planner is set in [planner] and [ramps] "
    "(docs/planner.md)";
constexpr std::string_view kHooks = "a WinCNC file or command option Gantry does not have";

constexpr Keyword kKeywords[] = {
    {"accel", Form::Letters, "S", kTuning},
    {"ad", Form::Letters, "LHXYAB", "a spindle current monitor: Gantry reads no analog input"},
    {"altaxishi", Form::Letters, "PBOAD",
     "Gantry reads one pair of limit switches per axis, not the second motor's: wire them in "
     "parallel with the first motor's"},
    {"altaxislo", Form::Letters, "PBOAD",
     "Gantry reads one pair of limit switches per axis, not the second motor's: wire them in "
     "parallel with the first motor's"},
    {"altaxisspec", Form::Letters, "PSDOE", ""},
    {"anykey", Form::Letters, "AP", kScreen},
    {"arc_err", Form::Raw, "",
     "Gantry checks an arc's radii with its own tolerance (docs/gcode.md)"},
    {"arc_min", Form::Raw, "", kTuning},
    {"arcs", Form::Letters, "MA",
     "the WinCNC dialect's G2/G3 are not modal and I J incremental (docs/gcode.md)"},
    {"arctype", Form::Letters, "IMO", kTuning},
    {"atc1", Form::Letters, "HOZAM", ""},
    {"atc2", Form::Letters, "HOZAM", ""},
    {"autoarcfeed", Form::Letters, "FSLMA", kTuning},
    {"autoaux", Form::Letters, "CISET", kProcess},
    {"autodir", Form::Raw, "", kScreen},
    {"autofdir", Form::Raw, "", kScreen},
    {"autogas", Form::Letters, "TCBNGD", kProcess},
    {"automode", Form::Raw, "", kScreen},
    {"auxin", Form::Letters, "CPBODFLIMA", ""},
    {"auxout", Form::Letters, "CPBOSETXWR", ""},
    {"auxoutvel", Form::Raw, "", "outputs switched by speed: Gantry's outputs switch at rest (SO)"},
    {"axisadj", Form::Letters, "TAVUDIBS", "height adjustment while a file runs: not offered"},
    {"axischar", Form::Raw, "", ""},
    {"axishi", Form::Letters, "PBOAD", ""},
    {"axislo", Form::Letters, "PBOAD", ""},
    {"axismap", Form::Letters, "SEM", "axis straightness maps: not offered"},
    {"axismode", Form::Raw, "", "the manual names axismode= but does not document it"},
    {"axisspec", Form::Letters, "PSDRAFOETBK", ""},
    {"axisvel", Form::Letters, "RFSMHAC", ""},
    {"backlash", Form::Letters, "BSF", ""},
    {"bitmapdir", Form::Raw, "", kScreen},
    {"bmpeditor", Form::Raw, "", kProcess},
    {"bmpend", Form::Raw, "", kProcess},
    {"bmpoffset", Form::Letters, "LHSF", kProcess},
    {"bmpstart", Form::Raw, "", kProcess},
    {"btnoptions", Form::Raw, "", kScreen},
    {"cmdabort", Form::Raw, "", kHooks},
    {"cmdend", Form::Raw, "", kHooks},
    {"cmdrestart", Form::Raw, "", kHooks},
    {"cmdrestartfeed", Form::Raw, "", kHooks},
    {"cmdrestartrapid", Form::Raw, "", kHooks},
    {"cmdstart", Form::Raw, "", kHooks},
    {"comchars", Form::Raw, "",
     "the WinCNC dialect's comments are [ ... ] and ( ... ) (docs/gcode.md)"},
    {"comdll", Form::Raw, "", kScreen},
    {"commatodec", Form::Raw, "", kHooks},
    {"contdelay", Form::Raw, "", kHooks},
    {"ctrlf1", Form::Raw, "", ""},
    {"ctrlf2", Form::Raw, "", ""},
    {"ctrlf3", Form::Raw, "", ""},
    {"ctrlf4", Form::Raw, "", ""},
    {"ctrlf5", Form::Raw, "", ""},
    {"ctrlf6", Form::Raw, "", ""},
    {"ctrlf7", Form::Raw, "", ""},
    {"ctrlf8", Form::Raw, "", ""},
    {"cutcomp", Form::Letters, "TD", kHooks},
    {"da", Form::Letters, "TAVICR", ""},
    {"drillbank", Form::Letters, "CN", "drill banks (M11 D): not offered"},
    {"editor", Form::Raw, "", "a Windows program; set machine.editor to a Linux one"},
    {"enab", Form::Letters, "CMTLIA", ""},
    {"esc_step", Form::Raw, "", ""},
    {"exaltaxishi", Form::Letters, "CPABO", "alternate limit switches (L210-L212): not offered"},
    {"exaltaxislo", Form::Letters, "CPABO", "alternate limit switches (L210-L212): not offered"},
    {"filetype", Form::Raw, "", "Gantry reads .nc .tap .gcode .ngc as G-code (docs/gcode.md)"},
    {"forcelim", Form::Letters, "XY", kHooks},
    {"fslock", Form::Raw, "", kProcess},
    {"g08", Form::Letters, "ELNT", kTuning},
    {"g09", Form::Letters, "SA", kTuning},
    {"g28_lim_cnt", Form::Raw, "", ""},
    {"g28altmove", Form::Letters, "XYZW", ""},
    {"g28check", Form::Raw, "", "Gantry does not ask before taking new home positions"},
    {"g28checktol", Form::Letters, "XYZ", "Gantry does not ask before taking new home positions"},
    {"g28coord", Form::Letters, "XYZW", ""},
    {"g28move", Form::Letters, "XYZWRFTAML", ""},
    {"g2modal", Form::Raw, "", "the WinCNC dialect's G2/G3 are not modal (docs/gcode.md)"},
    {"g37", Form::Letters, "XYIJDF", ""},
    {"g54", Form::Letters, "XYTROMA", "workspaces and head swaps (G54-G59): one head's workspace"},
    {"g55", Form::Letters, "XYTROMA", "workspaces and head swaps (G54-G59): one head's workspace"},
    {"g56", Form::Letters, "XYTROMA", "workspaces and head swaps (G54-G59): one head's workspace"},
    {"g57", Form::Letters, "XYTROMA", "workspaces and head swaps (G54-G59): one head's workspace"},
    {"g58", Form::Letters, "XYTROMA", "workspaces and head swaps (G54-G59): one head's workspace"},
    {"g59", Form::Letters, "XYTROMA", "workspaces and head swaps (G54-G59): one head's workspace"},
    {"g81dwell", Form::Raw, "", "G82's P gives the dwell (docs/gcode.md)"},
    {"g81set", Form::Letters, "DRL",
     "canned cycles take their values from the block (docs/gcode.md)"},
    {"helpfile", Form::Raw, "", kScreen},
    {"hibound", Form::Letters, "XYZW",
     "boundaries in workspace coordinates: Gantry has the soft limits only"},
    {"hilim", Form::Letters, "XYZWUVABC", ""},
    {"homedir", Form::Raw, "", kScreen},
    {"keyfact", Form::Raw, "", "the security key's timing: Gantry has no key"},
    {"keypad", Form::Letters, "CBPS",
     "serial keypads: Gantry reads the keyboard, the XHC pendant and gamepads (docs/hardware.md)"},
    {"keypaddir", Form::Raw, "",
     "serial keypads: Gantry reads the keyboard, the XHC pendant and gamepads (docs/hardware.md)"},
    {"knifeangle", Form::Letters, "AMXY", kProcess},
    {"knifemode", Form::Letters, "TALZPNCDMRV", kProcess},
    {"laser", Form::Letters, "PDSMOABR", kProcess},
    {"laserscan", Form::Letters, "SMUWAT", kProcess},
    {"lim_cnt", Form::Raw, "", ""},
    {"lim_mode", Form::Raw, "", ""},
    {"lim_step", Form::Raw, "", ""},
    {"lobound", Form::Letters, "XYZW",
     "boundaries in workspace coordinates: Gantry has the soft limits only"},
    {"logdir", Form::Raw, "", "Gantry keeps its own part-file log (gantry log)"},
    {"logfile", Form::Raw, "", "Gantry keeps its own part-file log (gantry log)"},
    {"lolim", Form::Letters, "XYZWUVABC", ""},
    {"mapping", Form::Letters, "IR", "axis straightness maps: not offered"},
    {"maxstepv", Form::Raw, "", ""},
    {"maxtrans", Form::Raw, "", "Gantry's keypad jogs run to the soft limits"},
    {"nmode", Form::Raw, "", "a G-code file starts in G90 (docs/gcode.md)"},
    {"numkp", Form::Raw, "", kScreen},
    {"override", Form::Letters, "ELHDU", ""},
    {"pci24h", Form::Letters, "A",
     "expansion I/O cards: Gantry drives the PCI-7200's 32 outputs and inputs"},
    {"pci48h", Form::Letters, "AB",
     "expansion I/O cards: Gantry drives the PCI-7200's 32 outputs and inputs"},
    {"portin", Form::Raw, "",
     "Gantry addresses the PCI-7200's inputs as ports 0-3 (docs/hardware.md)"},
    {"portout", Form::Raw, "",
     "Gantry addresses the PCI-7200's outputs as ports 0, 6 and 7 (docs/hardware.md)"},
    {"positions", Form::Letters, "PHTW", "stored positions: not offered"},
    {"pumpcont", Form::Letters, "TLHABIR", kProcess},
    {"pwm", Form::Letters, "FM", ""},
    {"quadmode", Form::Raw, "", "quadrature output: Gantry puts out step and direction"},
    {"rapid_lock", Form::Raw, "", "Gantry's feed override does not change jogs"},
    {"rapidjog", Form::Raw, "", "Gantry's keypad jogs at the jog speed (speeds.jog)"},
    {"restart", Form::Letters, "V",
     "Gantry's start at a line (--from-line) goes to the line's place by Safe-Z"},
    {"sawmode", Form::Letters, "TAROZ", kProcess},
    {"scan", Form::Letters, "TACSHFPD", ""},
    {"signal", Form::Letters, "CMTI", ""},
    {"skipchars", Form::Letters, "CN", kHooks},
    {"softlim", Form::Letters, "TMBV", ""},
    {"spinchar", Form::Raw, "", "the spindle speed is S in G-code, TR in OpenSBP"},
    {"spindle", Form::Letters, "TRI", ""},
    {"steppulse", Form::Letters, "PD", ""},
    {"table", Form::Letters, "XYWHBZ", ""},
    {"thc", Form::Letters, "AFVSEPOIDLTCWM", kProcess},
    {"thcauto", Form::Raw, "", kProcess},
    {"thcdisab", Form::Letters, "VT", kProcess},
    {"thcdiv", Form::Letters, "MB", kProcess},
    {"thclim", Form::Letters, "LH", kProcess},
    {"thcvel", Form::Letters, "FV", kProcess},
    {"timertype", Form::Raw, "", ""},
    {"torchbevel", Form::Letters, "BCR", kProcess},
    {"tranadj", Form::Raw, "", "Gantry's keypad jogs run to the soft limits"},
    {"unit", Form::Raw, "", ""},
    {"vgroup", Form::Raw, "", ""},
    {"vmatch", Form::Letters, "PT", kTuning},
    {"watch", Form::Letters, "TDC", ""},
    {"xhc", Form::Letters, "TDS", ""},
};

const Keyword* keyword(std::string_view name) {
  for (const Keyword& k : kKeywords)
    if (k.name == name) return &k;
  return nullptr;
}

// A letter's value, or a quoted text (M"message"), with its column.
struct Param {
  double value = 0;
  std::string text;
  bool quoted = false;
  int column = 0;
};

struct Line {
  const WincncFile* file = nullptr;
  int number = 0;
  std::string keyword;  // lower case
  int column = 1;       // of the keyword
  std::string value;    // after '=', trimmed, comment removed
  int value_column = 0;
  std::map<char, Param> params;  // Form::Letters
};

// The UTF-8 curly quotes the manual prints around texts, read as ASCII quotes.
std::string plain_quotes(std::string_view s) {
  std::string out;
  for (size_t i = 0; i < s.size(); ++i) {
    if (i + 2 < s.size() && static_cast<unsigned char>(s[i]) == 0xE2 &&
        static_cast<unsigned char>(s[i + 1]) == 0x80 &&
        (static_cast<unsigned char>(s[i + 2]) == 0x9C ||
         static_cast<unsigned char>(s[i + 2]) == 0x9D)) {
      out += '"';
      i += 2;
      continue;
    }
    out += s[i];
  }
  return out;
}

std::string num(double v) {
  return fmt::format("{}", v);
}

class Importer {
 public:
  explicit Importer(const WincncSources& in) : in_(in) {}

  WincncImport run() {
    r_.settings = default_settings();
    read_ini();
    if (in_.screen) read_screen();
    if (in_.macros) read_macros();
    if (!r_.errors.empty()) return std::move(r_);
    build();
    return std::move(r_);
  }

 private:
  // ---- messages ----
  SourceLoc at(const WincncFile& f, int line, int column = 0) const {
    return file_loc(f.path, line, column);
  }
  void error(const Line& l, int column, std::string msg) {
    r_.errors.push_back({at(*l.file, l.number, column), Severity::Error, std::move(msg)});
  }
  void unmapped(const Line& l, std::string keyword, std::string why) {
    r_.unmapped.push_back({at(*l.file, l.number), std::move(keyword), std::move(why)});
  }
  void mapped(const Line& l, std::string what) {
    r_.mapped.push_back(fmt::format("{}:{}: {}", l.file->path, l.number, what));
  }

  // A parameter's value as a whole number in [lo, hi], or an error at its column.
  std::optional<int> whole(const Line& l, char letter, int lo, int hi) {
    const Param& p = l.params.at(letter);
    if (p.quoted || p.value != std::round(p.value) || p.value < lo || p.value > hi) {
      error(l, p.column,
            fmt::format("{} {}{} is out of range: {} is a whole number from {} to {}", l.keyword,
                        letter, p.quoted ? "\"" + p.text + "\"" : num(p.value), letter, lo, hi));
      return std::nullopt;
    }
    return static_cast<int>(p.value);
  }
  std::optional<double> number(const Line& l, char letter, double lo, double hi,
                               bool lo_open = false) {
    const Param& p = l.params.at(letter);
    if (p.quoted || (lo_open ? p.value <= lo : p.value < lo) || p.value > hi) {
      error(l, p.column,
            fmt::format("{} {}{} is out of range: {} is a number {} {} and <= {}", l.keyword,
                        letter, p.quoted ? "\"" + p.text + "\"" : num(p.value), letter,
                        lo_open ? ">" : ">=", num(lo), num(hi)));
      return std::nullopt;
    }
    return p.value;
  }
  std::optional<double> raw_number(const Line& l, double lo, double hi) {
    double v = 0;
    const std::string& t = l.value;
    const auto res = std::from_chars(t.data(), t.data() + t.size(), v);
    if (t.empty() || res.ptr != t.data() + t.size()) {
      error(l, l.value_column, fmt::format("{}= needs a number, not \"{}\"", l.keyword, t));
      return std::nullopt;
    }
    if (v < lo || v > hi) {
      error(l, l.value_column,
            fmt::format("{}={} is out of range: from {} to {}", l.keyword, t, num(lo), num(hi)));
      return std::nullopt;
    }
    return v;
  }
  bool has(const Line& l, char c) const { return l.params.count(c) != 0; }

  // ---- WINCNC.INI ----
  // Letters and numbers ("p0 s0 d0 r818.5111"), texts in quotes (M"message").
  bool read_params(Line& l, std::string_view letters) {
    const std::string& v = l.value;
    size_t i = 0;
    while (i < v.size()) {
      if (v[i] == ' ' || v[i] == '\t' || v[i] == ',') {
        ++i;
        continue;
      }
      const int column = l.value_column + static_cast<int>(i);
      const char c = ascii::upper(v[i]);
      if (!(c >= 'A' && c <= 'Z')) {
        error(l, column,
              fmt::format("{}: expected a parameter letter, found '{}'", l.keyword, v[i]));
        return false;
      }
      if (letters.find(c) == std::string_view::npos) {
        error(l, column,
              fmt::format("{} has no parameter {}; the manual gives it {}", l.keyword, c,
                          fmt::join(letters, " ")));
        return false;
      }
      if (l.params.count(c)) {
        error(l, column, fmt::format("{}: {} is given twice", l.keyword, c));
        return false;
      }
      Param p;
      p.column = column;
      ++i;
      if (i < v.size() && v[i] == '"') {
        const size_t close = v.find('"', i + 1);
        if (close == std::string::npos) {
          error(l, column,
                fmt::format("{} {}: the text opened with \" is not closed", l.keyword, c));
          return false;
        }
        p.quoted = true;
        p.text = v.substr(i + 1, close - i - 1);
        i = close + 1;
      } else {
        size_t e = i;
        if (e < v.size() && (v[e] == '-' || v[e] == '+')) ++e;
        while (e < v.size() && ((v[e] >= '0' && v[e] <= '9') || v[e] == '.')) ++e;
        double d = 0;
        const char* b = v.data() + i + (v[i] == '+' ? 1 : 0);
        const auto res = std::from_chars(b, v.data() + e, d);
        if (e == i || res.ptr != v.data() + e) {
          error(l, column,
                fmt::format("{}: {} needs a number, as in {}1", l.keyword, c, ascii::lower(c)));
          return false;
        }
        p.value = d;
        i = e;
      }
      l.params[c] = p;
    }
    return true;
  }

  // Each line of an INI file that holds more than a comment, its quotes made plain and what
  // follows a '[' outside quotes cut (a comment: the manual's "[X Axis]" and "[Group 1]"),
  // with its place: fn(line, raw, trimmed text).
  template <class Fn>
  static void for_each_line(const WincncFile& f, Fn fn) {
    int number = 0;
    for (size_t pos = 0; pos <= f.text.size();) {
      size_t end = f.text.find('\n', pos);
      if (end == std::string::npos) end = f.text.size();
      std::string raw = plain_quotes(std::string_view(f.text).substr(pos, end - pos));
      pos = end + 1;
      ++number;
      if (!raw.empty() && raw.back() == '\r') raw.pop_back();
      bool quoted = false;
      for (size_t i = 0; i < raw.size(); ++i) {
        if (raw[i] == '"') quoted = !quoted;
        if (raw[i] == '[' && !quoted) {
          raw.resize(i);
          break;
        }
      }
      const std::string_view text = ascii::trim(raw);
      if (text.empty()) continue;
      Line l;
      l.file = &f;
      l.number = number;
      l.column = static_cast<int>(raw.find_first_not_of(" \t")) + 1;
      fn(std::move(l), raw, text);
    }
  }

  void read_ini() {
    bool first = true;
    for_each_line(in_.ini, [&](Line l, const std::string& raw, std::string_view text) {
      const size_t eq = raw.find('=');
      if (eq == std::string::npos) {
        error(l, l.column,
              fmt::format("expected keyword=value, as the manual writes every WINCNC.INI line "
                          "(\"{}\")",
                          text));
        return;
      }
      l.keyword = ascii::lower(ascii::trim(std::string_view(raw).substr(0, eq)));
      const std::string_view rest(raw.c_str() + eq + 1);
      const std::string_view value = ascii::trim(rest);
      l.value = std::string(value);
      l.value_column = static_cast<int>(eq + 1 + (value.empty() ? 0 : rest.find(value))) + 1;
      const Keyword* k = keyword(l.keyword);
      if (!k) {
        error(l, l.column,
              fmt::format("unknown keyword {}=: the WinCNC manual does not document it; check its "
                          "spelling, or remove the line",
                          l.keyword));
        return;
      }
      if (l.keyword == "unit" && !first)
        error(l, l.column,
              "unit= must be the first line of WINCNC.INI (the manual, Unit Settings)");
      first = false;
      if (k->form == Form::Letters && !read_params(l, k->letters)) return;
      lines_.push_back(std::move(l));
    });
  }

  // ---- CNCSCRN.INI: "Type", fields ... ----
  static std::vector<std::string> fields(std::string_view s) {
    std::vector<std::string> out;
    std::string cur;
    bool quoted = false;
    for (char c : s) {
      if (c == '"') {
        quoted = !quoted;
        continue;
      }
      if (c == ',' && !quoted) {
        out.emplace_back(ascii::trim(cur));
        cur.clear();
        continue;
      }
      cur += c;
    }
    out.emplace_back(ascii::trim(cur));
    return out;
  }

  void read_screen() {
    static constexpr std::string_view kTypes[] = {
        "icon",        "display",   "viewer",    "slidecontrol", "jogmode",   "jogmodeex",
        "frame",       "auxin",     "virtualin", "auxout",       "auxoutex",  "jobcmd",
        "shellcmdbtn", "userbtn",   "rptcmd",    "keypadout",    "menubtn",   "axiscontrol",
        "axislabel",   "rapidmode", "statebtn",  "statebtnex",   "virtinbtn", "virtinbtnex"};
    for_each_line(*in_.screen, [&](Line l, const std::string&, std::string_view text) {
      if (text.front() != '"') {
        error(l, l.column,
              "expected a record: a quoted type, then its fields, as \"UserBtn\", 5, 5, 50, 25, "
              "0, 0, \"G90\", \"G90\", \"\", -1, -1");
        return;
      }
      std::vector<std::string> fs = fields(text);
      const std::string type = ascii::lower(fs[0]);
      if (std::find(std::begin(kTypes), std::end(kTypes), type) == std::end(kTypes)) {
        error(l, l.column,
              fmt::format("unknown record \"{}\": the WinCNC manual's CNCSCRN.INI has no such "
                          "type",
                          fs[0]));
        return;
      }
      l.keyword = fs[0];
      screen_.push_back({std::move(l), std::move(fs)});
    });
  }

  // ---- CNC.MAC: NAME = COMMAND [comment] ----
  void read_macros() {
    const WincncFile& f = *in_.macros;
    int number = 0;
    size_t pos = 0;
    while (pos <= f.text.size()) {
      size_t end = f.text.find('\n', pos);
      if (end == std::string::npos) end = f.text.size();
      std::string raw(std::string_view(f.text).substr(pos, end - pos));
      pos = end + 1;
      ++number;
      if (!raw.empty() && raw.back() == '\r') raw.pop_back();
      Line l;
      l.file = &f;
      l.number = number;
      const std::string_view text = ascii::trim(raw);
      if (text.empty() || text.front() == '[') continue;  // a blank CNC.MAC is allowed
      l.column = static_cast<int>(raw.find_first_not_of(" \t")) + 1;
      const size_t eq = raw.find('=');
      const std::string name = eq == std::string::npos
                                   ? ""
                                   : ascii::upper(ascii::trim(std::string_view(raw).substr(0, eq)));
      const bool code = name.size() >= 2 && name[0] >= 'A' && name[0] <= 'Z' &&
                        name.find_first_not_of("0123456789.", 1) == std::string::npos;
      if (!code) {
        error(l, l.column,
              "expected CODE = COMMAND [comment], as the manual's \"M1 = M11C2 [SPINDLE ON]\"");
        continue;
      }
      std::string command(std::string_view(raw).substr(eq + 1));
      std::string comment;
      if (const size_t open = command.find('['); open != std::string::npos) {
        comment = std::string(ascii::trim(ascii::trim(command.substr(open + 1)), "] \t"));
        command.resize(open);
      }
      command = std::string(ascii::trim(command));
      l.keyword = name;
      if (command.empty()) {  // `M2=[`: the code is disabled
        unmapped(l, name + "=[",
                 "a disabled code: Gantry cannot turn a G-code off; remove " + name +
                     " from the CAM program's post");
        continue;
      }
      WincncMacro m;
      m.loc = at(f, number);
      m.name = name;
      m.command = command;
      m.comment = comment;
      m.cut = 100 + static_cast<int>(r_.macros.size());
      const std::string upper = ascii::upper(command);
      if (upper.starts_with("M98")) {
        std::string_view file = ascii::trim(std::string_view(command).substr(3));
        if (file.starts_with(".1")) file = ascii::trim(file.substr(2));
        m.file = std::string(file);
      }
      r_.macros.push_back(std::move(m));
    }
  }

  // A command bound to a key or a pendant button: a CNC.MAC macro's name runs its custom cut.
  std::string bound_command(std::string_view command) const {
    const std::string upper = ascii::upper(ascii::trim(command));
    for (const WincncMacro& m : r_.macros)
      if (m.name == upper) return fmt::format("C{}", m.cut);
    return std::string(ascii::trim(command));
  }

  // ---- the profile ----
  struct AxisBlock {
    char letter = 'X';
    int slot = -1;  // Gantry's axis: 0 X .. 5 C
    const Line* spec = nullptr;
    const Line *vel = nullptr, *lo = nullptr, *hi = nullptr, *alt = nullptr;
    int type = 1;  // axisspec T: 1, 2 horizontal, 3 vertical, 4 rotational
  };

  void build();

  const WincncSources& in_;
  WincncImport r_;
  std::vector<Line> lines_;
  struct ScreenRecord {
    Line line;
    std::vector<std::string> fields;
  };
  std::vector<ScreenRecord> screen_;
  const Line* limit_polarity_ = nullptr;  // the first limit switch line: its O is everyone's
  Settings defaults_ = default_settings();
};

// Output word bits: WinCNC's port 0 is the step/direction port (step S -> bit S, direction D
// -> bit 8 + D: Gantry's default layout), ports 6 and 7 the output bytes above (16-23,
// 24-31). Input word bits: ports 0-3, eight bits each (port P bit B -> 8 P + B).
int input_bit(int port, int bit) {
  return port >= 0 && port <= 3 ? 8 * port + bit : -1;
}
int output_bit(int port, int bit) {
  return port == 6 || port == 7 ? 16 + 8 * (port - 6) + bit : -1;
}

void Importer::build() {
  Settings& s = r_.settings;
  s.name = in_.name;
  s.gcode_dialect = GcodeDialect::WinCNC;
  // What WinCNC does not say is not Gantry's default machine's either: no switches, no
  // inputs, no outputs until the files name them.
  s.inputs.estop_bit = -1;
  s.inputs.probe_bit = -1;
  s.inputs.min_bit.fill(-1);
  s.inputs.max_bit.fill(-1);
  s.inputs.home_bit.fill(-1);
  s.inputs.switch_bits.fill(-1);
  s.outputs.charge_pump_bit = -1;
  s.outputs.spindle_bit = -1;
  s.outputs.aux_bits.clear();
  s.simulator = SimulatorSettings{};

  double len = 1;  // unit=CM: lengths in centimetres, the profile in millimetres
  std::string axischar;
  std::vector<AxisBlock> axes;
  std::map<std::string, const Line*> single;  // keywords read once: the last wins
  std::vector<const Line*> g28moves, auxins, auxouts;
  std::array<const Line*, 8> ctrlf{};
  const Line* axischar_line = nullptr;

  for (const Line& l : lines_) {
    const Keyword& k = *keyword(l.keyword);
    const std::string& key = l.keyword;
    if (key == "unit") {
      const std::string u = ascii::upper(l.value);
      if (u == "IN")
        s.units = Units::Inches;
      else if (u == "MM")
        s.units = Units::Millimetres;
      else if (u == "CM")
        s.units = Units::Millimetres, len = 10;
      else
        error(l, l.value_column, fmt::format("unit={} is not IN, CM or MM", l.value));
      if (u == "CM") mapped(l, "unit=CM -> units = \"mm\" (every length times 10)");
      continue;
    }
    if (key == "axischar") {
      axischar = ascii::upper(l.value);
      axischar_line = &l;
      bool ok = axischar.size() >= 2 && axischar[0] == 'X' && axischar[1] == 'Y';
      if (!ok)
        error(l, l.value_column, "axischar= must name X first and Y second (the manual, axischar)");
      std::set<char> seen;
      for (char c : axischar)
        if (std::string_view("XYZWUVABC").find(c) == std::string_view::npos ||
            !seen.insert(c).second)
          error(l, l.value_column,
                fmt::format("axischar={}: '{}' is not an axis letter (X Y Z W U V A B C), or is "
                            "named twice",
                            l.value, c));
      continue;
    }
    if (key == "axisspec") {
      if (!axischar_line) {
        error(l, l.column, "axisspec= before axischar=: name the axes first (axischar=XYZ)");
        continue;
      }
      if (axes.size() >= axischar.size()) {
        error(l, l.column,
              fmt::format("an axisspec= for a {}th axis, but axischar={} names {}", axes.size() + 1,
                          axischar, axischar.size()));
        continue;
      }
      AxisBlock b;
      b.letter = axischar[axes.size()];
      b.spec = &l;
      axes.push_back(b);
      continue;
    }
    if (key == "axisvel" || key == "axislo" || key == "axishi" || key == "altaxisspec" ||
        key == "altaxislo" || key == "altaxishi" || key == "axisadj" || key == "axismap" ||
        key == "axismode") {
      if (axes.empty()) {
        error(l, l.column,
              fmt::format("{}= comes before the first axisspec=: an axis's lines follow "
                          "its axisspec",
                          key));
        continue;
      }
      AxisBlock& b = axes.back();
      if (key == "axisvel") b.vel = &l;
      if (key == "axislo") b.lo = &l;
      if (key == "axishi") b.hi = &l;
      if (key == "altaxisspec") b.alt = &l;
      if (!k.reason.empty())
        unmapped(l, fmt::format("{} ({})", key, b.letter), std::string(k.reason));
      continue;
    }
    if (key == "g28move") {
      g28moves.push_back(&l);
      continue;
    }
    if (key == "auxin") {
      auxins.push_back(&l);
      continue;
    }
    if (key == "auxout") {
      auxouts.push_back(&l);
      continue;
    }
    if (key.starts_with("ctrlf")) {
      ctrlf[static_cast<size_t>(key[5] - '1')] = &l;
      continue;
    }
    if (!k.reason.empty()) {
      unmapped(l, key, std::string(k.reason));
      continue;
    }
    single[key] = &l;
  }
  if (!r_.errors.empty()) return;

  // Each axis's Gantry slot: X Y Z are theirs, A B C theirs, W the first of A B C that
  // axischar leaves free (display.w_axis; docs/hardware.md, "The W axis"); U and V have none.
  int w_slot = -1;
  for (char c : std::string_view("ABC"))
    if (axischar.find(c) == std::string::npos && w_slot < 0) w_slot = 3 + (c - 'A');
  int used = 3;
  for (AxisBlock& b : axes) {
    const size_t at = std::string_view("XYZABC").find(b.letter);
    if (at != std::string_view::npos) b.slot = static_cast<int>(at);
    if (b.letter == 'W') b.slot = w_slot;
    if (b.slot < 0) {
      unmapped(*b.spec, fmt::format("axisspec ({})", b.letter),
               b.letter == 'W' ? "W needs one of A, B, C free, and axischar names all three"
                               : "Gantry drives X Y Z A B C, and W as one of A B C: a third or "
                                 "fourth vertical head (U, V) has no axis");
      continue;
    }
    used = std::max(used, b.slot + 1);
  }
  auto block = [&](char letter) -> AxisBlock* {
    for (AxisBlock& b : axes)
      if (b.letter == letter && b.slot >= 0) return &b;
    return nullptr;
  };
  s.display.axes = used;
  s.display.w_axis = -1;

  // The card: the PCI-7200's step pulse and the step rate it allows.
  if (const auto it = single.find("timertype"); it != single.end()) {
    if (raw_number(*it->second, 7200, 7200)) {
      s.card.type = "pci7200";
      mapped(*it->second, "timertype=7200 -> card.type = \"pci7200\"");
    }
  }
  if (const auto it = single.find("steppulse"); it != single.end()) {
    const Line& l = *it->second;
    if (has(l, 'P'))
      if (auto v = number(l, 'P', 0, 1e4, true)) s.card.step_pulse_us = *v;
    if (has(l, 'D'))
      if (auto v = number(l, 'D', 0, 1e4)) s.card.dir_setup_us = *v;
    mapped(l, "steppulse P D -> card.step_pulse_us, card.dir_setup_us");
  }
  double maxstepv = 30000;  // the manual's default
  if (const auto it = single.find("maxstepv"); it != single.end())
    if (auto v = raw_number(*it->second, 1, 1e6)) {
      maxstepv = *v;
      mapped(*it->second, "maxstepv -> each axis's max_speed at most maxstepv / steps_per_unit");
    }
  const double tick_us = 1e6 / s.card.pacer_hz();
  const int pulse_ticks = static_cast<int>(std::ceil(s.card.step_pulse_us / tick_us - 1e-9));
  const double step_cap = std::min(maxstepv, s.card.pacer_hz() / (pulse_ticks + 1));

  // The axes.
  std::uint32_t steps_used = 0, dirs_used = 0;
  std::array<bool, kAxisCount> channel_set{};
  std::array<double, kAxisCount> feed{};  // axisvel F, units/s (0: not given)
  auto pins_from = [&](const Line& l, int channel, const char* what) {
    PinSettings p = s.pins[static_cast<size_t>(channel)];
    if (has(l, 'P'))
      if (auto v = whole(l, 'P', 0, 0)) (void)v;  // the PCI-7200's step port is 0
    if (has(l, 'S'))
      if (auto v = whole(l, 'S', 0, 5)) {
        if (steps_used >> *v & 1u)
          error(l, l.params.at('S').column,
                fmt::format("{} S{}: step bit {} is already another motor's", what, *v, *v));
        steps_used |= 1u << *v;
        p.step_bit = *v;
      }
    if (has(l, 'D'))
      if (auto v = whole(l, 'D', 0, 5)) {
        if (dirs_used >> *v & 1u)
          error(l, l.params.at('D').column,
                fmt::format("{} D{}: direction bit {} is already another motor's", what, *v, *v));
        dirs_used |= 1u << *v;
        p.dir_bit = 8 + *v;
      }
    p.invert_dir = true;  // O1, the manual's default
    if (has(l, 'O'))
      if (auto v = whole(l, 'O', 0, 1)) p.invert_dir = *v == 1;
    p.step_active_low = false;
    if (has(l, 'E'))
      if (auto v = whole(l, 'E', 0, 1)) p.step_active_low = *v == 1;
    s.pins[static_cast<size_t>(channel)] = p;
    channel_set[static_cast<size_t>(channel)] = true;
  };
  std::vector<std::string> keys;
  for (AxisBlock& b : axes) {
    if (b.slot < 0) continue;
    const Line& l = *b.spec;
    const int i = b.slot;
    AxisSettings& ax = s.axes[static_cast<size_t>(i)];
    const char L = kAxisLetters[static_cast<size_t>(i)];
    pins_from(l, i, "axisspec");
    if (has(l, 'T'))
      if (auto v = whole(l, 'T', 1, 4)) b.type = *v;
    if (b.letter == 'W') {
      b.type = 3;  // W is the second vertical head: Z's defaults, not A's degrees
      s.display.w_axis = i;
      ax = defaults_.axes[2];
      s.homing.at[static_cast<size_t>(i)] = defaults_.homing.at[2];
    }
    if (b.type == 4 && i < 3)
      error(l, l.params.at('T').column,
            fmt::format("axisspec T4 makes {} rotational; Gantry's X, Y and Z are lengths: put the "
                        "rotary axis on A, B or C",
                        b.letter));
    if (i >= 3)
      s.display.rotary_units[static_cast<size_t>(i - 3)] =
          b.type == 4 ? AxisUnit::Degrees
                      : (s.units == Units::Inches ? AxisUnit::Inches : AxisUnit::Millimetres);
    if (!has(l, 'R')) {
      error(l, l.column, fmt::format("axisspec ({}) needs R, the steps per unit", b.letter));
      continue;
    }
    const double per_unit = b.type == 4 ? 1 : len;  // degrees stay degrees
    if (auto v = number(l, 'R', -1e6 * per_unit, 1e6 * per_unit)) {
      if (*v == 0) error(l, l.params.at('R').column, "axisspec R0: the steps per unit is not 0");
      ax.steps_per_unit = *v / per_unit;
    }
    if (has(l, 'A')) {
      std::optional<double> a = number(l, 'A', 0, 6e8, true);
      std::optional<double> f = has(l, 'F') ? number(l, 'F', 0, 6e8, true) : a;
      if (a && f) ax.max_accel = std::min(*a, *f) / 60 * per_unit;
    }
    if (has(l, 'B'))
      if (auto v = number(l, 'B', 0, 1000 / per_unit)) ax.backlash = *v * per_unit;
    mapped(l,
           fmt::format("axisspec ({}) S D O E R A{} B -> pins.{}, axes.{}.steps_per_unit, "
                       "max_accel (units/min/s / 60{}), backlash",
                       b.letter, has(l, 'F') ? " F" : "", L, L, has(l, 'F') ? ", the lower" : ""));
    // axisspec K: the keyboard's jog keys; Gantry's keypad already has the arrows for X and Y
    // and PageUp/PageDown for Z (K1 K2 K3), so only other keys are bound.
    const int k_default = b.letter == 'X' ? 1 : b.letter == 'Y' ? 2 : b.letter == 'Z' ? 3 : 4;
    int k = k_default;
    if (has(l, 'K'))
      if (auto v = whole(l, 'K', -12, 12)) k = *v;
    const bool gantry_has = (i == 0 && k == 1) || (i == 1 && k == 2) || (i == 2 && k == 3);
    if (!gantry_has && k != 0) {
      const int which = (std::abs(k) - 1) % 4;
      static constexpr std::array<std::pair<const char*, const char*>, 4> kKeys{
          {{"Right", "Left"}, {"Up", "Down"}, {"PageUp", "PageDown"}, {"Home", "End"}}};
      const auto [plus, minus] = kKeys[static_cast<size_t>(which)];
      const bool reverse = k < 0;
      keys.push_back(fmt::format("{} = jog {}{}", plus, L, reverse ? '-' : '+'));
      keys.push_back(fmt::format("{} = jog {}{}", minus, L, reverse ? '+' : '-'));
      if (std::abs(k) > 4)
        unmapped(l, fmt::format("axisspec K{} ({})", k, b.letter),
                 "Scroll Lock's key sets: Gantry binds the keys whatever Scroll Lock is");
      mapped(l, fmt::format("axisspec K{} ({}) -> pendant.keys \"{}\", \"{}\"", k, b.letter,
                            keys[keys.size() - 2], keys.back()));
    }
    if (b.vel) {
      const Line& v = *b.vel;
      if (has(v, 'R'))
        if (auto r = number(v, 'R', 0, 6e6, true)) ax.max_speed = *r / 60 * per_unit;
      if (has(v, 'F'))
        if (auto f = number(v, 'F', 0, 6e6, true))
          feed[static_cast<size_t>(i)] = *f / 60 * per_unit;
      mapped(v, fmt::format("axisvel ({}) R F -> axes.{}.max_speed, the jog and move speeds "
                            "(units/min / 60)",
                            b.letter, L));
      for (char c : std::string_view("SMHAC"))
        if (has(v, c))
          unmapped(v, fmt::format("axisvel {} ({})", c, b.letter),
                   c == 'C' ? "a corner's lowest speed: Gantry's corners follow [planner]"
                            : "the keyboard's transit speeds: Gantry's keypad jogs at the jog "
                              "speed (speeds.jog) or its fast shift");
    }
    // maxstepv, and the card's own step rate, bound the speed.
    const double cap = step_cap / std::fabs(ax.steps_per_unit);
    if (ax.max_speed > cap) {
      mapped(l, fmt::format("({}) max_speed {} units/s lowered to {} by the step rate ({} "
                            "steps/s)",
                            b.letter, num(ax.max_speed), num(cap), num(step_cap)));
      ax.max_speed = cap;
    }
    // Limit switches: port P bit B of the inputs; one polarity for them all.
    for (const auto& [side, line] : {std::pair{'l', b.lo}, std::pair{'h', b.hi}}) {
      if (!line) continue;
      const Line& sw = *line;
      if (!has(sw, 'B')) {
        error(sw, sw.column, fmt::format("{}= needs B, the input bit", sw.keyword));
        continue;
      }
      const int port = has(sw, 'P') ? whole(sw, 'P', 0, 3).value_or(-1) : 0;
      const int bit = whole(sw, 'B', 0, 7).value_or(-1);
      if (port < 0 || bit < 0) continue;
      const int word = input_bit(port, bit);
      (side == 'l' ? s.inputs.min_bit : s.inputs.max_bit)[static_cast<size_t>(i)] = word;
      const bool low = has(sw, 'O') && sw.params.at('O').value == 1;
      if (!limit_polarity_) {
        limit_polarity_ = &sw;
        s.inputs.limits_active_low = low;
      } else if (low != s.inputs.limits_active_low) {
        unmapped(sw, fmt::format("{} O ({})", sw.keyword, b.letter),
                 fmt::format("Gantry reads every limit input with one polarity, "
                             "inputs.limits_active_low, taken from {}:{}",
                             limit_polarity_->file->path, limit_polarity_->number));
      }
      mapped(sw, fmt::format("{} ({}) P B O -> inputs.{}.{} = {} (port P bit B: 8 P + B)",
                             sw.keyword, b.letter, L, side == 'l' ? "min_bit" : "max_bit", word));
      for (char c : std::string_view("AD"))
        if (has(sw, c))
          unmapped(sw, fmt::format("{} {} ({})", sw.keyword, c, b.letter),
                   c == 'A' ? "alternate limit bits (L210-L212): not offered"
                            : "a debounce per switch: Gantry has one, limits.debounce (lim_cnt)");
    }
  }
  // Slaved axes: the second motor on a driver channel of an axis the machine does not use.
  for (AxisBlock& b : axes) {
    if (b.slot < 0 || !b.alt) continue;
    int spare = -1;
    for (int k = kAxisCount - 1; k >= s.display.axes && spare < 0; --k)
      if (!channel_set[static_cast<size_t>(k)]) spare = k;
    if (spare < 0) {
      unmapped(*b.alt, fmt::format("altaxisspec ({})", b.letter),
               "no driver channel is free for the second motor: the six are used");
      continue;
    }
    pins_from(*b.alt, spare, "altaxisspec");
    s.drivers.channel_axis[static_cast<size_t>(spare)] = b.slot;
    mapped(*b.alt, fmt::format("altaxisspec ({}) -> the second motor on driver channel {} "
                               "(drivers.channels, pins.{})",
                               b.letter, spare + 1, kAxisLetters[static_cast<size_t>(spare)]));
  }
  // The channels no motor of the files uses keep out of the way of those that are.
  for (int k = 0; k < kAxisCount; ++k) {
    if (channel_set[static_cast<size_t>(k)]) continue;
    int sb = 0, db = 0;
    while (steps_used >> sb & 1u) ++sb;
    while (dirs_used >> db & 1u) ++db;
    steps_used |= 1u << sb;
    dirs_used |= 1u << db;
    s.pins[static_cast<size_t>(k)] = {sb, 8 + db, false, false};
  }

  // Speeds: jogs at the rapid (G0) speed, moves at the default feed, each within max_speed.
  auto group_speed = [&](int g) {  // 0 XY, then Z A B C
    const std::array<int, 2> ax =
        g == 0 ? std::array<int, 2>{0, 1} : std::array<int, 2>{g + 1, g + 1};
    const double top = std::min(s.axes[static_cast<size_t>(ax[0])].max_speed,
                                s.axes[static_cast<size_t>(ax[1])].max_speed);
    double f =
        std::min(feed[static_cast<size_t>(ax[0])] ? feed[static_cast<size_t>(ax[0])] : 1e300,
                 feed[static_cast<size_t>(ax[1])] ? feed[static_cast<size_t>(ax[1])] : 1e300);
    return std::pair{top, f};
  };
  for (int g = 0; g < 5; ++g) {
    auto [top, f] = group_speed(g);
    double* move = g == 0   ? &s.speeds.move.xy
                   : g == 1 ? &s.speeds.move.z
                   : g == 2 ? &s.speeds.move.a
                   : g == 3 ? &s.speeds.move.b
                            : &s.speeds.move.c;
    double* jog = g == 0   ? &s.speeds.jog.xy
                  : g == 1 ? &s.speeds.jog.z
                  : g == 2 ? &s.speeds.jog.a
                  : g == 3 ? &s.speeds.jog.b
                           : &s.speeds.jog.c;
    const bool imported = g == 0 ? block('X') || block('Y') : [&] {
      for (const AxisBlock& b : axes)
        if (b.slot == g + 1) return true;
      return false;
    }();
    if (!imported) {  // an axis the files do not name keeps Gantry's speeds, within its limit
      *move = std::min(*move, top);
      *jog = std::min(*jog, top);
      continue;
    }
    *jog = top;
    *move = std::min(f < 1e300 ? f : *move, top);
  }

  // Soft limits: hilim and lolim, absolute (machine zero) positions; a side not given keeps
  // the default profile's distance from the other.
  const Line* hilim = single.count("hilim") ? single["hilim"] : nullptr;
  const Line* lolim = single.count("lolim") ? single["lolim"] : nullptr;
  for (AxisBlock& b : axes) {
    if (b.slot < 0) continue;
    AxisSettings& ax = s.axes[static_cast<size_t>(b.slot)];
    const double span = ax.max - ax.min;
    const double per_unit = b.type == 4 ? 1 : len;
    std::optional<double> hi, lo;
    if (hilim && has(*hilim, b.letter)) hi = number(*hilim, b.letter, -1e9, 1e9);
    if (lolim && has(*lolim, b.letter)) lo = number(*lolim, b.letter, -1e9, 1e9);
    if (hi) ax.max = *hi * per_unit;
    if (lo) ax.min = *lo * per_unit;
    if (hi && !lo) ax.min = ax.max - span;
    if (lo && !hi) ax.max = ax.min + span;
    if (hi && lo && ax.min >= ax.max)
      error(*lolim, lolim->params.at(b.letter).column,
            fmt::format("lolim {0}{1} is not below hilim {0}{2}", b.letter, num(*lo), num(*hi)));
  }
  for (const Line* l : {hilim, lolim}) {
    if (!l) continue;
    mapped(*l,
           fmt::format("{} -> axes.<axis>.{}", l->keyword, l->keyword == "hilim" ? "max" : "min"));
    for (const auto& [c, p] : l->params)
      if (!block(c))
        unmapped(*l, fmt::format("{} {}", l->keyword, c),
                 fmt::format("axischar names no {} axis Gantry drives", c));
  }
  if (const auto it = single.find("softlim"); it != single.end()) {
    const Line& l = *it->second;
    if (has(l, 'T'))
      if (auto t = whole(l, 'T', 0, 2)) {
        s.machine.limit_checking = *t == 1;
        mapped(l, fmt::format("softlim T{} -> machine.limit_checking = {}", *t, *t == 1));
      }
    // B1 clamps every axis to its soft limits; V1 only the vertical ones, silently.
    if (has(l, 'B') && l.params.at('B').value != 0) {
      s.limits.soft_clamp = SoftClamp::All;
      mapped(l, fmt::format("softlim B{} -> limits.soft_clamp = \"all\"",
                            num(l.params.at('B').value)));
    } else if (has(l, 'V') && l.params.at('V').value != 0) {
      s.limits.soft_clamp = SoftClamp::Vertical;
      mapped(l, fmt::format("softlim V{} -> limits.soft_clamp = \"vertical\"",
                            num(l.params.at('V').value)));
    }
    if (has(l, 'M')) unmapped(l, "softlim M", std::string(kScreen));
  }

  // Limit switches.
  if (const auto it = single.find("lim_mode"); it != single.end())
    if (auto m = raw_number(*it->second, 0, 3)) {
      const int mode = static_cast<int>(*m);
      s.limits.travel_only = mode == 1 || mode == 3;
      // Modes 2 and 3 differ from 0 and 1 by a shorter debounce as a switch opens: Gantry's
      // limit trips as a switch closes, so there is no release to debounce.
      mapped(*it->second,
             fmt::format("lim_mode={} -> limits.travel_only = {}{}", mode, s.limits.travel_only,
                         mode >= 2 ? " (the shorter debounce on opening: Gantry's limits trip "
                                     "on closing only)"
                                   : ""));
    }
  if (const auto it = single.find("lim_cnt"); it != single.end())
    if (auto n = raw_number(*it->second, 1, 1e6)) {
      // The manual: "MAXIMUM is 30. If set higher, it will default back to 30".
      s.limits.debounce = static_cast<int>(std::min(30.0, std::round(*n)));
      mapped(*it->second, fmt::format("lim_cnt -> limits.debounce = {}{}", s.limits.debounce,
                                      *n > 30 ? " (at most 30, as WinCNC)" : ""));
    }
  for (auto [k, steps] :
       {std::pair{"lim_step", &s.limits.cushion_steps}, std::pair{"esc_step", &s.limits.esc_steps}})
    if (const auto it = single.find(k); it != single.end())
      if (auto n = raw_number(*it->second, 0, 100000)) {  // the schema's range
        *steps = static_cast<int>(std::round(*n));
        mapped(*it->second, fmt::format("{} -> limits.{} = {}", k,
                                        k[0] == 'l' ? "cushion_steps" : "esc_steps", *steps));
      }
  if (const auto it = single.find("g28_lim_cnt"); it != single.end())
    if (auto n = raw_number(*it->second, 1, 1e6)) {
      // At most 30, as lim_cnt (the manual gives g28_lim_cnt no maximum of its own).
      s.homing.debounce = static_cast<int>(std::min(30.0, std::round(*n)));
      mapped(*it->second, fmt::format("g28_lim_cnt -> homing.debounce = {}{}", s.homing.debounce,
                                      *n > 30 ? " (at most 30, as lim_cnt)" : ""));
    }

  // Homing: G28's order, speeds, back-off and the place of each switch. On g28move, A is the
  // manual's alternate-switch flag ("A# is used to specify that an alternate limit switch is
  // to be used"), never an A axis's distance: the manual's axis letters there are X Y Z W.
  constexpr std::string_view kG28moveAxes = "XYZWBC";
  std::string order;
  for (const Line* l : g28moves) {
    std::string vertical, other;
    for (char c : std::string_view(kG28moveAxes))
      if (has(*l, c) && block(c))
        (block(c)->type == 3 ? vertical : other) +=
            kAxisLetters[static_cast<size_t>(block(c)->slot)];
    for (char c : vertical + other)
      if (order.find(c) == std::string::npos) order += c;
  }
  if (g28moves.empty() || order.empty()) {  // G28 homes every axis, vertical ones first
    std::string vertical, other;
    for (const AxisBlock& b : axes)
      if (b.slot >= 0 && b.type != 4)
        (b.type == 3 ? vertical : other) += kAxisLetters[static_cast<size_t>(b.slot)];
    order = vertical + other;
  }
  if (!order.empty()) s.homing.order = order;
  for (const AxisBlock& b : axes)  // vertical axes home high, the others low (G28's default)
    if (b.slot >= 0) s.homing.direction[static_cast<size_t>(b.slot)] = b.type == 3 ? 1 : -1;
  for (size_t n = 0; n < g28moves.size(); ++n) {
    const Line& l = *g28moves[n];
    if (n == 0) {
      if (has(l, 'F'))
        if (auto f = number(l, 'F', 0, 6e7, true)) s.homing.fast_speed = *f / 60 * len;
      s.homing.slow_speed = 10.0 / 60 * len;  // T's default
      if (has(l, 'T'))
        if (auto t = number(l, 'T', 0, 6e7, true)) s.homing.slow_speed = *t / 60 * len;
      if (has(l, 'R'))
        if (auto r = number(l, 'R', 0, 1e6, true)) s.homing.back_off = *r * len;
      mapped(l, "g28move F T R -> homing.fast_speed, slow_speed (units/min / 60), back_off");
    }
    // The axes this line homes: its speeds (a line after the first) and its search length
    // are theirs.
    std::vector<size_t> line_axes;
    for (char c : std::string_view(kG28moveAxes))
      if (has(l, c) && block(c)) line_axes.push_back(static_cast<size_t>(block(c)->slot));
    if (n > 0 && (has(l, 'F') || has(l, 'T') || has(l, 'R'))) {
      std::optional<double> f, t, r;
      if (has(l, 'F')) f = number(l, 'F', 0, 6e7, true);
      if (has(l, 'T')) t = number(l, 'T', 0, 6e7, true);
      if (has(l, 'R')) r = number(l, 'R', 0, 1e6, true);
      std::string keys;
      for (size_t i : line_axes) {
        if (f) s.homing.fast[i] = *f / 60 * len;
        if (t) s.homing.slow[i] = *t / 60 * len;
        if (r) s.homing.retract[i] = *r * len;
        keys += fmt::format("{}homing.{}", keys.empty() ? "" : ", ", kAxisLetters[i]);
      }
      if (!line_axes.empty())
        mapped(l, fmt::format("g28move F T R (this line's) -> {} fast_speed, slow_speed, back_off",
                              keys));
    }
    if (has(l, 'L'))
      if (auto len_l = number(l, 'L', 0, 1e9, true))
        for (size_t i : line_axes) {
          s.homing.search[i] = *len_l * len;
          mapped(l, fmt::format("g28move L -> homing.{}.search = {}", kAxisLetters[i],
                                num(s.homing.search[i].value_or(0))));
        }
    for (char c : std::string_view(kG28moveAxes)) {
      if (!has(l, c)) continue;
      const AxisBlock* b = block(c);
      if (!b) {
        unmapped(l, fmt::format("g28move {}", c),
                 fmt::format("axischar names no {} axis Gantry drives", c));
        continue;
      }
      if (auto d = number(l, c, 0, 1e9)) {
        const size_t i = static_cast<size_t>(b->slot);
        // The axis's zero is `d` inside its switch: the switch is at -d (homing low) or +d.
        s.homing.at[i] = s.homing.direction[i] * *d * len;
        mapped(l, fmt::format("g28move {0} -> homing.{1}.at = {2} (zero is {0} inside the switch)",
                              c, kAxisLetters[i], num(s.homing.at[i])));
        // WinCNC ends the homing cycle that far off the switch, at its zero.
        if (*d > 0) {
          s.homing.offset[i] = *d * len;
          mapped(l, fmt::format("g28move {} -> homing.{}.offset = {} (homing ends at zero)", c,
                                kAxisLetters[i], num(*d * len)));
        }
      }
    }
    if (has(l, 'A'))
      unmapped(l, "g28move A",
               "homing on an axis's alternate limit switch: Gantry homes on input switches, not "
               "on the limit inputs; set homing.<axis>.input to the input switch (auxin channel) "
               "that switch is wired to");
    if (has(l, 'M')) mapped(l, "g28move M: Gantry homes each axis on its own, in homing.order");
  }
  if (const auto it = single.find("g28altmove"); it != single.end()) {
    const Line& l = *it->second;
    for (const auto& [c, p] : l.params) {
      const AxisBlock* b = block(c);
      if (!b) {
        unmapped(l, fmt::format("g28altmove {}", c), fmt::format("axischar names no {} axis", c));
        continue;
      }
      if (auto v = number(l, c, -1e9, 1e9)) {
        s.homing.square_offset[static_cast<size_t>(b->slot)] = *v * len;
        mapped(l, fmt::format("g28altmove {} -> homing.{}.square_offset", c,
                              kAxisLetters[static_cast<size_t>(b->slot)]));
      }
    }
  }
  if (const auto it = single.find("g28coord"); it != single.end()) {
    // "not used if all positions are zero"
    const Line& l = *it->second;
    bool all_zero = true;
    for (const auto& [c, p] : l.params) all_zero = all_zero && p.value == 0;
    if (all_zero) {
      mapped(l, "g28coord: every position 0, not used (as WinCNC)");
    } else {
      for (const auto& [c, p] : l.params) {
        const AxisBlock* b = block(c);
        if (!b) {
          unmapped(l, fmt::format("g28coord {}", c), fmt::format("axischar names no {} axis", c));
          continue;
        }
        if (auto v = number(l, c, -1e9, 1e9)) {
          const size_t i = static_cast<size_t>(b->slot);
          s.homing.park[i] = *v * len;
          mapped(l, fmt::format("g28coord {} -> homing.{}.park = {}", c, kAxisLetters[i],
                                num(*v * len)));
        }
      }
    }
  }
  if (const auto it = single.find("override"); it != single.end()) {
    const Line& l = *it->second;
    std::optional<int> lo, hi;
    if (has(l, 'L')) lo = whole(l, 'L', 1, 200);
    if (has(l, 'H')) hi = whole(l, 'H', 1, 200);
    if (lo) s.feed_override.min = *lo;
    if (hi) s.feed_override.max = *hi;
    if (lo || hi)
      mapped(l, fmt::format("override L H -> feed_override.min = {}, max = {} (percent)",
                            s.feed_override.min, s.feed_override.max));
    if (has(l, 'E') && l.params.at('E').value == 0)
      unmapped(l, "override E0",
               "Gantry's feed override cannot be switched off: feed_override.min and max of "
               "100 would be the nearest, and they must differ");
    for (char c : {'D', 'U'})
      if (has(l, c))
        unmapped(l, fmt::format("override {}", c),
                 "an input switch that steps the feed override: the pendant's feed buttons and "
                 "keys do");
  }

  // Inputs: auxin channels are the input switches (1-12); enab, signal and scan give them
  // their roles.
  std::map<int, std::pair<int, const Line*>> channel_bit;  // auxin C -> input bit
  // A"axes" on an enable (enab, auxin F1): the axes to home again when it trips during motion,
  // homing.require.
  auto require_home = [&](const Line& l, std::string_view what) {
    const Param& p = l.params.at('A');
    for (char c : p.text) {
      const char upper = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
      const AxisBlock* b = block(upper);
      if (!b) {
        unmapped(l, fmt::format("{} A {}", what, upper),
                 fmt::format("axischar names no {} axis Gantry drives", upper));
        continue;
      }
      s.homing.require |= 1u << b->slot;
    }
    mapped(l, fmt::format("{} A\"{}\" -> homing.require (the axes to home again after it trips "
                          "during motion)",
                          what, p.text));
  };
  for (const Line* lp : auxins) {
    const Line& l = *lp;
    if (!has(l, 'C') || !has(l, 'B')) {
      error(l, l.column, "auxin= needs C, its channel, and B, its bit");
      continue;
    }
    const auto c = whole(l, 'C', 1, 32);
    const auto port = has(l, 'P') ? whole(l, 'P', 0, 12) : std::optional<int>(0);
    const auto bit = whole(l, 'B', 0, 7);
    if (!c || !port || !bit) continue;
    const int word = input_bit(*port, *bit);
    if (word < 0) {
      unmapped(l, fmt::format("auxin C{} P{}", *c, *port),
               "inputs on a port beyond 0-3 (an expansion card): Gantry reads the PCI-7200's 32");
      continue;
    }
    channel_bit[*c] = {word, &l};
    if (*c <= 12) {
      s.inputs.switch_bits[static_cast<size_t>(*c - 1)] = word;
      mapped(l, fmt::format("auxin C{} P B -> input switch {}: inputs.switch_bits bit {}", *c, *c,
                            word));
    } else {
      unmapped(l, fmt::format("auxin C{}", *c), "Gantry's part files read input switches 1-12");
    }
    if (has(l, 'F')) {
      const int f = static_cast<int>(l.params.at('F').value);
      const bool low = has(l, 'O') && l.params.at('O').value == 1;
      if (f == 1) {
        s.inputs.estop_bit = word;
        s.inputs.estop_active_low = low;
        mapped(l, fmt::format("auxin F1 (enable) -> inputs.estop_bit = {}", word));
      } else if (f == 100 && *c <= 12) {
        s.switches.input_modes[static_cast<size_t>(*c - 1)] = low ? 4 : 3;
        mapped(l, fmt::format("auxin F100 (abort) -> switches.input_modes: input {} a stop switch",
                              *c));
      } else if (f != 0) {
        unmapped(l, fmt::format("auxin F{}", f),
                 "pause, continue, start and user signals on inputs: Gantry's inputs stop "
                 "(VN) or are read by part files (ON INPUT)");
      }
    }
    for (char p : std::string_view("DLI"))
      if (has(l, p))
        unmapped(l, fmt::format("auxin {}", p),
                 "a debounce, signal or initial state per input: not offered");
    if (has(l, 'M')) unmapped(l, "auxin M", "a custom message: Gantry names the input");
    if (has(l, 'A')) {
      if (has(l, 'F') && l.params.at('F').value == 1)
        require_home(l, "auxin");
      else
        unmapped(l, "auxin A", "the manual's require-home flags belong to an enable (F1)");
    }
    if (has(l, 'O') && !has(l, 'F') && l.params.at('O').value == 1)
      unmapped(l, "auxin O", "an inverted input switch: Gantry reads 1 as closed");
  }
  auto channel = [&](const Line& l, const char* what) -> std::optional<int> {
    if (!has(l, 'C')) {
      error(l, l.column, fmt::format("{}= needs C, the input channel", what));
      return std::nullopt;
    }
    const auto c = whole(l, 'C', 1, 32);
    if (!c) return std::nullopt;
    if (!channel_bit.count(*c)) {
      error(l, l.params.at('C').column,
            fmt::format("{} C{}: no auxin= line defines input channel {}", what, *c, *c));
      return std::nullopt;
    }
    return *c;
  };
  if (const auto it = single.find("enab"); it != single.end()) {
    const Line& l = *it->second;
    if (const auto c = channel(l, "enab")) {
      const int t = has(l, 'T') ? static_cast<int>(l.params.at('T').value) : 1;
      if (t <= 2) {
        s.inputs.estop_bit = channel_bit[*c].first;
        const Line& in = *channel_bit[*c].second;
        s.inputs.estop_active_low = has(in, 'O') && in.params.at('O').value == 1;
        mapped(l, fmt::format("enab C{} T{} -> inputs.estop_bit = {}", *c, t, s.inputs.estop_bit));
      } else {
        unmapped(l, fmt::format("enab T{}", t),
                 "an enable that pauses or lets the keys jog: Gantry's E-stop input stops");
      }
      if (has(l, 'A')) {
        if (t <= 2)
          require_home(l, "enab");
        else
          unmapped(l, "enab A", "the require-home flags of an enable Gantry does not map");
      }
      for (char p : std::string_view("MLI"))
        if (has(l, p))
          unmapped(l, fmt::format("enab {}", p),
                   "a message, signal or initial state of the enable: not offered");
    }
  }
  if (const auto it = single.find("signal"); it != single.end()) {
    const Line& l = *it->second;
    if (const auto c = channel(l, "signal")) {
      const int t = has(l, 'T') ? static_cast<int>(l.params.at('T').value) : 0;
      if (t == 100 && *c <= 12) {
        const Line& in = *channel_bit[*c].second;
        s.switches.input_modes[static_cast<size_t>(*c - 1)] =
            has(in, 'O') && in.params.at('O').value == 1 ? 4 : 3;
        mapped(l, fmt::format(
                      "signal C{} T100 (abort) -> switches.input_modes: input {} a stop switch", *c,
                      *c));
      } else {
        unmapped(l, fmt::format("signal T{}", t),
                 "pause, continue, start, inhibit and user signals: Gantry's inputs stop (VN) or "
                 "are read by part files (ON INPUT)");
      }
    }
  }
  if (const auto it = single.find("scan"); it != single.end()) {
    const Line& l = *it->second;
    if (const auto c = channel(l, "scan")) {
      s.inputs.probe_bit = channel_bit[*c].first;
      mapped(l, fmt::format("scan C{} -> inputs.probe_bit = {} (the touch probe)", *c,
                            s.inputs.probe_bit));
    }
    unmapped(l, "scan T A S H F P D", "3D digitizing with the probe: not offered (G38.2 probes)");
  }

  // G28 homes each axis on its limit switch of the homing side (axislo homing down, axishi up).
  // Gantry homes on input switches: each such limit bit becomes one (the input switch an auxin
  // already puts on it, or the first free of 1-12), the axis's homing.<axis>.input. The card
  // does not trip on a bit homing watches, so the approach stops on the switch, not in a fault.
  if (!g28moves.empty()) {
    const Line& l = *g28moves.front();
    for (const char c : s.homing.order) {
      const auto i = std::string_view("xyzabc").find(c);
      if (i >= static_cast<size_t>(kAxisCount)) continue;
      const bool up = s.homing.direction[i] > 0;
      const int bit = (up ? s.inputs.max_bit : s.inputs.min_bit)[i];
      if (bit < 0) {
        unmapped(l, fmt::format("g28move ({})", c),
                 fmt::format("no {} limit switch (axis{}) to home on: homing.input's switch "
                             "stays this axis's",
                             up ? "high" : "low", up ? "hi" : "lo"));
        continue;
      }
      // An input switch reads 1 as closed: a switch that reads 0 when closed (O1) cannot be one.
      const Line* side = nullptr;
      for (const AxisBlock& b : axes)
        if (b.slot == static_cast<int>(i)) side = up ? b.hi : b.lo;
      if (side && has(*side, 'O') && side->params.at('O').value == 1) {
        unmapped(l, fmt::format("g28move ({})", c),
                 fmt::format("its {} limit switch reads 0 when closed (axis{} O1) and an input "
                             "switch reads 1 as closed: homing.input's switch stays this axis's",
                             up ? "high" : "low", up ? "hi" : "lo"));
        continue;
      }
      auto& bits = s.inputs.switch_bits;
      auto k = std::find(bits.begin(), bits.end(), bit);
      if (k == bits.end()) k = std::find(bits.begin(), bits.end(), -1);
      if (k == bits.end()) {
        unmapped(l, fmt::format("g28move ({})", c),
                 "every input switch 1-12 is taken: no switch for its homing limit");
        continue;
      }
      *k = bit;
      s.homing.axis_input[i] = static_cast<int>(k - bits.begin()) + 1;
      mapped(l, fmt::format("g28move: {} homes on its {} limit switch (bit {}): input switch {}, "
                            "homing.{}.input",
                            c, up ? "high" : "low", bit, s.homing.axis_input[i], c));
    }
  }

  // Outputs: auxout channels are the output switches (SO numbers).
  for (const Line* lp : auxouts) {
    const Line& l = *lp;
    if (!has(l, 'C') || !has(l, 'B')) {
      error(l, l.column, "auxout= needs C, its channel, and B, its bit");
      continue;
    }
    const auto c = whole(l, 'C', 1, 32);
    const auto port = has(l, 'P') ? whole(l, 'P', 0, 12) : std::optional<int>(7);
    const auto bit = whole(l, 'B', 0, 7);
    if (!c || !port || !bit) continue;
    const int word = output_bit(*port, *bit);
    if (word < 0) {
      unmapped(l, fmt::format("auxout C{} P{}", *c, *port),
               *port == 0 ? "port 0 is the step and direction port"
                          : "an output port other than 6 and 7 (docs/hardware.md): not mapped");
      continue;
    }
    if (*c > 12) {
      unmapped(l, fmt::format("auxout C{}", *c), "Gantry has output switches 1-12");
      continue;
    }
    if (s.outputs.aux_bits.size() < static_cast<size_t>(*c))
      s.outputs.aux_bits.resize(static_cast<size_t>(*c), -1);
    s.outputs.aux_bits[static_cast<size_t>(*c - 1)] = word;
    mapped(l, fmt::format("auxout C{} P B -> output switch {}: outputs.aux_bits bit {}", *c, *c,
                          word));
    for (char p : std::string_view("OSETXWR"))
      if (has(l, p))
        unmapped(l, fmt::format("auxout {}", p),
                 p == 'O' ? "an inverted output: Gantry's outputs are on at 1"
                          : "an output's state at start, exit, abort, pause or restart, or its "
                            "type: Gantry's outputs are off at start and when a run ends");
  }
  if (const auto it = single.find("watch"); it != single.end()) {
    const Line& l = *it->second;
    const int t = has(l, 'T') ? static_cast<int>(l.params.at('T').value) : 0;
    if (t == 7 && has(l, 'C')) {
      const auto c = whole(l, 'C', 1, 12);
      if (c && static_cast<size_t>(*c) <= s.outputs.aux_bits.size() &&
          s.outputs.aux_bits[static_cast<size_t>(*c - 1)] >= 0) {
        s.outputs.charge_pump_bit = s.outputs.aux_bits[static_cast<size_t>(*c - 1)];
        s.outputs.aux_bits[static_cast<size_t>(*c - 1)] = -1;
        // D: the square wave's period, ms.
        if (has(l, 'D'))
          if (auto d = number(l, 'D', 0, 1e6, true)) s.outputs.charge_pump_hz = 1000 / *d;
        mapped(l, fmt::format("watch T7 C{} D -> outputs.charge_pump_bit = {}", *c,
                              s.outputs.charge_pump_bit));
      } else if (c) {
        error(l, l.params.at('C').column,
              fmt::format("watch C{}: no auxout= line defines output channel {}", *c, *c));
      }
    } else {
      unmapped(l, fmt::format("watch T{}", t),
               "the watchdog on CN2 pins 11 and 15 (timer outputs): Gantry's charge pump is an "
               "output bit, outputs.charge_pump_bit");
    }
  }
  if (const auto it = single.find("spindle"); it != single.end()) {
    const Line& l = *it->second;
    if (has(l, 'R'))
      if (auto rpm = number(l, 'R', 0, 1e6, true)) {
        s.spindle.max_rpm = *rpm;
        mapped(l, "spindle R -> spindle.max_rpm");
      }
    if (has(l, 'I'))
      if (auto rpm = number(l, 'I', 0, 1e6)) {
        s.spindle.initial_rpm = *rpm;
        mapped(l, "spindle I -> spindle.initial_rpm");
      }
    if (has(l, 'T'))
      if (auto t = whole(l, 'T', 1, 3)) {
        if (*t == 1)
          unmapped(l, "spindle T1",
                   "the D/A converter on CN2 pins 12-14: Gantry carries the speed as a D/A word "
                   "on output bits (spindle.dac_bits), a PWM duty or a frequency "
                   "(spindle.pwm_bit); name the bits the converter is wired to");
        else if (*t == 2)
          mapped(l, "spindle T2 -> no speed output (Spin.mac's outputs set the speed)");
        else {
          s.spindle.speed_mode = SpindleSettings::SpeedMode::Frequency;
          mapped(l,
                 "spindle T3 -> spindle.speed_mode = \"frequency\" (name CN2 pin 11's bit in "
                 "spindle.pwm_bit)");
        }
      }
  }
  // The spindle's D/A (da=): its start voltage as a share of its top one is the RPM at start.
  if (const auto it = single.find("da"); it != single.end()) {
    const Line& l = *it->second;
    const auto sp = single.find("spindle");
    if (has(l, 'I') && sp != single.end() && has(*sp->second, 'I')) {
      unmapped(l, "da I", "the spindle's I gives the RPM at start (spindle.initial_rpm)");
    } else if (has(l, 'I')) {
      const std::optional<double> v = has(l, 'V') ? number(l, 'V', 0, 1000, true) : 10.0;
      const std::optional<double> i = number(l, 'I', 0, 1000);
      if (v && i && *i > *v) {
        error(l, l.params.at('I').column,
              fmt::format("da I{} is above its top voltage V{}", num(*i), num(*v)));
      } else if (v && i) {
        s.spindle.initial_rpm = *i / *v * s.spindle.max_rpm;
        mapped(l, fmt::format("da I V -> spindle.initial_rpm = {} (I / V of spindle.max_rpm)",
                              num(s.spindle.initial_rpm)));
      }
    }
    for (char c : std::string_view("TAC"))
      if (has(l, c))
        unmapped(l, fmt::format("da {}", c),
                 "the D/A's port (parallel, the PCI daughter board, serial): Gantry's D/A word "
                 "is output bits of the card (spindle.dac_bits); name them");
    if (has(l, 'R'))
      unmapped(l, "da R", "a refresh period: Gantry's D/A word stands until the speed changes");
  }
  if (const auto it = single.find("pwm"); it != single.end()) {
    const Line& l = *it->second;
    if (has(l, 'F'))
      if (auto f = number(l, 'F', 0, 1e6, true)) {
        s.spindle.pwm_hz = *f;
        mapped(l, "pwm F -> spindle.pwm_hz (the manual gives no unit: read as Hz)");
      }
    if (has(l, 'M') && l.params.at('M').value != 100)
      unmapped(l, "pwm M",
               "a top duty below 100 %: Gantry's duty reaches 100 % at spindle.max_rpm; give "
               "max_rpm the RPM that 100 % would run");
  }
  // The tool-length sensor (g37=): its place and feed; its input is not in WINCNC.INI.
  if (const auto it = single.find("g37"); it != single.end()) {
    const Line& l = *it->second;
    if (has(l, 'X'))
      if (auto x = number(l, 'X', -1e6 / len, 1e6 / len)) s.toolchanger.sensor_x = *x * len;
    if (has(l, 'Y'))
      if (auto y = number(l, 'Y', -1e6 / len, 1e6 / len)) s.toolchanger.sensor_y = *y * len;
    if (has(l, 'F'))
      if (auto f = number(l, 'F', 0, 1e6 / len, true)) s.toolchanger.sensor_speed = *f * len / 60;
    mapped(l,
           "g37 X Y F -> toolchanger.sensor_x, sensor_y, sensor_speed (name the sensor's input "
           "in toolchanger.sensor_input)");
    if (has(l, 'D'))
      unmapped(l, "g37 D",
               "the rapid descent: Gantry's probe starts at a height, "
               "toolchanger.sensor_start_z; set it that far below toolchanger.clear_z");
    for (char c : std::string_view("IJ"))
      if (has(l, c))
        unmapped(l, fmt::format("g37 {}", c),
                 "a second tool measure switch: Gantry has one tool-length sensor");
  }
  if (const auto it = single.find("atc1"); it != single.end()) {
    const Line& l = *it->second;
    if (has(l, 'H'))
      if (auto h = number(l, 'H', -1e6 / len, 1e6 / len)) {
        s.toolchanger.slot_z = *h * len;
        mapped(l,
               "atc1 H -> toolchanger.slot_z (the rack's slots are WinCNC's Tool Positions, "
               "not in WINCNC.INI: list them in toolchanger.slots, with release_output)");
      }
    if (has(l, 'A'))
      if (auto a = whole(l, 'A', 0, 8)) {
        if (*a == 2)
          mapped(l, "atc1 A2 -> the changer on Z");
        else
          unmapped(l, fmt::format("atc1 A{}", *a),
                   "a changer on another axis's head: Gantry's changer works on Z");
      }
    if (has(l, 'M')) mapped(l, "atc1 M -> the tool table (tool_table, G43's and M37's)");
    if (has(l, 'O'))
      unmapped(l, "atc1 O",
               "the offset to the tool sensor, from what the manual does not say: Gantry's "
               "lengths are from toolchanger.sensor_zero_z (calibrate it with M37.1)");
    if (has(l, 'Z'))
      unmapped(l, "atc1 Z",
               "the height of the changing spindle's nose: Gantry's lengths are from the "
               "sensor's zero, toolchanger.sensor_zero_z");
  }
  if (const auto it = single.find("atc2"); it != single.end())
    unmapped(*it->second, "atc2",
             "a second tool changer: the manual gives its line but not how it works (which "
             "head, its rack and sensor); Gantry has one changer, on Z (docs/hardware.md, "
             "\"Tool changer\")");
  if (const auto it = single.find("backlash"); it != single.end()) {
    const Line& l = *it->second;
    if (has(l, 'B') && l.params.at('B').value == 0) {
      for (AxisSettings& ax : s.axes) ax.backlash = 0;
      mapped(l, "backlash B0 -> no backlash compensation (axes.<axis>.backlash = 0)");
    }
    for (char c : std::string_view("SF"))
      if (has(l, c))
        unmapped(l, fmt::format("backlash {}", c),
                 "backlash smoothing and arc slow-down: the takeup runs at the corner jump speed "
                 "(docs/hardware.md, \"Backlash\")");
  }
  if (const auto it = single.find("table"); it != single.end()) {
    const Line& l = *it->second;
    if (has(l, 'W'))
      if (auto w = number(l, 'W', 0, 1e6 / len, true)) s.preview.table_x = *w * len;
    if (has(l, 'H'))
      if (auto h = number(l, 'H', 0, 1e6 / len, true)) s.preview.table_y = *h * len;
    mapped(l, "table W H -> preview.table_x, table_y");
    for (char c : std::string_view("XYBZ"))
      if (has(l, c)) unmapped(l, fmt::format("table {}", c), std::string(kScreen));
  }
  if (const auto it = single.find("vgroup"); it != single.end()) {
    const std::string g = ascii::upper(it->second->value);
    if (g == "FXY" || g == "XY" || g.size() == 1)
      mapped(*it->second, "vgroup=" + g + ": Gantry's speed groups are XY, Z, A, B, C already");
    else
      unmapped(*it->second, "vgroup=" + g, "Gantry's speed groups are XY, Z, A, B, C");
  }
  if (const auto it = single.find("xhc"); it != single.end())
    unmapped(*it->second, "xhc",
             "Gantry finds an XHC WHB04B pendant when it is plugged in (USB); no setting");

  // Keys: CTRL+F1..F8 and the XHC pendant's keys run the pendant's macros.
  std::array<std::string, 10>& macros = s.pendant.macros;
  for (std::string& m : macros) m.clear();
  const bool xhc = single.count("xhc") != 0;
  for (const ScreenRecord& rec : screen_) {
    const std::string type = ascii::lower(rec.fields[0]);
    const int scan = rec.fields.size() > 10 ? std::atoi(rec.fields[10].c_str()) : -1;
    if (xhc && type == "userbtn" && scan >= 1 && scan <= 10 && rec.fields.size() > 8 &&
        macros[static_cast<size_t>(scan - 1)].empty()) {
      macros[static_cast<size_t>(scan - 1)] = bound_command(rec.fields[8]);
      r_.mapped.push_back(fmt::format(
          "{}:{}: \"UserBtn\" on the XHC pendant's key {} -> pendant.macro_{} = \"{}\"",
          rec.line.file->path, rec.line.number, scan, scan, macros[static_cast<size_t>(scan - 1)]));
      continue;
    }
    std::string why;
    if (type == "userbtn" || type == "jobcmd" || type == "rptcmd" || type == "keypadout" ||
        type == "jogmode" || type == "jogmodeex" || type == "axiscontrol" || type == "axislabel")
      why = scan > 0 ? "a serial keypad's scan code: Gantry reads no serial keypad; bind a key "
                       "(pendant.keys) to a pendant macro instead"
                     : "a screen button: Gantry's window has its own";
    else
      why = "the WinCNC screen's layout, colours and indicators: Gantry's window is its own";
    unmapped(rec.line, "\"" + rec.fields[0] + "\"", why);
  }
  for (size_t n = 0; n < ctrlf.size(); ++n) {
    if (!ctrlf[n]) continue;
    const Line& l = *ctrlf[n];
    size_t slot = 0;
    while (slot < macros.size() && !macros[slot].empty()) ++slot;
    if (slot == macros.size()) {
      unmapped(l, l.keyword, "the pendant's ten macros are all bound");
      continue;
    }
    macros[slot] = bound_command(l.value);
    keys.push_back(fmt::format("Ctrl+F{} = macro {}", n + 1, slot + 1));
    mapped(l, fmt::format("{} -> pendant.macro_{} = \"{}\", pendant.keys \"{}\"", l.keyword,
                          slot + 1, macros[slot], keys.back()));
  }
  s.pendant.keys = keys;
  for (const WincncMacro& m : r_.macros)
    r_.mapped.push_back(fmt::format("{}:{}: {} -> custom cut C{} (C{}.sbp)",
                                    m.loc.file ? *m.loc.file : "", m.loc.line, m.name, m.cut,
                                    m.cut));

  if (!r_.errors.empty()) return;
  // The rules across keys, as the profile's loader checks them.
  for (const std::string& why : settings_problems(s))
    r_.errors.push_back(
        {file_loc(in_.ini.path), Severity::Error, "the imported profile breaks a rule: " + why});
  std::stable_sort(
      r_.unmapped.begin(), r_.unmapped.end(), [](const WincncUnmapped& a, const WincncUnmapped& b) {
        const std::string fa = a.loc.file ? *a.loc.file : "", fb = b.loc.file ? *b.loc.file : "";
        return std::tie(fa, a.loc.line) < std::tie(fb, b.loc.line);
      });
}

}  // namespace

WincncImport import_wincnc(const WincncSources& in) {
  return Importer(in).run();
}

std::string wincnc_profile_text(const WincncImport& r, const WincncSources& in) {
  std::string head = fmt::format(
      "# Gantry profile \"{}\", imported from a WinCNC set-up by `gantry import-wincnc`:\n# "
      "{}{}{}\n",
      r.settings.name, in.ini.path, in.screen ? ", " + in.screen->path : "",
      in.macros ? ", " + in.macros->path : "");
  head +=
      "# What WinCNC's files do not say is Gantry's default profile's. Not carried over (see\n"
      "# the import's report for why):\n";
  std::string line = "#  ";
  for (const WincncUnmapped& u : r.unmapped) {
    const std::string item =
        fmt::format(" {}:{} {};", u.loc.file ? *u.loc.file : "", u.loc.line, u.keyword);
    if (line.size() + item.size() > 98) {
      head += line + "\n";
      line = "#  ";
    }
    line += item;
  }
  if (line != "#  ") head += line + "\n";
  return head + "\n" + settings_text(r.settings);
}

std::string wincnc_report(const WincncImport& r) {
  std::string out = fmt::format("not mapped ({}):\n", r.unmapped.size());
  for (const WincncUnmapped& u : r.unmapped)
    out += fmt::format("  {}:{}: {}: {}\n", u.loc.file ? *u.loc.file : "", u.loc.line, u.keyword,
                       u.why);
  return out;
}

std::string wincnc_macro_cut(const WincncMacro& m) {
  std::string out = fmt::format(
      "' C{}: WinCNC's macro {} ({}:{}): {} = {}{}\n"
      "' Imported by gantry import-wincnc. It runs its command as a WinCNC G-code line\n"
      "' (gcode_dialect = \"wincnc\"); a part file calls it as C{}.\n",
      m.cut, m.name, m.loc.file ? *m.loc.file : "", m.loc.line, m.name, m.command,
      m.comment.empty() ? "" : " [" + m.comment + "]", m.cut);
  return out + m.command + "\n";
}

}  // namespace gantry
