// The manual page in roff (man(7)): nothing in it is written twice.
#include "man_page.hpp"

#include <fmt/format.h>

#include "gantry/commands/command_table.hpp"  // the two-letter commands
#include "gantry/lang/statement_table.hpp"    // the keyword statements

namespace gantry {
namespace {

// Text as roff reads it: backslashes escaped, a line never starting with a control character,
// hyphens that are minus signs in options.
std::string roff(std::string_view text) {
  std::string out;
  bool line_start = true;
  for (char c : text) {
    if (line_start && (c == '.' || c == '\'')) out += "\\&";
    if (c == '\\') {
      out += "\\e";
    } else if (c == '-') {
      out += "\\-";
    } else {
      out += c;
    }
    line_start = c == '\n';
  }
  return out;
}

}  // namespace

std::string man_page(const CLI::App& app) {
  std::string out = fmt::format(
      ".TH GANTRY 1 \"\" \"gantry {}\" \"User Commands\"\n"
      ".SH NAME\ngantry \\- OpenSBP and G\\-code CNC router controller\n"
      ".SH SYNOPSIS\n.B gantry\n.I command\n[\n.I options\n]\n"
      ".SH DESCRIPTION\n{}\n",
      GANTRY_VERSION, roff(app.get_description()));
  out += ".SH COMMANDS\n";
  for (const CLI::App* sub : app.get_subcommands({})) {
    out += fmt::format(".SS {}\n{}\n", roff(sub->get_name()), roff(sub->get_description()));
    for (const CLI::Option* o : sub->get_options()) {
      if (o->get_name() == "--help") continue;
      out += fmt::format(".TP\n.B {}\n{}\n", roff(o->get_name(false, true)),
                         roff(o->get_description()));
    }
  }
  out += ".SH PART FILE COMMANDS\nThe two\\-letter OpenSBP commands; "
         "\\fBgantry help\\fR \\fICODE\\fR gives a command's parameters.\n";
  for (const CommandSpec& c : CommandTable::standard().all())
    out += fmt::format(".TP\n.B {}\n{}\n", roff(c.code), roff(c.name));
  out += ".SH STATEMENTS\n";
  for (const StatementSpec& s : statement_table())
    out += fmt::format(".TP\n.B {}\n{}\n", roff(s.word), roff(s.title));
  out +=
      ".SH FILES\n"
      ".TP\n.I ~/.config/gantry/\nthe values file, persistent $variables, your macros "
      "(\\fImacros/C<n>.sbp\\fR)\n"
      ".TP\n.I /usr/share/gantry/macros/\nthe custom cuts Gantry ships (C2, C3, C6, C7, C9)\n"
      ".SH SEE ALSO\nThe documentation in /usr/share/doc/gantry and the project's docs/ folder.\n";
  return out;
}

}  // namespace gantry
