// G-code text to blocks, one physical line at a time: pure, no I/O (docs/gcode.md).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "gantry/core/diagnostic.hpp"  // SourceLoc, Diagnostic

namespace gantry {

// One word of a block: a letter and its value. The value is a plain number, or an
// expression (`[...]`, `#n`, a function) compiled when the line is read and evaluated when the
// block runs, or nothing at all (WinCNC's bare axis letters, `G28 Z`).
struct GcodeWord {
  char letter = 0;  // upper case
  double number = 0;
  int expr = -1;  // index into GcodeBlock::exprs, or -1
  bool bare = false;
  int column = 0;  // 1-based, the letter's
};

// `#n = value` or `#<name> = value`: applied after every word of the block is read.
struct GcodeAssign {
  std::string target;    // "5", "<name>" (name lower case, spaces removed) or "[expression]"
  int param = 0;         // `#5 = v`: 5 (0 for the other targets)
  int target_expr = -1;  // `#[expression] = v`: the target's number, index into exprs
  double number = 0;
  int expr = -1;  // index into GcodeBlock::exprs, or -1
  int column = 0;
};

// A comment that speaks: (MSG, text) prints text as written; (PRINT, text) and (DEBUG, text)
// print it with its parameters' values substituted; (ABORT, text) stops the program with the
// substituted text as a located error (docs/gcode.md, "Blocks").
enum class GcodeMessage : char { None, Msg, Print, Debug, Abort };

// An O-word line (docs/gcode.md, "O-words"): `o100 if [#1 GT 2]`, `o<name> call [1] [2]`, or a
// Fanuc program number `O1234` alone (kind Program).
enum class OwordKind : std::uint8_t {
  None,
  Sub,
  Endsub,
  Call,
  Return,
  If,
  Elseif,
  Else,
  Endif,
  While,
  Endwhile,
  Do,
  Repeat,
  Endrepeat,
  Break,
  Continue,
  Program
};
struct GcodeOword {
  OwordKind kind = OwordKind::None;
  std::string name;        // `o100`: "100" (leading zeros dropped); `o<Name>`: "name"
  int column = 0;          // the O's, 1-based
  int keyword_column = 0;  // the keyword's (the O's for Program)
  std::vector<int> args;   // indices into GcodeBlock::exprs: a condition, count, value, arguments
};

// The keyword as written in a program (`endsub`), for messages.
const char* oword_keyword(OwordKind kind);

// An expression is compiled when its line is read, into steps that run on a stack of values
// (postfix order: `[#1 + 2] * 3` is #1, 2, +, 3, *), so a loop that runs a line a million times
// reads its text once (docs/gcode.md, "Speed").
struct GcodeStep {
  enum class Op : std::uint8_t {
    Number,   // push `number`
    Param,    // push #index (a number known when the line is read)
    ParamAt,  // replace the top n by #n (`##1`, `#[#1 + 1]`): n checked when the block runs
    Named,    // push #<names[index]>
    Exists,   // push 1 when #<names[index]> has a value, else 0
    Neg,
    Abs,
    Acos,
    Asin,
    Cos,
    Exp,
    Fix,
    Fup,
    Ln,
    Round,
    Sin,
    Sqrt,
    Tan,   // the top value's function
    Atan,  // ATAN[y]/[x]: two values
    Pow,
    Mul,
    Div,
    Mod,
    Add,
    Sub,
    Eq,
    Ne,
    Gt,
    Ge,
    Lt,
    Le,
    And,
    Or,
    Xor  // two values
  };
  Op op = Op::Number;
  std::uint32_t offset = 0;  // of the step's text from the expression's first character
  std::int32_t index = 0;
  double number = 0;
};
struct GcodeCode {
  std::uint32_t begin = 0, end = 0;  // the expression's steps in GcodeBlock::steps
  std::uint32_t depth = 0;           // the most values it stacks
};

struct GcodeBlock {
  std::vector<GcodeWord> words;  // in the order written; N line numbers are left out
  std::vector<GcodeAssign> assigns;
  std::vector<std::string> exprs;      // expression texts; each starts at exprs_column
  std::vector<int> exprs_column;       // 1-based column of each expression's first character
  std::vector<GcodeCode> codes;        // each expression's steps (none for WinCNC's {braces})
  std::vector<GcodeStep> steps;        // every expression's steps, one expression after another
  std::vector<std::string> names;      // the named parameters steps read (lower case)
  std::optional<std::string> message;  // the text after the comma
  GcodeMessage message_kind = GcodeMessage::None;
  int message_column = 0;              // 1-based, the comment's '('
  std::optional<std::string> bracket;  // the first [comment]'s text: WinCNC's G4 prompt
  GcodeOword oword;                    // kind None: no O-word on this line
  // WinCNC's `M98 file.tap`: the file named after M98 (or M98.1), and its column.
  std::string call_file;
  int call_file_column = 0;
  std::uint8_t flow_m = 0;  // 98 or 99: the block holds M98 or M99 (a subprogram's call, end)
  bool empty() const {
    return words.empty() && assigns.empty() && !message && oword.kind == OwordKind::None &&
           call_file.empty();
  }
  void clear() {
    words.clear();
    assigns.clear();
    exprs.clear();
    exprs_column.clear();
    codes.clear();
    steps.clear();
    names.clear();
    message.reset();
    message_kind = GcodeMessage::None;
    message_column = 0;
    bracket.reset();
    oword.kind = OwordKind::None;
    call_file.clear();
    flow_m = 0;
  }
};

// Reads one line into `out` (cleared first, its storage reused: a plain block such as
// `G1 X1.5 Y2 Z-.1` allocates nothing once the vectors have grown). Returns false with
// `error` set when the line is not G-code; a line of only comments or `%` gives an empty
// block.
bool parse_gcode_block(std::string_view line, const std::shared_ptr<const std::string>& file,
                       int line_no, GcodeBlock* out, Diagnostic* error);

// Numbered (`#5`) and named (`#<depth>`) parameters, for expressions.
class GcodeParameters {
 public:
  virtual ~GcodeParameters() = default;
  // The value of #n (0 to 5602; one never set reads 0). `at`: where an expression reads it
  // (some of the machine's, above #5000, cannot be read at every moment); null when a
  // message shows it.
  virtual double numbered(int n, const SourceLoc* at) const = 0;
  // The value of #<name> (lower case), or null when it has none.
  virtual const double* named(std::string_view name) const = 0;
};

// Appends the expression `text` (`[1 + #2]`, `#5`, `SIN[30]`, WinCNC's `{TH1+2}`) to `b`,
// compiled, and returns its index. `at` is where the text starts: a syntax error is located
// from there. LinuxCNC's operators (** * / MOD + - EQ NE GT GE LT LE AND OR XOR) and functions
// (ABS ACOS ASIN ATAN COS EXP FIX FUP ROUND LN SIN SQRT TAN EXISTS), angles in degrees.
int add_gcode_expression(GcodeBlock* b, std::string_view text, const SourceLoc& at);

// The value of expression `expr` of `b` (not a {brace}, which the WinCNC dialect evaluates),
// with `params`. A value outside a function's domain, a division by zero, a parameter number
// out of range or a named parameter with no value is an error at its column of `line`.
double evaluate_gcode_expression(const GcodeBlock& b, int expr, const SourceLoc& line,
                                 const GcodeParameters& params);

// `text` with each parameter reference replaced by its value as LinuxCNC's (DEBUG,...) does:
// `#5` (#0 to #5601, digits only) and `#<name>` (spaces dropped, any case) become the value
// with six decimals (`2.500000`), a parameter that has no value becomes `######`, and any
// other `#` stays as written.
std::string substitute_gcode_parameters(std::string_view text, const GcodeParameters& params);

// Whether a line of an OpenSBP file is G-code (docs/gcode.md, "G-code in OpenSBP files"):
// it starts with G or N followed by a digit, or, on a line without commas, with M and two
// or more digits or M and a digit followed by a G-code word (`M30`, `M3 S12000`; `M3, 1, 2`,
// `M23, 3` and `M5` stay OpenSBP).
bool is_gcode_line(std::string_view line);

// Whether a file is G-code: by its extension (.nc .tap .gcode .ngc, any case), or, for any
// extension but .sbp, by its first line that is not blank: `%`, `(`, `;` or a G-code line.
bool is_gcode_file(std::string_view path, std::string_view first_text);

}  // namespace gantry
