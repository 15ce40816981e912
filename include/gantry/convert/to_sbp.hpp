// FC's converters: HP-GL plots and DXF drawings into part files of M2 and CG lines.
//
// A drawing becomes paths (lines and circular arcs, in X and Y); each path is cut at one Z,
// with jogs at a safe Z between paths. The converters are pure: text in, text out.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "gantry/settings/settings.hpp"  // Units

namespace gantry {

struct ConvertOptions {
  std::string source;           // the drawing's name: located errors and the header name it
  Units units = Units::Inches;  // of the part file
  // Part-file units per drawing unit; 0: from the file (HP-GL: 0.025 mm per plotter unit;
  // DXF: $INSUNITS, or 1 when the drawing has no units).
  double scale = 0;
  double cut_z = 0;   // Z of the cutting moves (the pen down)
  double safe_z = 1;  // Z of the jogs between paths (the pen up)
};

struct Conversion {
  std::string text;                // the part file
  std::size_t paths = 0;           // separate cuts (the tool lifts between them)
  std::vector<std::string> notes;  // what was left out, e.g. "3 TEXT entities"
};

// Each throws GantryError located in the drawing (line and column) when it cannot be read.
// HP-GL: IN, PU, PD, PA, PR, SP (after SP0, moves draw nothing until a pen is selected);
// other instructions are skipped and named in the notes.
Conversion hpgl_to_sbp(std::string_view text, const ConvertOptions& options);
// DXF (text form): LINE, ARC, CIRCLE, LWPOLYLINE and POLYLINE/VERTEX with bulges, from the
// ENTITIES section; other entities are skipped and named in the notes.
Conversion dxf_to_sbp(std::string_view text, const ConvertOptions& options);

}  // namespace gantry
