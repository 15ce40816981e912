// HP-GL (.plt, .hpg): the pen moves of a plot become the paths of a part file.
#include <fmt/format.h>  // messages

#include <cctype>    // isalpha, toupper
#include <charconv>  // from_chars
#include <set>
#include <string>

#include "gantry/convert/to_sbp.hpp"
#include "gantry/core/diagnostic.hpp"  // fail, file_loc
#include "part_writer.hpp"

namespace gantry {

using convert::Path;
using convert::Point;
using convert::Segment;

namespace {

// Where a character of the plot is, for messages.
SourceLoc where(std::string_view text, size_t at, const std::string& source) {
  int line = 1, column = 1;
  for (size_t i = 0; i < at && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return file_loc(source, line, column);
}

bool separator(char c) {
  return c == ',' || c == ' ' || c == '\t' || c == '\r' || c == '\n';
}

// Instructions that change only how the plotter draws (speed, line type, pen width...),
// never where: skipped without a note.
const std::set<std::string> kNoGeometry = {"DF", "VS", "LT", "PW", "PT", "FS", "SI", "SL",
                                           "SR", "DT", "CS", "CA", "SS", "SA", "PG", "NR"};

}  // namespace

Conversion hpgl_to_sbp(std::string_view text, const ConvertOptions& o) {
  std::vector<Path> paths;
  std::map<std::string, int> skipped;
  bool down = false, absolute = true, drawing = false;
  bool pen = true;  // a pen is in hand (until SP0 puts it away): only then PD draws
  Point cur;
  auto to = [&](Point p) {
    if (!absolute) p = {cur.x + p.x, cur.y + p.y};
    if (down && pen) {
      if (!drawing) paths.push_back({cur, {}});
      drawing = true;
      paths.back().segments.push_back(convert::line_to(p));
    }
    cur = p;
  };
  size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (c == ';' || separator(c)) {
      ++i;
      continue;
    }
    if (c == '\x1b') {  // a device-control sequence, ESC . X ... : -- nothing to draw
      const size_t end = text.find(':', i);
      i = end == std::string_view::npos ? text.size() : end + 1;
      continue;
    }
    if (!std::isalpha(static_cast<unsigned char>(c)) || i + 1 >= text.size() ||
        !std::isalpha(static_cast<unsigned char>(text[i + 1])))
      fail(where(text, i, o.source),
           fmt::format("FC: expected an HP-GL instruction (two letters) here, found '{}'", c));
    const size_t at = i;
    std::string name = {static_cast<char>(std::toupper(static_cast<unsigned char>(c))),
                        static_cast<char>(std::toupper(static_cast<unsigned char>(text[i + 1])))};
    i += 2;
    if (name == "LB") {  // a label: its text runs to the terminator (ETX)
      const size_t end = text.find('\x03', i);
      i = end == std::string_view::npos ? text.size() : end + 1;
      ++skipped["LB instruction(s) (labels)"];
      continue;
    }
    // The parameters: numbers up to the next instruction or ';'.
    std::vector<double> params;
    while (i < text.size()) {
      while (i < text.size() && separator(text[i])) ++i;
      if (i >= text.size() || text[i] == ';' || std::isalpha(static_cast<unsigned char>(text[i])) ||
          text[i] == '\x1b')
        break;
      const char* b = text.data() + i;
      const char* e = text.data() + text.size();
      if (*b == '+') ++b;  // from_chars takes no plus sign
      double v = 0;
      const auto r = std::from_chars(b, e, v);
      if (r.ec != std::errc{})
        fail(where(text, i, o.source),
             fmt::format("FC: {} expects numbers; '{}' is not one", name, text[i]));
      params.push_back(v);
      i = static_cast<size_t>(r.ptr - text.data());
    }
    if (name == "PU" || name == "PD" || name == "PA" || name == "PR") {
      if (params.size() % 2)
        fail(where(text, at, o.source),
             fmt::format("FC: {} has {} numbers; its points need an X and a Y each", name,
                         params.size()));
      if (name == "PU") down = false;
      if (name == "PD") down = true;
      if (name == "PA") absolute = true;
      if (name == "PR") absolute = false;
      if (!down || !pen) drawing = false;
      for (size_t k = 0; k + 1 < params.size(); k += 2) to({params[k], params[k + 1]});
    } else if (name == "IN") {  // initialise: pen up, absolute
      down = drawing = false;
      absolute = true;
    } else if (name == "SP") {  // pen 0 (or none) puts the pen away; moves then draw nothing
      pen = !params.empty() && params[0] != 0;
      if (!pen) drawing = false;
    } else if (!kNoGeometry.count(name)) {
      ++skipped[name + " instruction(s)"];
    }
  }
  const double mm = 0.025;  // a plotter unit
  const double scale = o.scale > 0 ? o.scale : (o.units == Units::Millimetres ? mm : mm / 25.4);
  return convert::write_part(paths, o, "HP-GL", scale, skipped);
}

}  // namespace gantry
