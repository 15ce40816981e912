// Evaluating expression trees: arithmetic, text, comparisons, logic, variables and calls.
#include "gantry/lang/number_literal.hpp"  // parse_number_literal
#include "gantry/interp/evaluator.hpp"

#include <fmt/format.h>  // messages

#include <algorithm>  // min, all_of
#include <climits>    // INT_MIN, INT_MAX
#include <cmath>

#include "gantry/lang/expr_node.hpp"
#include "builtin_functions.hpp"    // apply_function
#include "gantry/core/bounded.hpp"  // kMaxTextBytes
#include "persistent_path.hpp"      // describe_path

#include "gantry/core/text.hpp"  // upper

namespace gantry {

namespace {

constexpr double kTrue = -1.0;  // the handbook's truth values (002:L299)
constexpr double kFalse = 0.0;

using ascii::upper;

// Ordinal comparison of the upper-cased texts: strings compare without regard to case
// (handbook 002:L164), whatever case they are stored in.
int compare_text(std::string_view a, std::string_view b) {
  const size_t n = std::min(a.size(), b.size());
  for (size_t i = 0; i < n; ++i) {
    const auto x = static_cast<unsigned char>(upper(a[i]));
    const auto y = static_cast<unsigned char>(upper(b[i]));
    if (x != y) return x < y ? -1 : 1;
  }
  return a.size() == b.size() ? 0 : (a.size() < b.size() ? -1 : 1);
}

// `sign` is <0, 0 or >0 as left compares to right.
bool holds(ExprOp op, int sign) {
  switch (op) {
    case ExprOp::Eq:
      return sign == 0;
    case ExprOp::Ne:
      return sign != 0;
    case ExprOp::Lt:
      return sign < 0;
    case ExprOp::Gt:
      return sign > 0;
    case ExprOp::Le:
      return sign <= 0;
    default:
      return sign >= 0;  // Ge
  }
}

bool holds(ExprOp op, double x, double y) {
  switch (op) {
    case ExprOp::Eq:
      return x == y;  // exact, as the handbook warns (002:L162)
    case ExprOp::Ne:
      return x != y;
    case ExprOp::Lt:
      return x < y;
    case ExprOp::Gt:
      return x > y;
    case ExprOp::Le:
      return x <= y;
    default:
      return x >= y;  // Ge
  }
}

// Nodes whose value is always a number, so a comparison of two of them needs no Value.
bool numeric_result(const ExprNode& n) {
  switch (n.op) {
    case ExprOp::Text:
    case ExprOp::UserVar:
    case ExprOp::PersistVar:
    case ExprOp::SysVar:
    case ExprOp::Join:
      return false;
    default:
      return true;
  }
}

std::string_view op_text(ExprOp op) {
  switch (op) {
    case ExprOp::Add:
      return "+";
    case ExprOp::Sub:
      return "-";
    case ExprOp::Mul:
      return "*";
    case ExprOp::Div:
      return "/";
    case ExprOp::IntDiv:
      return "\\";
    case ExprOp::Mod:
      return "MOD";
    case ExprOp::Pow:
      return "^";
    default:
      return "?";
  }
}

class Evaluator {
 public:
  explicit Evaluator(EvalEnv& env) : env_(env) {}

