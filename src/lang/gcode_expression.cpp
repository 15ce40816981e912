// G-code expressions (docs/gcode.md, "Blocks"): compiled once when their line is read into
// postfix steps (GcodeStep), run on a small stack each time the block runs.
#include <fmt/format.h>  // messages

#include <cmath>  // math functions of expressions
#include <vector>

#include "gantry/lang/gcode.hpp"
#include "gantry/lang/wincnc.hpp"  // evaluate_wincnc_braces
#include "gcode_scan.hpp"          // numbers, function names

namespace gantry {
namespace {

using gcode_scan::function_at;
using gcode_scan::is_space;
using gcode_scan::read_unsigned;
using gcode_scan::word_at;
using Op = GcodeStep::Op;

// Brackets, signs, parameters and functions nested deeper than this are refused rather than
// risking the compiler's stack (about 33,000 `[` overflowed it), as OpenSBP expressions are.
constexpr int kMaxNesting = 200;

// LinuxCNC's numbered parameters a program may read.
constexpr double kLastParameter = 5602;

struct Function {
  std::string_view name;
  Op op;
};
constexpr Function kFunctionOps[] = {{"ABS", Op::Abs},     {"ACOS", Op::Acos}, {"ASIN", Op::Asin},
                                     {"ATAN", Op::Atan},   {"COS", Op::Cos},   {"EXP", Op::Exp},
                                     {"FIX", Op::Fix},     {"FUP", Op::Fup},   {"LN", Op::Ln},
                                     {"ROUND", Op::Round}, {"SIN", Op::Sin},   {"SQRT", Op::Sqrt},
                                     {"TAN", Op::Tan}};

struct Binary {
  std::string_view text;
  int prec;  // higher binds tighter
  Op op;
};
constexpr Binary kBinaries[] = {{"**", 5, Op::Pow},  {"*", 4, Op::Mul}, {"/", 4, Op::Div},
                                {"MOD", 4, Op::Mod}, {"+", 3, Op::Add}, {"-", 3, Op::Sub},
                                {"EQ", 2, Op::Eq},   {"NE", 2, Op::Ne}, {"GT", 2, Op::Gt},
                                {"GE", 2, Op::Ge},   {"LT", 2, Op::Lt}, {"LE", 2, Op::Le},
                                {"AND", 1, Op::And}, {"OR", 1, Op::Or}, {"XOR", 1, Op::Xor}};

std::string_view name_of(Op op) {
  for (const Function& f : kFunctionOps)
    if (f.op == op) return f.name;
  return "";
}

// A recursive-descent reader of the expression's text that emits its steps: each value's
// steps leave it on the stack, a binary operator's steps follow both its operands' steps.
class Compiler {
 public:
  Compiler(std::string_view s, const SourceLoc& at, GcodeBlock* b) : s_(s), at_(at), b_(b) {}

  GcodeCode whole() {
    GcodeCode c;
    c.begin = static_cast<std::uint32_t>(b_->steps.size());
    value();
    skip();
    if (i_ < s_.size()) error(i_, "unexpected text after the value");
    c.end = static_cast<std::uint32_t>(b_->steps.size());
    c.depth = static_cast<std::uint32_t>(max_depth_);
    return c;
  }

 private:
  [[noreturn]] void error(size_t i, const std::string& what) const {
    SourceLoc l = at_;
    l.column += static_cast<int>(i);
    fail(l, what);
  }
  void skip() {
    while (i_ < s_.size() && is_space(s_[i_])) ++i_;
  }
  void expect(char c, const char* what) {
    skip();
    if (i_ >= s_.size() || s_[i_] != c) error(i_, fmt::format("expected '{}' {}", c, what));
    ++i_;
  }
  // Appends a step; `pushes` is how it changes the stack's height.
  void emit(Op op, size_t at, int pushes, std::int32_t index = 0, double number = 0) {
    b_->steps.push_back({op, static_cast<std::uint32_t>(at), index, number});
    depth_ += pushes;
    if (depth_ > max_depth_) max_depth_ = depth_;
  }

  // A value: a number, [expression], #parameter, a function, each with an optional sign.
  // Every recursion passes through here, so one depth guard bounds the compiler's stack.
  void value() {
    skip();
    if (i_ >= s_.size()) error(i_, "expected a value: a number, [expression] or #parameter");
    const Nest nest(*this);
    const size_t at = i_;
    const char c = s_[i_];
    if (c == '-' || c == '+') {
      ++i_;
      value();
      if (c == '-') emit(Op::Neg, at, 0);
      return;
    }
    if (c == '[') {
      ++i_;
      binary(0);
      expect(']', "to close the expression");
      return;
    }
    if (c == '#') return parameter();
    double v = 0;
    if (const size_t e = read_unsigned(s_, i_, &v); e != i_) {
      i_ = e;
      return emit(Op::Number, at, 1, 0, v);
    }
    if (const std::string_view f = function_at(s_, i_); !f.empty()) return function(f);
    error(i_, "expected a value: a number, [expression], #parameter or a function such as SIN[x]");
  }

