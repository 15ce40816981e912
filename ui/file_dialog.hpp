// The file-open dialog, drawn with ImGui: a folder's subfolders and part files (.sbp, .nc,
// .ngc, .tap, .gcode), a path typed (Enter opens a file or goes into a folder), the files
// opened last, and the keys: Up/Down walk the list, Enter opens the entry marked, Backspace
// in an empty path goes to the parent folder.
#pragma once

#include <nlohmann/json.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace gantry::ui {

// A name the dialog lists as a part file: .sbp, .nc, .ngc, .tap or .gcode, any case.
bool is_part_file(const std::string& name);

class FileDialog {
 public:
  // Shows it in `folder` (the current file's, else the working folder).
  void open(const std::string& folder);
  // Shows it in the folder of `file` (Ctrl+O, the Open... button, File > Open...); with no
  // file, the working folder.
  void open_beside(const std::string& file);
  bool showing() const { return showing_; }
  // Draws it (a modal popup) while it shows; the file chosen, once (it closes then).
  // `clicked`: a script's click by name (an entry's name as listed, a recent file's path,
  // "Up", "Open", "Cancel").
  std::optional<std::string> draw(const std::vector<std::string>& recent,
                                  const std::function<bool(const std::string&)>& clicked);
  nlohmann::json state() const;

 private:
  struct Entry {
    std::string name;  // folders end in '/'
    bool folder = false;
  };
  void list();  // entries_ from folder_ (none marked)
  // Up/Down mark an entry; Backspace with the path empty before this frame's keys goes up.
  std::optional<std::string> walk_keys(bool path_was_empty);
  // A typed name, or an entry: a folder is entered, a file chosen, anything else an error.
  std::optional<std::string> go(const std::string& name);

  bool showing_ = false, fresh_ = false, all_files_ = false;
  std::string folder_, typed_, error_;
  std::vector<Entry> entries_;
  int marked_ = -1;             // the entry Up/Down marked (-1: none)
  bool scroll_to_mark_ = false;  // bring it into view at the next draw
  bool refocus_ = false;         // give the path field the keys again (Enter took them)
};

}  // namespace gantry::ui
