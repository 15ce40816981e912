// The statements a part file is made of, each with its source location.
#pragma once

#include <string>
#include <variant>
#include <vector>

#include "gantry/core/diagnostic.hpp"  // SourceLoc, Diagnostic

namespace gantry {

// One comma-separated parameter as written; empty text means "left blank".
struct Param {
  std::string text;  // trimmed
  SourceLoc loc;     // column of its first character (a blank: just after its comma)
  bool blank() const { return text.empty(); }
};

// A two-letter command such as `MX, 5.3`; the code is upper-cased.
struct CommandStmt {
  std::string code;
  std::vector<Param> params;
};

struct LabelStmt {  // `NAME:`; a jump target
  std::string name;
};

struct EndStmt {};  // END: the file stops here

using StatementBody = std::variant<CommandStmt, LabelStmt, EndStmt>;

struct Statement {
  SourceLoc loc;  // where the statement starts
  StatementBody body;
};

// A parsed file: its statements, or the diagnostics of every line that could not be read.
struct Program {
  std::shared_ptr<const std::string> file;
  std::vector<Statement> statements;
  std::vector<Diagnostic> errors;
  bool ok() const { return errors.empty(); }
};

}  // namespace gantry
