// Parsing expressions and lvalues: a one-token-lookahead lexer and a recursive-descent parser
// that builds a flat ExprTree.
#include "gantry/lang/expression.hpp"

#include <fmt/format.h>  // messages

#include <algorithm>  // max
#include <new>        // operator new for the tree's one block
#include <span>       // a call's arguments

#include "gantry/lang/expr_node.hpp"
#include "gantry/lang/check_only.hpp"  // ExprCheckOnly
#include "gantry/core/any_bytes.hpp"  // echoed: a token quoted in a message is capped
#include "gantry/core/text.hpp"  // upper
#include "gantry/lang/number_literal.hpp"  // literal::scan, literal::value

namespace gantry {

namespace {

constexpr FuncInfo kFunctions[] = {
    {"ABS", ExprFunc::Abs, 1, 1},
    {"INT", ExprFunc::Int, 1, 1},
    {"FIX", ExprFunc::Fix, 1, 1},
    {"SGN", ExprFunc::Sgn, 1, 1},
    {"SIN", ExprFunc::Sin, 1, 1},
    {"COS", ExprFunc::Cos, 1, 1},
    {"TAN", ExprFunc::Tan, 1, 1},
    {"ATN", ExprFunc::Atn, 1, 1},
    {"ATAN", ExprFunc::Atn, 1, 1},
    {"ATAN2", ExprFunc::Atan2, 2, 2},
    {"EXP", ExprFunc::Exp, 1, 1},
    {"LOG", ExprFunc::Log, 1, 1},
    {"SQR", ExprFunc::Sqr, 1, 1},
    {"SQRT", ExprFunc::Sqr, 1, 1},
    {"ROUND", ExprFunc::Round, 1, 2},
    {"MIN", ExprFunc::Min, 2, kMaxCallArgs},
    {"MAX", ExprFunc::Max, 2, kMaxCallArgs},
    {"CEIL", ExprFunc::Ceil, 1, 1},
    {"FLOOR", ExprFunc::Floor, 1, 1},
};

// Parentheses, calls, indices and signs nested deeper than this are refused rather than
// risking the parser's stack; no hand-written part file comes close.
constexpr int kMaxNesting = 200;
// Evaluation recurses once per tree level; a left-leaning chain `1+1+1+...` grows one level
// per operator, so the tree's height is bounded too.
constexpr int kMaxHeight = 1000;

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n';
}
using literal::is_digit;
bool is_name_start(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_';
}
bool is_name_char(char c) {
  return is_name_start(c) || is_digit(c);
}
using ascii::upper;

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (upper(a[i]) != upper(b[i])) return false;
  return true;
}

enum class Tok : std::uint8_t {
  End,
  Number,
  Text,
  UserVar,
  PersistVar,
  SysVar,  // `%(`
  Word,
  LParen,
  RParen,
  LBracket,
  RBracket,
  Comma,
  Plus,
  Minus,
  Star,
  Slash,
  Backslash,  // integer division
  Caret,
  Amp,
  Eq,
  Ne,
  Lt,
  Gt,
  Le,
  Ge,
};

struct Token {
  Tok kind = Tok::End;
  size_t pos = 0;  // offset in the text
  size_t len = 0;
  double number = 0;  // Number
};

// A node while the tree is being built: children are indices, texts are offsets into the
// string pool; ExprTree's pointers and views are set once everything has its final address.
struct Proto {
  ExprNode node;
  int a = -1, b = -1;
  int args_begin = -1;  // into arg_index
  int path = -1;
  std::uint32_t text_off = 0, text_len = 0;
  std::uint32_t spell_off = 0, spell_len = 0;
  int height = 1;
};

// The growing buffers of one parse. A top-level parse reuses its thread's (their capacity
// stays from expression to expression, so a steady stream of lines allocates nothing for
// them); the sub-parse of a `$name[index]` has its own.
struct Scratch {
  std::vector<Proto> protos;
  std::string strings;
  std::vector<int> arg_index;
  void clear() {
    protos.clear();
    strings.clear();
    arg_index.clear();
  }
};

thread_local bool t_check_only = false;  // see ExprCheckOnly

// What a checked expression gives under ExprCheckOnly: the number 0, owning nothing.
const ExprTree kPlaceholderTree{};
const ExprNode kPlaceholder = [] {
  ExprNode n;
  n.tree = &kPlaceholderTree;
  return n;
}();

Scratch& thread_scratch() {
  thread_local Scratch s;
  s.clear();
  return s;
}

