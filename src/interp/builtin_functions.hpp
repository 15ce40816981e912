// The built-in functions of expressions (ABS ... FLOOR): their values and domain errors.
#pragma once

#include "gantry/lang/expr_node.hpp"  // ExprNode

namespace gantry {

// Applies `call.fn` to the already evaluated `args[0 .. call.argc)`. Angles are degrees when
// `degrees`, else radians. Domain errors are located at the offending argument.
double apply_function(const ExprNode& call, const double* args, bool degrees);

// Whether `f` works with angles, so the caller knows to ask which unit is in force.
bool uses_angles(ExprFunc f);

}  // namespace gantry
