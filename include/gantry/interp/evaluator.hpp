// Evaluating expressions against the interpreter's variables and the machine.
#pragma once

#include <nlohmann/json.hpp>  // composite persistent values

#include <optional>  // the unit placeholder

#include "gantry/interp/value.hpp"     // Value
#include "gantry/lang/expression.hpp"  // Expr, LValue

namespace gantry {

// What an expression can read. The interpreter implements it.
class EvalEnv {
 public:
  virtual ~EvalEnv() = default;
  // A user variable (`&NAME`, name upper case without `&`), or null when undefined.
  virtual const Value* user_variable(std::string_view name) const = 0;
  // A persistent variable (`$NAME`): its stored JSON value, or null when undefined.
  virtual const nlohmann::json* persistent_variable(std::string_view name) const = 0;
  // System variable %(n); errors (unknown n) are thrown located at `loc`.
  virtual Value system_variable(int n, const SourceLoc& loc) = 0;
  // Trigonometry in degrees (dialect = "fabmo") rather than radians (SB3).
  virtual bool trig_in_degrees() const = 0;
  // `+` with text on either side joins, as in FabMo's JavaScript runtime (dialect = "fabmo").
  virtual bool plus_joins_text() const { return false; }
};

// Evaluates `e`; throws GantryError located at the failing part of the expression.
Value evaluate(const Expr& e, EvalEnv& env);

// The truth of a value as IF uses it: a number is true when non-zero.
bool is_true(const Value& v, const SourceLoc& loc);

// Stores `v` at `place` inside `root` (the persistent variable's JSON, created as needed:
// fields make objects, indices make arrays). Index expressions are evaluated with `env`; an
// empty index `[]` stands for `placeholder` (FabMo's unit index), and is an error without.
void assign_path(nlohmann::json& root, const std::vector<Accessor>& path, const Value& v,
                 EvalEnv& env, const SourceLoc& loc,
                 std::optional<size_t> placeholder = std::nullopt);

// Reads the value at `path` inside `root`; a composite or missing element is an error.
Value read_path(const nlohmann::json& root, const std::vector<Accessor>& path, EvalEnv& env,
                const SourceLoc& loc, std::string_view name,
                std::optional<size_t> placeholder = std::nullopt);

}  // namespace gantry
