// The console's line editor: key decoding, the line buffer, history, completion, drawing.
#include "line_editor.hpp"

#include <fmt/format.h>  // escape sequences

#include <algorithm>  // min, max
#include <cctype>     // toupper, isalnum

#include "gantry/lang/scan.hpp"  // upper

namespace gantry {
namespace {

bool continuation(unsigned char c) {
  return (c & 0xC0) == 0x80;
}

// The length of the UTF-8 character a lead byte starts; 0 for a byte no character starts with.
std::size_t utf8_length(unsigned char c) {
  if (c < 0x80) return 1;
  if (c >= 0xC2 && c <= 0xDF) return 2;
  if (c >= 0xE0 && c <= 0xEF) return 3;
  if (c >= 0xF0 && c <= 0xF4) return 4;
  return 0;
}

using scan::upper;

bool alnum(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) != 0;
}

std::size_t columns_of(std::string_view s) {
  return static_cast<std::size_t>(
      std::count_if(s.begin(), s.end(), [](char c) { return !continuation(c); }));
}

// F1-F12 as CSI n ~ (xterm's and VT220's numbers; 0: none).
int function_number(int n) {
  if (n >= 11 && n <= 15) return n - 10;  // F1-F5
  if (n >= 17 && n <= 21) return n - 11;  // F6-F10
  if (n == 23 || n == 24) return n - 12;  // F11, F12
  return 0;
}

// F1-F4 as the final letter of SS3 (ESC O P) or CSI 1;m P.
int pf_number(char c) {
  return c >= 'P' && c <= 'S' ? c - 'P' + 1 : 0;
}

// The keys of CSI sequences ending in '~': ESC [ n ~ (n as in xterm and the Linux console).
KeyCode tilde_key(int n) {
  switch (n) {
    case 1:
    case 7:
      return KeyCode::Home;
    case 4:
    case 8:
      return KeyCode::End;
    case 3:
      return KeyCode::Delete;
    case 5:
      return KeyCode::PageUp;
    case 6:
      return KeyCode::PageDown;
    case 2:
      return KeyCode::Insert;
    default:
      return function_number(n) > 0 ? KeyCode::Function : KeyCode::Unknown;
  }
}

KeyCode letter_key(char c) {  // the final letter of ESC [ ... X or ESC O X
  switch (c) {
    case 'A':
      return KeyCode::Up;
    case 'B':
      return KeyCode::Down;
    case 'C':
      return KeyCode::Right;
    case 'D':
      return KeyCode::Left;
    case 'H':
      return KeyCode::Home;
    case 'F':
      return KeyCode::End;
    default:
      return KeyCode::Unknown;
  }
}

KeyCode control_key(unsigned char c) {
  switch (c) {
    case '\r':
    case '\n':
      return KeyCode::Enter;
    case '\t':
      return KeyCode::Tab;
    case 0x7f:
    case 0x08:
      return KeyCode::Backspace;
    case 0x03:
      return KeyCode::Interrupt;
    case 0x04:
      return KeyCode::EndOfInput;
    case 0x01:
      return KeyCode::Home;
    case 0x05:
      return KeyCode::End;
    case 0x02:
      return KeyCode::Left;
    case 0x06:
      return KeyCode::Right;
    case 0x10:
      return KeyCode::Up;
    case 0x0e:
      return KeyCode::Down;
    case 0x0b:
      return KeyCode::KillToEnd;
    case 0x15:
      return KeyCode::KillToStart;
    case 0x0c:
      return KeyCode::Redraw;
    default:
      return KeyCode::Unknown;
  }
}

}  // namespace

// ---- keys --------------------------------------------------------------------------------

