// WinCNC's `{}` substitution in a G-code value (docs/gcode.md, "The WinCNC dialect").
#pragma once

#include <functional>
#include <string_view>

#include "gantry/core/diagnostic.hpp"  // SourceLoc

namespace gantry {

// The value of a variable named in braces (`TH1`, `LZ0`, an axis letter), or a located error.
using WinCncVariable = std::function<double(std::string_view name, const SourceLoc& at)>;

// The value of `{...}` as the WinCNC manual ("Braces") defines it: a variable (or a number)
// and then numbers, joined by * / + - (* and / first, then left to right), as in {TH1+2}.
// The manual requires a number after the first value, so `{TH1}` alone is an error. `lookup`
// null: only the syntax is checked (every variable reads 0). Errors are located at `at` plus
// the offset in `text`, which includes the braces.
double evaluate_wincnc_braces(std::string_view text, const SourceLoc& at,
                              const WinCncVariable* lookup);

}  // namespace gantry