  void parameter() {
    const size_t at = i_++;
    skip();
    if (i_ < s_.size() && s_[i_] == '<') return emit(Op::Named, at, 1, name_index());
    const size_t first = b_->steps.size();
    value();
    // `#5`: the number is known now. Anything else (`##1`, `#[#1 + 1]`, `#-1`, `#1.5`) is read
    // and checked when the block runs, as LinuxCNC does.
    const GcodeStep& only = b_->steps.back();
    if (b_->steps.size() == first + 1 && only.op == Op::Number && only.number >= 1 &&
        only.number <= kLastParameter && only.number == std::round(only.number)) {
      const auto n = static_cast<std::int32_t>(only.number);
      b_->steps.pop_back();
      --depth_;
      return emit(Op::Param, at, 1, n);
    }
    emit(Op::ParamAt, at, 0);
  }

  std::int32_t name_index() {  // at '<'
    const size_t open = i_;
    const size_t close = s_.find('>', open);
    if (close == std::string_view::npos) error(open, "a parameter name opened with '<' needs '>'");
    std::string name;
    for (size_t k = open + 1; k < close; ++k)
      if (!is_space(s_[k]))
        name += static_cast<char>(std::tolower(static_cast<unsigned char>(s_[k])));
    if (name.empty()) error(open, "the parameter name between < and > is empty");
    i_ = close + 1;
    b_->names.push_back(std::move(name));
    return static_cast<std::int32_t>(b_->names.size()) - 1;
  }

  void function(std::string_view f) {
    const size_t at = i_;
    i_ += f.size();
    if (f == "EXISTS") {
      expect('[', "after EXISTS");
      skip();
      if (i_ >= s_.size() || s_[i_] != '#')
        error(i_, "EXISTS takes a named parameter: EXISTS[#<name>]");
      ++i_;
      skip();
      if (i_ >= s_.size() || s_[i_] != '<')
        error(i_, "EXISTS takes a named parameter: EXISTS[#<name>]");
      emit(Op::Exists, at, 1, name_index());
      expect(']', "to close EXISTS[...]");
      return;
    }
    expect('[', "after the function name");
    binary(0);
    expect(']', "to close the function's argument");
    Op op = Op::Abs;
    for (const Function& fn : kFunctionOps)
      if (fn.name == f) op = fn.op;
    if (op == Op::Atan) {  // ATAN[y]/[x], in degrees
      expect('/', "in ATAN[y]/[x]");
      expect('[', "in ATAN[y]/[x]");
      binary(0);
      expect(']', "in ATAN[y]/[x]");
      return emit(Op::Atan, at, -1);
    }
    emit(op, at, 0);
  }

  // The binary operator at i_, or null when none.
  const Binary* op_at() {
    skip();
    if (i_ >= s_.size()) return nullptr;
    // Most values end at ']': no operator starts with any other character than these.
    if (std::string_view("*/+-MmEeNnGgLlAaOoXx").find(s_[i_]) == std::string_view::npos)
      return nullptr;
    for (const Binary& o : kBinaries)
      if (word_at(s_, i_, o.text)) return &o;
    return nullptr;
  }

  void binary(int min_prec) {
    value();
    while (true) {
      const Binary* op = op_at();
      if (!op || op->prec < min_prec) return;
      const size_t at = i_;
      i_ += op->text.size();
      binary(op->prec + 1);  // left-associative
      emit(op->op, at, -1);
    }
  }

  struct Nest {
    explicit Nest(Compiler& c) : c_(c) {
      if (++c_.nesting_ > kMaxNesting)
        c_.error(c_.i_, fmt::format("this expression is nested more than {} deep; split it using "
                                    "parameters (#1 = [...])",
                                    kMaxNesting));
    }
    ~Nest() { --c_.nesting_; }
    Compiler& c_;
  };

