// G-code expressions compiled to steps (src/lang/gcode_expression.cpp): values as LinuxCNC
// 2.9's rs274 computes them (each expected value below was printed by rs274 with
// (DEBUG, #2) after #2 = the expression, #1 = 3 and #<d> = 0.5), and errors at their column.
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "gantry/lang/gcode.hpp"

namespace gantry {
namespace {

class Params : public GcodeParameters {
 public:
  double numbered(int n, const SourceLoc*) const override {
    auto it = numbered_.find(n);
    return it == numbered_.end() ? 0 : it->second;
  }
  const double* named(std::string_view name) const override {
    auto it = named_.find(std::string(name));
    return it == named_.end() ? nullptr : &it->second;
  }
  std::map<int, double> numbered_{{1, 3}};
  std::map<std::string, double> named_{{"d", 0.5}};
};

const auto kFile = std::make_shared<const std::string>("t.ngc");

// The value of `text` written at column 7 of line 4, as `#2 = text` would give it.
double value(const std::string& text, const Params& p = Params()) {
  GcodeBlock b;
  const int e = add_gcode_expression(&b, text, SourceLoc{kFile, 4, 7});
  return evaluate_gcode_expression(b, e, SourceLoc{kFile, 4, 1}, p);
}

// The error `text` gives when it runs (or when it is compiled): "column: message".
std::string error(const std::string& text, const Params& p = Params()) {
  try {
    value(text, p);
  } catch (const GantryError& e) {
    return std::to_string(e.diagnostic().loc.column) + ": " + e.diagnostic().message;
  }
  return "no error";
}

TEST(GcodeExpression, ValuesAsRs274ComputesThem) {
  const std::pair<const char*, double> cases[] = {
      {"[1 + 2 * 3 ** 2]", 19},
      {"[-7 MOD 3]", 2},
      {"[7 MOD -3]", 1},
      {"[ATAN[1]/[-1]]", 135},
      {"[##1 + #<d> * 4]", 2},  // ##1 is #3, never set: 0
      {"[0.1 + 0.2 EQ 0.3]", 1},
      {"[1 - 2 - 3]", -4},
      {"[2 ** 3 ** 2]", 64},  // left to right
      {"[EXISTS[#<d>] + EXISTS[#<nope>] * 10]", 1},
      {"[FIX[-2.5] + FUP[-2.5] * 10 + ROUND[2.5] * 100]", 277},
      {"[1 OR 0 AND 0]", 0},  // one precedence, left to right
      {"[-SQRT[16] + ABS[-3] - -1]", 0},
      {"[3 GT 2 + 1]", 0},
  };
  for (const auto& [text, expected] : cases) EXPECT_DOUBLE_EQ(value(text), expected) << text;
}

TEST(GcodeExpression, ReadsParametersWhenItRunsNotWhenCompiled) {
  GcodeBlock b;
  const int e = add_gcode_expression(&b, "[#1 * #<d>]", SourceLoc{kFile, 1, 1});
  Params p;
  const SourceLoc line{kFile, 1, 1};
  EXPECT_DOUBLE_EQ(evaluate_gcode_expression(b, e, line, p), 1.5);
  p.numbered_[1] = 10;
  p.named_["d"] = 2;
  EXPECT_DOUBLE_EQ(evaluate_gcode_expression(b, e, line, p), 20);
}

TEST(GcodeExpression, DeepExpressionsStackOnTheHeap) {
  // 100 values stacked at once (more than the evaluator keeps on its own stack).
  std::string text = "1";
  for (int i = 0; i < 99; ++i) text = "[1 + " + text + "]";
  std::string right = "1";
  for (int i = 0; i < 99; ++i) right = "[1 + " + right;
  right += std::string(99, ']');
  EXPECT_DOUBLE_EQ(value(text), 100);
  EXPECT_DOUBLE_EQ(value(right), 100);
}

TEST(GcodeExpression, RunTimeErrorsAreAtTheirColumn) {
  // The text starts at column 7: its first character's offset 0.
  EXPECT_EQ(error("[1 / [#1 - 3]]"), "10: division by zero");
  EXPECT_EQ(error("[2 MOD 0]"), "10: MOD by zero");
  EXPECT_EQ(error("[1 + SQRT[-4]]"), "12: SQRT[-4] is not defined");
  EXPECT_EQ(error("[ACOS[2]]"), "8: ACOS[2] is not defined");
  EXPECT_EQ(error("[LN[0]]"), "8: LN[0] is not defined");
  EXPECT_EQ(error("[1 + #<depth>]"),
            "12: #<depth> has no value yet; set it first, as #<depth> = 1");
  EXPECT_EQ(error("#[#1 + 0.5]"), "7: #3.5 is not a parameter: parameters are #1 to #5602");
  EXPECT_EQ(error("#[5603]"), "7: #5603 is not a parameter: parameters are #1 to #5602");
}

TEST(GcodeExpression, SyntaxErrorsAreFoundWhenCompiled) {
  GcodeBlock b;
  const auto compile_error = [&](const std::string& text) {
    try {
      add_gcode_expression(&b, text, SourceLoc{kFile, 4, 7});
    } catch (const GantryError& e) {
      return std::to_string(e.diagnostic().loc.column) + ": " + e.diagnostic().message;
    }
    return std::string("no error");
  };
  EXPECT_EQ(compile_error("[1 + ]"),
            "12: expected a value: a number, [expression], #parameter or "
            "a function such as SIN[x]");
  EXPECT_EQ(compile_error("[1 + 2 3"),
            "15: expected ']' to close the expression");  // `2 3` is 23, as in LinuxCNC
  EXPECT_EQ(compile_error("[#<>]"), "9: the parameter name between < and > is empty");
  std::string deep(300, '[');
  EXPECT_NE(compile_error(deep + "1" + std::string(300, ']')).find("nested more than 200"),
            std::string::npos);
  // A failed expression leaves nothing behind: the block holds only what compiled.
  EXPECT_TRUE(b.exprs.empty());
  EXPECT_TRUE(b.steps.empty());
  EXPECT_TRUE(b.names.empty());
}

}  // namespace
}  // namespace gantry
