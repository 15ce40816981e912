// Line access, the label index and the whole-file syntax pass.
#include "gantry/lang/script.hpp"

#include <fmt/format.h>  // messages

#include <cstring>     // memchr
#include <deque>       // the forward jumps
#include <filesystem>  // weakly_canonical: one key per called file

#include <fcntl.h>     // open
#include <sys/stat.h>  // fstat: only regular files
#include <unistd.h>    // close

#include "gantry/core/file_problem.hpp"  // read_problem: why a part file cannot be opened
#include "gantry/core/text.hpp"          // ascii::lower
#include "gantry/lang/check_only.hpp"    // check_line: the load pass builds no tree
#include "gantry/lang/fm.hpp"            // parse_fm_line: Friendly Motion's load pass
#include "gcode_oword.hpp"               // OwordIndexer
#include "label_index.hpp"               // LabelIndex
#include "script_file.hpp"               // ScriptFile: the file's blocks
#include "simple_command.hpp"            // simple_command_code

namespace gantry {
namespace {

// Jumps found in a statement (GOTO/GOSUB, also as IF and ON INPUT actions).
void collect_jumps(const Statement& st, std::vector<const JumpStmt*>& out) {
  if (const auto* j = std::get_if<JumpStmt>(&st.body)) out.push_back(j);
  if (const auto* i = std::get_if<IfStmt>(&st.body)) collect_jumps(*i->action, out);
  if (const auto* o = std::get_if<OnInputStmt>(&st.body))
    if (o->action) collect_jumps(*o->action, out);
}

// The index of the first '\r' or '\n' at or after `from`, or s.size(). memchr for each in
// chunks: find_first_of with a set calls memchr once per character, and one memchr over the
// rest of the text for '\n' would read all of it for each line of a '\r'-only file.
[[gnu::always_inline]] inline size_t line_end(std::string_view s, size_t from) {
  constexpr size_t kChunk = 256;
  const char* base = s.data();
  for (size_t at = from; at < s.size(); at += kChunk) {
    const size_t len = std::min(kChunk, s.size() - at);
    const void* nl = std::memchr(base + at, '\n', len);
    const size_t lf = nl ? static_cast<size_t>(static_cast<const char*>(nl) - base) : at + len;
    if (const void* cr = std::memchr(base + at, '\r', lf - at))
      return static_cast<size_t>(static_cast<const char*>(cr) - base);
    if (nl) return lf;
  }
  return s.size();
}

// Commands in a statement (also as IF and ON INPUT actions).
void collect_commands(const Statement& st, std::vector<const Statement*>& out) {
  if (std::holds_alternative<CommandStmt>(st.body)) out.push_back(&st);
  if (const auto* i = std::get_if<IfStmt>(&st.body)) collect_commands(*i->action, out);
  if (const auto* o = std::get_if<OnInputStmt>(&st.body))
    if (o->action) collect_commands(*o->action, out);
}

// The bytes at the start of a file that decide whether it is G-code (is_gcode_file): the
// window the file was first read through before blocks replaced it.
constexpr size_t kFirstText = size_t{1} << 20;
constexpr size_t kBlock = ScriptFile::kBlock;

}  // namespace

std::string unknown_command_message(std::string_view code) {
  return fmt::format("unknown command '{}'; see docs/commands.md for the commands Gantry knows",
                     code);
}

std::optional<Language> language_named(std::string_view name) {
  const std::string n = ascii::lower(name);
  if (n == "sbp" || n == "opensbp") return Language::OpenSbp;
  if (n == "gcode" || n == "g-code" || n == "nc") return Language::Gcode;
  if (n == "fm" || n == "friendlymotion") return Language::FriendlyMotion;
  return std::nullopt;
}

Language file_language(std::string_view path, std::string_view first_text) {
  const size_t dot = path.rfind('.');
  const std::string ext = dot == std::string_view::npos ? "" : ascii::lower(path.substr(dot));
  if (ext == ".fm") return Language::FriendlyMotion;
  if (ext != ".sbp") {
    const size_t b = first_text.find_first_not_of(" \t\r\n");
    if (b != std::string_view::npos && first_text[b] == '!') return Language::FriendlyMotion;
  }
  return is_gcode_file(path, first_text) ? Language::Gcode : Language::OpenSbp;
}

void Script::set_language(std::optional<Language> forced, std::string_view path,
                          std::string_view first) {
  const Language l = forced ? *forced : file_language(path, first);
  gcode_ = l == Language::Gcode;
  fm_ = l == Language::FriendlyMotion;
}

Script::Script(std::string text, const std::string& name)
    : size_(text.size()),
      text_(std::move(text)),
      name_(std::make_shared<const std::string>(name)),
      labels_(std::make_unique<LabelIndex>()) {
  if (text_.rfind("\xEF\xBB\xBF", 0) == 0) text_start_ = 3;
}

Script::~Script() = default;

std::shared_ptr<const Script> Script::load(const std::string& path, const IsCommand& is_command,
                                           std::optional<Language> language) {
  std::shared_ptr<Script> s(new Script(std::string(), path));
  // O_NONBLOCK: a FIFO opens at once (and is refused below) instead of waiting for a writer.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  struct stat st {};
  if (fd < 0 || ::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    if (fd >= 0) ::close(fd);
    const std::string why = read_problem(path);
    s->errors_.push_back({SourceLoc{s->name_, 0, 0}, Severity::Error,
                          fmt::format("cannot open the part file: {}",
                                      why.empty() ? "it is not a regular file" : why)});
    return s;
  }
  s->size_ = static_cast<size_t>(st.st_size);
  s->file_ = std::make_unique<ScriptFile>(fd, s->size_, st.st_mtim);
  try {
    const std::string_view first = s->bytes(0, std::min(s->size_, kFirstText), Cursor{});
    if (first.rfind("\xEF\xBB\xBF", 0) == 0) s->text_start_ = 3;
    s->set_language(language, path, first.substr(s->text_start_));
    std::string().swap(s->joined_);  // a mebibyte for a line across blocks is seldom needed
    s->index(is_command);
  } catch (const GantryError& e) {  // written while being loaded
    s->errors_.push_back(e.diagnostic());
  }
  return s;
}

std::shared_ptr<const Script> Script::from_text(std::string text, const std::string& name,
                                                const IsCommand& is_command,
                                                std::optional<Language> language) {
  std::shared_ptr<Script> s(new Script(std::move(text), name));
  s->set_language(language, name, std::string_view(s->text_).substr(s->text_start_));
  s->index(is_command);
  return s;
}

bool Script::ok() const {
  for (const Diagnostic& d : errors_)
    if (d.severity == Severity::Error) return false;
  return true;
}

// Lines end at "\n", "\r\n" or a lone "\r" (DOS, Unix and old Mac files alike); "\r\n" is one
// terminator wherever it falls. The fast path: the line, its terminator and the byte after it
// are in the text, or in the block of the file read last (ScriptFile::last).
std::string_view Script::line_at(Cursor c, Cursor* next) const {
  if (c.offset >= size_) {
    if (next) *next = {size_, c.line + 1};
    return {};
  }
  const std::string_view w = file_ ? file_->last() : std::string_view(text_);
  const size_t base = file_ ? file_->last_start() : 0;
  if (c.offset >= base && c.offset - base < w.size()) {
    const size_t at = c.offset - base;
    const size_t stop = line_end(w, at);
    if (stop + 1 < w.size() || (stop < w.size() && w[stop] == '\n') || base + w.size() == size_) {
      size_t after = base + stop;
      if (after < size_)
        after += (w[stop] == '\r' && stop + 1 < w.size() && w[stop + 1] == '\n') ? 2 : 1;
      if (next) *next = {after, c.line + 1};
      return w.substr(at, stop - at);
    }
  }
  return file_line_at(c, next);
}

// The line at `c` when it is not in the block read last: its block is read (or found kept);
// a line that runs into the next block, or whose "\r" is its block's last byte, is copied
// into joined_ up to its terminator and the byte after it.
std::string_view Script::file_line_at(Cursor c, Cursor* next) const {
  size_t b = c.offset / kBlock;
  std::string_view block = file_->last();
  if (file_->last_start() != b * kBlock || block.empty()) {
    block_or_throw(b, c);
    return line_at(c, next);  // the fast path now, or back here with the block for the slow one
  }
  const size_t in = c.offset - b * kBlock;
  joined_.assign(block.substr(in));
  bool after_cr = line_end(block, in) < block.size();  // the block ends with the "\r"
  while (c.offset + joined_.size() < size_) {
    const std::string_view more = block_or_throw(++b, c);
    if (after_cr) {  // the byte that tells "\r\n" from a lone "\r"
      joined_ += more.front();
      break;
    }
    const size_t stop = line_end(more, 0);
    if (stop == more.size() || (more[stop] == '\r' && stop + 1 == more.size())) {
      joined_.append(more);  // the line goes on, or its "\r" ends this block too
      after_cr = stop < more.size();
      continue;
    }
    joined_.append(more.substr(0, stop + 2));  // to the terminator and the byte after it
    break;
  }
  const size_t stop = line_end(joined_, 0);
  size_t after = c.offset + stop;
  if (after < size_)
    after +=
        (joined_[stop] == '\r' && stop + 1 < joined_.size() && joined_[stop + 1] == '\n') ? 2 : 1;
  if (next) *next = {after, c.line + 1};
  return std::string_view(joined_).substr(0, stop);
}

std::string_view Script::block_or_throw(size_t n, Cursor at) const {
  if (const std::optional<std::string_view> b = file_->block(n)) return *b;
  throw GantryError({SourceLoc{name_, at.line, 0}, Severity::Error,
                     "the part file changed on disk after it was checked (it was written over "
                     "while loaded); stopped here: nothing from this line on ran. Save a new "
                     "file under a new name, or run this one again to check it anew"});
}

std::string_view Script::bytes(size_t begin, size_t end, Cursor at) const {
  if (!file_) return std::string_view(text_).substr(begin, end - begin);
  if (begin >= end) return {};
  const size_t first = begin / kBlock, last = (end - 1) / kBlock;
  if (first == last) return block_or_throw(first, at).substr(begin % kBlock, end - begin);
  joined_.clear();
  for (size_t i = first; i <= last; ++i) joined_.append(block_or_throw(i, at));
  return std::string_view(joined_).substr(begin % kBlock, end - begin);
}

std::optional<std::string_view> Script::line_before(Cursor c) const {
  if (c.offset <= text_start_ || c.offset > size_) return std::nullopt;
  // Read back up to 64 KiB (from the start of its block): a comment worth showing is never
  // longer. A script made from text looks back to its start.
  const size_t window_start =
      file_ ? (c.offset > 65536 ? c.offset - 65536 : 0) / kBlock * kBlock : 0;
  const std::string_view w = bytes(window_start, c.offset, Cursor{c.offset, 0});
  size_t end = w.size();  // strip the previous line's terminator
  if (end > 0 && w[end - 1] == '\n') --end;
  if (end > 0 && w[end - 1] == '\r') --end;
  size_t begin = end == 0 ? std::string_view::npos : w.find_last_of("\r\n", end - 1);
  if (begin == std::string_view::npos) {
    if (window_start > 0) return std::nullopt;  // longer than we look back
    begin = text_start_;
  } else {
    ++begin;
  }
  if (begin > end) begin = end;
  return w.substr(begin, end - begin);
}

std::optional<Cursor> Script::gcode_sub(const std::string& name) const {
  auto it = gcode_subs_.find(name);
  if (it == gcode_subs_.end()) return std::nullopt;
  return it->second;
}

std::optional<Cursor> Script::gcode_program(const std::string& number) const {
  auto it = gcode_programs_.find(number);
  if (it == gcode_programs_.end()) return std::nullopt;
  return it->second;
}

std::optional<Cursor> Script::label(std::string_view name) const {
  return labels_->find(name);
}

namespace {

std::string same_file_key(const std::string& path) {
  std::error_code ec;
  const std::filesystem::path p = std::filesystem::weakly_canonical(path, ec);
  return ec ? path : p.string();
}

}  // namespace

std::shared_ptr<const Script> Script::called(
    const std::string& path, const std::function<std::shared_ptr<const Script>()>& load) const {
  const std::string key = same_file_key(path);
  std::lock_guard lock(called_m_);
  auto it = called_.find(key);
  if (it != called_.end()) return it->second;
  std::shared_ptr<const Script> s = load();
  if (s && s->file_ && s->ok()) called_.emplace(key, s);
  return s;
}

void Script::forget_called(const std::string& path) const {
  const std::string key = same_file_key(path);
  std::lock_guard lock(called_m_);
  called_.erase(key);
}

// Inline here, its only user: a loop's line looks its slot up twice (read_common, parse).
[[gnu::always_inline]] inline Script::CachedParse& Script::cache_slot(size_t offset) const {
  constexpr size_t kCacheSlots = 1024;
  if (cache_.empty()) [[unlikely]]
    cache_.resize(kCacheSlots);
  // Fibonacci hashing spreads nearby offsets (consecutive lines) over the slots.
  return cache_[(offset * 0x9E3779B97F4A7C15ull) >> 54];
}

std::shared_ptr<const LineParse> Script::parse(Cursor c, Cursor* next) const {
  CachedParse& slot = cache_slot(c.offset);
  if (slot.parse && slot.offset == c.offset) {
    *next = slot.next;
    return slot.parse;
  }
  const std::string_view text = line_at(c, next);
  slot.offset = c.offset;
  slot.next = *next;
  slot.seen = false;
  slot.parse = std::make_shared<const LineParse>(gcode_ ? parse_gcode_line(text, name_, c.line)
                                                 : fm_  ? parse_fm(text, name_, c.line)
                                                        : parse_line(text, name_, c.line));
  return slot.parse;
}

bool Script::read_common(Cursor c, std::string_view text, Cursor next, Statement* out) const {
  if (gcode_ || fm_) return false;
  CachedParse& slot = cache_slot(c.offset);
  const bool here = slot.offset == c.offset;
  if (here && slot.parse) return false;
  if (!parse_common_statement(text, name_, c.line, out)) return false;
  if (here && slot.seen) {  // read again: a loop's line, kept as parse() keeps one
    auto lp = std::make_shared<LineParse>();
    lp->statement = *out;
    slot.parse = std::move(lp);
    slot.next = next;
    slot.seen = false;
  } else {
    slot.offset = c.offset;
    slot.parse.reset();
    slot.seen = true;
  }
  return true;
}

// Friendly Motion: every line's syntax, the sequence numbers (a duplicate is a warning: J and
// K go to the first), and every J and K target.
void Script::index_fm() {
  FmLine line;
  Diagnostic error;
  std::vector<std::pair<int, SourceLoc>> targets;  // checked at the end: J and K go forward too
  std::vector<std::pair<int, SourceLoc>> special;  // V72-V79 written (digest §7.1, §7.18)
  bool scribes = false;                            // a G16: V73 is its %i %f %c value
  for (Cursor c = start(), next; !at_end(c); c = next) {
    const std::string_view text = line_at(c, &next);
    ++lines_;
    if (!parse_fm_line(text, name_, c.line, &line, &error)) {
      errors_.push_back(error);
      continue;
    }
    for (const FmCommand& cmd : line.commands) {
      scribes = scribes || (cmd.op == FmOp::G && cmd.code == 16);
      if ((cmd.op == FmOp::Assign || (cmd.op == FmOp::Prompt && cmd.axis != '@')) &&
          cmd.code >= 72 && cmd.code <= 79)
        special.emplace_back(cmd.code, SourceLoc{name_, c.line, cmd.column});
    }
    if (line.sequence) {
      const std::string key = fmt::format("N{}", *line.sequence);
      const LabelIndex::Id id = labels_->intern(key);
      if (!labels_->define(id, c))
        errors_.push_back({{name_, c.line, 1},
                           Severity::Warning,
                           fmt::format("{} is numbered again; J and K go to the first, line {}",
                                       key, labels_->at(id)->line)});
    }
    for (size_t k = 0; k < line.commands.size(); ++k) {
      const FmCommand& cmd = line.commands[k];
      if (cmd.op != FmOp::Jump && cmd.op != FmOp::Call) continue;
      targets.emplace_back(cmd.target, SourceLoc{name_, c.line, cmd.column});
      // The manual writes J and K alone: what follows one on its line is Gantry's reading.
      if (k + 1 < line.commands.size())
        errors_.push_back({{name_, c.line, line.commands[k + 1].column},
                           Severity::Warning,
                           fmt::format("{} is followed on its line: the commands after it run "
                                       "when it does not jump{}",
                                       cmd.op == FmOp::Jump ? "J" : "K",
                                       cmd.op == FmOp::Call ? ", and after the subroutine returns"
                                                            : "")});
    }
  }
  // V72-V79 are the manual's special variables: V72 its diagnostic mode, V73 scribing's
  // value, V74-V79 the trim's. Gantry runs no T, so writing one outside scribing is most
  // likely a program that uses it for its own purposes, which would break on U.S. Laser's.
  for (const auto& [n, loc] : special) {
    if (n == 73 && scribes) continue;
    errors_.push_back(
        {loc, Severity::Warning,
         fmt::format("V{} is {}; the manual reserves it, so a program should not use it for "
                     "its own values (here it is an ordinary variable)",
                     n,
                     n == 72   ? "the manual's diagnostic mode"
                     : n == 73 ? "the value G16 scribes with %i %f %c, and this file scribes "
                                 "nothing"
                               : "one of the resistor trim's (T) variables V74-V79, and Gantry "
                                 "runs no T")});
  }
  for (const auto& [n, loc] : targets)
    if (!labels_->find(fmt::format("N{}", n)))
      errors_.push_back({loc, Severity::Error,
                         fmt::format("no line in this file starts with N{}; J and K go to a "
                                     "sequence number written first on its line",
                                     n)});
}

void Script::index(const IsCommand& is_command) {
  if (fm_) return index_fm();
  if (gcode_) {  // G-code: each block's syntax, and the O-words' pairs (gcode_oword.hpp)
    GcodeBlock block;
    Diagnostic error;
    OwordIndexer owords(*this);
    // 1 once the first line that is not blank is `%` (LinuxCNC's program marker), -1 when it
    // is anything else; 0 before it.
    int opened = 0;
    for (Cursor c = start(), next; !at_end(c); c = next) {
      const std::string_view text = line_at(c, &next);
      const size_t b = text.find_first_not_of(" \t");
      if (b != std::string_view::npos) {
        const bool percent = text[b] == '%';
        if (percent && opened == 1) {  // the closing `%`: the program ends here
          program_end_ = c.offset;
          break;
        }
        if (opened == 0) opened = percent ? 1 : -1;
      }
      ++lines_;
      if (!parse_gcode_block(text, name_, c.line, &block, &error))
        errors_.push_back(error);
      else if (block.oword.kind != OwordKind::None)
        owords.add(block, c, next);
    }
    owords.finish();
    return;
  }
  // A jump to a label not defined when it is read: checked at the end. A name's number and a
  // place (12 bytes, not the name's text and a SourceLoc), since a long file jumps forward to
  // millions of labels.
  struct Forward {
    LabelIndex::Id label;
    int line, column;
  };
  std::deque<Forward> forward;  // chunked: no copy of them all as it grows
  Statement common;           // its storage reused line after line
  const ExprCheckOnly check;  // this pass keeps no statement: expressions checked, not built
  auto check_command = [&](const Statement& st) {
    const std::string& code = std::get<CommandStmt>(st.body).code;
    if (!is_command(code))
      errors_.push_back({st.loc, Severity::Error, unknown_command_message(code)});
  };
  std::vector<const Statement*> commands;  // reused: no allocation a line
  std::vector<const JumpStmt*> jumps;
  // A statement without error: its commands, label and jumps.
  auto record = [&](const Statement& st, Cursor next) {
    if (is_command) {
      commands.clear();
      collect_commands(st, commands);
      for (const Statement* cmd : commands) check_command(*cmd);
    }
    if (const auto* l = std::get_if<LabelStmt>(&st.body)) {
      const LabelIndex::Id id = labels_->intern(l->name);
      if (!labels_->define(id, next))
        errors_.push_back({st.loc, Severity::Warning,
                           fmt::format("label {} is defined again; jumps go to the first one, "
                                       "line {}",
                                       l->name, labels_->at(id)->line - 1)});
    }
    jumps.clear();
    collect_jumps(st, jumps);
    for (const JumpStmt* j : jumps)
      if (const LabelIndex::Id id = labels_->intern(j->label); !labels_->at(id))
        forward.push_back({id, j->label_loc.line, j->label_loc.column});
  };
  char known[2] = {};  // the last simple command's code that is a command: asked once a run
  Cursor c = start();
  while (!at_end(c)) {
    Cursor next;
    const std::string_view text = line_at(c, &next);
    ++lines_;
    // A simple command has no error, label or jump in it; only its code may be unknown, so
    // its numbers are not read here (the run reads them).
    if (char code[2]; simple_command_code(text, code)) {
      if (code[0] != known[0] || code[1] != known[1]) {
        if (!is_command || is_command(std::string_view(code, 2))) {
          known[0] = code[0];
          known[1] = code[1];
        } else {
          const size_t b = text.find_first_not_of(ascii::kBlanks);  // the statement's column
          errors_.push_back({SourceLoc{name_, c.line, static_cast<int>(b) + 1}, Severity::Error,
                             unknown_command_message(std::string_view(code, 2))});
        }
      }
      c = next;
      continue;
    }
    if (parse_common_statement(text, name_, c.line, &common)) {
      record(common, next);
      c = next;
      continue;
    }
    LineParse lp = check_line(text, name_, c.line);
    if (lp.error) errors_.push_back(*lp.error);
    if (lp.statement) record(*lp.statement, next);
    c = next;
  }
  for (const Forward& f : forward)
    if (!labels_->at(f.label))
      errors_.push_back({SourceLoc{name_, f.line, f.column}, Severity::Error,
                         fmt::format("no label {}: in this file; labels are written on their own "
                                     "line as NAME:",
                                     labels_->name(f.label))});
}

}  // namespace gantry
