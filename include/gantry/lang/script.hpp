// A loaded part file: its text, its label index, and the errors one pass over it finds.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "gantry/core/diagnostic.hpp"  // Diagnostic
#include "gantry/lang/parser.hpp"      // LineParse

namespace gantry {

class ScriptFile;  // src/lang/script_file.hpp
class LabelIndex;  // src/lang/label_index.hpp

// The start of a physical line.
struct Cursor {
  size_t offset = 0;
  int line = 1;
};

// Where an O-word control line of a G-code file leads, found when the file is loaded
// (docs/gcode.md, "O-words"), so that every jump is one lookup:
//   if, elseif: `jump` the next branch line (elseif, else or endif); elseif, else: `end` the
//   line after endif. while (opening a loop), repeat: `jump` the line after the loop's end.
//   endwhile, continue: `jump` the line that tests the condition. endrepeat: `jump` the first
//   line of the body, `end` the repeat line (its count's key). do: nothing. while (closing a
//   do): `jump` the first line of the body. break: `jump` the line after the loop. sub: `end`
//   the line after endsub.
struct OwordLink {
  Cursor jump, end;
  bool closes_do = false;  // a `while` that ends a do-while loop
  bool complete = false;   // its block is closed (else the load pass reported it)
};

// The language a part file is written in: OpenSBP, G-code (docs/gcode.md) or Friendly
// Motion (docs/friendlymotion.md).
enum class Language { OpenSbp, Gcode, FriendlyMotion };
// `--language`'s names: "sbp" (or "opensbp"), "gcode", "fm" (or "friendlymotion"); nullopt
// for any other.
std::optional<Language> language_named(std::string_view name);
// A file's language by its name and first text: .fm is Friendly Motion, as is a file (not
// .sbp) whose first line that is not blank starts with `!` (a Friendly Motion comment, which
// neither OpenSBP nor G-code has: U.S. Laser's own files are .nc); then is_gcode_file; else
// OpenSBP.
Language file_language(std::string_view path, std::string_view first_text);

// Whether a two-letter code (upper case) names a command. The command table, in a layer above
// this one, answers (CommandTable::is_command); a script loaded with one reports an unknown
// command on every line, whether a run would reach it or not.
using IsCommand = std::function<bool(std::string_view code)>;

// The error for an unknown command: the load pass and the interpreter say the same.
std::string unknown_command_message(std::string_view code);

// Statements are parsed when they are executed, so memory does not grow with the file: a
// script loaded from disk keeps the file open and reads it in 64 KiB blocks (pread), keeping
// the 16 most recently used (1 MiB), plus one entry per label. A line is found by its byte
// offset (Cursor), so a jump or RETURN anywhere in the file costs one lookup, and no read while
// its block is kept: a loop or subroutine far from its caller is read from the disk once.
// Loading makes one pass over every line to index the labels and to find every syntax error,
// duplicate label and jump to a missing label (and, given `is_command`, every unknown command)
// before anything runs.
//
// What runs is what was checked: that pass also records a hash of every 64 KiB block, and
// every later read of a block must give the same hash, the file the same size and
// modification time, or line_at throws (a CAM program writing over the file in place while
// it runs). A file replaced by a new one (rename) is no change: the open file is the old one.
// A block kept in memory is what was read and checked; why the file is not memory-mapped:
// src/lang/script_file.hpp.
class Script {
 public:
  // Reads `path`; an unreadable file gives a script with one error and no text.
  // `language`: the file is read as that language whatever its name (--language).
  static std::shared_ptr<const Script> load(const std::string& path,
                                            const IsCommand& is_command = {},
                                            std::optional<Language> language = std::nullopt);
  static std::shared_ptr<const Script> from_text(std::string text, const std::string& name,
                                                 const IsCommand& is_command = {},
                                                 std::optional<Language> language = std::nullopt);

  const std::shared_ptr<const std::string>& name() const { return name_; }
  const std::vector<Diagnostic>& errors() const { return errors_; }  // all severities
  bool ok() const;                                                   // no errors (warnings ok)
  int line_count() const { return lines_; }
  // A G-code file (by its extension or first line: is_gcode_file): every line is a block.
  bool gcode() const { return gcode_; }
  // A Friendly Motion file: every line is a FmStmt; labels are its sequence numbers ("N50",
  // at the line itself: the rest of that line runs).
  bool fm() const { return fm_; }
  Language language() const {
    return fm_ ? Language::FriendlyMotion : gcode_ ? Language::Gcode : Language::OpenSbp;
  }