std::size_t KeyDecoder::decode(Key& k) const {
  const std::string& b = buf_;
  const auto c = static_cast<unsigned char>(b[0]);
  k = Key{};
  if (c == 0x1b) {
    if (b.size() == 1) return 0;
    if (b[1] == '[') {  // CSI: parameter bytes 0x20-0x3f, then one final byte
      std::size_t i = 2;
      while (i < b.size() && static_cast<unsigned char>(b[i]) >= 0x20 &&
             static_cast<unsigned char>(b[i]) <= 0x3f)
        ++i;
      if (i >= b.size()) return b.size() > 32 ? b.size() : 0;  // a runaway sequence: dropped
      std::vector<int> params{0};
      for (std::size_t j = 2; j < i; ++j) {
        if (b[j] == ';')
          params.push_back(0);
        else if (b[j] >= '0' && b[j] <= '9')
          params.back() = std::min(params.back() * 10 + (b[j] - '0'), 9999);
      }
      // The modifier parameter: 1 + (1 Shift, 2 Alt, 4 Ctrl).
      const int mod = params.size() >= 2 && params[1] > 0 ? params[1] - 1 : 0;
      k.shift = (mod & 1) != 0;
      k.alt = (mod & 2) != 0;
      k.ctrl = (mod & 4) != 0;
      k.code = b[i] == '~' ? tilde_key(params[0]) : letter_key(b[i]);
      k.number = b[i] == '~' ? function_number(params[0]) : pf_number(b[i]);
      if (k.number > 0) k.code = KeyCode::Function;
      return i + 1;
    }
    if (b[1] == 'O') {  // SS3: the cursor keys in application mode, Home, End, F1-F4
      if (b.size() < 3) return 0;
      k.code = letter_key(b[2]);
      k.number = pf_number(b[2]);
      if (k.number > 0) k.code = KeyCode::Function;
      return 3;
    }
    // ESC and a printable character at once: Alt+character, which a terminal sends as the
    // two (xterm's metaSendsEscape, the Linux console, tmux). A lone ESC waits for flush().
    // ESC [ and ESC O start sequences, so Alt+[ and Alt+O read as Escape and the character.
    if (const auto next = static_cast<unsigned char>(b[1]); next > 0x20 && next < 0x7f) {
      k.code = KeyCode::Char;
      k.text = b.substr(1, 1);
      k.alt = true;
      return 2;
    }
    k.code = KeyCode::Escape;  // ESC and then another key (a control, ESC): both count
    return 1;
  }
  if (c < 0x20 || c == 0x7f) {
    k.code = control_key(c);
    // Ctrl+letter, for the bindings (Tab, Enter and Backspace are their own keys).
    if (c >= 0x01 && c <= 0x1a && c != '\t' && c != '\n' && c != '\r' && c != 0x08)
      k.control = static_cast<char>('A' + c - 1);
    return 1;
  }
  const std::size_t n = utf8_length(c);
  if (n == 0) return 1;  // a stray continuation or invalid byte: Unknown
  if (b.size() < n) return 0;
  for (std::size_t i = 1; i < n; ++i)
    if (!continuation(static_cast<unsigned char>(b[i]))) return 1;  // broken: dropped
  k.code = KeyCode::Char;
  k.text = b.substr(0, n);
  return n;
}

void KeyDecoder::feed(std::string_view bytes, std::vector<Key>& out) {
  buf_.append(bytes);
  while (!buf_.empty()) {
    if (after_cr_ && buf_[0] == '\n') {  // CR LF (a paste, or a terminal in CRLF mode): one Enter
      after_cr_ = false;
      buf_.erase(0, 1);
      continue;
    }
    Key k;
    const std::size_t n = decode(k);
    if (n == 0) return;  // the rest of a sequence is still to come
    after_cr_ = buf_[0] == '\r';
    buf_.erase(0, n);
    out.push_back(std::move(k));
  }
}

void KeyDecoder::flush(std::vector<Key>& out) {
  while (!buf_.empty()) {
    Key k;
    std::size_t n = decode(k);
    if (n == 0) {  // an unfinished sequence: a lone ESC is the Escape key
      k = Key{};
      if (buf_[0] == 0x1b) k.code = KeyCode::Escape;
      n = 1;
    }
    after_cr_ = buf_[0] == '\r';
    buf_.erase(0, n);
    out.push_back(std::move(k));
  }
}

