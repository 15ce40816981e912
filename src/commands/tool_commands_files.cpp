// The tools that write part files around part files: the header writer (TH) adds a comment
// header to one; the indexer (TI) writes one that runs another at each turn of a rotary axis.
#include <fmt/format.h>  // the part files' text, messages

#include <ctime>  // the date in TH's header
#include <string>
#include <utility>  // pair
#include <vector>

#include "gantry/commands/command_table.hpp"
#include "gantry/core/text.hpp"  // upper
#include "gantry/interp/command_context.hpp"
#include "tool_commands.hpp"  // the tools' parameters, PartFile

namespace gantry::tools {
namespace {

// ---- TH: header writer ---------------------------------------------------------------------

enum Th {
  kThFile,
  kThTitle,
  kThContact,
  kThMaterial,
  kThBlankX,
  kThBlankY,
  kThThickness,
  kThBit,
  kThZero,
  kThNotes,
  kThFirst,
  kThLast
};

constexpr std::string_view kHeaderBegin = "'---- Header (Gantry TH) ----";
constexpr std::string_view kHeaderEnd = "'---- End of header ----";
constexpr std::string_view kLastBegin = "'---- Run last (Gantry TH) ----";

// `text` without the header and the closing FP a previous TH wrote.
std::string without_old_header(std::string text, const CommandCall& call, const std::string& path) {
  if (text.starts_with(kHeaderBegin)) {
    const size_t end = text.find(kHeaderEnd);
    if (end == std::string::npos)
      fail(call.param_loc(kThFile),
           fmt::format("{} starts with a header TH wrote but its end line ({}) is gone; remove "
                       "the old header by hand, then run TH again",
                       path, kHeaderEnd));
    const size_t next = text.find('\n', end);
    text.erase(0, next == std::string::npos ? text.size() : next + 1);
  }
  const size_t last = text.rfind(kLastBegin);
  if (last != std::string::npos && (last == 0 || text[last - 1] == '\n')) {
    const size_t fp = text.find('\n', last);  // the FP line follows, and nothing after it
    const size_t after = fp == std::string::npos ? fp : text.find('\n', fp + 1);
    if (fp != std::string::npos &&
        (after == std::string::npos || text.find_first_not_of("\r\n", after) == std::string::npos))
      text.erase(last);
  }
  return text;
}

std::string quoted_file(const CommandCall& call, size_t i) {
  const std::string name = *call.text(i);
  if (name.find('"') != std::string::npos)
    fail(call.param_loc(i), "a file name for FP cannot hold a double quote");
  return fmt::format("FP, \"{}\"", name);
}

void header_writer(CommandContext& ctx, const CommandCall& call) {
  std::string path;
  const std::optional<std::string> old =
      ctx.read_file(*call.text(kThFile), call.param_loc(kThFile), &path);
  if (!old)
    fail(call.param_loc(kThFile),
         fmt::format("cannot read {}; TH adds a header to an existing part file", path));
  constexpr std::string_view kBom = "\xEF\xBB\xBF";  // kept first, where a reader looks for it
  const bool bom = old->starts_with(kBom);
  const std::string body = without_old_header(old->substr(bom ? kBom.size() : 0), call, path);
  const std::string eol = old->find("\r\n") != std::string::npos ? "\r\n" : "\n";
  const Settings& s = ctx.settings();
  std::vector<std::string> lines = {std::string(kHeaderBegin)};
  auto field = [&](std::string_view label, size_t i) {
    if (const std::optional<std::string> v = call.text(i); v && !v->empty())
      lines.push_back(fmt::format("' {}: {}", label, *v));
  };
  field("Title", kThTitle);
  field("Contact", kThContact);
  field("Material", kThMaterial);
  std::string blank;
  const std::pair<std::string_view, size_t> sizes[] = {
      {"X", kThBlankX}, {"Y", kThBlankY}, {"thickness", kThThickness}};
  for (const auto& [label, i] : sizes)
    if (const std::optional<double> v = call.number(i))
      blank += fmt::format("{}{} {}", blank.empty() ? "" : ", ", label, part_number(*v));
  if (!blank.empty()) lines.push_back(fmt::format("' Blank: {} {}", blank, units_name(s.units)));
  field("Bit", kThBit);
  if (call.number(kThZero))
    lines.push_back(fmt::format("' Z zero: {}", choice(call, kThZero, "surface", "table top")
                                                    ? "the table top"
                                                    : "the material surface"));
  field("Notes", kThNotes);
  const std::time_t now = std::time(nullptr);
  std::tm day{};
  localtime_r(&now, &day);
  char date[16];
  std::strftime(date, sizeof date, "%Y-%m-%d", &day);
  lines.push_back(fmt::format("' Units: {}; machine profile \"{}\"", units_name(s.units), s.name));
  lines.push_back(fmt::format("' Header written {} by Gantry {} (TH)", date, GANTRY_VERSION));
  if (call.text(kThFirst) && !call.text(kThFirst)->empty())
    lines.push_back(quoted_file(call, kThFirst));
  lines.push_back(std::string(kHeaderEnd));
  std::string text(bom ? kBom : "");
  for (const std::string& l : lines) text += l + eol;
  text += body;
  if (call.text(kThLast) && !call.text(kThLast)->empty()) {
    if (!text.empty() && text.back() != '\n') text += eol;
    text += std::string(kLastBegin) + eol + quoted_file(call, kThLast) + eol;
  }
  const std::string written = ctx.write_file(*call.text(kThFile), text, call.param_loc(kThFile));
  ctx.print(fmt::format("TH wrote a header of {} lines to {}\n", lines.size(), written));
}

// ---- TI: indexer ----------------------------------------------------------------------------

enum Ti { kTiFile, kTiPart, kTiAxis, kTiDivisions, kTiStart, kTiSafeZ };

// Writes a part file that runs another one at each of `divisions` equal turns of a rotary
// axis (a column fluted all round, a pattern on each face): up to safe Z, index, run it.
// SB3 names TI without describing it; this is what an indexer's virtual tool is for.
void indexer(CommandContext& ctx, const CommandCall& call) {
  const std::string part = *call.text(kTiPart);
  const std::string axis = ascii::upper(call.text(kTiAxis).value_or("B"));
  const int n = whole(call, kTiDivisions, 1, 3600);
  const double start = call.number(kTiStart).value_or(0);
  const double safe = safe_z(ctx, call, kTiSafeZ, 0);
  PartFile f(ctx, "TI", "Indexer",
             {fmt::format("Runs {} at {} position{} of {}, {} degrees apart from {}", part, n,
                          n == 1 ? "" : "s", axis, part_number(360.0 / n), part_number(start)),
              fmt::format("Safe Z {} before each turn", part_number(safe))});
  for (int k = 0; k < n; ++k) {
    f.comment(fmt::format("Position {} of {}", k + 1, n));
    f.jog_z(safe);
    f.line(fmt::format("J{}, {}", axis, part_number(start + 360.0 * k / n)));
    f.line(fmt::format("FP, {}", part));
  }
  f.jog_z(safe);
  f.write(ctx, call, fmt::format("{} at {} positions of {}", part, n, axis));
}

}  // namespace

void add_file_tools(std::vector<CommandSpec>& out) {
  const auto T = CommandGroup::Tools;
  out.push_back(
      {"TH",
       "Tools: header writer",
       T,
       "Adds a comment header to a part file: the given fields, the units, the machine profile "
       "and the date, and optionally FP lines that run a file first and last. A header TH "
       "wrote before is replaced.",
       {file_param("The part file to add the header to."),
        {"title", "", false, std::nullopt, "What the file makes.", ParamKind::Text},
        {"contact", "", false, std::nullopt, "Who to ask; use restrictions.", ParamKind::Text},
        {"material", "", false, std::nullopt, "The material.", ParamKind::Text},
        length("blank X", std::nullopt, "Blank size in X."),
        length("blank Y", std::nullopt, "Blank size in Y."),
        length("thickness", std::nullopt, "Blank thickness."),
        {"bit", "", false, std::nullopt, "Bit size and type.", ParamKind::Text},
        count("Z zero", std::nullopt, "0 the material surface, 1 the table top (blank: not said)."),
        {"notes", "", false, std::nullopt, "Anything else (offsets used, ...).", ParamKind::Text},
        {"run first", "", false, std::nullopt, "A part file run (FP) before the file's own lines.",
         ParamKind::Text},
        {"run last", "", false, std::nullopt, "A part file run (FP) after them.", ParamKind::Text}},
       header_writer});
  out.push_back(
      {"TI",
       "Tools: indexer",
       T,
       "Writes a part file that runs another at equal turns of a rotary axis: up to safe Z, "
       "turn, run it, for each division. Run the file it writes with FP.",
       {file_param("The part file to write; a relative name goes beside this file."),
        {"part file", "", true, std::nullopt, "The part file to run at each position.",
         ParamKind::Text},
        ParamSpec{"axis", "", false, std::nullopt, "A or B (blank: B).", ParamKind::Text}.one_of(
            "A B"),
        count("divisions", 4.0, "Equal positions in a turn."),
        {"start angle", "deg", false, 0.0, "The first position."},
        length("safe Z", std::nullopt, "Z before each turn (blank: the profile's safe Z).")},
       indexer});
}

}  // namespace gantry::tools