  // The value of `n` as a number; text that is not a number literal is an error at `n`.
  double num(const ExprNode& n) {
    switch (n.op) {
      case ExprOp::Number:
        return n.number;
      case ExprOp::UserVar: {
        const Value* v = env_.user_variable(n.text);
        if (!v) undefined(n);
        if (v->is_number()) return v->num();
        if (std::optional<double> d = parse_number_literal(v->str())) return *d;
        return v->to_number(n.token_loc(), fmt::format("&{}", n.text));  // throws
      }
      case ExprOp::PersistVar: {
        const Value v = persistent(n);
        if (v.is_number()) return v.num();
        if (std::optional<double> d = parse_number_literal(v.str())) return *d;
        return v.to_number(n.token_loc(), describe_path(n.text, *n.path, env_));  // throws
      }
      case ExprOp::SysVar: {
        const int index = system_index(n);
        const Value v = env_.system_variable(index, n.token_loc());
        if (v.is_number()) return v.num();
        return v.to_number(n.token_loc(), fmt::format("%({})", index));
      }
      case ExprOp::Text:
      case ExprOp::Join:
        return val(n).to_number(n.start_loc());
      case ExprOp::Call:
        return call(n);
      case ExprOp::Neg:
        return -num(*n.a);
      case ExprOp::Pos:
        return num(*n.a);
      case ExprOp::Not:
        return truth(*n.a) ? kFalse : kTrue;
      case ExprOp::Add: {
        const double x = add_operand(*n.a);
        return finite(x + add_operand(*n.b), n);
      }
      case ExprOp::Sub: {
        const double x = num(*n.a);
        return finite(x - num(*n.b), n);
      }
      case ExprOp::Mul: {
        const double x = num(*n.a);
        return finite(x * num(*n.b), n);
      }
      case ExprOp::Div: {
        const double x = num(*n.a);
        const double y = num(*n.b);
        if (y == 0) fail(n.b->start_loc(), "division by zero");
        return finite(x / y, n);
      }
      case ExprOp::IntDiv: {  // BASIC's `\`, truncating toward zero (docs/language.md §3)
        const double x = num(*n.a);
        const double y = num(*n.b);
        if (y == 0) fail(n.b->start_loc(), "division by zero (the right side of \\ is 0)");
        return finite(std::trunc(x / y), n);
      }
      case ExprOp::Mod: {
        const double x = num(*n.a);
        const double y = num(*n.b);
        if (y == 0) fail(n.b->start_loc(), "division by zero (the right side of MOD is 0)");
        return floored_mod(x, y);
      }
      case ExprOp::Pow: {
        const double x = num(*n.a);
        return power(x, num(*n.b), n);
      }
      case ExprOp::And: {
        // Both sides are always evaluated (as in VB), so an error in either one shows on
        // every run, not only when the left side happens to decide the result.
        const bool x = truth(*n.a);
        const bool y = truth(*n.b);
        return x && y ? kTrue : kFalse;
      }
      case ExprOp::Or: {
        const bool x = truth(*n.a);
        const bool y = truth(*n.b);
        return x || y ? kTrue : kFalse;
      }
      case ExprOp::Eq:
      case ExprOp::Ne:
      case ExprOp::Lt:
      case ExprOp::Gt:
      case ExprOp::Le:
      case ExprOp::Ge:
        return compare(n) ? kTrue : kFalse;
    }
    return 0;  // unreachable: every op is handled above
  }

  Value val(const ExprNode& n) {
    switch (n.op) {
      case ExprOp::Text:
        return Value::string(std::string(n.text));
      case ExprOp::UserVar: {
        // An undefined variable is the text of its own name (spec §3.5), as the handbook's
        // PRINT shows it.
        const Value* v = env_.user_variable(n.text);
        return v ? *v : Value::string(std::string(n.spelling));
      }
      case ExprOp::PersistVar:
        return persistent(n);
      case ExprOp::SysVar: {
        const int index = system_index(n);
        return env_.system_variable(index, n.token_loc());
      }
      case ExprOp::Join: {
        std::string s;
        append(n, s);
        return Value::string(bounded_text(std::move(s), n));
      }
      case ExprOp::Add:
        if (env_.plus_joins_text()) return plus(n);
        return Value::number(num(n));
      default:
        return Value::number(num(n));
    }
  }

  // FabMo's `+`: text that is not a number on either side makes the sum the two joined
  // (its macros write DIALOG "Offset: " + $z); numbers, and text that reads as one, add.
  Value plus(const ExprNode& n) {
    const Value a = val(*n.a);
    const Value b = val(*n.b);
    const auto text = [](const Value& v) {
      return v.is_string() && !parse_number_literal(v.str());
    };
    if (text(a) || text(b)) return Value::string(bounded_text(a.to_string() + b.to_string(), n));
    const auto number = [](const Value& v) {
      return v.is_number() ? v.num() : *parse_number_literal(v.str());
    };
    return Value::number(finite(number(a) + number(b), n));
  }

 private:
  // Appends the text of `n`; a chain of joins builds one string instead of one per `&`.
  void append(const ExprNode& n, std::string& out) {
    switch (n.op) {
      case ExprOp::Join:
        append(*n.a, out);
        append(*n.b, out);
        return;
      case ExprOp::Text:
        out += n.text;
        return;
      case ExprOp::UserVar: {
        const Value* v = env_.user_variable(n.text);
        if (!v)
          out += n.spelling;
        else if (v->is_string())
          out += v->str();
        else
          out += format_number(v->num());
        return;
      }
      default:
        out += val(n).to_string();
    }
  }

  [[noreturn]] void undefined(const ExprNode& n) {
    fail(n.token_loc(), fmt::format("undefined variable &{}", n.text));
  }

  // `+` on text is a common slip for `&`: say so.
  double add_operand(const ExprNode& n) {
    if (n.op != ExprOp::Text && n.op != ExprOp::Join) return num(n);
    const Value v = val(n);
    if (std::optional<double> d = parse_number_literal(v.str())) return *d;
    try {
      return v.to_number(n.start_loc());
    } catch (const GantryError& e) {
      Diagnostic d = e.diagnostic();
      d.message += "; to join text use & instead of +";
      throw GantryError(std::move(d));
    }
  }

  bool truth(const ExprNode& n) { return num(n) != 0; }