  Cursor start() const { return {text_start_, 1}; }
  bool at_end(Cursor c) const { return c.offset >= size_ || c.offset >= program_end_; }
  // The line at `c` (without its terminator); `next` receives the following line's cursor.
  // The view is valid until the next call on this script. Throws GantryError when the file
  // on disk is no longer the one loaded.
  std::string_view line_at(Cursor c, Cursor* next) const;
  // The physical line just above `c`, if any (same validity).
  std::optional<std::string_view> line_before(Cursor c) const;
  // The line after `NAME:` (name upper case, inner spaces single), or nullopt.
  std::optional<Cursor> label(std::string_view name) const;

  // G-code O-words: the links of the O-word line starting at `offset` (null when it has none),
  // the first body line of subroutine `name` (`o<name> sub`, `o100 sub`: "100") and of the
  // Fanuc subprogram `O<number>`.
  const OwordLink* oword_link(size_t offset) const {
    auto it = oword_links_.find(offset);
    return it == oword_links_.end() ? nullptr : &it->second;
  }
  std::optional<Cursor> gcode_sub(const std::string& name) const;
  std::optional<Cursor> gcode_program(const std::string& number) const;

  // The line at `c` through the general parser. Parses are kept in a small direct-mapped
  // cache, so the body of a loop or subroutine is parsed once rather than on every pass,
  // while memory stays bounded.
  std::shared_ptr<const LineParse> parse(Cursor c, Cursor* next) const;
  // The line at `c` (its `text` and `next` as line_at gave them) read by
  // parse_common_statement into `out`, without a LineParse: true when it is one of those
  // shapes and not in the parse cache (false: take it from parse()). A line read so twice
  // while its cache slot holds nothing else (a loop's) is put in the cache as parse() would,
  // so a loop's lines are still parsed once.
  bool read_common(Cursor c, std::string_view text, Cursor next, Statement* out) const;

  // The file `path` that this script's job calls (FP, C#, a custom cut), loaded by `load`
  // the first time and kept: a check and the run after it read one loaded file, so the
  // called file's bytes are verified against the check's too. Only files read from disk are
  // kept (a file the check wrote itself, in its sandbox, is not the run's).
  std::shared_ptr<const Script> called(
      const std::string& path, const std::function<std::shared_ptr<const Script>()>& load) const;
  // The job wrote `path` itself: a later call loads what it wrote.
  void forget_called(const std::string& path) const;

  ~Script();
  Script(const Script&) = delete;
  Script& operator=(const Script&) = delete;

 private:
  Script(std::string text, const std::string& name);
  void index(const IsCommand& is_command);
  void index_fm();
  void set_language(std::optional<Language> forced, std::string_view path, std::string_view first);
  // The file's block `n` (ScriptFile::block), or throws, located at `at`: the file changed.
  std::string_view block_or_throw(size_t n, Cursor at) const;
  // The file's bytes [begin, end) in one piece: a view into a block, or a copy in joined_.
  std::string_view bytes(size_t begin, size_t end, Cursor at) const;
  std::string_view file_line_at(Cursor c, Cursor* next) const;

  std::unique_ptr<ScriptFile> file_;  // the open file; null for a script made from text
  size_t size_ = 0;                   // bytes in the file (or text)
  size_t text_start_ = 0;             // past a UTF-8 byte-order mark
  std::string text_;                  // a script made from text: all of it
  mutable std::string joined_;        // a file's line (or lines) across blocks
  std::shared_ptr<const std::string> name_;
  struct CachedParse {
    size_t offset = 0;
    Cursor next;  // the line after it: a hit reads no text
    std::shared_ptr<const LineParse> parse;
    bool seen = false;  // `offset` was read by read_common once, and not kept
  };
  mutable std::vector<CachedParse> cache_;  // kCacheSlots entries once the first line is parsed
  CachedParse& cache_slot(size_t offset) const;
  std::unique_ptr<LabelIndex> labels_;  // OpenSBP labels, Friendly Motion sequence numbers
  std::unordered_map<size_t, OwordLink> oword_links_;
  std::unordered_map<std::string, Cursor> gcode_subs_, gcode_programs_;
  friend class OwordIndexer;
  mutable std::mutex called_m_;
  mutable std::map<std::string, std::shared_ptr<const Script>> called_;
  std::vector<Diagnostic> errors_;
  int lines_ = 0;
  bool gcode_ = false;
  bool fm_ = false;
  // A G-code file opened with `%` ends at the next `%` line: what follows it is not the program.
  size_t program_end_ = SIZE_MAX;
};

}  // namespace gantry
