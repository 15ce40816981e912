// Macro buttons: one per custom cut Gantry ships (C2 zero Z with the plate, C3 home, C6 and C7
// spindle on and off, C9 tool change) and one per part file in the operator's macro folder.
// Each runs what typing it at the command line runs.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace gantry::ui {

// The custom cuts with a button.
inline constexpr int kMacroCuts[] = {2, 3, 6, 7, 9};

// Draws the buttons in the current window (`files`: session::user_part_files). `button(label, enabled)` draws a button as the
// window does (a script may click it by its label). Returns the line to run ("C2",
// "FP, \"...\"") or "".
std::string macro_panel(const std::vector<std::string>& files, const std::string& folder,
                        bool can_run, const std::function<bool(const std::string&, bool)>& button);

}  // namespace gantry::ui