// An allocator that allocates `extra` bytes after the object it is asked for, and says where
// they start: allocate_shared then makes a tree, its control block and its nodes in one block.
template <class T>
struct TailAllocator {
  using value_type = T;
  TailAllocator(size_t extra, char** tail) : extra(extra), tail(tail) {}
  template <class U>
  TailAllocator(const TailAllocator<U>& o) : extra(o.extra), tail(o.tail) {}  // NOLINT
  static constexpr size_t head_bytes(size_t n) {
    constexpr size_t a = alignof(std::max_align_t);
    return (n * sizeof(T) + a - 1) / a * a;
  }
  T* allocate(size_t n) {
    char* p = static_cast<char*>(::operator new(head_bytes(n) + extra));
    *tail = p + head_bytes(n);
    return reinterpret_cast<T*>(p);
  }
  void deallocate(T* p, size_t) noexcept { ::operator delete(p); }
  template <class U>
  bool operator==(const TailAllocator<U>&) const {
    return true;
  }
  size_t extra;
  char** tail;
};

class Parser {
 public:
  // `at` locates text[0]; a location without a column (0) counts text[0] as column 1.
  // `scratch`: the buffers to build in (null: the parser's own).
  Parser(std::string_view text, const SourceLoc& at, size_t pos, int nesting,
         bool bare_words = false, Scratch* scratch = nullptr)
      : text_(text),
        at_(at),
        base_(at.column > 0 ? at.column : 1),
        pos_(pos),
        nesting_(nesting),
        bare_words_(bare_words),
        s_(scratch ? *scratch : own_),
        protos_(s_.protos),
        strings_(s_.strings),
        arg_index_(s_.arg_index) {}

  Expr parse_whole() {
    advance();
    if (tok_.kind == Tok::End) fail(loc(0), "expected an expression");
    const int root = parse_or();
    expect_end("the expression");
    return finish(root);
  }

  LValue parse_lvalue() {
    advance();
    const Token t = tok_;
    LValue v;
    v.loc = loc(t.pos);
    switch (t.kind) {
      case Tok::UserVar:
        v.name = upper(text_.substr(t.pos + 1, t.len - 1));
        reject_user_accessor(t);
        break;
      case Tok::PersistVar:
        v.persistent = true;
        v.name = upper(text_.substr(t.pos + 1, t.len - 1));
        v.path = accessors();
        break;
      case Tok::SysVar:
        fail(loc(t.pos), "system variables %(n) are read-only; assign to a &variable instead");
      case Tok::End:
        fail(loc(t.pos), "expected a variable such as &name");
      default:
        fail(loc(t.pos), fmt::format("expected a variable such as &name, found {}", describe(t)));
    }
    advance();
    expect_end("the variable");
    return v;
  }

 private:
  // ---- locations and messages ----

  std::int32_t col(size_t pos) const { return base_ + static_cast<std::int32_t>(pos); }
  SourceLoc loc(size_t pos) const {
    SourceLoc l = at_;
    l.column = col(pos);
    return l;
  }
  std::string_view source(const Token& t) const { return text_.substr(t.pos, t.len); }

  std::string describe(const Token& t) const {
    if (t.kind == Tok::End) return "the end of the text";
    return fmt::format("'{}'", echoed(source(t), 30));
  }

  bool is_keyword(const Token& t, std::string_view kw) const {
    return t.kind == Tok::Word && iequals(source(t), kw);
  }

  void expect_end(std::string_view what) {
    if (tok_.kind == Tok::End) return;
    switch (tok_.kind) {
      case Tok::RParen:
        fail(loc(tok_.pos), "unexpected ')' with no matching '('");
      case Tok::RBracket:
        fail(loc(tok_.pos), "unexpected ']' with no matching '['");
      case Tok::Number:
      case Tok::Text:
      case Tok::UserVar:
      case Tok::PersistVar:
      case Tok::SysVar:
      case Tok::LParen:
        fail(loc(tok_.pos),
             fmt::format("unexpected {} after {}: two values need an operator between them "
                         "(join text with ' & ')",
                         describe(tok_), what));
      default:
        fail(loc(tok_.pos), fmt::format("unexpected {} after {}", describe(tok_), what));
    }
  }

  // ---- lexer ----

