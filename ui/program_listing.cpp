// The program listing window part (docs/console.md, "Console window").
#include "program_listing.hpp"

#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>

#include "gantry/core/text_file.hpp"  // read_text_file
#include "theme.hpp"                    // current_palette

namespace gantry::ui {

std::string_view ListingText::line(std::size_t n) const {
  if (n == 0 || n > starts.size()) return {};
  const std::size_t begin = starts[n - 1];
  std::size_t end = n < starts.size() ? starts[n] : text.size();
  while (end > begin && (text[end - 1] == '\n' || text[end - 1] == '\r')) --end;
  return std::string_view(text).substr(begin, end - begin);
}

std::shared_ptr<const ListingText> ListingText::read(const std::string& path) {
  std::optional<std::string> bytes = read_text_file(path);
  if (!bytes) return nullptr;
  auto t = std::make_shared<ListingText>();
  t->path = path;
  t->text = std::move(*bytes);
  // Lines as the interpreter numbers them: each \n ends one; a last line without one counts.
  for (std::size_t i = 0; i < t->text.size();) {
    t->starts.push_back(i);
    const std::size_t nl = t->text.find('\n', i);
    i = nl == std::string::npos ? t->text.size() : nl + 1;
  }
  return t;
}

void ProgramListing::set(std::shared_ptr<const ListingText> text) {
  text_ = std::move(text);
  called_.reset();
  checked_.clear();
  checked_other_ = false;
  shown_ = text_.get();
  highlighted_ = followed_ = first_shown_ = last_shown_ = 0;
}

const ListingText* ProgramListing::called(const std::shared_ptr<const std::string>& file) {
  if (!file || !text_) return nullptr;
  if (*file != checked_) {  // a new name: the same file as the loaded one, or another
    checked_ = *file;
    std::error_code e1, e2;
    checked_other_ =
        *file != text_->path && std::filesystem::weakly_canonical(*file, e1) !=
                                    std::filesystem::weakly_canonical(text_->path, e2);
    if (checked_other_ && (!called_ || called_->path != *file))
      called_ = ListingText::read(*file);  // null: not a file (a typed line), nothing to show
  }
  return checked_other_ && called_ ? called_.get() : nullptr;
}

std::size_t ProgramListing::draw(std::size_t playing, const std::shared_ptr<const std::string>& file,
                                 bool follow, bool pick, int start_line,
                                 std::string& pending_click) {
  // The file that plays: the loaded one, or one it called (FP, C#) while that plays.
  const ListingText* other = called(file);
  if (file && text_ && checked_other_ && !other) playing = 0;  // a line of no file shown
  const ListingText* shown = other ? other : text_.get();
  if (shown != shown_) followed_ = 0;  // another file: bring its line into view
  shown_ = shown;
  const bool at_rest = pick;
  pick = pick && !other;  // the start line is a line of the loaded file
  const std::size_t lines = shown ? shown->lines() : 0;
  highlighted_ = playing <= lines ? playing : 0;
  std::size_t chosen = 0;
  // A script names a line "line N"; it may be out of view, so it is taken here, not drawn.
  if (pick && pending_click.rfind("line ", 0) == 0) {
    std::size_t n = 0;
    const char* digits = pending_click.c_str() + 5;
    const char* end = pending_click.c_str() + pending_click.size();
    if (std::from_chars(digits, end, n).ptr == end && n >= 1 && n <= lines) {
      chosen = n;
      pending_click.clear();
    }
  }
  const float row = ImGui::GetTextLineHeightWithSpacing();
  heading_.clear();
  if (other) {  // say which file plays, or where at rest the run stopped
    const std::string name = std::filesystem::path(other->path).filename().string();
    const std::string top = std::filesystem::path(text_->path).filename().string();
    heading_ = fmt::format("{} {} (called from {})", at_rest ? "stopped in" : "playing", name, top);
    ImGui::TextColored(current_palette().yellow, "%s", heading_.c_str());
    if (at_rest && ImGui::IsItemHovered())
      ImGui::SetTooltip("Start at line starts %s, at its line", top.c_str());
  }
  const float height = std::max(ImGui::GetContentRegionAvail().y, 4 * row + 8);
  // Each file its own child (and scroll position): the called file's, the loaded one's.
  ImGui::BeginChild(other ? "listing_called" : "listing", ImVec2(0, height), true,
                    ImGuiWindowFlags_HorizontalScrollbar);
  if (lines == 0) {
    ImGui::TextDisabled("the part file's lines show here once it is loaded");
    first_shown_ = last_shown_ = 0;
    ImGui::EndChild();
    return chosen;
  }
  // While the file runs the playing line stays in view: once it leaves the view, it is
  // brought a third of the way down (not every line: the operator can still scroll).
  const float view = ImGui::GetWindowHeight();
  if (follow && highlighted_ > 0 && highlighted_ != followed_) {
    const float y = static_cast<float>(highlighted_ - 1) * row;
    const float top = ImGui::GetScrollY();
    if (y < top || y + 2 * row > top + view) ImGui::SetScrollY(std::max(0.0f, y - view / 3));
    followed_ = highlighted_;
  }
  if (!follow) followed_ = 0;
  const float top = ImGui::GetScrollY();
  first_shown_ = static_cast<std::size_t>(std::floor(top / row)) + 1;
  last_shown_ = std::min(lines, static_cast<std::size_t>(std::floor((top + view) / row)));
  // The theme's colours (yellow, cyan, grey on dark; their darker kin on light).
  const Palette& colours = current_palette();
  const ImVec4 playing_colour = colours.yellow, start_colour = colours.cyan;
  ImGuiListClipper clip;
  clip.Begin(static_cast<int>(lines), row);
  while (clip.Step())
    for (int i = clip.DisplayStart; i < clip.DisplayEnd; ++i) {
      const auto n = static_cast<std::size_t>(i) + 1;
      const bool is_start = static_cast<int>(n) == start_line && start_line > 1;
      ImGui::PushID(i);
      const float x = ImGui::GetCursorPosX();
      // The text is drawn apart from the selectable: a line's own "##" is no ImGui id.
      if (ImGui::Selectable("##line", n == highlighted_) && pick) chosen = n;
      if (pick && ImGui::IsItemHovered()) ImGui::SetTooltip("start at line %zu", n);
      ImGui::SameLine(x);
      const std::string_view text = shown->line(n);
      const std::string number = fmt::format("{}{:>6}  ", is_start ? ">" : " ", n);
      ImGui::TextColored(n == highlighted_ ? playing_colour
                         : is_start        ? start_colour
                                           : colours.grey,
                         "%s", number.c_str());
      ImGui::SameLine(0, 0);
      if (n == highlighted_) ImGui::PushStyleColor(ImGuiCol_Text, playing_colour);
      ImGui::TextUnformatted(text.data(), text.data() + text.size());
      if (n == highlighted_) ImGui::PopStyleColor();
      ImGui::PopID();
    }
  ImGui::EndChild();
  return chosen;
}

nlohmann::json ProgramListing::state() const {
  return {{"lines", shown_ ? shown_->lines() : 0},
          {"file", shown_ ? shown_->path : std::string()},
          {"called", shown_ != nullptr && shown_ != text_.get()},
          {"heading", heading_},
          {"highlighted", highlighted_},
          {"first_shown", first_shown_},
          {"last_shown", last_shown_}};
}

}  // namespace gantry::ui
