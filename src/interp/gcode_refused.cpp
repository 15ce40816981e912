// Why a LinuxCNC code Gantry does not run is refused: each one by name, with what to do
// instead (docs/gcode.md, "Every G and M code").
#include <fmt/format.h>

#include "gcode_words.hpp"

namespace gantry::gcode {
namespace {

struct Refused {
  char letter;
  int code;  // x10
  const char* why;
};

constexpr const char* kSpline = "splines are not supported; post the toolpath as lines and arcs";
constexpr const char* kLathe = "it is a lathe code; Gantry drives a router";
constexpr const char* kSpindleSync =
    "it needs a spindle encoder; Gantry's spindle is an on/off output with no position or speed "
    "feedback";
constexpr const char* kUvw = "Gantry has no U, V or W axes";

constexpr Refused kRefused[] = {
    {'G', 50, kSpline},  // G5: cubic spline
    {'G', 51, kSpline},  // G5.1: quadratic spline
    {'G', 52, kSpline},  // G5.2, G5.3: NURBS
    {'G', 53, kSpline},
    {'G', 70, kLathe},  // G7: diameter mode
    {'G', 80, kLathe},  // G8: radius mode
    {'G', 171, kUvw},   // G17.1, G18.1, G19.1: the UV, WU, VW planes
    {'G', 181, kUvw},
    {'G', 191, kUvw},
    {'G', 330, kSpindleSync},  // G33: spindle-synchronized motion
    {'G', 331, kSpindleSync},  // G33.1: rigid tapping
    {'G', 432, "an added tool length offset is not supported; give the total with G43.1 Z"},
    {'G', 520, "local offsets are not supported; use G92 or a work coordinate system (G10 L2)"},
    {'G', 700, kLathe},  // G70, G71, G72: lathe finishing and roughing cycles
    {'G', 710, kLathe},
    {'G', 720, kLathe},
    {'G', 740, kSpindleSync},  // G74: left-hand tapping
    {'G', 760, kLathe},        // G76: threading
    {'G', 950, kSpindleSync},  // G95: feed per revolution
    {'G', 960, kLathe},        // G96: constant surface speed
    {'M', 190, "spindle orientation needs a spindle encoder; Gantry's spindle is an on/off output"},
    {'M', 480, "feed and speed overrides cannot be switched off or on by the program"},
    {'M', 490, "feed and speed overrides cannot be switched off or on by the program"},
    {'M', 500, "feed and speed overrides cannot be switched off or on by the program"},
    {'M', 510, "feed and speed overrides cannot be switched off or on by the program"},
    {'M', 520, "there is no adaptive feed input"},
    {'M', 530, "there is no feed stop input"},
    {'M', 600, "there is no pallet shuttle; use M0 to pause"},
    {'M', 660, "waiting on an input is not supported in G-code; use OpenSBP's ON INPUT or M0"},
    {'M', 670, "there are no analog outputs"},
    {'M', 680, "there are no analog outputs"},
    {'M', 700, "saving and restoring modal state is not supported; set the modes again"},
    {'M', 710, "saving and restoring modal state is not supported; set the modes again"},
    {'M', 720, "saving and restoring modal state is not supported; set the modes again"},
    {'M', 730, "saving and restoring modal state is not supported; set the modes again"},
};

}  // namespace

std::string unknown_code_message(char letter, int code, bool wincnc) {
  const std::string name = code_name(letter, code);
  if (!wincnc) {
    for (const Refused& r : kRefused)
      if (r.letter == letter && r.code == code)
        return fmt::format("{} is refused: {}", name, r.why);
    if (letter == 'M' && code >= 1000 && code <= 1990)
      return fmt::format(
          "{} is refused: user M codes run external programs, which Gantry does "
          "not do; use an output (M64/M65 P) or OpenSBP",
          name);
  }
  return fmt::format("{} is not a code Gantry knows; docs/gcode.md lists the codes it runs", name);
}

}  // namespace gantry::gcode
