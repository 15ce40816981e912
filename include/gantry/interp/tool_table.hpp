// The tool table: LinuxCNC's text file, one tool a line (`T1 P1 D0.25 Z+1.5 ;comment`),
// read, changed by G10 L1/L10/L11 and written back (docs/gcode.md, "Tool table").
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "gantry/core/diagnostic.hpp"  // SourceLoc

namespace gantry {

struct ToolEntry {
  int number = 0;                  // T
  int pocket = 0;                  // P
  std::array<double, 9> offset{};  // X Y Z A B C U V W, machine units (degrees for A B C)
  double diameter = 0;             // D
  double front_angle = 0;          // I (lathes)
  double back_angle = 0;           // J (lathes)
  int orientation = 0;             // Q (lathes), 0-9
  std::string comment;             // after the `;`, without it
  double length() const { return offset[2]; }
};

// The letters of ToolEntry::offset, in order.
inline constexpr std::string_view kToolOffsetLetters = "XYZABCUVW";

class ToolTable {
 public:
  // No file: every tool exists, with zero offsets and diameter until G10 L1 gives some
  // (kept in memory only).
  ToolTable() = default;

  // The file's path ("" for the implicit table) and the text it was read from.
  const std::string& path() const { return path_; }
  bool implicit() const { return path_.empty(); }
  const std::string& source_text() const { return source_; }

  // Tool `number`'s entry; nullptr when a table read from a file has no such tool (the
  // implicit table has every tool: a zero entry).
  const ToolEntry* find(int number) const;
  // The entry to change (G10 L1): added for the implicit table, nullptr when the file's
  // table has no such tool. Marks it changed, so text() writes it in the standard form.
  ToolEntry* change(int number);

  const std::vector<ToolEntry>& tools() const { return tools_; }

  // The file's text: lines of tools not changed exactly as they were read, comments and
  // blank lines kept, changed tools in the standard form (format_tool_line).
  std::string text() const;

  // Every length (X Y Z U V W, D) times `k` (a change of the machine's units).
  void scale(double k);

  // Reads `text` (the file at `path`); a malformed line is a GantryError located at
  // path:line:column saying what to write instead.
  static ToolTable parse(std::string_view text, const std::string& path);

 private:
  struct Line {
    std::string text;  // as read, end of line excluded
    int tool = -1;     // index into tools_, or -1: a comment or blank line
    bool changed = false;
  };
  std::string path_;
  std::string source_;
  std::vector<ToolEntry> tools_;
  std::vector<Line> lines_;
  bool final_newline_ = true;
};

// `T1 P1 D+0.25 Z+1.5 ;comment`: T and P always, then D X Y Z A B C U V W I J Q where not
// 0, each number with its sign in its shortest exact form (LinuxCNC reads it back).
std::string format_tool_line(const ToolEntry& t);

// Reads the table at `path`: a GantryError naming the path when it is missing or cannot be
// read (located at `need`, the line that needed the table, when given), or for a bad line.
ToolTable load_tool_table(const std::string& path, const SourceLoc& need = {});

// `table` as the file at `path` is now: read again when an editor changed it since `table`
// was read (or it was read from another path); located at `loc` as load_tool_table.
void refresh_tool_table(ToolTable& table, const std::string& path, const SourceLoc& loc);

// Writes `changed` to its file atomically, then makes it the table as written (re-read from
// its own text); false with `why` when the write failed, the file and `changed` untouched.
bool save_tool_table(ToolTable& changed, std::string* why);

class CommandContext;
// VC changed the cutter's diameter to `diameter`: with a tool table file configured and a tool
// (not T0) in the spindle, it becomes that tool's D in the file (tool_table_cutter.cpp), the
// other lines as they were; a check or a preview changes the table in memory only.
void cutter_to_tool_table(CommandContext& ctx, double diameter, const SourceLoc& loc);
// An OpenSBP tool change (&Tool = n, then C9): tool `number` is in the spindle from here on,
// and with a tool table file configured its D, when it gives one, becomes VC's diameter
// (M6's rule); a tool the file does not list is a warning and keeps VC's.
void tool_into_spindle(CommandContext& ctx, int number, const SourceLoc& loc);

}  // namespace gantry
