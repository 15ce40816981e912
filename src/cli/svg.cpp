// `gantry moves --svg`: the moves as a toolpath, drawn by the preview.
#include "svg.hpp"

#include "gantry/preview/render.hpp"    // render_svg
#include "gantry/preview/toolpath.hpp"  // Toolpath

namespace gantry {

std::string moves_svg(const std::vector<CanonMove>& moves, const Settings& settings) {
  Toolpath path;
  for (const CanonMove& m : moves) path.add(m, settings.planner.chord_tolerance);
  PreviewOptions opts;
  opts.width = 440;
  opts.height = 0;  // from the drawing's aspect
  opts.table = false;
  opts.leading_jogs = false;
  opts.dimensions = false;  // a figure: no scale bar
  return render_svg(path, settings, opts);
}

}  // namespace gantry
