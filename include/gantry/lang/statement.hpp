// The statements of a part file, each with its source location.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "gantry/core/diagnostic.hpp"  // SourceLoc, Diagnostic
#include "gantry/lang/expression.hpp"  // Expr, LValue
#include "gantry/lang/fm.hpp"          // FmLine
#include "gantry/lang/gcode.hpp"       // GcodeBlock

namespace gantry {

// A parameter or argument as written. When the whole text is one expression, `expr` holds
// it; otherwise the text is a bare word (a file name, `T`, `Material Surface`) and
// `expr_error` says why it is not an expression, for commands that needed a number.
struct Arg {
  std::string text;              // trimmed
  SourceLoc loc;                 // its first character (a blank: just after its comma)
  std::optional<double> number;  // a plain number literal, kept without an expression tree
  std::optional<Expr> expr;
  std::optional<Diagnostic> expr_error;
  bool blank() const { return text.empty(); }
  bool is_expression() const { return number || expr; }
};

struct Statement;
using StatementPtr = std::shared_ptr<const Statement>;

// A two-letter command such as `MX, 5.3` (code upper-cased), or a custom cut `C9`.
struct CommandStmt {
  std::string code;
  std::vector<Arg> args;
};
// Custom cuts are numbered 0 to 9999 (FabMo's macros pass 200).
constexpr int kMaxCustomCutDigits = 4;
constexpr int kMaxCustomCut = 9999;
struct CustomCutStmt {  // C<n> or C#, n: runs the macro file numbered n
  int number = 0;
  std::optional<Arg> computed;  // C#, &n: the number, an expression evaluated when it runs
  std::vector<Arg> args;
};
struct LabelStmt {
  std::string name;  // upper case, inner spaces single
};
struct AssignStmt {  // &x = e, $x.y = e; `:=` assigns only when the variable is undefined
  LValue target;
  Arg value;
  bool weak = false;
};
struct JumpStmt {  // GOTO / GOSUB label
  std::string label;
  bool gosub = false;
  SourceLoc label_loc;
};
struct ReturnStmt {};
struct EndStmt {
  enum class Scope { File, All, Exit } scope = Scope::File;  // END, ENDALL, EXIT SHOPBOT
  std::optional<Arg> message;                                // FabMo: END "why"
};
struct IfStmt {
  Expr test;
  StatementPtr action;
};
struct OnInputStmt {  // ON INPUT(switch, condition) [action]; no action clears
  Expr input, condition;
  StatementPtr action;
};
struct PauseStmt {
  enum class Kind { Operator, Timed, Until } kind = Kind::Operator;
  std::optional<Arg> value;          // Timed: seconds or a message (decided by its value's type)
  std::optional<Expr> input, state;  // Until
  std::optional<LValue> into;        // PAUSE "message", &var
  std::vector<std::pair<std::string, Arg>> options;  // FabMo: OKTEXT=..., CANCELTEXT=...
};
struct PrintStmt {           // PRINT items / WRITE #n items / PRINT #n items
  std::optional<Expr> file;  // the #n, for WRITE
  std::vector<Arg> items;
  bool comma_mode = true;
  bool newline = true;
};
struct InputStmt {  // INPUT prompt [; | :&default,] &vars   or   INPUT #n, &vars
  std::optional<Expr> file;
  std::optional<Arg> prompt;
  std::optional<LValue> default_var;
  std::vector<LValue> vars;
};
struct MsgBoxStmt {
  Arg body, buttons, title;
};
struct DialogStmt {  // FabMo: DIALOG message, OKTEXT=..., CANCELTEXT=...
  Arg message;
  std::vector<std::pair<std::string, Arg>> options;
};
struct FailStmt {  // FabMo: FAIL message
  Arg message;
};
struct OpenStmt {
  enum class Mode { Input, Output, Append } mode = Mode::Input;
  Arg path;
  Expr number;
};
struct CloseStmt {
  std::optional<Expr> number;
};
struct ShellStmt {
  Arg command;
  std::vector<Arg> options;
};
struct WarningOffStmt {};
struct PlayStmt {
  Arg path;
};
struct GcodeStmt {  // a G-code block: a line of a G-code file, or a G-code line in OpenSBP
  GcodeBlock block;
};
struct FmStmt {  // a line of a Friendly Motion file: its commands, run left to right
  FmLine line;
};
struct RegistryStmt {  // SetUsrVal, GetUsrVal, ... (name upper case)
  std::string name;
  Arg arg;
  std::optional<LValue> target;  // Get* statements
};

using StatementBody =
    std::variant<CommandStmt, CustomCutStmt, LabelStmt, AssignStmt, JumpStmt, ReturnStmt, EndStmt,
                 IfStmt, OnInputStmt, PauseStmt, PrintStmt, InputStmt, MsgBoxStmt, DialogStmt,
                 FailStmt, OpenStmt, CloseStmt, ShellStmt, WarningOffStmt, PlayStmt, RegistryStmt,
                 GcodeStmt, FmStmt>;

struct Statement {
  SourceLoc loc;  // where the statement starts
  StatementBody body;
};

}  // namespace gantry