std::string key_name(const Key& k) {
  if (k.control != 0) return std::string("Ctrl+") + k.control;
  std::string base;
  switch (k.code) {
    case KeyCode::Char:
      if (k.text == " ") {
        base = "Space";
        break;
      }
      return (k.alt ? "Alt+" : "") + k.text;
    case KeyCode::Enter:
      base = "Enter";
      break;
    case KeyCode::Tab:
      base = "Tab";
      break;
    case KeyCode::Backspace:
      base = "Backspace";
      break;
    case KeyCode::Delete:
      base = "Delete";
      break;
    case KeyCode::Insert:
      base = "Insert";
      break;
    case KeyCode::Left:
      base = "Left";
      break;
    case KeyCode::Right:
      base = "Right";
      break;
    case KeyCode::Up:
      base = "Up";
      break;
    case KeyCode::Down:
      base = "Down";
      break;
    case KeyCode::Home:
      base = "Home";
      break;
    case KeyCode::End:
      base = "End";
      break;
    case KeyCode::PageUp:
      base = "PageUp";
      break;
    case KeyCode::PageDown:
      base = "PageDown";
      break;
    case KeyCode::Escape:
      base = "Escape";
      break;
    case KeyCode::Function:
      base = "F" + std::to_string(k.number);
      break;
    default:
      return "";
  }
  return std::string(k.ctrl ? "Ctrl+" : "") + (k.alt ? "Alt+" : "") + (k.shift ? "Shift+" : "") +
         base;
}

std::vector<Key> escape_and_char(const Key& k) {
  if (k.code != KeyCode::Char || !k.alt) return {k};
  Key esc;
  esc.code = KeyCode::Escape;
  Key c = k;
  c.alt = false;
  return {esc, c};
}

// ---- the line ----------------------------------------------------------------------------

std::size_t LineBuffer::cursor_column() const {
  return columns_of(std::string_view(text_).substr(0, cursor_));
}

void LineBuffer::set(std::string text) {
  text_ = std::move(text);
  cursor_ = text_.size();
}

void LineBuffer::insert(std::string_view s) {
  text_.insert(cursor_, s);
  cursor_ += s.size();
}

void LineBuffer::left() {
  while (cursor_ > 0) {
    --cursor_;
    if (!continuation(static_cast<unsigned char>(text_[cursor_]))) break;
  }
}

void LineBuffer::right() {
  if (cursor_ < text_.size()) ++cursor_;
  while (cursor_ < text_.size() && continuation(static_cast<unsigned char>(text_[cursor_])))
    ++cursor_;
}

void LineBuffer::backspace() {
  const std::size_t end = cursor_;
  left();
  text_.erase(cursor_, end - cursor_);
}

void LineBuffer::del() {
  const std::size_t start = cursor_;
  right();
  text_.erase(start, cursor_ - start);
  cursor_ = start;
}

void LineBuffer::kill_to_start() {
  text_.erase(0, cursor_);
  cursor_ = 0;
}

// ---- history -----------------------------------------------------------------------------

void History::add(const std::string& line) {
  if (!line.empty() && (lines_.empty() || lines_.back() != line)) {
    lines_.push_back(line);
    if (lines_.size() > capacity_) lines_.erase(lines_.begin());
  }
  reset();
}

bool History::up(LineBuffer& b) {
  if (pos_ == 0) return false;
  if (pos_ == lines_.size()) draft_ = b.text();
  b.set(lines_[--pos_]);
  return true;
}

bool History::down(LineBuffer& b) {
  if (pos_ >= lines_.size()) return false;
  ++pos_;
  b.set(pos_ == lines_.size() ? draft_ : lines_[pos_]);
  return true;
}

void History::reset() {
  pos_ = lines_.size();
  draft_.clear();
}

// ---- completion --------------------------------------------------------------------------

Completion complete(const LineBuffer& b, const std::vector<CompletionWord>& words) {
  const std::string& t = b.text();
  std::size_t start = 0;
  while (start < t.size() && (t[start] == ' ' || t[start] == '\t')) ++start;
  std::size_t end = start;
  while (end < t.size() && alnum(t[end])) ++end;
  Completion c;
  c.start = start;
  c.end = end;
  if (end == start || b.cursor() != end) return c;
  const std::string typed = upper(std::string_view(t).substr(start, end - start));
  std::vector<const CompletionWord*> matches;
  for (const CompletionWord& w : words)
    if (upper(w.word).starts_with(typed)) matches.push_back(&w);
  if (matches.empty()) return c;
  if (matches.size() == 1) {
    c.replacement = matches[0]->word;
    if (end == t.size()) c.replacement += matches[0]->suffix;
    return c;
  }
  // The longest prefix every match shares (compared in upper case; written as the first).
  std::size_t common = matches[0]->word.size();
  for (const CompletionWord* w : matches) {
    std::size_t i = 0;
    while (i < common && i < w->word.size() &&
           std::toupper(static_cast<unsigned char>(w->word[i])) ==
               std::toupper(static_cast<unsigned char>(matches[0]->word[i])))
      ++i;
    common = i;
  }
  if (common > typed.size())
    c.replacement = matches[0]->word.substr(0, common);
  else
    c.list = std::move(matches);
  return c;
}