  // Reads the token at pos_ into tok_; lexical errors are thrown at their character.
  void advance() {
    prev_ = tok_;
    const size_t n = text_.size();
    size_t i = pos_;
    while (i < n && is_space(text_[i])) ++i;
    tok_ = Token{};
    tok_.pos = i;
    if (i >= n) {
      pos_ = i;
      return;
    }
    const char c = text_[i];
    const char next = i + 1 < n ? text_[i + 1] : '\0';
    auto set = [&](Tok k, size_t len) {
      tok_.kind = k;
      tok_.len = len;
    };
    switch (c) {
      case '(':
        set(Tok::LParen, 1);
        break;
      case ')':
        set(Tok::RParen, 1);
        break;
      case '[':
        set(Tok::LBracket, 1);
        break;
      case ']':
        set(Tok::RBracket, 1);
        break;
      case ',':
        set(Tok::Comma, 1);
        break;
      case '+':
        set(Tok::Plus, 1);
        break;
      case '-':
        set(Tok::Minus, 1);
        break;
      case '*':
        set(Tok::Star, 1);
        break;
      case '/':
        set(Tok::Slash, 1);
        break;
      case '\\':
        set(Tok::Backslash, 1);
        break;
      case '^':
        set(Tok::Caret, 1);
        break;
      case '"': {
        const size_t close = text_.find('"', i + 1);
        if (close == std::string_view::npos)
          fail(loc(i), "this text has no closing '\"'; add one at its end");
        set(Tok::Text, close - i + 1);
        break;
      }
      case '&':
        // `&` followed by a name starts a variable; otherwise it is the join operator, so
        // `"a"&&x` joins "a" and &x (handbook examples always space the operator). SB3 also
        // takes names that start with a digit (`&3zero_input`): a run of name characters
        // with a letter or `_` in it is a name, so `"a"&3` still joins the number 3.
        if (is_name_start(next) || variable_name_at(i + 1))
          set(Tok::UserVar, name_end(i + 1) - i);
        else
          set(Tok::Amp, 1);
        break;
      case '$':
        if (!is_name_start(next)) fail(loc(i), "'$' must be followed by a name, as in $name");
        set(Tok::PersistVar, name_end(i + 1) - i);
        break;
      case '%':
        if (is_name_start(next))
          fail(loc(i), fmt::format("{} reads FabMo's configuration tree, which Gantry does not "
                                   "offer; read %(n) system variables or set a $variable instead",
                                   text_.substr(i, name_path_end(i + 1) - i)));
        if (next != '(')
          fail(loc(i),
               "'%' is not an operator: use MOD for a remainder; %(n) reads a system variable");
        set(Tok::SysVar, 2);
        break;
      case '=':
        if (next == '>') fail(loc(i), "'=>' is not an operator; write >=");
        if (next == '<') fail(loc(i), "'=<' is not an operator; write <=");
        set(Tok::Eq, next == '=' ? 2 : 1);
        break;
      case '<':
        if (next == '>')
          set(Tok::Ne, 2);
        else if (next == '=')
          set(Tok::Le, 2);
        else
          set(Tok::Lt, 1);
        break;
      case '>':
        if (next == '=')
          set(Tok::Ge, 2);
        else
          set(Tok::Gt, 1);
        break;
      case '!':
        if (next != '=')
          fail(loc(i), "unexpected '!': write <> (or !=) for 'not equal' and NOT for negation");
        set(Tok::Ne, 2);
        break;
      default:
        if (is_digit(c) || (c == '.' && is_digit(next))) {
          lex_number(i);
        } else if (is_name_start(c)) {
          set(Tok::Word, name_end(i) - i);
        } else if (c == '.') {
          fail(loc(i), "unexpected '.'");
        } else {
          // Show a whole UTF-8 character (`°`), not its first byte.
          size_t e = i + 1;
          if (static_cast<unsigned char>(c) >= 0x80)
            while (e < n && (static_cast<unsigned char>(text_[e]) & 0xC0) == 0x80) ++e;
          fail(loc(i), fmt::format("unexpected character '{}'", text_.substr(i, e - i)));
        }
    }
    pos_ = i + tok_.len;
  }

  size_t name_end(size_t i) const {
    while (i < text_.size() && is_name_char(text_[i])) ++i;
    return i;
  }
  // Digits then a letter or `_` at i: a user variable's name that starts with a digit.
  bool variable_name_at(size_t i) const {
    if (i >= text_.size() || !is_digit(text_[i])) return false;
    const size_t e = name_end(i);
    for (size_t k = i; k < e; ++k)
      if (is_name_start(text_[k])) return true;
    return false;
  }
  // A dotted name such as machine.envelope.ymax.
  size_t name_path_end(size_t i) const {
    while (i < text_.size() && (is_name_char(text_[i]) || text_[i] == '.')) ++i;
    return i;
  }

