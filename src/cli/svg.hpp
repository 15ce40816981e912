// `gantry moves --svg`: a top view of canonical moves for docs/figures, drawn by the
// preview's SVG routine (one drawing code for both).
#pragma once

#include <string>
#include <vector>

#include "gantry/canon/canon_move.hpp"  // CanonMove
#include "gantry/settings/settings.hpp"  // Settings (the chord tolerance)

namespace gantry {

// The moves from the first cut on (the jogs before it only place the tool), fitted to a
// picture 440 pixels wide, without the table outline; styles as docs/preview.md gives them.
std::string moves_svg(const std::vector<CanonMove>& moves, const Settings& settings);

}  // namespace gantry
