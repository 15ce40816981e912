// Friendly Motion (U.S. Laser) text to commands, one physical line at a time: pure, no I/O
// (docs/friendlymotion.md). A line holds several space-separated commands that run left to
// right; each command is one token (`X1Y1` one interpolated move, `X1 Y1` two moves).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "gantry/core/diagnostic.hpp"  // SourceLoc, Diagnostic

namespace gantry {

// A numeric argument compiled into postfix steps: `5*(3+2)` is 5, 3, 2, +, *. Variables are
// read when it runs, so a loop reads its text once.
struct FmStep {
  enum class Op : std::uint8_t {
    Number,  // push `number`
    Var,     // push V[index]
    Neg,
    Add,
    Sub,
    Mul,
    Div,
    Pow,
    Sin,
    Cos,
    Tan,
    Asin,
    Acos,
    Atan  // the top value's function, in degrees
  };
  Op op = Op::Number;
  int index = 0;
  double number = 0;
  int column = 0;  // 1-based, of the step's text (a division's `/`, a function's name)
};

struct FmExpr {
  std::vector<FmStep> steps;
  int column = 0;  // 1-based, its first character
  std::string text;
  // A plain number literal (no variable, no operator): its value.
  std::optional<double> literal() const {
    if (steps.size() == 1 && steps[0].op == FmStep::Op::Number) return steps[0].number;
    return std::nullopt;
  }
};

// What a command is. The command table (fm_commands) names and documents each.
enum class FmOp : std::uint8_t {
  Sequence,      // Nxxx (first on its line): a target of J and K
  Move,          // X, Y, Z, A, B, C words in one token; with I and J an arc; R repeats an arc
  Feed,          // F, FX, FY, FC
  G,             // a G code: `code` and its tail
  M,             // an M code: `code` (or `expr` for MVnn), `axis` for M98X / M99Y
  Jump,          // J [Mxxx | Vxx] Nxxx
  Call,          // K [Mxxx | Vxx] Nxxx [R#]
  Assign,        // Vxx=expression
  Prompt,        // Vxx=?  Vxx=?(text)   @n=?  (a string)
  ShowVariable,  // Vxx
  SetString,     // @n=text, An=text
  ShowString,    // @n
  Relay,         // PA#, PB#, PD
  Analog,        // Sf#, SC#
};

// One G58 / G25 element: quoted text, a variable's value, or a string's contents.
struct FmShowItem {
  enum class Kind : std::uint8_t { Text, Variable, String } kind = Kind::Text;
  std::string text;
  int index = 0;
};

struct FmCommand {
  FmOp op = FmOp::Sequence;
  int column = 0;  // 1-based, the command's first character
  int code = 0;    // G or M code; variable or string index; sequence number; probe number
  char axis = 0;   // F: X Y C or 0 (X and Y); G68: X, Y or 0; M98/M99: X, Y or 0; G60: X A C;
                   // P: A, B or D; S: F or C; J/K condition: 'M' (input), 'V' (variable), 0
  int cond = 0;    // J/K: the M-function or variable tested
  int target = 0;  // J/K: the sequence number
  // Expression indices into FmLine::exprs (-1: none). Move: X Y Z A B C, then I J, then R.
  std::array<int, 6> axes{-1, -1, -1, -1, -1, -1};
  int i = -1, j = -1, repeat = -1;
  int expr = -1;                  // F, G4, G19, G68, V=, M (MVnn), S: its value
  bool quick = false;             // G4 ... Q
  std::vector<int> list;          // G26's values; G27's variable indices
  int record = -1;                // G27 R
  std::string text;               // G10/G16 text; G20/G21/G23 file name; prompt; string value
  bool has_text = false;          // G16"..." given (G16 alone prompts); prompt text given
  int string_index = -1;          // G20@n / G23@n
  std::vector<FmShowItem> items;  // G58 / G25
};

struct FmLine {
  std::vector<FmCommand> commands;
  std::vector<FmExpr> exprs;
  std::optional<int> sequence;  // the line's N number, when it has one
};

// Reads one line into `out` (cleared first). Returns false with `error` set (located at its
// column) when the line is not Friendly Motion; a blank or comment line gives no commands.
bool parse_fm_line(std::string_view line, const std::shared_ptr<const std::string>& file,
                   int line_no, FmLine* out, Diagnostic* error);

// The command table: every command Friendly Motion has, what it does here, and whether Gantry
// runs it. The parser's code lists, `gantry help fm` and docs/friendlymotion.md's command
// table come from it (a test keeps the page in step).
struct FmCommandInfo {
  std::string_view code;     // "G4", "M100-M131", "X", "@"
  std::string_view name;     // the manual's name
  std::string_view form;     // how it is written: "G4X# [Q]"
  std::string_view summary;  // what Gantry does with it
  bool runs = true;          // false: refused with a located error naming it and why
};
const std::vector<FmCommandInfo>& fm_commands();
// `gantry help fm`: the table as text, one command a line.
std::string fm_command_list();
// The table as docs/friendlymotion.md's command table (Markdown), between its markers.
std::string fm_commands_markdown();
// The G and M codes the parser knows (longest match against these: `G68.1` is G68 `.1`).
bool fm_is_g_code(int code);
bool fm_is_m_code(int code);

}  // namespace gantry