  void lex_number(size_t i) {
    // The common literal (no exponent, at most 15 digits) is valued as its digits are read:
    // literal::plain_value's exact m / 10^decimals, without walking the literal again.
    {
      const size_t n = text_.size();
      const char* s = text_.data();
      size_t j = i, digits = 0, decimals = 0;
      std::uint64_t m = 0;  // wraps past 19 digits: then unused
      while (j < n && is_digit(s[j])) m = m * 10 + static_cast<unsigned>(s[j++] - '0'), ++digits;
      if (j < n && s[j] == '.') {
        ++j;
        while (j < n && is_digit(s[j]))
          m = m * 10 + static_cast<unsigned>(s[j++] - '0'), ++digits, ++decimals;
      }
      // An `e` that starts an exponent (literal::scan takes it only with digits after it).
      bool exponent = false;
      if (j < n && (s[j] == 'e' || s[j] == 'E')) {
        size_t k = j + 1;
        if (k < n && (s[k] == '+' || s[k] == '-')) ++k;
        exponent = k < n && is_digit(s[k]);
      }
      if (!exponent && digits <= 15) {
        tok_.kind = Tok::Number;
        tok_.len = j - i;
        tok_.number = static_cast<double>(m) / literal::kPow10[decimals];
        return;
      }
    }
    const size_t j = literal::scan(text_, i);
    const std::string_view lit = text_.substr(i, j - i);
    // Without an exponent, the fast exact reading (plain_value: the same double as value(),
    // infinite only where value() finds the literal too large).
    std::optional<double> d;
    if (lit.find_first_of("eE") == std::string_view::npos) {
      if (const double v = literal::plain_value(lit); v != HUGE_VAL) d = v;
    } else {
      d = literal::value(lit);
    }
    if (!d) fail(loc(i), fmt::format("the number {} is too large", echoed(text_.substr(i, j - i))));
    tok_.kind = Tok::Number;
    tok_.len = j - i;
    tok_.number = *d;
  }

  // ---- tree building ----

  int add(ExprOp op, size_t pos, int a = -1, int b = -1) {
    Proto p;
    p.node.op = op;
    p.node.col = col(pos);
    p.node.start = a >= 0 && b >= 0 ? protos_[a].node.start : p.node.col;
    p.a = a;
    p.b = b;
    if (a >= 0) p.height = std::max(p.height, protos_[a].height + 1);
    if (b >= 0) p.height = std::max(p.height, protos_[b].height + 1);
    if (p.height > kMaxHeight)
      fail(loc(pos), "this expression is too long to evaluate; split it using variables");
    protos_.push_back(std::move(p));
    return static_cast<int>(protos_.size()) - 1;
  }

  void set_text(int node, std::string_view s) {
    protos_[node].text_off = static_cast<std::uint32_t>(strings_.size());
    protos_[node].text_len = static_cast<std::uint32_t>(s.size());
    strings_ += s;
  }
  // set_text of `s` in upper case, without a temporary string.
  void set_upper_text(int node, std::string_view s) {
    set_text(node, s);
    for (size_t i = strings_.size() - s.size(); i < strings_.size(); ++i)
      strings_[i] = upper(strings_[i]);
  }

  // Nesting guard for the recursive descent; see kMaxNesting.
  struct Nest {
    explicit Nest(Parser& p, size_t pos) : p_(p) {
      if (++p_.nesting_ > kMaxNesting)
        fail(p_.loc(pos), "this expression is nested too deeply; split it using variables");
    }
    ~Nest() { --p_.nesting_; }
    Parser& p_;
  };

  // The tree, its nodes, call arguments and strings in one heap block (one allocation).
  Expr finish(int root) {
    if (t_check_only)  // aliasing an empty owner: no allocation, no reference count
      return Expr(std::shared_ptr<const ExprNode>(std::shared_ptr<const void>(), &kPlaceholder));
    const size_t node_bytes = protos_.size() * sizeof(ExprNode);
    const size_t arg_bytes = arg_index_.size() * sizeof(const ExprNode*);
    static_assert(alignof(ExprNode) >= alignof(const ExprNode*));
    char* tail = nullptr;
    auto tree = std::allocate_shared<ExprTree>(
        TailAllocator<ExprTree>(node_bytes + arg_bytes + strings_.size(), &tail));
    auto* nodes = reinterpret_cast<ExprNode*>(tail);
    auto* args = reinterpret_cast<const ExprNode**>(tail + node_bytes);
    char* pool_chars = tail + node_bytes + arg_bytes;
    strings_.copy(pool_chars, strings_.size());
    const std::string_view pool(pool_chars, strings_.size());
    tree->at = at_;
    tree->paths = std::move(paths_);
    for (size_t k = 0; k < arg_index_.size(); ++k)
      new (&args[k]) const ExprNode*(&nodes[arg_index_[k]]);
    for (size_t i = 0; i < protos_.size(); ++i) {
      const Proto& p = protos_[i];
      ExprNode& n = *new (&nodes[i]) ExprNode(p.node);
      n.tree = tree.get();
      if (p.a >= 0) n.a = &nodes[p.a];
      if (p.b >= 0) n.b = &nodes[p.b];
      n.text = pool.substr(p.text_off, p.text_len);
      n.spelling = pool.substr(p.spell_off, p.spell_len);
      if (p.args_begin >= 0) n.args = args + p.args_begin;
      if (p.path >= 0) n.path = &tree->paths[p.path];
    }
    tree->nodes = std::span<const ExprNode>(nodes, protos_.size());
    tree->strings = pool;
    tree->arglist = std::span<const ExprNode* const>(args, arg_index_.size());
    const ExprNode* r = &nodes[root];
    return Expr(std::shared_ptr<const ExprNode>(std::move(tree), r));
  }