  std::string_view s_;
  size_t i_ = 0;
  int nesting_ = 0;
  int depth_ = 0, max_depth_ = 0;
  SourceLoc at_;
  GcodeBlock* b_;
};

}  // namespace

int add_gcode_expression(GcodeBlock* b, std::string_view text, const SourceLoc& at) {
  if (!text.empty() && text[0] == '{') {  // WinCNC's substitution: its syntax now, kept as text
    evaluate_wincnc_braces(text, at, nullptr);
    b->codes.push_back({});
  } else {
    const size_t steps = b->steps.size(), names = b->names.size();
    try {
      b->codes.push_back(Compiler(text, at, b).whole());
    } catch (...) {  // the block stays as it was
      b->steps.resize(steps);
      b->names.resize(names);
      throw;
    }
  }
  b->exprs.emplace_back(text);
  b->exprs_column.push_back(at.column);
  return static_cast<int>(b->exprs.size()) - 1;
}

double evaluate_gcode_expression(const GcodeBlock& b, int expr, const SourceLoc& line,
                                 const GcodeParameters& params) {
  const GcodeCode& code = b.codes[static_cast<size_t>(expr)];
  // Most expressions stack a handful of values; deeper ones get the heap.
  constexpr std::uint32_t kOnStack = 32;
  double small[kOnStack];
  std::vector<double> large;
  if (code.depth > kOnStack) large.resize(code.depth);
  double* const stack = code.depth > kOnStack ? large.data() : small;
  double* top = stack;  // past the last value pushed
  // A step's location, made only when needed (a SourceLoc copy costs an atomic increment).
  auto located = [&](const GcodeStep& s) {
    SourceLoc l = line;
    l.column = b.exprs_column[static_cast<size_t>(expr)] + static_cast<int>(s.offset);
    return l;
  };
  auto error = [&](const GcodeStep& s, const std::string& what) { fail(located(s), what); };
  // #n: a machine parameter (above #5000) is given its reader's location, in case it cannot
  // be read now; the others never need one.
  auto parameter = [&](const GcodeStep& s, int n) {
    if (n <= 5000) return params.numbered(n, &line);
    const SourceLoc at = located(s);
    return params.numbered(n, &at);
  };
  auto domain = [&](const GcodeStep& s, bool ok) {
    if (!ok) error(s, fmt::format("{}[{}] is not defined", name_of(s.op), top[-1]));
  };
  constexpr double deg = M_PI / 180;
  for (std::uint32_t i = code.begin; i < code.end; ++i) {
    const GcodeStep& s = b.steps[i];
    if (s.op >= Op::Atan) {  // the two-value steps
      const double y = *--top;
      double& x = top[-1];
      switch (s.op) {
        case Op::Atan:
          x = std::atan2(x, y) / deg;
          break;
        case Op::Pow:
          x = std::pow(x, y);
          break;
        case Op::Mul:
          x *= y;
          break;
        case Op::Div:
          if (y == 0) error(s, "division by zero");
          x /= y;
          break;
        case Op::Mod: {
          if (y == 0) error(s, "MOD by zero");
          const double r = std::fmod(x, y);
          x = r < 0 ? r + std::abs(y) : r;
          break;
        }
        case Op::Add:
          x += y;
          break;
        case Op::Sub:
          x -= y;
          break;
        // EQ and NE count values within 0.0001 as equal, as LinuxCNC does ([0.1 + 0.2 EQ 0.3]
        // is 1); GT, GE, LT and LE compare exactly there too.
        case Op::Eq:
          x = std::abs(x - y) < 0.0001;
          break;
        case Op::Ne:
          x = !(std::abs(x - y) < 0.0001);
          break;
        case Op::Gt:
          x = x > y;
          break;
        case Op::Ge:
          x = x >= y;
          break;
        case Op::Lt:
          x = x < y;
          break;
        case Op::Le:
          x = x <= y;
          break;
        case Op::And:
          x = x != 0 && y != 0;
          break;
        case Op::Or:
          x = x != 0 || y != 0;
          break;
        default:
          x = (x != 0) != (y != 0);
          break;  // XOR
      }
      continue;
    }
    switch (s.op) {
      case Op::Number:
        *top++ = s.number;
        break;
      case Op::Param:
        *top++ = parameter(s, s.index);
        break;
      case Op::ParamAt: {
        const double n = top[-1];
        if (n != std::round(n) || n < 1 || n > kLastParameter)
          error(s, fmt::format("#{} is not a parameter: parameters are #1 to #5602", n));
        top[-1] = parameter(s, static_cast<int>(n));
        break;
      }
      case Op::Named: {
        const std::string& name = b.names[static_cast<size_t>(s.index)];
        const double* v = params.named(name);
        if (!v)
          error(s, fmt::format("#<{}> has no value yet; set it first, as #<{}> = 1", name, name));
        *top++ = *v;
        break;
      }
      case Op::Exists:
        *top++ = params.named(b.names[static_cast<size_t>(s.index)]) ? 1 : 0;
        break;
      case Op::Neg:
        top[-1] = -top[-1];
        break;
      case Op::Abs:
        top[-1] = std::abs(top[-1]);
        break;
      case Op::Acos:
        domain(s, top[-1] >= -1 && top[-1] <= 1), top[-1] = std::acos(top[-1]) / deg;
        break;
      case Op::Asin:
        domain(s, top[-1] >= -1 && top[-1] <= 1), top[-1] = std::asin(top[-1]) / deg;
        break;
      case Op::Cos:
        top[-1] = std::cos(top[-1] * deg);
        break;
      case Op::Exp:
        top[-1] = std::exp(top[-1]);
        break;
      case Op::Fix:
        top[-1] = std::floor(top[-1]);
        break;
      case Op::Fup:
        top[-1] = std::ceil(top[-1]);
        break;
      case Op::Ln:
        domain(s, top[-1] > 0), top[-1] = std::log(top[-1]);
        break;
      case Op::Round:
        top[-1] = std::round(top[-1]);
        break;
      case Op::Sin:
        top[-1] = std::sin(top[-1] * deg);
        break;
      case Op::Sqrt:
        domain(s, top[-1] >= 0), top[-1] = std::sqrt(top[-1]);
        break;
      default:
        top[-1] = std::tan(top[-1] * deg);
        break;  // TAN
    }
  }
  return top[-1];
}

}  // namespace gantry
