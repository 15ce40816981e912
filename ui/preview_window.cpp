// The Preview window: the part file loaded on a thread of its own and drawn with its
// camera, the tool and the hovered line.
#include "app.hpp"

#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>

#include "window_common.hpp"  // kFixed, place, the palette colours

namespace gantry::ui {
using Clock = std::chrono::steady_clock;

void App::load(const std::string& path) {
  file_ = path;
  if (std::error_code ec; std::filesystem::is_regular_file(path, ec))
    if (std::string why; !recent_.add(path, &why))
      log(LogLine::Error, fmt::format("recent files: {}", why));
  cancel_ = true;
  if (loader_.joinable()) loader_.join();
  cancel_ = false;
  loading_ = true;
  loaded_so_far_ = 0;
  load_started_ = Clock::now();
  // On its own thread: a million segments take a while, and the command line must not wait.
  loader_ = std::thread([this, path, settings = settings_] {
    ToolpathOptions o;
    o.job.yes = true;  // a preview answers PAUSE and MSGBOX as --yes does
    o.job.input_defaults = true;  // and INPUT with its default, as `gantry preview` does
    o.cancel = &cancel_;
    o.progress = [this](const Toolpath& so_far) { loaded_so_far_ = so_far.segments.size(); };
    std::shared_ptr<const ListingText> text = ListingText::read(path);
    auto tp = std::make_shared<Toolpath>(load_toolpath(path, settings, o));
    std::lock_guard lock(loaded_m_);
    if (!cancel_) loaded_ = std::move(tp), loaded_text_ = std::move(text);
  });
}

void App::preview_window() {
  const float top = ImGui::GetFrameHeight();
  const ImVec2 size = ImGui::GetIO().DisplaySize;
  place({{kLeft, top}, {size.x - kLeft, size.y - top - kConsole}});
  ImGui::Begin("Preview", nullptr, kFixed);
  const std::pair<const char*, View> views[] = {
      {"Top", View::Top}, {"Front", View::Front}, {"Side", View::Side}, {"Iso", View::Iso}};
  for (const auto& [name, v] : views) {
    if (button(name)) camera_.set_view(v), fit_ = true;
    ImGui::SameLine();
  }
  if (button(camera_.perspective ? "Perspective" : "Orthographic"))
    camera_.perspective = !camera_.perspective, fit_ = true;
  ImGui::SameLine();
  if (button("Fit")) fit_ = true;
  ImGui::SameLine();
  ImGui::Checkbox("jogs", &show_jogs_);
  ImGui::SameLine();
  if (!loading_ && !path_)
    ImGui::TextDisabled("no part file loaded");
  else if (loading_)
    ImGui::TextColored(kYellow, "loading %s: %zu segments ...", file_.c_str(),
                       loaded_so_far_.load());
  else if (path_)
    ImGui::TextDisabled("%zu segments, %zu moves%s", path_->segments.size(), path_->moves,
                        path_->violations.empty()
                            ? ""
                            : fmt::format(", {} problems (log)", path_->violations.size()).c_str());
  const ImVec2 avail = ImGui::GetContentRegionAvail();
  const int w = std::max(static_cast<int>(avail.x), 16),
            h = std::max(static_cast<int>(avail.y), 16);
  const float aspect = static_cast<float>(w) / static_cast<float>(h);
  if (fit_) {
    Eigen::AlignedBox3f box(Eigen::Vector3f::Zero(),
                            Eigen::Vector3f(static_cast<float>(settings_.preview.table_x),
                                            static_cast<float>(settings_.preview.table_y), 0));
    if (path_ && !path_->bounds.isEmpty()) box.extend(path_->bounds);
    camera_.fit(box, aspect);
    fit_ = false;
  }
  Overlay o;
  o.table = {static_cast<float>(settings_.preview.table_x),
             static_cast<float>(settings_.preview.table_y)};
  o.grid = static_cast<float>(settings_.preview.grid);
  o.show_jogs = show_jogs_;
  const Vec6 p = position(status_);
  if (settings_.preview.draw_tool)
    o.tool = Eigen::Vector3f(static_cast<float>(p[0]), static_cast<float>(p[1]),
                             static_cast<float>(p[2]));
  o.tool_size = 0.02f * std::max(o.table.x(), o.table.y());
  if (!at_rest() && status_.playing_line > 0)
    o.current_line = static_cast<std::uint32_t>(status_.playing_line);
  o.hover_line = hover_line_;
  // Drawing a million segments takes a software renderer a tenth of a second: the picture
  // is drawn again only when the view changed, and at 5 Hz for the tool while it moves.
  const ViewKey view{camera_.yaw,
                     camera_.pitch,
                     camera_.distance,
                     camera_.target.x(),
                     camera_.target.y(),
                     camera_.target.z(),
                     camera_.perspective,
                     w,
                     h,
                     path_.get(),
                     show_jogs_,
                     hover_line_,
                     o.table.x(),
                     o.table.y(),
                     o.grid};
  const LiveKey live{o.tool.value_or(Eigen::Vector3f::Zero()), o.current_line};
  const bool stale = !(view == view_) || (!(live == live_) && Clock::now() - drawn_at_ >
                                                                  std::chrono::milliseconds(200));
  if (stale || always_redraw_) {
    tex_ = gl_->render(w, h, camera_, o);
    view_ = view;
    live_ = live;
    drawn_at_ = Clock::now();
  }
  const unsigned tex = tex_;
  const ImVec2 corner = ImGui::GetCursorScreenPos();
  ImGui::Image(reinterpret_cast<ImTextureID>(static_cast<std::uintptr_t>(tex)),
               ImVec2(static_cast<float>(w), static_cast<float>(h)), ImVec2(0, 1), ImVec2(1, 0));
  const ImGuiIO& io = ImGui::GetIO();
  std::optional<Eigen::Vector2f> pointer;
  if (scripted_hover_) {
    pointer = Eigen::Vector2f(scripted_hover_->x() * static_cast<float>(w),
                              scripted_hover_->y() * static_cast<float>(h));
  } else if (ImGui::IsItemHovered()) {
    pointer = Eigen::Vector2f(io.MousePos.x - corner.x, io.MousePos.y - corner.y);
    if (ImGui::IsMouseDragging(0)) camera_.orbit(io.MouseDelta.x, io.MouseDelta.y);
    if (ImGui::IsMouseDragging(1) || ImGui::IsMouseDragging(2))
      camera_.pan(io.MouseDelta.x, io.MouseDelta.y, static_cast<float>(h));
    if (io.MouseWheel != 0) camera_.zoom(std::pow(0.85f, io.MouseWheel));
  }
  if (pointer) {
    if (*pointer != last_mouse_) {
      hover_line_ =
          gl_->pick(static_cast<int>(pointer->x()), static_cast<int>(pointer->y()), camera_);
      last_mouse_ = *pointer;
    }
    if (hover_line_ > 0 && !ImGui::IsPopupOpen(nullptr, ImGuiPopupFlags_AnyPopupId))
      ImGui::SetTooltip("line %u", hover_line_);
  } else {
    hover_line_ = 0;
    last_mouse_ = {-1, -1};
  }
  ImGui::End();
}

}  // namespace gantry::ui
