// Help commands, HA to HW. SB3 opens a help screen or a web page for each; Gantry prints the
// console equivalent where the command runs: its version, a quick reference generated from
// the command table, the page of the documentation to read, or the web address to open.
#include <fmt/format.h>  // layout

#include <algorithm>  // max
#include <string>

#include "gantry/commands/command_docs.hpp"  // command_list
#include "gantry/commands/command_table.hpp"
#include "gantry/interp/command_context.hpp"

namespace gantry {
namespace {

constexpr std::string_view kShopBotSite = "https://www.shopbottools.com";  // SB3's HW

const CommandGroup kGroups[] = {
    CommandGroup::Cuts,  CommandGroup::File,      CommandGroup::Help,   CommandGroup::Jog,
    CommandGroup::Move,  CommandGroup::Probe,     CommandGroup::Record, CommandGroup::Settings,
    CommandGroup::Tools, CommandGroup::Utilities, CommandGroup::Values, CommandGroup::Zero};

bool runs_here(const CommandSpec& s) {
  return !s.coverage.starts_with("refused by name: ");
}

// HA: what is running, and on which machine profile.
void help_about(CommandContext& ctx, const CommandCall&) {
  const CommandTable& table = CommandTable::standard();
  size_t complete = 0, working = 0;
  for (const CommandSpec& s : table.all()) {
    complete += s.coverage.empty();
    working += runs_here(s);
  }
  const Settings& st = ctx.settings();
  ctx.print(
      fmt::format("Gantry {}\n"
                  "An open-source controller for OpenSBP part files in the style of ShopBot's SB3 "
                  "software; ShopBot Tools neither makes nor supports it.\n"
                  "Machine profile: {} (units: {}, card: {})\n"
                  "Commands: {} of {} codes run here, {} of them completely (docs/commands.md).\n",
                  GANTRY_VERSION, st.name.empty() ? "(unnamed)" : st.name, units_name(st.units),
                  st.card.type, working, table.all().size(), complete));
}

// HB: the bulletins are ShopBot's, on ShopBot's site.
void help_bulletins(CommandContext& ctx, const CommandCall&) {
  ctx.print(fmt::format(
      "ShopBot's technical bulletins are on ShopBot's website: {}\n"
      "They describe ShopBot's own machines and software; Gantry's behaviour is in its docs "
      "folder (HU lists the pages).\n",
      kShopBotSite));
}

// HC: the contents of the command reference, and where the full text is.
void help_commands(CommandContext& ctx, const CommandCall&) {
  std::string out =
      "Command reference: docs/commands.md in Gantry's source tree (`gantry help --markdown` "
      "prints the same page; `gantry help CODE` one command's sheet).\n"
      "The part-file language is in docs/language.md, the system variables %(n) in "
      "docs/system_variables.md.\nContents:\n";
  for (CommandGroup g : kGroups) {
    out += fmt::format("  {:<10}", group_name(g));
    for (const CommandSpec& s : CommandTable::standard().all())
      if (s.group == g) out += fmt::format(" {}", s.code);
    out += "\n";
  }
  ctx.print(out);
}

// HE: every command with its parameters in part-file order, in columns.
void help_parameters(CommandContext& ctx, const CommandCall&) {
  const CommandTable& table = CommandTable::standard();
  size_t width = 0;
  for (const CommandSpec& s : table.all()) width = std::max(width, s.name.size());
  std::string out = "Parameters in part-file order (blank: the command takes none):\n";
  for (CommandGroup g : kGroups) {
    out += fmt::format("{}:\n", group_name(g));
    for (const CommandSpec& s : table.all()) {
      if (s.group != g) continue;
      std::string params;
      for (const ParamSpec& p : s.params)
        params += fmt::format("{}{}", params.empty() ? "" : ", ", p.name);
      std::string line = fmt::format("  {}  {:<{}}  {}", s.code, s.name, width, params);
      if (!runs_here(s)) line += "  [cannot run here]";
      while (!line.empty() && line.back() == ' ') line.pop_back();
      out += line + "\n";
    }
  }
  ctx.print(out);
}

// HN: Gantry has no support desk; say what a useful report holds.
void help_support(CommandContext& ctx, const CommandCall&) {
  ctx.print(fmt::format(
      "Gantry is not ShopBot software: ShopBot Technical Support does not support it, and "
      "Gantry has no support desk that this command could send a request to.\n"
      "A useful problem report to Gantry's maintainers holds:\n"
      "  - the version (HA, or `gantry --version`) and the machine profile (--settings);\n"
      "  - the part file, and what `gantry check FILE` prints for it;\n"
      "  - the report of `gantry run FILE --json` (the card's counts and any fault).\n"
      "For a ShopBot machine's own hardware, ShopBot is at {}\n",
      kShopBotSite));
}

// HQ: the first few files at the machine.
void help_quick_start(CommandContext& ctx, const CommandCall&) {
  ctx.print(
      "Quick start:\n"
      "  1. Read a file without moving anything: `gantry check FILE.sbp` reports every "
      "error with its line and column.\n"
      "  2. See what it will do: `gantry moves FILE.sbp` lists the moves, `gantry estimate "
      "FILE.sbp` the time they take.\n"
      "  3. Set up the tool: move it where the part starts, zero X and Y there (Z2) and Z on "
      "the material (ZZ); set the cutting and jog speeds with MS and JS.\n"
      "  4. Cut: `gantry run FILE.sbp` checks the whole file again first; a file with an "
      "error never moves the machine.\n"
      "More in README.md (the gantry command) and docs/language.md (part files).\n");
}

// HR: one line per command, to find a code.
void help_quick_reference(CommandContext& ctx, const CommandCall&) {
  ctx.print(command_list(CommandTable::standard()));
}

// HT: where to look when something goes wrong.
void help_troubleshooting(CommandContext& ctx, const CommandCall&) {
  ctx.print(
      "Troubleshooting:\n"
      "  - Every error names FILE:LINE:COLUMN and what to change; `gantry check FILE` lists "
      "all of a file's errors at once.\n"
      "  - A move outside the soft limits: the limits are min and max in [axes.*] of the "
      "machine profile (docs/settings.md); check where 0 was set (ZX, Z2, Z3, ...).\n"
      "  - A profile that does not load: every bad key is reported with its line and the "
      "allowed range (docs/settings.md).\n"
      "  - The card stopped by itself (E-stop, a limit switch, an underrun): the run's "
      "report says why in `fault`, and where the tool stopped (docs/hardware.md).\n"
      "  - Wiring and timing of a real card: docs/hardware.md, \"Setting up a real card\".\n"
      "Upkeep of the machine itself (lubrication, belts, spindle) is in its maker's "
      "manual.\n");
}

// HU: the documentation, page by page.
void help_user_guide(CommandContext& ctx, const CommandCall&) {
  ctx.print(
      "Gantry's documentation (in its source tree):\n"
      "  README.md                 the gantry command: run, check, moves, estimate, help\n"
      "  docs/language.md          the part-file language: values, expressions, statements\n"
      "  docs/commands.md          every command and its parameters\n"
      "  docs/system_variables.md  the system variables %(n)\n"
      "  docs/settings.md          the machine profile's keys\n"
      "  docs/hardware.md          step cards, pulse timing, wiring a real card\n"
      "  docs/planner.md           how speeds and corners are planned\n"
      "  docs/architecture.md      how Gantry is built\n");
}

// HW: ShopBot's website.
void help_website(CommandContext& ctx, const CommandCall&) {
  ctx.print(fmt::format("ShopBot Tools' website: {}\n", kShopBotSite));
}

}  // namespace

void add_help_commands(std::vector<CommandSpec>& out) {
  const auto H = CommandGroup::Help;
  out.push_back({"HA",
                 "Help: about",
                 H,
                 "Prints Gantry's version, the machine profile in use and how many commands "
                 "run.",
                 {},
                 help_about});
  out.push_back({"HB",
                 "Help: technical bulletins",
                 H,
                 "Prints the address of ShopBot's website, where ShopBot keeps its technical "
                 "bulletins. No browser is opened.",
                 {},
                 help_bulletins,
                 "the address of the bulletins' own page (the site's address is printed)"});
  out.push_back({"HC",
                 "Help: command reference",
                 H,
                 "Prints the contents of the command reference, group by group, and where the "
                 "full reference and the language pages are.",
                 {},
                 help_commands});
  out.push_back({"HE",
                 "Help: quick reference (parameters)",
                 H,
                 "Prints every command with its parameters in the order a part file gives "
                 "them, in columns, for writing part files.",
                 {},
                 help_parameters});
  out.push_back({"HN",
                 "Help: request for support",
                 H,
                 "Prints what a problem report should hold. Gantry is not ShopBot software and "
                 "sends no request anywhere.",
                 {},
                 help_support,
                 "sending a request (Gantry has no support desk; what to report is printed)"});
  out.push_back({"HQ",
                 "Help: quick start",
                 H,
                 "Prints the steps from a part file to a cut: check it, preview it, set up "
                 "the tool, run it.",
                 {},
                 help_quick_start});
  out.push_back({"HR",
                 "Help: quick reference",
                 H,
                 "Prints every command code with its name, group by group, marking those "
                 "that are partial or cannot run here.",
                 {},
                 help_quick_reference});
  out.push_back({"HT",
                 "Help: troubleshooting",
                 H,
                 "Prints where to look when a file, the profile or the card reports a problem.",
                 {},
                 help_troubleshooting,
                 "maintenance of the machine (its maker's manual covers it)"});
  out.push_back({"HU",
                 "Help: user guide",
                 H,
                 "Prints the pages of Gantry's documentation and what each covers.",
                 {},
                 help_user_guide});
  out.push_back({"HW",
                 "Help: ShopBot website",
                 H,
                 "Prints the address of ShopBot Tools' website. No browser is opened.",
                 {},
                 help_website});
}

}  // namespace gantry
