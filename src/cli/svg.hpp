// A top view (XY) of canonical moves as an SVG picture, for docs/figures and for people.
#pragma once

#include <string>
#include <vector>

#include "gantry/motion/canon_move.hpp"  // CanonMove

namespace gantry {

// Cutting moves solid, blue at the deepest Z of their command (source line) and orange
// above it (tabs, spiral descents, upper passes); jogs dashed grey, those before the first
// cut left out; arcs as true SVG arcs. The start is a green dot, the end a red one. Y points
// up, as on the table.
std::string moves_svg(const std::vector<CanonMove>& moves);

}  // namespace gantry