  // ---- grammar, lowest precedence first ----
  //   or   := and { OR and }
  //   and  := not { AND not }
  //   not  := NOT not | cmp
  //   cmp  := join [ cmpop join ]           one comparison; a second one is an error
  //   join := add { "&" add }
  //   add  := mod { ("+" | "-") mod }
  //   mod  := idiv { MOD idiv }             VB's level, between \ and + -
  //   idiv := mul { "\" mul }               VB's level, between * / and MOD
  //   mul  := unary { ("*" | "/") unary }
  //   unary:= ("-" | "+") unary | pow        so -2^2 = -(2^2) = -4
  //   pow  := primary { "^" signed }        LEFT-associative: 2^3^2 = (2^3)^2 = 64
  //   signed := ("-" | "+") signed | primary   so 2^-1 = 0.5
  // Every binary operator is left-associative: 8/4/2 = (8/4)/2 = 1.

  int parse_or() {
    Nest nest(*this, tok_.pos);
    int x = parse_and();
    while (is_keyword(tok_, "OR")) {
      const Token op = tok_;
      advance();
      x = add(ExprOp::Or, op.pos, x, parse_and());
    }
    return x;
  }

  int parse_and() {
    int x = parse_not();
    while (is_keyword(tok_, "AND")) {
      const Token op = tok_;
      advance();
      x = add(ExprOp::And, op.pos, x, parse_not());
    }
    return x;
  }

  int parse_not() {
    if (is_keyword(tok_, "NOT")) {
      const Token op = tok_;
      Nest nest(*this, op.pos);
      advance();
      return add(ExprOp::Not, op.pos, parse_not());
    }
    return parse_cmp();
  }

  static bool comparison(Tok k, ExprOp* op) {
    switch (k) {
      case Tok::Eq:
        *op = ExprOp::Eq;
        return true;
      case Tok::Ne:
        *op = ExprOp::Ne;
        return true;
      case Tok::Lt:
        *op = ExprOp::Lt;
        return true;
      case Tok::Gt:
        *op = ExprOp::Gt;
        return true;
      case Tok::Le:
        *op = ExprOp::Le;
        return true;
      case Tok::Ge:
        *op = ExprOp::Ge;
        return true;
      default:
        return false;
    }
  }

  int parse_cmp() {
    const int x = parse_join();
    ExprOp op;
    if (!comparison(tok_.kind, &op)) return x;
    const Token t = tok_;
    advance();
    const int r = add(op, t.pos, x, parse_join());
    if (comparison(tok_.kind, &op))
      fail(loc(tok_.pos),
           "comparisons cannot be chained; combine them with AND, as in &a < &b AND &b < &c");
    return r;
  }

  int parse_join() {
    int x = parse_add();
    while (tok_.kind == Tok::Amp) {
      const Token op = tok_;
      advance();
      x = add(ExprOp::Join, op.pos, x, parse_add());
    }
    return x;
  }

  int parse_add() {
    int x = parse_mod();
    while (tok_.kind == Tok::Plus || tok_.kind == Tok::Minus) {
      const Token op = tok_;
      advance();
      x = add(op.kind == Tok::Plus ? ExprOp::Add : ExprOp::Sub, op.pos, x, parse_mod());
    }
    return x;
  }

  int parse_mod() {
    int x = parse_int_div();
    while (is_keyword(tok_, "MOD")) {
      const Token op = tok_;
      advance();
      x = add(ExprOp::Mod, op.pos, x, parse_int_div());
    }
    return x;
  }

  int parse_int_div() {
    int x = parse_mul();
    while (tok_.kind == Tok::Backslash) {
      const Token op = tok_;
      advance();
      x = add(ExprOp::IntDiv, op.pos, x, parse_mul());
    }
    return x;
  }