// ---- the prompt line ---------------------------------------------------------------------

void LineEditor::start(std::string prompt) {
  prompt_ = std::move(prompt);
  buf_.set("");
  history_.reset();
  redraw();
}

LineEditor::Event LineEditor::key(const Key& k) {
  switch (k.code) {
    case KeyCode::Char:
      buf_.insert(k.text);
      break;
    case KeyCode::Enter:
      buf_.end();
      redraw();
      write_("\r\n");
      return Event::Submit;
    case KeyCode::Tab: {
      const Completion c = complete(buf_, words_);
      if (!c.replacement.empty()) {
        std::string t = buf_.text();
        t.replace(c.start, c.end - c.start, c.replacement);
        const std::string rest = t.substr(c.start + c.replacement.size());
        buf_.set(t);
        for (std::size_t n = columns_of(rest); n > 0; --n) buf_.left();
      } else if (!c.list.empty()) {
        std::string out = "\r\n";
        for (const CompletionWord* w : c.list)
          out += fmt::format("  {:<8} {}\r\n", w->word, w->description);
        write_(out);
      }
      break;
    }
    case KeyCode::Backspace:
      buf_.backspace();
      break;
    case KeyCode::Delete:
      buf_.del();
      break;
    case KeyCode::Left:
      buf_.left();
      break;
    case KeyCode::Right:
      buf_.right();
      break;
    case KeyCode::Home:
      buf_.home();
      break;
    case KeyCode::End:
      buf_.end();
      break;
    case KeyCode::Up:
      history_.up(buf_);
      break;
    case KeyCode::Down:
      history_.down(buf_);
      break;
    case KeyCode::KillToEnd:
      buf_.kill_to_end();
      break;
    case KeyCode::KillToStart:
      buf_.kill_to_start();
      break;
    case KeyCode::EndOfInput:
      if (buf_.text().empty()) return Event::EndOfInput;
      buf_.del();
      break;
    case KeyCode::Interrupt:
      return Event::Interrupt;
    case KeyCode::Escape:
      return Event::Escape;
    case KeyCode::Redraw:
    case KeyCode::PageUp:
    case KeyCode::PageDown:
    case KeyCode::Insert:
    case KeyCode::Function:
    case KeyCode::Unknown:
      break;
  }
  redraw();
  return Event::None;
}

std::string LineEditor::take() {
  std::string line = buf_.text();
  if (remember) history_.add(line);
  buf_.set("");
  history_.reset();
  return line;
}

void LineEditor::redraw() {
  const std::string& t = buf_.text();
  std::vector<std::size_t> starts;  // byte offset of each character
  for (std::size_t i = 0; i < t.size(); ++i)
    if (!continuation(static_cast<unsigned char>(t[i]))) starts.push_back(i);
  starts.push_back(t.size());
  const std::size_t total = starts.size() - 1;
  const std::size_t prompt_cols = columns_of(prompt_);
  // The columns left for the line, keeping the last column free so the cursor never wraps.
  const std::size_t room = std::max<std::size_t>(
      8, static_cast<std::size_t>(columns_) > prompt_cols + 1 ? columns_ - prompt_cols - 1 : 0);
  const std::size_t col = buf_.cursor_column();
  const std::size_t first = col >= room ? col - room + 1 : 0;  // scrolled so the cursor shows
  const std::size_t last = std::min(total, first + room);
  std::string out =
      "\r" + prompt_ + t.substr(starts[first], starts[last] - starts[first]) + "\x1b[K";
  if (last > col) out += fmt::format("\x1b[{}D", last - col);
  write_(out);
}

void LineEditor::erase() {
  write_("\r\x1b[K");
}

}  // namespace gantry
