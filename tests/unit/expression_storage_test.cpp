// How a parsed expression is stored: one heap block per tree, the parser's reused buffers,
// and the load pass's check-only parse (ExprCheckOnly, check_line).
#include <gtest/gtest.h>

#include <algorithm>  // max
#include <memory>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "gantry/interp/evaluator.hpp"
#include "gantry/lang/check_only.hpp"
#include "gantry/lang/expr_node.hpp"
#include "gantry/lang/expression.hpp"
#include "gantry/lang/parser.hpp"

namespace gantry {
namespace {

class Vars : public EvalEnv {
 public:
  const Value* user_variable(std::string_view name) const override {
    if (name == "X") return &x_;
    if (name == "LONG_VARIABLE_NAME_OF_MANY_LETTERS") return &long_;
    return nullptr;
  }
  const nlohmann::json* persistent_variable(std::string_view) const override { return nullptr; }
  Value system_variable(int, const SourceLoc& loc) override { fail(loc, "none"); }
  bool trig_in_degrees() const override { return false; }

 private:
  Value x_ = Value::number(5);
  Value long_ = Value::number(2);
};

SourceLoc at(int column = 1) {
  return SourceLoc{std::make_shared<const std::string>("t.sbp"), 3, column};
}

Expr parse(std::string_view text, int column = 1) {
  ExprParse p = parse_expression(text, at(column));
  EXPECT_TRUE(p.expr) << text << ": " << (p.error ? format(*p.error) : "");
  return p.expr ? *p.expr : Expr();
}

double num(const Expr& e) {
  Vars env;
  const Value v = evaluate(e, env);
  EXPECT_TRUE(v.is_number());
  return v.is_number() ? v.num() : -1e300;
}

template <class T, class Span>
bool inside(const T* p, const Span& s) {
  return !s.empty() && p >= &s.front() && p <= &s.back();
}

bool inside_text(std::string_view v, std::string_view pool) {
  return v.empty() || (v.data() >= pool.data() && v.data() + v.size() <= pool.data() + pool.size());
}

TEST(ExpressionStorage, ATreeViewsOnlyItsOwnBlock) {
  const Expr e =
      parse("ABS(&long_variable_name_of_many_letters) + MIN(1, &x, 3) & \"some quoted text\"");
  const ExprTree& t = *e.root()->tree;
  EXPECT_EQ(&t.nodes.back(), e.root()) << "the root is last";
  EXPECT_EQ(t.arglist.size(), 4u);
  for (const ExprNode& n : t.nodes) {
    EXPECT_EQ(n.tree, &t);
    EXPECT_TRUE(!n.a || inside(n.a, t.nodes));
    EXPECT_TRUE(!n.b || inside(n.b, t.nodes));
    for (int k = 0; k < n.argc; ++k) EXPECT_TRUE(inside(n.args[k], t.nodes));
    EXPECT_TRUE(inside_text(n.text, t.strings));
    EXPECT_TRUE(inside_text(n.spelling, t.strings));
  }
  Vars env;
  EXPECT_EQ(evaluate(e, env).to_string(), "3some quoted text");
}

TEST(ExpressionStorage, TreesOutliveTheParserBuffersTheyWereBuiltIn) {
  // The parser's buffers are reused from expression to expression: a tree made earlier must
  // not see a later one's nodes or names.
  std::vector<Expr> kept;
  for (int k = 0; k < 50; ++k)
    kept.push_back(parse(k % 2
                             ? fmt::format("&x * {} + MAX({}, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10)", k, k)
                             : fmt::format("{} - &LONG_variable_name_of_many_letters", k)));
  for (int k = 0; k < 50; ++k)
    EXPECT_EQ(num(kept[static_cast<size_t>(k)]), k % 2 ? 5.0 * k + std::max(k, 10) : k - 2.0) << k;
  EXPECT_EQ(kept[1].root()->tree->nodes.size(), 16u);  // its own nodes only
}

TEST(ExpressionStorage, CallsWithManyArguments) {
  // A call keeps its first arguments on the stack and the rest on the heap.
  std::string args;
  for (int k = 1; k <= 32; ++k) args += fmt::format("{}{}", k > 1 ? ", " : "", k);
  EXPECT_EQ(num(parse("MAX(" + args + ")")), 32);
  EXPECT_EQ(num(parse("MIN(" + args + ") + MAX(MIN(4, 5, 6, 7, 8, 9, 10, 11, 12), 2)")), 5);
  const ExprParse p = parse_expression("  MAX(" + args + ", 33)", at(4));
  ASSERT_TRUE(p.error);
  EXPECT_EQ(p.error->message, "MAX takes at least 2 arguments (at most 32), not 33");
  EXPECT_EQ(p.error->loc.column, 6);
}

TEST(ExpressionStorage, DeepExpressions) {
  std::string chain = "1";
  for (int k = 1; k < 999; ++k) chain += "+1";
  EXPECT_EQ(num(parse(chain)), 999);
  const ExprParse too_long = parse_expression(chain + "+1+1", at());
  ASSERT_TRUE(too_long.error);
  EXPECT_EQ(too_long.error->message,
            "this expression is too long to evaluate; split it using variables");
  const std::string nested = std::string(90, '(') + "&x" + std::string(90, ')') + " * 2";
  EXPECT_EQ(num(parse(nested)), 10);
  const ExprParse too_deep =
      parse_expression(std::string(250, '(') + "1" + std::string(250, ')'), at());
  ASSERT_TRUE(too_deep.error);
  EXPECT_EQ(too_deep.error->message,
            "this expression is nested too deeply; split it using variables");
  EXPECT_EQ(num(parse("&x - 1")), 4) << "a failed parse leaves nothing behind";
}

TEST(ExpressionStorage, ErrorColumnsAfterALongExpression) {
  parse("SIN(&x) * (1 + 2 + 3 + 4 + 5 + 6 + 7 + 8 + 9) / &long_variable_name_of_many_letters");
  const ExprParse p = parse_expression("&x + (2 * 3", at(10));
  ASSERT_TRUE(p.error);
  EXPECT_EQ(p.error->message, "this '(' is never closed; add ')'");
  EXPECT_EQ(p.error->loc.column, 15);
  EXPECT_EQ(p.error->loc.line, 3);
  const ExprParse q = parse_expression("1 + SQR(4, 5)", at(2));
  ASSERT_TRUE(q.error);
  EXPECT_EQ(q.error->loc.column, 6);
}

TEST(ExpressionStorage, EachThreadParsesInItsOwnBuffers) {
  auto work = [](int seed, double* sum) {
    for (int k = 0; k < 2000; ++k) *sum += num(parse(fmt::format("({} + {}) * &x", seed, k % 7)));
  };
  double a = 0, b = 0;
  std::thread t1(work, 1, &a), t2(work, 100, &b);
  t1.join();
  t2.join();
  double want_a = 0, want_b = 0;
  for (int k = 0; k < 2000; ++k) {
    want_a += (1 + k % 7) * 5.0;
    want_b += (100 + k % 7) * 5.0;
  }
  EXPECT_EQ(a, want_a);
  EXPECT_EQ(b, want_b);
}

TEST(ExpressionStorage, CheckOnlyGivesPlaceholders) {
  {
    const ExprCheckOnly check;
    const ExprParse good = parse_expression("&x + $p[&i].z * 2", at());
    ASSERT_TRUE(good.expr);
    EXPECT_EQ(good.expr->root()->op, ExprOp::Number);
    { const ExprCheckOnly nested; }
    const ExprParse bad = parse_expression("&x + (2", at(4));
    ASSERT_TRUE(bad.error);
    EXPECT_EQ(bad.error->message, "this '(' is never closed; add ')'");
    EXPECT_EQ(bad.error->loc.column, 9);
  }
  EXPECT_EQ(num(parse("&x + 2")), 7) << "the scope ended: trees are built again";
}

TEST(ExpressionStorage, CheckLineFindsWhatParseLineFinds) {
  const auto file = std::make_shared<const std::string>("t.sbp");
  const char* lines[] = {
      "&x = 1 + (&i MOD 100) * &dx",
      "IF &x > 1.5 THEN &x = &x - 0.5",
      "IF &a = Cancel THEN GOTO DONE",
      "&x = &y +",
      "&x = SQR(1, 2)",
      "M3, &x, 2 + SIN(&i / 10) / 2, (1",
      "MX, 1 + ",
      "PRINT \"a\", &x * 2; ",
      "$tool[&n].z = 3 + ",
      "C#, &n + 1",
      "PAUSE SQR(4",
      "ON INPUT(&sw, 1) GOSUB HIT",
      "LOOP:",
      "&s = Material Surface",
      "IF &x < (2 THEN GOTO A",
  };
  for (const char* text : lines) {
    const LineParse full = parse_line(text, file, 9);
    const LineParse check = check_line(text, file, 9);
    EXPECT_EQ(full.statement.has_value(), check.statement.has_value()) << text;
    ASSERT_EQ(full.error.has_value(), check.error.has_value()) << text;
    if (full.error) {
      EXPECT_EQ(format(*full.error), format(*check.error)) << text;
    } else {
      EXPECT_EQ(full.statement->body.index(), check.statement->body.index()) << text;
    }
  }
}

TEST(ExpressionStorage, AssignmentTargetsReadAsParseLvalueReadsThem) {
  // LineParser reads a plain `&name` target itself; every other target goes to parse_lvalue.
  const auto file = std::make_shared<const std::string>("t.sbp");
  const char* targets[] = {"&x",   "&Abc_1", "&_9",      "  &tool_Z  ", "&3zero", "&x[1]",
                           "&x.y", "$p",     "$p[&i].z", "&",           "&x y",   "&x-1"};
  for (const char* target : targets) {
    const std::string text = std::string(target) + " = 2";
    const LineParse line = parse_line(text, file, 4);
    const std::string_view t(target);
    const size_t b = t.find_first_not_of(' ');
    const size_t e = t.find_last_not_of(' ') + 1;
    std::optional<Diagnostic> err;
    const std::optional<LValue> want =
        parse_lvalue(t.substr(b, e - b), SourceLoc{file, 4, static_cast<int>(b) + 1}, &err);
    if (!want) {
      ASSERT_TRUE(line.error) << text;
      EXPECT_EQ(format(*line.error), format(*err)) << text;
      continue;
    }
    ASSERT_TRUE(line.statement) << text << ": " << (line.error ? format(*line.error) : "");
    const auto& got = std::get<AssignStmt>(line.statement->body).target;
    EXPECT_EQ(got.persistent, want->persistent) << text;
    EXPECT_EQ(got.name, want->name) << text;
    EXPECT_EQ(got.path.size(), want->path.size()) << text;
    EXPECT_EQ(got.loc.file, want->loc.file) << text;
    EXPECT_EQ(got.loc.line, want->loc.line) << text;
    EXPECT_EQ(got.loc.column, want->loc.column) << text;
  }
}

}  // namespace
}  // namespace gantry
