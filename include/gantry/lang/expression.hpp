// Expressions of the part-file language: syntax trees and their parser.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "gantry/core/diagnostic.hpp"  // SourceLoc, Diagnostic

namespace gantry {

struct ExprNode;  // defined in src/lang/expression.cpp (or a private header)

// A parsed expression. Cheap to move; copyable (shares its immutable tree).
class Expr {
 public:
  Expr() = default;
  explicit Expr(std::shared_ptr<const ExprNode> root) : root_(std::move(root)) {}
  const ExprNode* root() const { return root_.get(); }
  explicit operator bool() const { return root_ != nullptr; }

 private:
  std::shared_ptr<const ExprNode> root_;
};

// One step of a persistent-variable path: `.field` or `[index]` (`[]`: no index).
struct Accessor {
  bool is_field = false;
  std::string field;          // upper case, when is_field
  std::optional<Expr> index;  // when !is_field; empty for `[]`
};

// An assignable place: `&name` or `$name` with accessors (`$x[&u].z`).
struct LValue {
  bool persistent = false;  // `$` (true) or `&` (false)
  std::string name;         // upper case, without the sigil
  std::vector<Accessor> path;
  SourceLoc loc;
};

struct ExprParse {
  std::optional<Expr> expr;         // set when the whole text is one expression
  std::optional<Diagnostic> error;  // otherwise: what is wrong and where
};

// Parses `text` as exactly one expression (leading/trailing spaces allowed). `at` is the
// location of text[0]; error columns are computed from it. With `bare_words`, unquoted
// words beside a comparison are text (`&answer = Cancel`), as in IF tests.
ExprParse parse_expression(std::string_view text, const SourceLoc& at, bool bare_words = false);

// Parses `text` as exactly one lvalue; nullopt with `error` set otherwise.
std::optional<LValue> parse_lvalue(std::string_view text, const SourceLoc& at,
                                   std::optional<Diagnostic>* error = nullptr);

}  // namespace gantry
