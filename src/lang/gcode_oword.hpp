// The O-word part of a G-code line (docs/gcode.md, "O-words"). Private to src/lang.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "gantry/lang/gcode.hpp"
#include "gantry/lang/script.hpp"  // Cursor

namespace gantry::gcode_oword {

// Reads the O-word starting at line[at] (the 'O' or 'o') and the rest of the line into
// out->oword, its expressions appended to out->exprs. Throws GantryError at the column of
// anything that is not an O-word line: an O-word line holds the O-word, its keyword, its
// bracketed values and comments, nothing else.
void read(std::string_view line, size_t at, const SourceLoc& line_loc, GcodeBlock* out);

// Whether the text after `M98` at line[at] (spaces skipped) is a file name (WinCNC's
// `M98 Texas.tap`) rather than words (`M98 P100 L2`); *end receives the name's end.
bool file_name_at(std::string_view line, size_t at, size_t* end);

}  // namespace gantry::gcode_oword

namespace gantry {

class Script;

// The load pass over a G-code file's O-words: pairs every block's lines, records where each
// jumps (Script's OwordLink) and reports what LinuxCNC refuses and can be seen without running
// the file: an end with nothing open or of another block, a block never closed, a subroutine
// defined twice or inside another, return outside a subroutine, break/continue of no loop.
class OwordIndexer {
 public:
  explicit OwordIndexer(Script& script) : s_(script) {}
  // One line: `at` its start, `next` the line after it.
  void add(const GcodeBlock& b, Cursor at, Cursor next);
  void finish();

 private:
  struct Open {
    OwordKind kind;
    std::string name;
    Cursor at, next;
    SourceLoc loc;
    std::vector<size_t> branches;  // if: the offsets of its if/elseif/else lines
    bool had_else = false;
    std::vector<size_t> breaks, continues;
  };
  void error(const SourceLoc& loc, std::string what);
  SourceLoc loc(const Cursor& at, int column) const;
  bool close(const GcodeOword& o, OwordKind opener, const SourceLoc& at);
  void declare(const GcodeOword& o, const SourceLoc& at);
  Script& s_;
  std::vector<Open> open_;
  std::optional<std::string> sub_;  // the subroutine being defined
  // Control-flow numbers used in the current scope (the main program or one subroutine), and
  // where: LinuxCNC refuses one number for two blocks.
  std::unordered_map<std::string, int> used_;
  std::unordered_map<std::string, int> main_used_;
};

}  // namespace gantry
