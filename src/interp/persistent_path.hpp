// Private helpers shared by the evaluator and the persistent-variable paths.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "gantry/interp/evaluator.hpp"  // EvalEnv, Accessor

namespace gantry {

// Evaluates `e` as a number (defined in evaluator.cpp): an undefined variable or text is an
// error located in `e`, as in arithmetic.
double evaluate_number(const Expr& e, EvalEnv& env);

// `$NAME.FIELD[3]` as written, indices evaluated, for messages. An index that cannot be
// evaluated shows as `[?]`.
std::string describe_path(std::string_view name, const std::vector<Accessor>& path, EvalEnv& env);

}  // namespace gantry
