// The window's colours, sizes and fonts.
#include "theme.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace gantry::ui {
namespace {

ImFont* g_digits = nullptr;
float g_digits_size = 0;

// A sans mono bold for the digits when the system has one (fonts-dejavu-core), else
// Dear ImGui's own font, larger.
const char* const kDigitFonts[] = {"/usr/share/fonts/truetype/dejavu/DejaVuSansMono-Bold.ttf",
                                   "/usr/share/fonts/dejavu/DejaVuSansMono-Bold.ttf"};

}  // namespace

const Palette& palette(bool light) {
  static const Palette dark{
      {1.0f, 0.35f, 0.35f, 1}, {0.4f, 0.9f, 0.4f, 1},    {1, 0.85f, 0.3f, 1}, {0.6f, 0.6f, 0.6f, 1},
      {0.5f, 0.85f, 1, 1},     {0.95f, 0.45f, 0.95f, 1}, {1, 1, 1, 1},        {0.3f, 0.3f, 0.3f, 1},
      {0.06f, 0.06f, 0.07f, 1}};
  // On white the same hues, darker: each at least 4.5:1 against the window's background.
  static const Palette bright{
      {0.75f, 0.05f, 0.05f, 1}, {0.05f, 0.45f, 0.05f, 1}, {0.55f, 0.38f, 0.0f, 1},
      {0.35f, 0.35f, 0.35f, 1}, {0.0f, 0.35f, 0.6f, 1},   {0.6f, 0.0f, 0.6f, 1},
      {0.0f, 0.0f, 0.0f, 1},    {0.75f, 0.75f, 0.75f, 1}, {0.86f, 0.86f, 0.86f, 1}};
  return light ? bright : dark;
}

const Palette& current_palette() {
  const ImVec4& bg = ImGui::GetStyle().Colors[ImGuiCol_WindowBg];
  return palette(bg.x + bg.y + bg.z > 1.5f);
}

void build_fonts(float scale) {
  ImFontAtlas& atlas = *ImGui::GetIO().Fonts;
  atlas.Clear();
  ImFontConfig text;
  text.SizePixels = std::round(13 * scale);
  atlas.AddFontDefault(&text);
  // Only what a readout shows, so that the large size keeps the atlas small.
  static const ImWchar digits[] = {' ', ' ', '+', '.', '0', '9', 'A', 'C', 'X', 'Z', 0};
  g_digits_size = std::round(std::min(64 * scale, 160.0f));
  g_digits = nullptr;
  for (const char* path : kDigitFonts)
    if (std::error_code ec; std::filesystem::exists(path, ec)) {
      g_digits = atlas.AddFontFromFileTTF(path, g_digits_size, nullptr, digits);
      if (g_digits) break;
    }
  if (!g_digits) {
    ImFontConfig big;
    big.SizePixels = g_digits_size;
    g_digits = atlas.AddFontDefault(&big);
  }
  atlas.Build();
}

ImFont* digits_font() {
  return g_digits;
}

float digits_font_size() {
  return g_digits_size;
}

void apply_style(bool light, float scale) {
  ImGuiStyle& style = ImGui::GetStyle();
  style = ImGuiStyle();
  if (light) {
    ImGui::StyleColorsLight(&style);
    style.Colors[ImGuiCol_WindowBg] = ImVec4(0.97f, 0.97f, 0.97f, 1);
    style.Colors[ImGuiCol_TextDisabled] = ImVec4(0.38f, 0.38f, 0.38f, 1);  // 6:1 on the background
    style.FrameBorderSize = 1;
  } else {
    ImGui::StyleColorsDark(&style);
  }
  // Dialogs and menus opaque: a question over the preview must read at once.
  style.Colors[ImGuiCol_PopupBg].w = 1.0f;
  style.ScaleAllSizes(scale);
}

void push_estop_colours() {
  ImGui::PushStyleColor(ImGuiCol_Button, ImVec4(0.7f, 0.1f, 0.1f, 1));
  ImGui::PushStyleColor(ImGuiCol_ButtonHovered, ImVec4(0.82f, 0.12f, 0.12f, 1));
  ImGui::PushStyleColor(ImGuiCol_ButtonActive, ImVec4(0.55f, 0.05f, 0.05f, 1));
  ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1, 1, 1, 1));
}

}  // namespace gantry::ui
