// The Keys window (F1): the keys the window takes, and those the profile binds.
#include "app.hpp"

#include <imgui.h>

#include "gantry/session/console_help.hpp"  // help_answer, window_status, keys_help
#include "window_common.hpp"                // kFixed, place, the palette colours

namespace gantry::ui {

void App::keys_window() {
  ImGui::SetNextWindowPos(ImVec2(kLeft + 60, 80), ImGuiCond_FirstUseEver);
  if (ImGui::Begin("Keys", &show_keys_, ImGuiWindowFlags_AlwaysAutoResize))
    ImGui::TextUnformatted(session::keys_help(session::FrontEnd::Window,
                                              key_pendant_ ? &key_pendant_->bindings() : nullptr)
                               .c_str());
  ImGui::End();
}

}  // namespace gantry::ui