  int parse_mul() {
    int x = parse_unary();
    while (tok_.kind == Tok::Star || tok_.kind == Tok::Slash) {
      const Token op = tok_;
      advance();
      x = add(op.kind == Tok::Star ? ExprOp::Mul : ExprOp::Div, op.pos, x, parse_unary());
    }
    return x;
  }

  // A sign applied to `operand`; a sign on a number literal is folded into it, so the
  // common `-0.5` is a single node.
  int sign(const Token& op, int operand) {
    Proto& p = protos_[operand];
    if (p.node.op == ExprOp::Number) {
      if (op.kind == Tok::Minus) p.node.number = -p.node.number;
      p.node.col = p.node.start = col(op.pos);
      return operand;
    }
    return add(op.kind == Tok::Minus ? ExprOp::Neg : ExprOp::Pos, op.pos, operand);
  }

  int parse_unary() {
    if (tok_.kind == Tok::Minus || tok_.kind == Tok::Plus) {
      const Token op = tok_;
      Nest nest(*this, op.pos);
      advance();
      return sign(op, parse_unary());
    }
    return parse_pow();
  }

  int parse_pow() {
    int x = parse_primary();
    while (tok_.kind == Tok::Caret) {
      const Token op = tok_;
      advance();
      x = add(ExprOp::Pow, op.pos, x, parse_signed());
    }
    return x;
  }

  int parse_signed() {
    if (tok_.kind == Tok::Minus || tok_.kind == Tok::Plus) {
      const Token op = tok_;
      Nest nest(*this, op.pos);
      advance();
      return sign(op, parse_signed());
    }
    return parse_primary();
  }

  [[noreturn]] void missing_value() {
    if (tok_.kind == Tok::End) {
      if (prev_.len > 0)
        fail(loc(tok_.pos), fmt::format("expected a value after {}", describe(prev_)));
      fail(loc(tok_.pos), "expected an expression");
    }
    if (tok_.kind == Tok::Word)
      fail(loc(tok_.pos), fmt::format("expected a value before {}", upper(source(tok_))));
    fail(loc(tok_.pos), fmt::format("expected a value, found {}", describe(tok_)));
  }

  void expect_close(Tok close, const Token& open, std::string_view what) {
    if (tok_.kind == close) return;
    const char c = close == Tok::RParen ? ')' : ']';
    if (tok_.kind == Tok::End)
      fail(loc(open.pos), fmt::format("this '{}' is never closed; add '{}'", source(open), c));
    fail(loc(tok_.pos),
         fmt::format("expected '{}' to close {}, found {}", c, what, describe(tok_)));
  }

  void reject_user_accessor(const Token& t) const {
    if (pos_ < text_.size() &&
        (text_[pos_] == '[' ||
         (text_[pos_] == '.' && pos_ + 1 < text_.size() && is_name_start(text_[pos_ + 1]))))
      fail(loc(pos_), fmt::format("{} is a plain variable: only $ variables have fields and "
                                  "indices",
                                  upper(source(t))));
  }

  // `.field` and `[index]` steps written right after a `$name` (pos_ is just past the name).
  std::vector<Accessor> accessors() {
    std::vector<Accessor> path;
    const size_t n = text_.size();
    while (pos_ < n && (text_[pos_] == '.' || text_[pos_] == '[')) {
      Accessor step;
      if (text_[pos_] == '.') {
        const size_t b = pos_ + 1;
        if (b >= n || !is_name_start(text_[b]))
          fail(loc(pos_), "expected a field name after '.', as in $name.field");
        const size_t e = name_end(b);
        step.is_field = true;
        step.field = upper(text_.substr(b, e - b));
        pos_ = e;
      } else {
        Token open;
        open.kind = Tok::LBracket;
        open.pos = pos_;
        open.len = 1;
        // The index is an expression of its own (an Accessor owns an Expr), parsed in place.
        Parser sub(text_, at_, pos_ + 1, nesting_ + 1);
        if (sub.nesting_ > kMaxNesting)
          fail(loc(pos_), "this expression is nested too deeply; split it using variables");
        sub.advance();
        if (sub.tok_.kind != Tok::RBracket) {
          const int r = sub.parse_or();
          sub.expect_close(Tok::RBracket, open, "the index");
          step.index = sub.finish(r);
        }
        pos_ = sub.tok_.pos + 1;
      }
      path.push_back(std::move(step));
    }
    return path;
  }

