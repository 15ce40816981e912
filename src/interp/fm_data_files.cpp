// G20-G27, Friendly Motion's data files (docs/friendlymotion.md, "Data files, scribed text and
// the display").
#include "gantry/interp/fm_data_files.hpp"

#include <fmt/format.h>

#include <algorithm>  // upper_bound
#include <charconv>   // from_chars
#include <cmath>      // isfinite, trunc
#include <istream>
#include <iterator>      // istreambuf_iterator
#include <system_error>  // errc

#include "gantry/core/file_problem.hpp"  // kNoSuchFile
#include "gantry/interp/file_system.hpp"
#include "gantry/interp/fm_display.hpp"  // fm_number_text

namespace gantry {
namespace {

// What separates two values in a data file.
bool separator(char c) {
  return c == ',' || c == ' ' || c == '\t' || c == '\r' || c == '\n';
}

}  // namespace

std::string fm_data_file_name(std::string_view name, const SourceLoc& loc) {
  if (name.empty()) fail(loc, "the data file's name is empty");
  std::string out(name);
  const std::size_t slash = out.find_last_of("/\\");
  const std::size_t base = slash == std::string::npos ? 0 : slash + 1;
  if (base == out.size()) fail(loc, fmt::format("{} names a folder, not a data file", out));
  // A dot that starts the name (".hidden") is not an extension.
  if (out.find('.', base + 1) == std::string::npos) out += ".dat";
  return out;
}

FmDataFiles::FmDataFiles(Resolve resolve) : resolve_(std::move(resolve)) {}

void FmDataFiles::open_output(FileSystem& files, std::string_view name, bool append,
                              const SourceLoc& loc) {
  const char* command = append ? "G21" : "G20";
  if (out_)
    fail(loc, fmt::format("{}: an output file is open already ({}); G22 closes it (one output "
                          "file at a time)",
                          command, out_path_));
  const std::string path = resolve_(fm_data_file_name(name, loc), FileAccess::Write, loc);
  if (const std::string why = files.write_problem(path); !why.empty())
    fail(loc, fmt::format("{}: cannot write {}: {}", command, path, why));
  std::shared_ptr<std::ostream> out = files.open_write(path, append);
  if (!out || !*out) fail(loc, fmt::format("{}: cannot open {} for writing", command, path));
  out_ = std::move(out);
  out_path_ = path;
}

void FmDataFiles::create_output(FileSystem& files, std::string_view name, const SourceLoc& loc) {
  open_output(files, name, false, loc);
}

void FmDataFiles::append_output(FileSystem& files, std::string_view name, const SourceLoc& loc) {
  open_output(files, name, true, loc);
}

void FmDataFiles::close_output(const SourceLoc& loc) {
  if (!out_) fail(loc, "G22: no output file is open to close (G20 or G21 opens one)");
  out_->flush();
  out_.reset();
  out_path_.clear();
}

void FmDataFiles::open_input(FileSystem& files, std::string_view name, const SourceLoc& loc) {
  if (in_)
    fail(loc, fmt::format("G23: an input file is open already ({}); G24 closes it (one input "
                          "file at a time)",
                          in_path_));
  std::string path = resolve_(fm_data_file_name(name, loc), FileAccess::Read, loc);
  // Programs written on DOS name files in any case: `G23LOT` finds lot.dat (an exact name wins).
  const PartFileLookup found = find_part_file(files, path);
  if (!found.error.empty()) fail(loc, fmt::format("G23: {}", found.error));
  if (found.path != path) path = resolve_(found.path, FileAccess::Read, loc);  // may be a link
  if (const std::string why = files.read_problem(path); why == kNoSuchFile)
    fail(loc, fmt::format("G23: there is no file {}", path));
  else if (!why.empty())
    fail(loc, fmt::format("G23: cannot read the data file {}: {}", path, why));
  std::shared_ptr<std::istream> in = files.open_read(path);
  if (!in) fail(loc, fmt::format("G23: cannot read the data file {}", path));
  in_ = std::string(std::istreambuf_iterator<char>(*in), std::istreambuf_iterator<char>());
  in_path_ = path;
  in_pos_ = 0;
  in_records_.clear();
}

void FmDataFiles::close_input(const SourceLoc& loc) {
  if (!in_) fail(loc, "G24: no input file is open to close (G23 opens one)");
  in_.reset();
  in_path_.clear();
  in_records_.clear();
}

void FmDataFiles::close_all() {
  if (out_) out_->flush();
  out_.reset();
  out_path_.clear();
  in_.reset();
  in_path_.clear();
  in_records_.clear();
}

std::ostream& FmDataFiles::output(const char* command, const SourceLoc& loc) {
  if (!out_)
    fail(loc,
         fmt::format("{}: no output file is open (G20 creates one, G21 appends to one)", command));
  return *out_;
}

void FmDataFiles::flushed(const char* command, const SourceLoc& loc) {
  out_->flush();
  if (!*out_)
    fail(loc, fmt::format("{}: writing {} failed (is the disk full?)", command, out_path_));
}

void FmDataFiles::write_text(std::string_view line, const SourceLoc& loc) {
  output("G25", loc) << line << "\r\n";
  flushed("G25", loc);
}

void FmDataFiles::write_values(std::span<const double> values, const SourceLoc& loc) {
  std::ostream& out = output("G26", loc);
  if (values.empty() || values.size() > kMaxValues)
    fail(loc, fmt::format("G26 writes 1 to {} values, not {}", kMaxValues, values.size()));
  std::string text;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i]))
      fail(loc, fmt::format("G26: value {} is not a number ({})", i + 1, values[i]));
    if (i) text += ',';
    text += fm_number_text(values[i]);
  }
  out << text << "\r\n";
  flushed("G26", loc);
}

