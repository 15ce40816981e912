// Whether the fast reading of a simple command line equals the general parser's, field by
// field. Shared by the unit tests and the fuzz target.
#pragma once

#include <cstring>  // memcmp: -0 and 0 differ
#include <string>
#include <variant>

#include "gantry/lang/parser.hpp"  // LineParse, Statement

namespace gantry::testing {

inline bool same_loc(const SourceLoc& a, const SourceLoc& b) {
  return a.file == b.file && a.line == b.line && a.column == b.column;
}

// Empty when `fast` (from parse_simple_command) equals `general` (from parse_line); otherwise
// what differs.
inline std::string simple_command_mismatch(const Statement& fast, const LineParse& general) {
  if (general.error) return "the general parser found an error: " + general.error->message;
  if (!general.statement) return "the general parser found no statement";
  const auto* g = std::get_if<CommandStmt>(&general.statement->body);
  const auto* f = std::get_if<CommandStmt>(&fast.body);
  if (!g || !f) return "not both commands";
  if (!same_loc(fast.loc, general.statement->loc)) return "statement location";
  if (g->code != f->code) return "code " + f->code + " vs " + g->code;
  if (g->args.size() != f->args.size()) return "parameter count";
  for (size_t i = 0; i < g->args.size(); ++i) {
    const Arg &x = f->args[i], &y = g->args[i];
    const std::string which = "parameter " + std::to_string(i + 1) + ": ";
    if (x.text != y.text) return which + "text '" + x.text + "' vs '" + y.text + "'";
    if (!same_loc(x.loc, y.loc)) return which + "location";
    if (x.number.has_value() != y.number.has_value()) return which + "number or not";
    if (x.number && std::memcmp(&*x.number, &*y.number, sizeof(double)) != 0)
      return which + "value";
    if (x.expr || y.expr || x.expr_error || y.expr_error) return which + "expression parts";
  }
  return {};
}

}  // namespace gantry::testing