  // Joined text is bounded, as numbers are: `&s = &s & &s` in a loop doubles it each pass.
  std::string bounded_text(std::string s, const ExprNode& n) {
    if (s.size() > kMaxTextBytes)
      fail(n.token_loc(), fmt::format("this text would be {} bytes long; a value holds at most "
                                      "{} bytes (1 MiB)",
                                      s.size(), kMaxTextBytes));
    return s;
  }

  double finite(double r, const ExprNode& n) {
    if (!std::isfinite(r))
      fail(n.token_loc(), fmt::format("the result of {} is too large for a number", op_text(n.op)));
    return r;
  }

  // The remainder takes the sign of the divisor (floored division), so that
  // x = INT(x / y) * y + (x MOD y) holds with INT = floor, and `&i MOD 2` is 0 or 1 even for
  // negative &i. -7 MOD 3 = 2; 7 MOD -3 = -2; 7.5 MOD 2 = 1.5.
  static double floored_mod(double x, double y) {
    double r = std::fmod(x, y);
    if (r != 0 && ((r < 0) != (y < 0))) r += y;
    return r == 0 ? 0.0 : r;  // no -0
  }

  double power(double x, double y, const ExprNode& n) {
    if (x == 0 && y < 0) fail(n.b->start_loc(), "division by zero: 0 raised to a negative power");
    const double r = std::pow(x, y);
    if (std::isnan(r))
      fail(n.token_loc(), fmt::format("{} ^ {} has no real value: a negative number has no "
                                      "fractional power",
                                      format_number(x), format_number(y)));
    return finite(r, n);
  }

  double call(const ExprNode& n) {
    double args[kMaxCallArgs];
    for (int i = 0; i < n.argc; ++i) args[i] = num(*n.args[i]);
    return apply_function(n, args, uses_angles(n.fn) && env_.trig_in_degrees());
  }

  Value persistent(const ExprNode& n) {
    const nlohmann::json* root = env_.persistent_variable(n.text);
    if (!root)
      fail(n.token_loc(),
           fmt::format("undefined persistent variable ${0}; set it first (${0} := value keeps an "
                       "existing value). FabMo machines define such variables in their "
                       "configuration, which Gantry does not read",
                       n.text));
    return read_path(*root, *n.path, env_, n.token_loc(), n.text);
  }

  int system_index(const ExprNode& n) {
    const double d = num(*n.a);
    if (d != std::trunc(d))
      fail(n.a->start_loc(), fmt::format("a system variable number must be a whole number, not {}",
                                         format_number(d)));
    if (d < INT_MIN || d > INT_MAX)
      fail(n.a->start_loc(), fmt::format("there is no system variable %({})", format_number(d)));
    return static_cast<int>(d);
  }

  // Two numbers compare as numbers, two texts as texts without regard to case; a number
  // and a text compare as numbers when the text is a number literal, else as texts (spec
  // §4.5). An undefined variable compared with a number is an error (spec §3.5): its
  // stand-in text would make the test silently false.
  bool compare(const ExprNode& n) {
    if (numeric_result(*n.a) && numeric_result(*n.b)) {
      const double x = num(*n.a);
      return holds(n.op, x, num(*n.b));
    }
    const Value x = val(*n.a);
    const Value y = val(*n.b);
    if (x.is_number() && y.is_number()) return holds(n.op, x.num(), y.num());
    if (x.is_string() && y.is_string()) return holds(n.op, compare_text(x.str(), y.str()));
    const bool text_left = x.is_string();
    const Value& text = text_left ? x : y;
    if (std::optional<double> d = parse_number_literal(text.str()))
      return text_left ? holds(n.op, *d, y.num()) : holds(n.op, x.num(), *d);
    const ExprNode& text_node = text_left ? *n.a : *n.b;
    if (text_node.op == ExprOp::UserVar && !env_.user_variable(text_node.text))
      undefined(text_node);
    return holds(n.op, compare_text(x.to_string(), y.to_string()));
  }

  EvalEnv& env_;
};

}  // namespace

Value evaluate(const Expr& e, EvalEnv& env) {
  if (!e) fail(SourceLoc{}, "expected an expression");
  return Evaluator(env).val(*e.root());
}

double evaluate_number(const Expr& e, EvalEnv& env) {
  if (!e) fail(SourceLoc{}, "expected an expression");
  return Evaluator(env).num(*e.root());
}

bool is_true(const Value& v, const SourceLoc& loc) {
  if (v.is_number()) return v.num() != 0;
  if (std::optional<double> d = parse_number_literal(v.str())) return *d != 0;
  // An undefined &variable reads as its own name.
  const std::string& t = v.str();
  if (t.size() > 1 && t[0] == '&' && std::all_of(t.begin() + 1, t.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
      }))
    fail(loc,
         fmt::format("undefined variable &{}; set it before this line", ascii::upper(t.substr(1))));
  fail(loc, "IF needs a number or a comparison");
}

}  // namespace gantry