const std::vector<std::size_t>& FmDataFiles::record_starts() {
  if (in_records_.empty()) {
    const std::string& t = *in_;
    in_records_.push_back(0);
    for (std::size_t i = 0; i < t.size(); ++i)
      if (t[i] == '\n' && i + 1 < t.size()) in_records_.push_back(i + 1);
  }
  return in_records_;
}

// The record (from 1) byte `pos` is in.
std::size_t FmDataFiles::record_of(std::size_t pos) {
  const std::vector<std::size_t>& starts = record_starts();
  return static_cast<std::size_t>(std::upper_bound(starts.begin(), starts.end(), pos) -
                                  starts.begin());
}

std::size_t FmDataFiles::input_record() const {
  if (!in_) return 0;
  std::size_t record = 1;
  for (std::size_t i = 0; i < in_pos_ && i < in_->size(); ++i)
    if ((*in_)[i] == '\n' && i + 1 < in_->size()) ++record;
  return record;
}

std::size_t FmDataFiles::input_column() const {
  if (!in_) return 0;
  const std::size_t nl = in_pos_ == 0 ? std::string::npos : in_->rfind('\n', in_pos_ - 1);
  return in_pos_ - (nl == std::string::npos ? 0 : nl + 1) + 1;
}

std::vector<double> FmDataFiles::read_values(std::optional<double> record, std::size_t count,
                                             const SourceLoc& loc) {
  if (!in_) fail(loc, "G27: no input file is open (G23 opens one)");
  if (count == 0 || count > kMaxValues)
    fail(loc, fmt::format("G27 reads 1 to {} values, not {}", kMaxValues, count));
  const std::string& t = *in_;
  std::size_t pos = in_pos_;
  if (record) {
    const double r = *record;
    if (!std::isfinite(r) || r != std::trunc(r) || r < 1)
      fail(loc, fmt::format("G27: record {} does not exist: records (lines) count from 1", r));
    const std::vector<std::size_t>& starts = record_starts();
    const std::size_t records = t.empty() ? 0 : starts.size();
    if (r > static_cast<double>(records))
      fail(loc, fmt::format("G27: {} has {} record{}; record {} is past its end", in_path_, records,
                            records == 1 ? "" : "s", r));
    pos = starts[static_cast<std::size_t>(r) - 1];
  }
  std::vector<double> values;
  while (values.size() < count) {
    while (pos < t.size() && separator(t[pos])) ++pos;
    if (pos >= t.size())
      fail(loc, fmt::format("G27 read past the end of {}: value {} of {} is not there", in_path_,
                            values.size() + 1, count));
    std::size_t end = pos;
    while (end < t.size() && !separator(t[end])) ++end;
    const std::string_view word(t.data() + pos, end - pos);
    // from_chars takes no leading '+', which a hand-written file may have.
    const std::string_view digits = word.front() == '+' ? word.substr(1) : word;
    double v = 0;
    const auto [stop, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
    const bool number = ec == std::errc() && stop == digits.data() + digits.size() &&
                        std::isfinite(v) && !(word.front() == '+' && digits.front() == '-');
    if (!number) {
      const std::size_t rec = record_of(pos);
      // A binary file read by mistake has one long word: show its start.
      const std::string shown =
          word.size() > 40 ? std::string(word.substr(0, 40)) + "..." : std::string(word);
      fail(loc, fmt::format("G27: record {} of {}, column {}: \"{}\" is not a number", rec,
                            in_path_, pos - record_starts()[rec - 1] + 1, shown));
    }
    values.push_back(v);
    pos = end;
  }
  in_pos_ = pos;
  return values;
}

}  // namespace gantry
