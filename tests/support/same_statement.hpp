// Whether the fast readings of a line (a simple command, a common statement) equal the general
// parser's, field by field. Shared by the unit tests and the fuzz target.
#pragma once

#include <cstring>  // memcmp: -0 and 0 differ
#include <string>
#include <variant>

#include "gantry/lang/expr_node.hpp"  // ExprNode: trees compared node by node
#include "gantry/lang/parser.hpp"     // LineParse, Statement

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

// Empty when the trees are the same, node by node (locations, texts, numbers bit for bit).
inline std::string expr_mismatch(const ExprNode* x, const ExprNode* y) {
  if (!x || !y) return x == y ? "" : "one tree is missing";
  if (x->op != y->op) return "node kind";
  if (x->fn != y->fn || x->argc != y->argc) return "call";
  if (x->col != y->col || x->start != y->start) return "node columns";
  if (std::memcmp(&x->number, &y->number, sizeof(double)) != 0) return "number";
  if (x->text != y->text || x->spelling != y->spelling) return "node text";
  if ((x->path == nullptr) != (y->path == nullptr)) return "accessors";
  if (!same_loc(x->tree->at, y->tree->at)) return "tree location";
  for (const auto& [a, b] : {std::pair{x->a, y->a}, std::pair{x->b, y->b}})
    if (std::string why = expr_mismatch(a, b); !why.empty()) return why;
  for (int i = 0; i < x->argc; ++i)
    if (std::string why = expr_mismatch(x->args[i], y->args[i]); !why.empty()) return why;
  return {};
}

inline std::string arg_mismatch(const Arg& x, const Arg& y) {
  if (x.text != y.text) return "text '" + x.text + "' vs '" + y.text + "'";
  if (!same_loc(x.loc, y.loc)) return "location";
  if (x.number.has_value() != y.number.has_value()) return "number or not";
  if (x.number && std::memcmp(&*x.number, &*y.number, sizeof(double)) != 0) return "value";
  if (x.expr.has_value() != y.expr.has_value()) return "expression or not";
  if (x.expr) return expr_mismatch(x.expr->root(), y.expr->root());
  if (x.expr_error || y.expr_error) return "expression error";
  return {};
}

// Empty when `fast` equals `general` for the kinds parse_common_statement gives (and
// commands); otherwise what differs.
inline std::string statement_mismatch(const Statement& fast, const Statement& general) {
  if (!same_loc(fast.loc, general.loc)) return "statement location";
  if (fast.body.index() != general.body.index()) return "statement kind";
  if (const auto* f = std::get_if<LabelStmt>(&fast.body))
    return f->name == std::get<LabelStmt>(general.body).name ? "" : "label name";
  if (std::holds_alternative<ReturnStmt>(fast.body)) return {};
  if (const auto* f = std::get_if<JumpStmt>(&fast.body)) {
    const auto& g = std::get<JumpStmt>(general.body);
    if (f->label != g.label) return "jump label " + f->label + " vs " + g.label;
    if (f->gosub != g.gosub) return "GOTO or GOSUB";
    return same_loc(f->label_loc, g.label_loc) ? "" : "jump label location";
  }
  if (const auto* f = std::get_if<AssignStmt>(&fast.body)) {
    const auto& g = std::get<AssignStmt>(general.body);
    if (f->target.persistent != g.target.persistent || f->target.name != g.target.name ||
        !f->target.path.empty() || !g.target.path.empty())
      return "assignment target";
    if (!same_loc(f->target.loc, g.target.loc)) return "assignment target location";
    if (f->weak != g.weak) return "weak assignment";
    if (std::string why = arg_mismatch(f->value, g.value); !why.empty()) return "value: " + why;
    return {};
  }
  if (const auto* f = std::get_if<IfStmt>(&fast.body)) {
    const auto& g = std::get<IfStmt>(general.body);
    if (std::string why = expr_mismatch(f->test.root(), g.test.root()); !why.empty())
      return "IF test: " + why;
    if (!f->action || !g.action) return "IF action missing";
    if (std::string why = statement_mismatch(*f->action, *g.action); !why.empty())
      return "IF action: " + why;
    return {};
  }
  if (const auto* f = std::get_if<CommandStmt>(&fast.body)) {
    const auto& g = std::get<CommandStmt>(general.body);
    if (f->code != g.code || f->args.size() != g.args.size()) return "command";
    for (size_t i = 0; i < f->args.size(); ++i)
      if (std::string why = arg_mismatch(f->args[i], g.args[i]); !why.empty())
        return "parameter " + std::to_string(i + 1) + ": " + why;
    return {};
  }
  return "a kind of statement the fast readers do not give";
}

// statement_mismatch against what parse_line gave.
inline std::string common_statement_mismatch(const Statement& fast, const LineParse& general) {
  if (general.error) return "the general parser found an error: " + general.error->message;
  if (!general.statement) return "the general parser found no statement";
  return statement_mismatch(fast, *general.statement);
}

}  // namespace gantry::testing
