// Scripted actions for driving the console window without a person (tests, screenshots,
// the benchmark): `gantry gui --script FILE` plays them one after another, then exits.
// docs/console.md ("Console window", "Scripted runs") lists the actions.
#pragma once

#include <string>
#include <vector>

namespace gantry::ui {

struct Action {
  enum class Kind {
    Type,        // type TEXT: characters, as if typed where the keyboard focus is
    Key,         // key [ctrl+|alt+|shift+]NAME: one press and release
    Tap,         // tap NAME: a press and its release between two frames (a quick tap)
    Hold,        // hold NAME SECONDS: press, wait (wall-clock time), release
    Click,       // click NAME: the button (or menu item) of that name
    WaitIdle,    // wait idle: the machine at rest, no dialog pending, the preview loaded
    WaitDialog,  // wait dialog: a PAUSE, INPUT or MSGBOX dialog is showing
    WaitFrames,  // wait frames N
    Hover,       // hover FX FY: the pointer over the preview, as fractions of its size
    Screenshot,  // screenshot FILE.png: the whole window
    Dump,        // dump FILE.json: the window's state
    Quit,        // quit: leave now (also the end of the script)
  } kind;
  std::string text;     // Type, Click, Screenshot, Dump: the argument
  int key = 0;          // Key, Hold, Tap: the GLFW key code
  int mods = 0;         // Key: GLFW modifier bits
  double a = 0, b = 0;  // Hold: seconds; WaitFrames: frames; Hover: fractions
  int line = 0;         // in the script, for messages
};

// Parses a script; on an error returns false with "FILE:LINE: what is wrong" in `error`.
bool parse_script(const std::string& text, const std::string& name, std::vector<Action>& out,
                  std::string& error);

// The GLFW key code of a key's name (Enter, Escape, Tab, Space, Backspace, Delete, Up, Down,
// Left, Right, PageUp, PageDown, Home, End, Minus, Equal, F1-F12, a letter or a digit); -1 if
// none.
int key_code(const std::string& name);

}  // namespace gantry::ui
