// Friendly Motion's character scribing, G10 / G16 / G19: text to pen-down polylines in
// Gantry's single-stroke font (the one TT engraves with: gantry/commands/stroke_font.hpp)
// (docs/friendlymotion.md, "Data files, scribed text and the display"). Pure: the caller
// gives V73 and @0, places the polylines (its G60 frame) and moves along them with the laser
// on while the pen is down.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "gantry/core/diagnostic.hpp"  // SourceLoc

namespace gantry {

struct FmScribeStyle {
  double height = 1;         // of the capitals and digits, in the program's units
  double width_ratio = 0.5;  // a standard character's width over its height: the manual's 2:1
};

using FmPoint = std::array<double, 2>;

// What G16 draws, as offsets from where it starts: the table's position is the lower left
// corner of the first character (its baseline; a comma's tail reaches below it).
struct FmScribePath {
  // Pen-down polylines in the order they are drawn; the pen is up between two. A polyline
  // of one point is a dot (the laser on and off there).
  std::vector<std::vector<FmPoint>> strokes;
  // Where the table ends: where the next character would start, on the last line's baseline.
  FmPoint end{0, 0};
};

// The height G19 `#` gives: # inches (the manual's 1" start-up size scaled by #), in the
// program's units (`metric`: millimetres, 25.4 #). G19 is absolute: G19 2 then G19 3 is 3".
// A size that is not above 0 is an error at `loc`.
double fm_character_height(double g19, bool metric, const SourceLoc& loc);

// G10"name": the default font file, fontfile.txt (any case, any folder), selects the font G16
// already uses; any other is refused at `loc`, naming it and why (its format is not given).
void fm_select_font(std::string_view name, const SourceLoc& loc);

// Whether G16 scribes `c` (after `_` became a space): the manual's set, A-Z, 0-9 and
// !#'*+,-./:;<=>[\]^, and the space. Lower case is scribed as capitals (fm_scribe).
bool fm_scribable(char c);

// G16's text with its one variable put in, C printf style: %s the string @0 (`s0`), %i V73
// truncated to an integer, %f V73 (bare: its shortest form, 66.55; with a precision, printf's),
// %c the character whose code V73 holds (truncated); flags, width and precision between the
// % and the letter (either case) as C's printf. `_` and `)` are left as they are.
// `text_loc` locates the text's first character: an error points at the column at fault.
std::string fm_scribe_insert(std::string_view text, double v73, std::string_view s0,
                             const SourceLoc& text_loc);

// G16: the text (its variable put in, fm_scribe_insert) as polylines. `_` is a space, `)` a new
// line 1.5 heights below the last, back at the start's X; lower case is scribed as capitals;
// any other character outside fm_scribable is an error naming it and its column.
FmScribePath fm_scribe(std::string_view text, double v73, std::string_view s0,
                       const FmScribeStyle& style, const SourceLoc& text_loc);

}  // namespace gantry
