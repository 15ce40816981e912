// What the G-code executor's files share: one block's words, the codes' names and the
// outputs M3, M7 and M8 drive. Private to src/interp.
#pragma once

#include <fmt/format.h>

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

#include "gantry/interp/gcode_executor.hpp"

namespace gantry::gcode {

constexpr int kProbeInput = 1;  // the Z zero plate: input switch 1
constexpr int kSpindleOutput = 1;
constexpr int kFloodOutput = 2;  // M8
constexpr int kMistOutput = 3;   // M7
constexpr std::string_view kAxes = "XYZABC";
// The most moves one block may make (canned cycles' holes and pecks), as an arc may have at
// most kMaxArcChords chords: beyond it a block is a mistake, and checking it would take long.
constexpr double kMaxBlockMoves = 1e6;

inline std::string code_name(char letter, int code) {
  return code % 10 ? fmt::format("{}{}.{}", letter, code / 10, code % 10)
                   : fmt::format("{}{}", letter, code / 10);
}

// Why `letter` `code` (x10) is refused: LinuxCNC's codes that Gantry does not run say why
// and what to do instead (gcode_refused.cpp); any other is an unknown code.
std::string unknown_code_message(char letter, int code, bool wincnc);

inline bool is_cycle(int motion) {
  return motion == 730 || (motion >= 810 && motion <= 890 && motion % 10 == 0);
}

// The non-modal codes whose axis words are theirs, not a motion's.
inline bool takes_axis_words(int non_modal, bool wincnc) {
  return non_modal == 100 || non_modal == 280 || non_modal == 300 || non_modal == 920 ||
         (wincnc && (non_modal == 921 || non_modal == 922 || non_modal == 40));
}

// The codes only the WinCNC dialect has (gcode_wincnc.cpp), x10: G0.1, G5, G9, G31, G50-G52.1,
// G92.4, G95; M11-M14, M17.x, M18.x, M28, M29, M37.x, M99.1.
bool wincnc_own_g(int code);
bool wincnc_own_m(int code);

// WinCNC's peck clearance: G73 lifts, and G83 comes back down to, 0.05 in from the last peck
// (manual, G73 and G83); the standard cycles use 0.010 in.
constexpr double kWinCncPeckClearanceIn = 0.05;

}  // namespace gantry::gcode

namespace gantry {

// One block's values: every letter but G and M at most once, the G and M codes by group.
struct GcodeExecutor::Words {
  std::array<double, 26> value{};
  std::array<int, 26> column{};
  std::uint32_t present = 0;
  std::array<int, 16> g{};  // by group: code x10, or -1
  std::array<int, 16> g_col{};
  int non_modal = -1;  // group 0 other than G53
  bool g53 = false;
  std::array<int, 10> m{};  // by group
  std::array<int, 10> m_col{};
  // WinCNC: its own G code (G0.1, G5, G9, G31, G50-G52, G92.4, G95), M code (M11-M37, M99.1)
  // and L code, x10, or -1; and whether one of its codes takes the axis words (G53, L3 X...).
  int wg = -1, wg_col = 0, wm = -1, wm_col = 0, wl = -1, wl_col = 0;
  bool wincnc_axes = false;
  // WinCNC's M and L codes read their own letters (C channels, D, H, P, T ...).
  bool own_letters() const { return wincnc_axes && (wm >= 0 || wl >= 0 || wg >= 0); }
  bool has(char c) const { return present & (1u << (c - 'A')); }
  double get(char c) const { return value[c - 'A']; }
  SourceLoc at(char c, const SourceLoc& loc) const {
    SourceLoc l = loc;
    l.column = column[c - 'A'];
    return l;
  }
  bool any_axis() const {
    for (char c : gcode::kAxes)
      if (has(c)) return true;
    return false;
  }
  // G43.1 without a motion code: its axis words are the offsets, and nothing moves.
  bool g431_alone() const { return g[8] == 431 && g[1] < 0; }
  // Whether a block in an arc mode makes an arc: a G2/G3 word, an axis word, or only the
  // centre (`G2 I0.5`, a full circle). WinCNC's bare `G2` keeps the last centre: it needs more.
  bool makes_arc(bool wincnc) const {
    return (g[1] >= 0 && !wincnc) || any_axis() || has('I') || has('J') || has('K');
  }
};

}  // namespace gantry
