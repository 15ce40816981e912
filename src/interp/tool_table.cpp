// LinuxCNC's tool table file (docs/gcode.md, "Tool table"): reading it strictly (LinuxCNC
// skips a line it cannot read; here it is a located error, since a skipped line is a tool
// whose length silently becomes 0), and writing it back with every line not changed kept
// as it was.
#include "gantry/interp/tool_table.hpp"

#include <fmt/format.h>

#include <algorithm>  // find_if
#include <cctype>     // toupper
#include <charconv>   // from_chars
#include <cmath>      // isfinite

#include "gantry/core/file_problem.hpp"  // read_problem, kNoSuchFile
#include "gantry/core/text_file.hpp"     // read_text_file, write_file_atomically

namespace gantry {
namespace {

constexpr std::string_view kLetters = "TPXYZABCUVWDIJQ";
constexpr int kMaxPocket = 1000;  // LinuxCNC's largest pocket number

std::optional<double> read_number(std::string_view s) {
  if (s.starts_with('+')) {  // from_chars takes a minus sign only
    s.remove_prefix(1);
    if (s.starts_with('-')) return std::nullopt;
  }
  double v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc{} || end != s.data() + s.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

// A number with its sign, in the shortest form that reads back as the same double.
std::string signed_number(double v) {
  return v == 0 ? "0" : fmt::format("{:+}", v);
}

}  // namespace

const ToolEntry* ToolTable::find(int number) const {
  const auto it = std::find_if(tools_.begin(), tools_.end(),
                               [&](const ToolEntry& t) { return t.number == number; });
  if (it != tools_.end()) return &*it;
  if (!implicit()) return nullptr;
  static thread_local ToolEntry zero;
  zero = ToolEntry{};
  zero.number = zero.pocket = number;
  return &zero;
}

ToolEntry* ToolTable::change(int number) {
  for (size_t i = 0; i < tools_.size(); ++i)
    if (tools_[i].number == number) {
      for (Line& l : lines_)
        if (l.tool == static_cast<int>(i)) l.changed = true;
      return &tools_[i];
    }
  if (!implicit()) return nullptr;
  ToolEntry t;
  t.number = t.pocket = number;
  tools_.push_back(t);
  lines_.push_back({"", static_cast<int>(tools_.size() - 1), true});
  return &tools_.back();
}

std::string ToolTable::text() const {
  std::string out;
  for (size_t i = 0; i < lines_.size(); ++i) {
    const Line& l = lines_[i];
    out += l.changed ? format_tool_line(tools_[static_cast<size_t>(l.tool)]) : l.text;
    if (i + 1 < lines_.size() || final_newline_ || l.changed) out += '\n';
  }
  return out;
}

void ToolTable::scale(double k) {
  for (size_t i = 0; i < tools_.size(); ++i) {
    ToolEntry& t = tools_[i];
    for (size_t a = 0; a < t.offset.size(); ++a)
      if (a < 3 || a > 5) t.offset[a] *= k;
    t.diameter *= k;
    for (Line& l : lines_)
      if (l.tool == static_cast<int>(i)) l.changed = true;
  }
}

ToolTable ToolTable::parse(std::string_view text, const std::string& path) {
  ToolTable table;
  table.path_ = path;
  table.source_ = std::string(text);
  const auto file = std::make_shared<const std::string>(path);
  table.final_newline_ = text.empty() || text.back() == '\n';
  int line_no = 0;
  size_t pos = 0;
  while (pos < text.size()) {
    const size_t nl = text.find('\n', pos);
    const std::string_view raw =
        text.substr(pos, nl == std::string_view::npos ? std::string_view::npos : nl - pos);
    pos = nl == std::string_view::npos ? text.size() : nl + 1;
    ++line_no;
    Line line{std::string(raw)};
    std::string_view body = raw;
    if (body.ends_with('\r')) body.remove_suffix(1);
    const size_t semi = body.find(';');
    const std::string_view fields = body.substr(0, semi);
    auto at = [&](size_t column, std::string message) {
      fail(SourceLoc{file, line_no, static_cast<int>(column) + 1}, std::move(message));
    };
    if (fields.find_first_not_of(" \t") == std::string_view::npos) {  // a comment, or blank
      table.lines_.push_back(std::move(line));
      continue;
    }
    ToolEntry t;
    if (semi != std::string_view::npos) {
      std::string_view c = body.substr(semi + 1);
      t.comment = std::string(c);
    }
    std::string seen;
    size_t i = 0;
    while (i < fields.size()) {
      if (fields[i] == ' ' || fields[i] == '\t') {
        ++i;
        continue;
      }
      const size_t start = i;
      while (i < fields.size() && fields[i] != ' ' && fields[i] != '\t') ++i;
      const std::string_view token = fields.substr(start, i - start);
      const char letter = static_cast<char>(std::toupper(static_cast<unsigned char>(token[0])));
      if (kLetters.find(letter) == std::string_view::npos)
        at(start, fmt::format("\"{}\" is not a tool table field; a line is T (tool) and P "
                              "(pocket) then any of X Y Z A B C U V W (offsets), D (diameter), "
                              "I J Q (lathe), each a letter and its number with no space "
                              "between, and a comment after `;`, as T1 P1 D0.25 Z+1.5 ;flat",
                              token));
      if (seen.find(letter) != std::string::npos)
        at(start, fmt::format("{} is given twice on this line; keep one", letter));
      seen += letter;
      const std::string_view value = token.substr(1);
      const std::optional<double> v = read_number(value);
      const bool whole = letter == 'T' || letter == 'P' || letter == 'Q';
      if (!v)
        at(start, value.empty()
                      ? fmt::format("{} needs its number right after it, as {}{}", letter, letter,
                                    whole ? "1" : "0.25")
                      : fmt::format("{}{}: \"{}\" is not a number; write the letter and a "
                                    "number, as {}{}",
                                    letter, value, value, letter, whole ? "1" : "+1.5"));
      if (whole && *v != static_cast<double>(static_cast<long>(*v)))
        at(start, fmt::format("{}{}: {} takes a whole number", letter, value, letter));
      switch (letter) {
        case 'T':
          if (*v < 1 || *v > 1e9)
            at(start, fmt::format("T{}: tool numbers are whole numbers from 1 (T0 is the empty "
                                  "spindle)",
                                  value));
          t.number = static_cast<int>(*v);
          break;
        case 'P':
          if (*v < 0 || *v > kMaxPocket)
            at(start, fmt::format("P{}: pocket numbers are 0 to {}", value, kMaxPocket));
          t.pocket = static_cast<int>(*v);
          break;
        case 'Q':
          if (*v < 0 || *v > 9) at(start, fmt::format("Q{}: the orientation is 0 to 9", value));
          t.orientation = static_cast<int>(*v);
          break;
        case 'D':
          t.diameter = *v;
          break;
        case 'I':
          t.front_angle = *v;
          break;
        case 'J':
          t.back_angle = *v;
          break;
        default:
          t.offset[kToolOffsetLetters.find(letter)] = *v;
      }
    }
    const size_t first = fields.find_first_not_of(" \t");
    if (seen.find('T') == std::string::npos)
      at(first, "this line has no tool number; start it with T and the number, as T1 P1 Z+1.5");
    if (seen.find('P') == std::string::npos)
      at(first, fmt::format("tool {} has no pocket; give one after the tool number, as T{} P{}",
                            t.number, t.number, t.number));
    for (const ToolEntry& other : table.tools_)
      if (other.number == t.number)
        at(first, fmt::format("tool {} is already in the table, on an earlier line; keep one "
                              "line per tool",
                              t.number));
    line.tool = static_cast<int>(table.tools_.size());
    table.tools_.push_back(std::move(t));
    table.lines_.push_back(std::move(line));
  }
  return table;
}

std::string format_tool_line(const ToolEntry& t) {
  std::string out = fmt::format("T{} P{}", t.number, t.pocket);
  auto field = [&](char letter, double v) {
    if (v != 0) out += fmt::format(" {}{}", letter, signed_number(v));
  };
  field('D', t.diameter);
  for (size_t a = 0; a < t.offset.size(); ++a) field(kToolOffsetLetters[a], t.offset[a]);
  field('I', t.front_angle);
  field('J', t.back_angle);
  if (t.orientation != 0) out += fmt::format(" Q{}", t.orientation);
  if (!t.comment.empty()) out += " ;" + t.comment;
  return out;
}

ToolTable load_tool_table(const std::string& path, const SourceLoc& need) {
  const SourceLoc at = need.file ? need : file_loc(path);
  if (const std::string why = read_problem(path); why == kNoSuchFile)
    fail(at, fmt::format("the tool table {} does not exist; create it (one tool a line, as "
                         "T1 P1 D0.25 Z+1.5), or leave tool_table out of the profile and "
                         "--tool-table off to use tools of length 0",
                         path));
  else if (!why.empty())
    fail(at, fmt::format("cannot read the tool table {}: {}", path, why));
  const std::optional<std::string> text = read_text_file(path);
  if (!text) fail(at, fmt::format("cannot read the tool table {}; check its permissions", path));
  return ToolTable::parse(*text, path);
}

void refresh_tool_table(ToolTable& table, const std::string& path, const SourceLoc& loc) {
  const std::optional<std::string> text = read_text_file(path);
  if (table.path() != path || !text || *text != table.source_text())
    table = load_tool_table(path, loc);
}

bool save_tool_table(ToolTable& changed, std::string* why) {
  const std::string text = changed.text();
  if (!write_file_atomically(changed.path(), text, why)) return false;
  changed = ToolTable::parse(text, changed.path());
  return true;
}

}  // namespace gantry
