// The file-open dialog (docs/console.md, "Console window").
#include "file_dialog.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>  // key codes
#include <fmt/format.h>
#include <imgui.h>
#include <imgui_stdlib.h>  // InputText on std::string

#include <algorithm>
#include <cctype>   // tolower
#include <cstdlib>  // getenv
#include <filesystem>

#include "gantry/lang/scan.hpp"  // trim
#include "theme.hpp"                // current_palette

namespace gantry::ui {
namespace {

namespace fs = std::filesystem;
constexpr const char* kTitle = "Open part file";

}  // namespace

bool is_part_file(const std::string& name) {
  const std::size_t dot = name.find_last_of('.');
  if (dot == std::string::npos) return false;
  std::string ext = name.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == "sbp" || ext == "nc" || ext == "ngc" || ext == "tap" || ext == "gcode";
}

void FileDialog::open(const std::string& folder) {
  std::error_code ec;
  const fs::path f = folder.empty() ? fs::current_path(ec) : fs::absolute(folder, ec);
  folder_ = f.lexically_normal().string();
  typed_.clear();
  error_.clear();
  showing_ = fresh_ = true;
  list();
}

void FileDialog::open_beside(const std::string& file) {
  open(file.empty() ? std::string() : fs::path(file).parent_path().string());
}

void FileDialog::list() {
  entries_.clear();
  marked_ = -1;
  std::error_code ec;
  std::vector<Entry> folders, files;
  for (fs::directory_iterator it(folder_, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.empty() || name[0] == '.') continue;  // hidden
    std::error_code e;
    if (it->is_directory(e))
      folders.push_back({name + "/", true});
    else if (all_files_ || is_part_file(name))
      files.push_back({name, false});
  }
  if (ec) error_ = fmt::format("{}: {}", folder_, ec.message());
  auto by_name = [](const Entry& a, const Entry& b) { return a.name < b.name; };
  std::sort(folders.begin(), folders.end(), by_name);
  std::sort(files.begin(), files.end(), by_name);
  entries_ = std::move(folders);
  entries_.insert(entries_.end(), files.begin(), files.end());
}

std::optional<std::string> FileDialog::go(const std::string& name) {
  const std::string n(scan::trim(name));
  if (n.empty()) return std::nullopt;
  fs::path p(n);
  const char* home = std::getenv("HOME");
  if (home && (n == "~" || n.rfind("~/", 0) == 0))
    p = fs::path(home) / n.substr(n.size() > 1 ? 2 : 1);
  if (p.is_relative()) p = fs::path(folder_) / p;
  p = p.lexically_normal();
  std::error_code ec;
  if (fs::is_directory(p, ec)) {
    const fs::path from(folder_);
    folder_ = p.string();
    if (folder_.size() > 1 && folder_.back() == '/') folder_.pop_back();
    typed_.clear();
    error_.clear();
    list();
    // Up to the parent: the folder left is marked, so Enter goes back into it.
    const std::string left = from.filename().string() + "/";
    if (from.parent_path() == fs::path(folder_))
      for (std::size_t i = 0; i < entries_.size(); ++i)
        if (entries_[i].name == left) marked_ = static_cast<int>(i), scroll_to_mark_ = true;
    return std::nullopt;
  }
  if (fs::is_regular_file(p, ec)) {
    showing_ = false;
    return p.string();
  }
  error_ = fmt::format("{}: no such file or folder", p.string());
  return std::nullopt;
}

std::optional<std::string> FileDialog::draw(
    const std::vector<std::string>& recent,
    const std::function<bool(const std::string&)>& clicked) {
  if (!showing_) return std::nullopt;
  if (fresh_ && !ImGui::IsPopupOpen(kTitle)) ImGui::OpenPopup(kTitle);
  const ImVec2 size = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(size.x / 2, size.y / 2), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowSize(ImVec2(std::min(720.0f, size.x - 40), std::min(520.0f, size.y - 40)),
                           ImGuiCond_Appearing);
  if (!ImGui::BeginPopupModal(kTitle, nullptr, ImGuiWindowFlags_NoSavedSettings)) {
    if (!fresh_) showing_ = false;  // closed by ImGui
    return std::nullopt;
  }
  const bool fresh = fresh_;
  fresh_ = false;
  std::optional<std::string> chosen;
  ImGui::TextDisabled("in %s", folder_.c_str());
  if (fresh || refocus_) ImGui::SetKeyboardFocusHere();
  refocus_ = false;
  ImGui::SetNextItemWidth(-120);
  const bool path_was_empty = typed_.empty();
  if (ImGui::InputTextWithHint("##path", "type a name, or Up/Down and Enter; Backspace: up",
                               &typed_, ImGuiInputTextFlags_EnterReturnsTrue)) {
    // Enter: the name typed, else the entry Up/Down marked. The keys stay in the field.
    const bool mark = scan::trim(typed_).empty() && marked_ >= 0 &&
                      marked_ < static_cast<int>(entries_.size());
    chosen = go(mark ? entries_[static_cast<std::size_t>(marked_)].name : typed_);
    refocus_ = true;
  }
  if (!fresh && !chosen) chosen = walk_keys(path_was_empty);
  ImGui::SameLine();
  if (ImGui::Button("Up") || clicked("Up")) {
    typed_.clear();
    chosen = go("..");
  }
  ImGui::SameLine();
  if (ImGui::Checkbox("all", &all_files_)) list();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("every file, not only .sbp .nc .ngc .tap .gcode");
  if (!error_.empty()) ImGui::TextColored(current_palette().red, "%s", error_.c_str());
  const float row = ImGui::GetTextLineHeightWithSpacing();
  if (!recent.empty()) {
    ImGui::TextDisabled("recent");
    const float h = std::min(static_cast<float>(recent.size()), 5.0f) * row + 8;
    ImGui::BeginChild("recent", ImVec2(0, h), true);
    for (const std::string& f : recent)
      if ((ImGui::Selectable(f.c_str()) || clicked(f)) && !chosen) chosen = go(f);
    ImGui::EndChild();
  }
  ImGui::TextDisabled("folders and part files");
  ImGui::BeginChild("entries", ImVec2(0, -ImGui::GetFrameHeightWithSpacing()), true);
  for (std::size_t i = 0; i < entries_.size(); ++i) {
    const Entry& e = entries_[i];
    const bool marked = static_cast<int>(i) == marked_;
    if (e.folder) ImGui::PushStyleColor(ImGuiCol_Text, current_palette().cyan);
    const bool pick = ImGui::Selectable(e.name.c_str(), marked) || clicked(e.name);
    if (e.folder) ImGui::PopStyleColor();
    if (marked && scroll_to_mark_) {
      ImGui::SetScrollHereY();
      scroll_to_mark_ = false;
    }
    if (pick && !chosen) {
      chosen = go(e.name);
      break;  // the list may have changed
    }
  }
  if (entries_.empty()) ImGui::TextDisabled("no folders or part files here");
  ImGui::EndChild();
  if (ImGui::Button("Open") || clicked("Open")) chosen = go(typed_.empty() ? "." : typed_);
  ImGui::SameLine();
  if (ImGui::Button("Cancel") || clicked("Cancel") ||
      (!fresh && ImGui::IsKeyPressed(GLFW_KEY_ESCAPE, false)))
    showing_ = false;
  if (!showing_) ImGui::CloseCurrentPopup();
  ImGui::EndPopup();
  return chosen;
}

std::optional<std::string> FileDialog::walk_keys(bool path_was_empty) {
  const int n = static_cast<int>(entries_.size());
  if (n > 0 && ImGui::IsKeyPressed(GLFW_KEY_DOWN, true)) {
    marked_ = std::min(marked_ + 1, n - 1);
    scroll_to_mark_ = true;
  }
  if (n > 0 && ImGui::IsKeyPressed(GLFW_KEY_UP, true)) {
    marked_ = std::max(marked_ - 1, 0);
    scroll_to_mark_ = true;
  }
  // Backspace in a path that was empty before this frame: the parent folder (a Backspace that
  // deleted the last letter typed stays in the field).
  if (path_was_empty && ImGui::IsKeyPressed(GLFW_KEY_BACKSPACE, false)) {
    refocus_ = true;
    return go("..");
  }
  return std::nullopt;
}

nlohmann::json FileDialog::state() const {
  nlohmann::json entries = nlohmann::json::array();
  for (const Entry& e : entries_) entries.push_back(e.name);
  return {{"showing", showing_},
          {"folder", folder_},
          {"typed", typed_},
          {"error", error_},
          {"entries", entries},
          {"marked", marked_ >= 0 && marked_ < static_cast<int>(entries_.size())
                         ? entries_[static_cast<std::size_t>(marked_)].name
                         : std::string()}};
}

}  // namespace gantry::ui
