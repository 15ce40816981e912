// The compiled form of an expression: a compact tree of nodes stored flat in one ExprTree.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "gantry/core/diagnostic.hpp"  // SourceLoc
#include "gantry/lang/expression.hpp"  // Accessor

namespace gantry {

enum class ExprOp : std::uint8_t {
  // Operands.
  Number,      // `number`
  Text,        // quoted string: `text` holds its contents
  UserVar,     // &name: `text` = upper-case name, `spelling` = source text (`&Foo`)
  PersistVar,  // $name with accessors: `text` = upper-case name, `path`
  SysVar,      // %(a)
  Call,        // fn(args[0..argc))
  // Unary operators on `a`.
  Neg,
  Pos,
  Not,
  // Binary operators on `a` and `b`.
  Add,
  Sub,
  Mul,
  Div,
  IntDiv,  // `\`: the quotient truncated toward zero
  Mod,
  Pow,
  Join,  // `&`
  Eq,
  Ne,
  Lt,
  Gt,
  Le,
  Ge,
  And,
  Or,
};

enum class ExprFunc : std::uint8_t {
  Abs,
  Int,
  Fix,
  Sgn,
  Sin,
  Cos,
  Tan,
  Atn,
  Atan2,
  Exp,
  Log,
  Sqr,
  Round,
  Min,
  Max,
  Ceil,
  Floor,
};

// A built-in function: its canonical name and how many arguments it takes.
struct FuncInfo {
  std::string_view name;
  ExprFunc id;
  int min_args;
  int max_args;
};

// The most arguments a call may have; the evaluator keeps them in a fixed stack buffer.
inline constexpr int kMaxCallArgs = 32;

// The function named `upper_name` (aliases included), or null.
const FuncInfo* find_function(std::string_view upper_name);
// The canonical name of `f` for messages.
std::string_view function_name(ExprFunc f);

struct ExprTree;

// One node. Fields not used by a node's `op` are left at their defaults. The fields read on
// every evaluation come first, so they sit together in memory; locations and the rarely
// used pointers come last.
struct ExprNode {
  ExprOp op = ExprOp::Number;
  ExprFunc fn = ExprFunc::Abs;  // Call
  std::uint16_t argc = 0;       // Call
  // 1-based columns: `col` is the node's own token (the operator of a binary node, the
  // name of a variable or function); `start` is where the whole sub-expression begins,
  // including an opening parenthesis around it. Errors about a value point at `start`,
  // errors about a token at `col`.
  std::int32_t col = 0;
  std::int32_t start = 0;
  double number = 0;                            // Number
  const ExprNode* a = nullptr;                  // first operand
  const ExprNode* b = nullptr;                  // second operand
  std::string_view text;                        // Text, UserVar, PersistVar
  std::string_view spelling;                    // UserVar
  const ExprNode* const* args = nullptr;        // Call
  const std::vector<Accessor>* path = nullptr;  // PersistVar
  const ExprTree* tree = nullptr;               // owner, for locations

  SourceLoc loc_at(std::int32_t column) const;
  SourceLoc token_loc() const { return loc_at(col); }
  SourceLoc start_loc() const { return loc_at(start); }
};

// Owns every node of one expression and the storage their views and pointers refer to.
// Immutable once built, so an Expr shares it freely. The nodes, the call arguments and the
// strings live in the same heap block as the tree (one allocation per expression, see
// expression.cpp's finish), so the spans below view memory the tree owns.
struct ExprTree {
  SourceLoc at;                              // file and line; columns are stored per node
  std::span<const ExprNode> nodes;           // root last
  std::string_view strings;                  // names and string literals, viewed by nodes
  std::span<const ExprNode* const> arglist;  // call arguments, viewed by nodes
  std::vector<std::vector<Accessor>> paths;  // persistent-variable accessors
};

inline SourceLoc ExprNode::loc_at(std::int32_t column) const {
  SourceLoc l = tree->at;
  l.column = column;
  return l;
}

}  // namespace gantry
