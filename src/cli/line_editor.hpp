// A small line editor for the console's raw terminal: keys decoded from the bytes a terminal
// sends, a line buffer with cursor movement, history and Tab completion, and the drawing of
// the prompt line. No terminal I/O of its own (console.cpp reads and writes), so every part
// can be driven by tests.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace gantry {

enum class KeyCode {
  Char,  // text: one UTF-8 character
  Enter,
  Tab,
  Backspace,
  Delete,
  Left,
  Right,
  Up,
  Down,
  Home,
  End,
  PageUp,
  PageDown,
  Escape,
  Interrupt,    // Ctrl-C
  EndOfInput,   // Ctrl-D
  KillToEnd,    // Ctrl-K
  KillToStart,  // Ctrl-U
  Redraw,       // Ctrl-L
  Insert,
  Function,  // F1-F12 (Key::number)
  Unknown,   // any other control key or escape sequence
};

struct Key {
  KeyCode code = KeyCode::Unknown;
  std::string text;    // KeyCode::Char
  bool ctrl = false;   // Ctrl held with an arrow or page key (xterm's modifier parameter)
  bool alt = false;    // Alt held, likewise
  bool shift = false;  // Shift held, likewise
  int number = 0;      // Function: 1-12
  char control = 0;    // the letter of a Ctrl+letter byte ('A' for 0x01), whatever `code` it is

  bool is_char(char c) const { return code == KeyCode::Char && text.size() == 1 && text[0] == c; }
};

// The key's name as the [pendant] keys bindings write it (session/key_bindings.hpp): "F5",
// "Ctrl+Right", "Ctrl+G", "a"; "" for a key that has none (an unknown sequence).
std::string key_name(const Key& k);

// A terminal's Alt+character is ESC and the character at once (KeyCode::Char with alt): when no
// binding takes it, it is the two keys it was before Alt+ could be bound, Escape then the
// character, as if typed quickly. Any other key is itself.
std::vector<Key> escape_and_char(const Key& k);

// Bytes from a terminal in raw mode into keys. Escape sequences (CSI `ESC [`, SS3 `ESC O`) are
// decoded whole, even when they arrive split across reads. ESC and a printable character is
// Alt+character. A lone ESC is the Escape key, but only once nothing follows it: the caller
// calls flush() after a short quiet time (30 ms), so an Esc pressed alone stays the Escape key.
class KeyDecoder {
 public:
  void feed(std::string_view bytes, std::vector<Key>& out);
  bool pending() const { return !buf_.empty(); }  // bytes waiting for the rest of a sequence
  void flush(std::vector<Key>& out);              // what is waiting, as keys (ESC: Escape)

 private:
  // Decodes one key from the start of buf_; returns the bytes used, 0 when more are needed.
  std::size_t decode(Key& k) const;
  std::string buf_;
  bool after_cr_ = false;  // a CR was the last byte: a following LF belongs to it
};

// The text being edited and the cursor in it (a byte offset, always at a character start).
class LineBuffer {
 public:
  const std::string& text() const { return text_; }
  std::size_t cursor() const { return cursor_; }
  std::size_t cursor_column() const;  // characters before the cursor

  void set(std::string text);  // cursor at the end
  void insert(std::string_view s);
  void left();
  void right();
  void home() { cursor_ = 0; }
  void end() { cursor_ = text_.size(); }
  void backspace();
  void del();
  void kill_to_end() { text_.erase(cursor_); }
  void kill_to_start();

 private:
  std::string text_;
  std::size_t cursor_ = 0;
};

// Lines entered before, newest last. Up and Down walk through them; the line being typed is
// kept and comes back below the newest. A line equal to the newest is not added twice.
class History {
 public:
  explicit History(std::size_t capacity = 500) : capacity_(capacity) {}
  void add(const std::string& line);
  bool up(LineBuffer& b);    // false at the oldest line
  bool down(LineBuffer& b);  // false below the newest (the typed line)
  void reset();              // back to the line being typed (after a line is entered)
  const std::vector<std::string>& lines() const { return lines_; }

 private:
  std::vector<std::string> lines_;
  std::size_t capacity_;
  std::size_t pos_ = 0;  // == lines_.size(): the line being typed
  std::string draft_;
};

// A word Tab can complete: a two-letter code or a console word, what Tab adds after it when
// it is the only match (", " for a command that takes parameters), and a description for
// the list of matches.
struct CompletionWord {
  std::string word;
  std::string suffix;
  std::string description;
};

struct Completion {
  std::size_t start = 0, end = 0;           // the word completed: bytes [start, end)
  std::string replacement;                  // what replaces it; empty: nothing to add
  std::vector<const CompletionWord*> list;  // the matches, when Tab cannot decide alone
};

// Completes the line's first word (letters and digits, any case) when the cursor is at its
// end: the only match in full (with its suffix when nothing follows), or the longest prefix
// all matches share; when that adds nothing and several match, `list` holds them.
Completion complete(const LineBuffer& b, const std::vector<CompletionWord>& words);

// The prompt line on a terminal: the prompt, the line (scrolled sideways when it is wider
// than the terminal) and the cursor, drawn with CR and the ANSI erase-line sequence only.
class LineEditor {
 public:
  enum class Event { None, Submit, EndOfInput, Interrupt, Escape };
  using Writer = std::function<void(std::string_view)>;

  LineEditor(Writer write, std::vector<CompletionWord> words)
      : write_(std::move(write)), words_(std::move(words)) {}

  // Starts a new empty line under `prompt` and draws it.
  void start(std::string prompt);
  // Edits with one key. Submit: take() has the line; EndOfInput: Ctrl-D on an empty line;
  // Interrupt: Ctrl-C; Escape: the Escape key (the line is kept).
  Event key(const Key& k);
  std::string take();  // the entered line, added to the history (if `remember`)
  void set_columns(int columns) { columns_ = columns > 8 ? columns : 80; }
  void redraw();  // the prompt line again, e.g. after something was printed above it
  void erase();   // clears the prompt line (the caller prints, then redraws)
  void clear_line() { buf_.set(""); }
  const LineBuffer& buffer() const { return buf_; }
  History& history() { return history_; }
  bool remember = true;  // take() adds to the history (off for answers to questions)

 private:
  Writer write_;
  std::vector<CompletionWord> words_;
  std::string prompt_;
  LineBuffer buf_;
  History history_;
  int columns_ = 80;
};

}  // namespace gantry
