// The program listing: the loaded part file's lines, the playing line highlighted and kept in
// view while the file runs (in the file that plays: a file FP calls is shown, named, while it
// plays), and a click at rest choosing the line "Start at line" starts at.
#pragma once

#include <nlohmann/json.hpp>

#include <cstddef>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace gantry::ui {

// A part file's text cut into lines (read on the preview loader's thread: a file of a
// million lines takes a while).
struct ListingText {
  std::string path;  // as read
  std::string text;
  std::vector<std::size_t> starts;  // where each line begins: line n at starts[n - 1]
  std::size_t lines() const { return starts.size(); }
  std::string_view line(std::size_t n) const;  // 1-based, without its end of line
  // Null when the file cannot be read.
  static std::shared_ptr<const ListingText> read(const std::string& path);
};

class ProgramListing {
 public:
  // A new file (or none): nothing highlighted, the top in view.
  void set(std::shared_ptr<const ListingText> text);
  // Draws the lines in the space left in the window. `playing`: the line highlighted (0:
  // none), in file `file` (null: the loaded file; another, a file the loaded one called, is
  // shown instead while it plays, and at rest where a run stopped in it); `follow`: it is
  // kept in view (a file runs); `pick`: at rest, a click chooses the start line (in the loaded
  // file). A script's click "line N" (`pending_click`, cleared when taken) is a click on line
  // N. Returns the line clicked (0: none); `start_line` is marked.
  std::size_t draw(std::size_t playing, const std::shared_ptr<const std::string>& file,
                   bool follow, bool pick, int start_line, std::string& pending_click);
  // The rows the layout gives the listing before the readout's digits (down to twice the
  // text's size): at 1280 x 800 the readout left it about 4.
  static constexpr int kRows = 8;
  // For the state dump: the lines, the one highlighted and the range in view.
  nlohmann::json state() const;

 private:
  // The file `file` names, when it is another than the loaded one (cached: read once).
  const ListingText* called(const std::shared_ptr<const std::string>& file);

  std::shared_ptr<const ListingText> text_;
  std::shared_ptr<const ListingText> called_;  // the called file last shown (null: none)
  std::string checked_;                        // the file name last compared with the loaded
  bool checked_other_ = false;                 // ... and whether it is another file
  const ListingText* shown_ = nullptr;         // the text drawn at the last frame
  std::string heading_;  // above a called file's lines: playing it, or stopped in it
  std::size_t highlighted_ = 0;
  std::size_t followed_ = 0;  // the playing line last brought into view
  std::size_t first_shown_ = 0, last_shown_ = 0;
};

}  // namespace gantry::ui