  int parse_call(const Token& name) {
    // The name upper-cased on the stack (no function's name is longer), not in a string.
    const std::string_view src = source(name);
    char up[8];
    const FuncInfo* f = nullptr;
    if (src.size() <= sizeof up) {
      for (size_t i = 0; i < src.size(); ++i) up[i] = upper(src[i]);
      f = find_function(std::string_view(up, src.size()));
    }
    if (!f)
      fail(loc(name.pos),
           fmt::format("unknown function {}; the functions are ABS, INT, FIX, SGN, SIN, COS, TAN, "
                       "ATN, ATAN2, EXP, LOG, SQR, ROUND, MIN, MAX, CEIL and FLOOR",
                       upper(src)));
    const Token open = tok_;
    Nest nest(*this, open.pos);
    advance();
    // The arguments' nodes; calls take few, so they are kept on the stack (a nested call's
    // arguments are parsed in between, so they cannot go to arg_index_ yet).
    constexpr int kInline = 8;
    int inline_args[kInline];
    std::vector<int> more;  // past kInline: all of them
    int count = 0;
    if (tok_.kind != Tok::RParen) {
      while (true) {
        const int a = parse_or();
        if (count < kInline) {
          inline_args[count] = a;
        } else {
          if (more.empty()) more.assign(inline_args, inline_args + kInline);
          more.push_back(a);
        }
        ++count;
        if (tok_.kind != Tok::Comma) break;
        advance();
      }
    }
    const std::span<const int> args(count <= kInline ? inline_args : more.data(),
                                    static_cast<size_t>(count));
    if (tok_.kind != Tok::RParen)  // the message is made only when it is needed
      expect_close(Tok::RParen, open, fmt::format("the arguments of {}", f->name));
    advance();
    if (count < f->min_args || count > f->max_args) {
      std::string want;
      if (f->min_args == f->max_args)
        want = fmt::format("{} argument{}", f->min_args, f->min_args == 1 ? "" : "s");
      else if (f->max_args == kMaxCallArgs)
        want = fmt::format("at least {} arguments (at most {})", f->min_args, kMaxCallArgs);
      else
        want = fmt::format("{} or {} arguments", f->min_args, f->max_args);
      fail(loc(name.pos), fmt::format("{} takes {}, not {}", f->name, want, count));
    }
    const int node = add(ExprOp::Call, name.pos);
    Proto& p = protos_[node];
    p.node.fn = f->id;
    p.node.argc = static_cast<std::uint16_t>(count);
    p.args_begin = static_cast<int>(arg_index_.size());
    for (int a : args) {
      arg_index_.push_back(a);
      p.height = std::max(p.height, protos_[a].height + 1);
    }
    if (p.height > kMaxHeight)
      fail(loc(name.pos), "this expression is too long to evaluate; split it using variables");
    return node;
  }

  int parse_primary() {
    const Token t = tok_;
    switch (t.kind) {
      case Tok::Number: {
        advance();
        const int node = add(ExprOp::Number, t.pos);
        protos_[node].node.number = t.number;
        return node;
      }
      case Tok::Text: {
        advance();
        const int node = add(ExprOp::Text, t.pos);
        set_text(node, text_.substr(t.pos + 1, t.len - 2));
        return node;
      }
      case Tok::UserVar: {
        reject_user_accessor(t);
        advance();
        const int node = add(ExprOp::UserVar, t.pos);
        set_upper_text(node, text_.substr(t.pos + 1, t.len - 1));
        Proto& p = protos_[node];
        p.spell_off = static_cast<std::uint32_t>(strings_.size());
        p.spell_len = static_cast<std::uint32_t>(t.len);
        strings_ += source(t);
        return node;
      }
      case Tok::PersistVar: {
        std::vector<Accessor> path = accessors();
        advance();
        const int node = add(ExprOp::PersistVar, t.pos);
        set_upper_text(node, text_.substr(t.pos + 1, t.len - 1));
        protos_[node].path = static_cast<int>(paths_.size());
        paths_.push_back(std::move(path));
        return node;
      }
      case Tok::SysVar: {
        Nest nest(*this, t.pos);
        advance();
        if (tok_.kind == Tok::RParen)
          fail(loc(tok_.pos), "expected the system variable's number, as in %(1)");
        const int inner = parse_or();
        expect_close(Tok::RParen, t, "the system variable");
        advance();
        return add(ExprOp::SysVar, t.pos, inner);
      }
      case Tok::LParen: {
        Nest nest(*this, t.pos);
        advance();
        if (tok_.kind == Tok::RParen) fail(loc(tok_.pos), "expected a value inside '( )'");
        const int inner = parse_or();
        if (tok_.kind != Tok::RParen)  // the message is made only when it is needed
          expect_close(Tok::RParen, t, "the '(' at column " + std::to_string(col(t.pos)));
        advance();
        // A parenthesised sub-expression starts at its '(' (errors about its value point
        // there); its own tokens keep their columns.
        protos_[inner].node.start = col(t.pos);
        return inner;
      }
      case Tok::Word: {
        if (is_keyword(t, "AND") || is_keyword(t, "OR") || is_keyword(t, "MOD")) missing_value();
        if (is_keyword(t, "NOT"))
          fail(loc(t.pos),
               "NOT applies to a whole condition; put it in parentheses, as in "
               "(NOT &a)");
        // Peek at the raw text, so that a word followed by something unlexable (`C:\x`) is
        // reported as the word.
        size_t next = pos_;
        while (next < text_.size() && is_space(text_[next])) ++next;
        if (next < text_.size() && text_[next] == '(') {
          advance();
          return parse_call(t);
        }
        if (bare_words_) {
          if (const int node = bare_text(t); node >= 0) return node;
        }
        fail(loc(t.pos), fmt::format("{} is not a value: put text in double quotes, write a "
                                     "variable as &name, or call a function as NAME(x)",
                                     describe(t)));
      }
      default:
        missing_value();
    }
  }

