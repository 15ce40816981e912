// Friendly Motion's data files, G20-G27: one output file and one input file open at a time,
// plain text, `.dat` by default (docs/friendlymotion.md, "Data files, scribed text and the
// display"). The executor evaluates the commands' expressions and hands the values here; this
// keeps the two files, writes records, and reads values back by record. Files are opened
// through the FileSystem the interpreter uses at that moment (a check's sandbox, a start
// line's quiet sandbox, the disk; a test's temporary folder), given to each open; an open file
// stays where it was opened. Where a name lands, and whether the part file may reach it, the
// executor decides (Resolve).
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <ostream>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "gantry/core/diagnostic.hpp"    // SourceLoc
#include "gantry/interp/file_reach.hpp"  // FileAccess

namespace gantry {

class FileSystem;

// The name G20, G21 or G23 gives (or the string @n holds), as the file to open: `.dat` added
// when its last part has no extension (`PARTS` -> `PARTS.dat`, `log.txt` stays). An empty
// name is an error at `loc`.
std::string fm_data_file_name(std::string_view name, const SourceLoc& loc);

class FmDataFiles {
 public:
  // Turns a data file's name (fm_data_file_name's) into the path to open, throwing a located
  // error for one the part file may not reach. The executor passes
  // CommandContext::reachable_path, which finds a relative name in the parts folder (beside
  // the part file, or where FS points): Gantry's stand-in for the manual's /ncfiles.
  using Resolve =
      std::function<std::string(const std::string& name, FileAccess access, const SourceLoc& loc)>;

  // The most values one G26 writes and one G27 reads.
  static constexpr std::size_t kMaxValues = 5;

  explicit FmDataFiles(Resolve resolve);

  // G20: creates the output file, emptying one that exists. G21: opens it to append, creating
  // it when missing. Either is an error while an output file is open (G22 closes it).
  void create_output(FileSystem& files, std::string_view name, const SourceLoc& loc);
  void append_output(FileSystem& files, std::string_view name, const SourceLoc& loc);
  // G22. An error when no output file is open.
  void close_output(const SourceLoc& loc);
  // G23: opens the input file, read as it is now; reading starts at its beginning. A missing
  // or unreadable file is an error saying why. An error while an input file is open.
  void open_input(FileSystem& files, std::string_view name, const SourceLoc& loc);
  // G24. An error when no input file is open.
  void close_input(const SourceLoc& loc);
  // The job's end: both files closed, without complaint when none is open.
  void close_all();

  // G25: one line of text (fm_display_line's) and CR/LF.
  void write_text(std::string_view line, const SourceLoc& loc);
  // G26: 1 to 5 values, four decimals each (fm_number_text), separated by commas, then CR/LF:
  // `1.5000,-2.0000`. A value that is not finite is an error naming its place.
  void write_values(std::span<const double> values, const SourceLoc& loc);
  // Both flush what they wrote before returning: a job stopped later has lost nothing written.

  // G27: `count` (1 to 5) values read from record `record` (a line, from 1) when given, else
  // from where the last G27 stopped (a file just opened: its start). Values are numbers
  // separated by commas, blanks or line ends; reading stops right after the last one needed,
  // so the next G27 goes on in the same record. A record that is not a whole number from 1,
  // a record past the file's last, reading past its end, or text that is not a number is an
  // error naming the file, record and column. Nothing is read when it fails.
  std::vector<double> read_values(std::optional<double> record, std::size_t count,
                                  const SourceLoc& loc);

  bool output_open() const { return out_ != nullptr; }
  bool input_open() const { return in_.has_value(); }
  const std::string& output_path() const { return out_path_; }
  const std::string& input_path() const { return in_path_; }
  // Where the next G27 without R reads: its record (from 1) and column (from 1).
  std::size_t input_record() const;
  std::size_t input_column() const;

 private:
  void open_output(FileSystem& files, std::string_view name, bool append, const SourceLoc& loc);
  std::ostream& output(const char* command, const SourceLoc& loc);
  void flushed(const char* command, const SourceLoc& loc);
  const std::vector<std::size_t>& record_starts();
  std::size_t record_of(std::size_t pos);

  Resolve resolve_;
  std::shared_ptr<std::ostream> out_;
  std::string out_path_;
  std::optional<std::string> in_;  // the input file's text
  std::string in_path_;
  std::size_t in_pos_ = 0;               // where reading goes on
  std::vector<std::size_t> in_records_;  // each record's first byte, made at the first need
};

}  // namespace gantry
