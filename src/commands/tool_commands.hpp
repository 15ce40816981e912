// What the tools' files (tool_commands_*.cpp) share: their parameters, the cutter, and the
// part file a tool writes.
#pragma once

#include <fmt/format.h>  // the part files' text, messages

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "gantry/commands/command_table.hpp"
#include "gantry/convert/part_file.hpp"  // PartText, part_number
#include "gantry/interp/command_context.hpp"

namespace gantry::tools {

// ---- parameters -------------------------------------------------------------------------

inline ParamSpec file_param(std::string_view help) {
  return {"file name", "", true, std::nullopt, help, ParamKind::Text};
}
inline ParamSpec length(std::string_view name, std::optional<double> def, std::string_view help,
                        bool required = false) {
  return {name, "units", required, def, help};
}
inline ParamSpec count(std::string_view name, std::optional<double> def, std::string_view help) {
  return {name, "", false, def, help};
}

// Parameter i as a whole number in [lo, hi].
inline int whole(const CommandCall& call, size_t i, int lo, int hi) {
  const double v = *call.number(i);
  if (v != std::round(v) || v < lo || v > hi)
    fail(call.param_loc(i),
         fmt::format("{} ({}) is {}; it must be a whole number from {} to {}",
                     call.spec.params[i].name, call.spec.code, part_number(v), lo, hi));
  return static_cast<int>(v);
}

// Parameter i, which must be above 0; `fallback` when blank (nullopt: it must be given).
inline double positive(const CommandCall& call, size_t i,
                       std::optional<double> fallback = std::nullopt) {
  const std::optional<double> v = call.number(i) ? call.number(i) : fallback;
  if (!v)
    fail(call.param_loc(i), fmt::format("{} needs its parameter {} ({})", call.spec.code, i + 1,
                                        call.spec.params[i].name));
  if (!(*v > 0))
    fail(call.param_loc(i), fmt::format("{} ({}) is {}; it must be above 0",
                                        call.spec.params[i].name, call.spec.code, part_number(*v)));
  return *v;
}

// Parameter i as an overlap in percent, 0 up to (not including) 100.
inline double overlap(const CommandCall& call, size_t i, double fallback) {
  const double v = call.number(i).value_or(fallback);
  if (!(v >= 0 && v < 100))
    fail(call.param_loc(i),
         fmt::format("{} ({}) is {} %; it must be from 0 up to (not including) 100",
                     call.spec.params[i].name, call.spec.code, part_number(v)));
  return v;
}

// Parameter i as a choice between 0 and 1.
inline bool choice(const CommandCall& call, size_t i, std::string_view zero, std::string_view one) {
  const double v = call.number(i).value_or(0);
  if (v != 0 && v != 1)
    fail(call.param_loc(i),
         fmt::format("{} ({}) is {}; it is 0 ({}) or 1 ({})", call.spec.params[i].name,
                     call.spec.code, part_number(v), zero, one));
  return v == 1;
}

// The cutter values of the profile (VC) the tools fall back on when a parameter is blank.
struct Cutter {
  double diameter, safe_z, overlap;
};
inline Cutter cutter(const CommandContext& ctx) {
  const CutterSettings& c = ctx.settings().cutter;
  return {c.diameter, c.safe_z, c.pocket_overlap};
}

// Safe Z (parameter i): blank is the profile's Safe-Z above `surface`; it must clear it.
inline double safe_z(const CommandContext& ctx, const CommandCall& call, size_t i, double surface) {
  const double z = call.number(i).value_or(surface + cutter(ctx).safe_z);
  if (!(z > surface))
    fail(call.param_loc(i),
         fmt::format("safe Z ({}) is {}, not above the material surface (Z {}); the tool "
                     "would travel through the material",
                     call.spec.code, part_number(z), part_number(surface)));
  return z;
}

// The Z of each pass, evenly down to `bottom` from `surface`.
inline std::vector<double> pass_depths(double surface, double bottom, int passes) {
  std::vector<double> z;
  for (int k = 1; k <= passes; ++k) z.push_back(surface + (bottom - surface) * k / passes);
  return z;
}

// ---- the part file a tool writes -----------------------------------------------------------

// A tool's part file: its header, then what the tool writes through PartText.
class PartFile : public PartText {
 public:
  // The first lines: what wrote it, for which machine and units, and the summary `about`.
  PartFile(const CommandContext& ctx, std::string_view code, std::string_view tool,
           const std::vector<std::string>& about) {
    const Settings& s = ctx.settings();
    comment(fmt::format("{} written by Gantry {} ({}) for the machine profile \"{}\"", tool,
                        GANTRY_VERSION, code, s.name));
    comment(fmt::format("Units: {}. Absolute coordinates from working 0 (it sets SA).",
                        units_name(s.units)));
    for (const std::string& a : about) comment(a);
    line("SA");
  }
  // Writes the file through the interpreter (a check keeps it in its sandbox) and tells the
  // operator how to run it.
  void write(CommandContext& ctx, const CommandCall& call, std::string_view what) {
    const std::string name = *call.text(0);
    const std::string path = ctx.write_file(name, text(), call.param_loc(0));
    ctx.print(
        fmt::format("{} wrote {} to {}; run it with FP, {} (`gantry moves {}` lists its "
                    "moves)\n",
                    call.spec.code, what, path, name, path));
  }
};

// ---- parameters several tools share ------------------------------------------------------

inline ParamSpec safe_z_param() {
  return length("safe Z", std::nullopt,
                "Z of the moves between cuts (blank: the profile's safe Z above "
                "the surface).");
}
inline ParamSpec passes_param() {
  return count("passes", 1.0, "Cuts to the full depth, evenly deeper.");
}
inline ParamSpec bit_param() {
  return length("bit diameter", std::nullopt,
                "The cutter (blank: cutter.diameter of the profile).");
}
inline ParamSpec overlap_param() {
  return {"overlap", "%", false, std::nullopt,
          "Of the bit, between neighbouring paths (blank: the profile's "
          "cutter.pocket_overlap)."};
}

// Registration of each family, in tool_commands_<family>.cpp.
void add_machining_tools(std::vector<CommandSpec>& out);  // TD, TF, TU
void add_text_tools(std::vector<CommandSpec>& out);       // TT
void add_file_tools(std::vector<CommandSpec>& out);       // TH, TI
void add_machine_tools(std::vector<CommandSpec>& out);    // TC, TS

}  // namespace gantry::tools
