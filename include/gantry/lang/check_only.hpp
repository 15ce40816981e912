// The load pass's parse: every error found, no expression tree built.
#pragma once

#include <memory>
#include <string>
#include <string_view>

#include "gantry/lang/parser.hpp"  // LineParse

namespace gantry {

// While one lives on a thread, parse_expression checks expressions without building them: a
// good one gives a placeholder Expr (true, but its tree is one node, the number 0: never
// evaluate it). A pass that needs every error but no tree saves the tree's allocation and
// construction. Scopes nest.
class ExprCheckOnly {
 public:
  ExprCheckOnly();
  ~ExprCheckOnly();
  ExprCheckOnly(const ExprCheckOnly&) = delete;
  ExprCheckOnly& operator=(const ExprCheckOnly&) = delete;

 private:
  bool was_;
};

// parse_line for a pass that keeps no statement (a script's load pass): the same result,
// except that every expression in it is a placeholder (ExprCheckOnly), checked but not built.
LineParse check_line(std::string_view line, const std::shared_ptr<const std::string>& file,
                     int line_no);

}  // namespace gantry