  static bool is_comparison(Tok k) {
    ExprOp op;
    return comparison(k, &op);
  }

  // Unquoted words right beside a comparison (`&answer = Cancel`, `Yes <> &a`) are text,
  // as the handbook allows strings without quotation marks; elsewhere a word stays an
  // error, so a forgotten `&` or quote is not silently taken as text. The words run to the
  // next token that is not a plain word; their spacing is kept. -1: not bare text here.
  int bare_text(const Token& first) {
    const bool after_comparison = is_comparison(prev_.kind);
    const size_t saved_pos = pos_;
    const Token saved_tok = tok_, saved_prev = prev_;
    Token last = first;
    advance();
    while (tok_.kind == Tok::Word && !is_keyword(tok_, "AND") && !is_keyword(tok_, "OR") &&
           !is_keyword(tok_, "MOD") && !is_keyword(tok_, "NOT")) {
      size_t next = pos_;
      while (next < text_.size() && is_space(text_[next])) ++next;
      if (next < text_.size() && text_[next] == '(') break;  // a call: not part of the text
      last = tok_;
      advance();
    }
    if (!after_comparison && !is_comparison(tok_.kind)) {
      pos_ = saved_pos;
      tok_ = saved_tok;
      prev_ = saved_prev;
      return -1;
    }
    const int node = add(ExprOp::Text, first.pos);
    set_text(node, text_.substr(first.pos, last.pos + last.len - first.pos));
    return node;
  }

  std::string_view text_;
  const SourceLoc& at_;  // the location of text[0] (the caller's: it outlives the parse)
  std::int32_t base_;
  size_t pos_;
  int nesting_;
  bool bare_words_;  // unquoted words beside a comparison are text (IF tests)
  Token tok_, prev_;
  Scratch own_;
  Scratch& s_;
  std::vector<Proto>& protos_;
  std::string& strings_;
  std::vector<int>& arg_index_;
  std::vector<std::vector<Accessor>> paths_;
};

}  // namespace

const FuncInfo* find_function(std::string_view upper_name) {
  const size_t n = upper_name.size();
  if (n == 0) return nullptr;
  for (const FuncInfo& f : kFunctions) {  // lengths first: few names share one
    if (f.name.size() != n || f.name[0] != upper_name[0]) continue;
    size_t k = 1;  // names are short: a loop, not a memcmp call
    while (k < n && f.name[k] == upper_name[k]) ++k;
    if (k == n) return &f;
  }
  return nullptr;
}

std::string_view function_name(ExprFunc f) {
  for (const FuncInfo& info : kFunctions)
    if (info.id == f) return info.name;
  return "?";
}

ExprCheckOnly::ExprCheckOnly() : was_(t_check_only) {
  t_check_only = true;
}

ExprCheckOnly::~ExprCheckOnly() {
  t_check_only = was_;
}

ExprParse parse_expression(std::string_view text, const SourceLoc& at, bool bare_words) {
  ExprParse out;
  try {
    out.expr = Parser(text, at, 0, 0, bare_words, &thread_scratch()).parse_whole();
  } catch (const GantryError& e) {
    out.error = e.diagnostic();
  }
  return out;
}

std::optional<LValue> parse_lvalue(std::string_view text, const SourceLoc& at,
                                   std::optional<Diagnostic>* error) {
  try {
    return Parser(text, at, 0, 0).parse_lvalue();
  } catch (const GantryError& e) {
    if (error) *error = e.diagnostic();
    return std::nullopt;
  }
}

}  // namespace gantry
