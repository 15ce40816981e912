// `gantry preview`: toolpath, picture, summary.
#include "preview_command.hpp"

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include <algorithm>  // max
#include <charconv>   // from_chars
#include <iostream>   // JSON to stdout

#include "gantry/core/any_bytes.hpp"    // json_text
#include "gantry/core/text.hpp"         // lower
#include "gantry/core/text_file.hpp"    // write_file_atomically
#include "gantry/preview/material.hpp"  // carve, render_material
#include "gantry/preview/render.hpp"    // render_lines, render_svg
#include "gantry/preview/toolpath.hpp"  // load_toolpath
#include "machine_profile.hpp"          // add_profile_option
#include "report.hpp"                   // to_json(Diagnostic)

namespace gantry {
namespace {

// "WxH" with both from 16 to 8192 pixels.
bool parse_size(const std::string& text, int& w, int& h) {
  const size_t x = text.find_first_of("xX");
  if (x == std::string::npos) return false;
  const char* end = text.data() + text.size();
  const auto a = std::from_chars(text.data(), text.data() + x, w);
  const auto b = std::from_chars(text.data() + x + 1, end, h);
  return a.ec == std::errc{} && a.ptr == text.data() + x && b.ec == std::errc{} && b.ptr == end &&
         w >= 16 && h >= 16 && w <= 8192 && h <= 8192;
}

// "WxHxD" or "WxHxD@X,Y,Z": the stock's size along X, Y and Z, and its front left corner's
// X and Y and its top's Z (default 0, 0 and --stock-top). Sizes above 0.
std::optional<Eigen::AlignedBox3f> parse_stock(const std::string& text, double top) {
  double v[6] = {0, 0, 0, 0, 0, top};
  const char* p = text.data();
  const char* end = p + text.size();
  for (int i = 0; i < 6; ++i) {
    const auto r = std::from_chars(p, end, v[i]);
    if (r.ec != std::errc{}) return std::nullopt;
    p = r.ptr;
    if (p == end) {
      if (i == 2 || i == 5) break;
      return std::nullopt;
    }
    const char want = i < 2 ? 'x' : i == 2 ? '@' : ',';
    if (i < 2 ? (*p != 'x' && *p != 'X') : *p != want) return std::nullopt;
    if (i == 5 || ++p == end) return std::nullopt;
  }
  if (v[0] <= 0 || v[1] <= 0 || v[2] <= 0) return std::nullopt;
  const Eigen::Vector3f lo(static_cast<float>(v[3]), static_cast<float>(v[4]),
                           static_cast<float>(v[5] - v[2]));
  return Eigen::AlignedBox3f(lo, lo + Eigen::Vector3f(static_cast<float>(v[0]),
                                                      static_cast<float>(v[1]),
                                                      static_cast<float>(v[2])));
}

std::string extension(const std::string& path) {
  const size_t dot = path.find_last_of('.');
  return ascii::lower(dot == std::string::npos ? "" : std::string_view(path).substr(dot + 1));
}

}  // namespace

CLI::App* add_preview_command(CLI::App& app, PreviewArgs& a) {
  CLI::App* cmd = app.add_subcommand(
      "preview",
      "Draw a part file's toolpath to a PNG or SVG file, without a display or a machine");
  cmd->add_option("file", a.file, "Part file (.sbp)")->required();
  cmd->add_option("-o,--output", a.output, "Picture to write: NAME.png or NAME.svg")->required();
  add_profile_option(cmd, a.settings);
  cmd->add_option("--view", a.view, "top, iso, front or side")
      ->check(CLI::IsMember({"top", "iso", "front", "side"}));
  cmd->add_option("--size", a.size, "Picture size in pixels, WxH (16 to 8192 each)");
  cmd->add_flag("--material", a.material,
                "Draw the stock as the cutter leaves it (VC's diameter) instead of the lines");
  cmd->add_option("--cutter", a.cutter,
                  "Cutter shape for --material: flat, ball, v (90 degrees) or v<angle>, e.g. v60");
  cmd->add_option("--stock-top", a.stock_top,
                  "Z of the material's surface for --material (default 0)");
  cmd->add_option("--stock", a.stock,
                  "Stock block WxHxD[@X,Y,Z] in the file's units: size along X, Y, Z, and its "
                  "front left corner and top (default @0,0,--stock-top); default the profile's "
                  "VP table size");
  cmd->add_option("--play", a.play_s,
                  "Draw the path and the cut as they stand at machine time T seconds");
  cmd->add_option("--play-line", a.play_line,
                  "Draw the path and the cut as they stand after line N first runs");
  cmd->add_flag("--json", a.json, "Print the summary as one JSON object");
  return cmd;
}

int run_preview(const PreviewArgs& a, const Settings& settings, const JobOptions& job,
                const PersistentStore& store) {
  PreviewOptions opts;
  opts.view = *parse_view(a.view);  // CLI11 checked the name
  if (!parse_size(a.size, opts.width, opts.height)) {
    fmt::print(stderr, "error: --size {} must be WIDTHxHEIGHT in pixels, e.g. 800x600\n", a.size);
    return 1;
  }
  const std::string ext = extension(a.output);
  if (ext != "png" && ext != "svg") {
    fmt::print(stderr, "error: -o {}: the picture must be a .png or an .svg file\n", a.output);
    return 1;
  }
  if (a.material && ext != "png") {
    fmt::print(stderr, "error: --material draws an image: write it to a .png file\n");
    return 1;
  }
  const std::optional<Cutter> cutter = parse_cutter(a.cutter, settings.cutter.diameter);
  if (!cutter) {
    fmt::print(stderr,
               "error: --cutter {} must be flat, ball, v or v<angle> (0 to 180), e.g. v60\n",
               a.cutter);
    return 1;
  }

  std::optional<Eigen::AlignedBox3f> stock;
  if (!a.stock.empty() && !(stock = parse_stock(a.stock, a.stock_top))) {
    fmt::print(stderr,
               "error: --stock {} must be WIDTHxHEIGHTxDEPTH[@X,Y,Z] with sizes above 0, "
               "e.g. 24x18x0.75 or 10x8x0.5@2,2,0\n",
               a.stock);
    return 1;
  }
  if (a.play_s && a.play_line) {
    fmt::print(stderr, "error: --play and --play-line: give one of them\n");
    return 1;
  }
  if (a.play_s && *a.play_s < 0) {
    fmt::print(stderr, "error: --play {:g}: the time must be 0 s or more\n", *a.play_s);
    return 1;
  }

  ToolpathOptions topts;
  topts.job = job;
  topts.store = &store;
  topts.estimate = true;
  const Toolpath whole = load_toolpath(a.file, settings, topts);
  const bool failed = whole.has_errors();
  Cutter cut = *cutter;
  cut.diameter = whole.cutter_diameter;  // VC's, in the units the file left in force
  const Toolpath path = a.play_s      ? played_to_time(whole, *a.play_s)
                        : a.play_line ? played_to_line(whole, *a.play_line)
                                      : whole;
  // The profile's stock (VP's table size, SB3's preview material) is in its units; the
  // path is in the units the file left in force.
  if (!stock) {
    const auto k = static_cast<float>(units_factor(settings.units, whole.units));
    const Eigen::Vector3f size(static_cast<float>(settings.preview.table_x),
                               static_cast<float>(settings.preview.table_y),
                               static_cast<float>(settings.preview.table_z));
    const auto top = static_cast<float>(a.stock_top);
    stock = Eigen::AlignedBox3f(Eigen::Vector3f(0, 0, top - k * size.z()),
                                Eigen::Vector3f(k * size.x(), k * size.y(), top));
  }
  opts.stock = stock;

  // A file that cannot be read (or makes no move for its errors) has nothing to draw.
  const bool draw = !(failed && path.moves == 0);
  bool written = false;
  if (draw) {
    if (a.material) {
      if (whole.bounds.isEmpty() || whole.bounds.min().z() >= stock->max().z())
        fmt::print(stderr,
                   "warning: no move goes below the stock top (Z {:g}; --stock-top sets it): "
                   "the material map shows uncut stock\n",
                   stock->max().z());
      const HeightMap map = carve(path, cut, *stock, std::max(opts.width, opts.height));
      written = write_png(a.output, render_material(map, opts, &path));
    } else if (ext == "png") {
      written = write_png(a.output, render_lines(path, settings, opts));
    } else {
      written = write_file_atomically(a.output, render_svg(path, settings, opts));
    }
    if (!written) fmt::print(stderr, "error: cannot write {}\n", a.output);
  }

  const char* units = units_name(whole.units);
  const Eigen::AlignedBox3f& b = path.bounds;
  if (a.json) {
    nlohmann::ordered_json j;
    j["file"] = a.file;
    j["output"] = written ? a.output : "";
    j["view"] = a.view;
    j["material"] = a.material;
    j["moves"] = path.moves;
    j["segments"] = path.segments.size();
    j["units"] = units;
    if (!b.isEmpty())
      j["bounds"] = {{"min", {b.min().x(), b.min().y(), b.min().z()}},
                     {"max", {b.max().x(), b.max().y(), b.max().z()}}};
    j["stock"] = {{"min", {stock->min().x(), stock->min().y(), stock->min().z()}},
                  {"max", {stock->max().x(), stock->max().y(), stock->max().z()}}};
    j["estimated_time_s"] = path.estimated_time_s;
    if (a.play_s || a.play_line) {
      j["played"] = {{"segments", path.segments.size()},
                     {"time_s", path.timeline.empty() ? 0.0 : path.timeline.back().end_s}};
      if (a.play_s) j["played"]["at_s"] = *a.play_s;
      if (a.play_line) j["played"]["line"] = *a.play_line;
    }
    // The cutter per range of segments: VC's at the start, then each change.
    j["tools"] = nlohmann::ordered_json::array();
    j["tools"].push_back({{"first_segment", 0},
                          {"line", 0},
                          {"diameter", cut.diameter},
                          {"tool", path.tool}});
    for (const Toolpath::CutterChange& c : path.cutter_changes)
      j["tools"].push_back({{"first_segment", c.first},
                            {"line", c.line},
                            {"diameter", c.diameter},
                            {"tool", c.tool}});
    j["spindle"] = nlohmann::ordered_json::array();
    for (const Toolpath::SpindleChange& c : path.spindle_changes)
      j["spindle"].push_back({{"first_segment", c.first}, {"line", c.line}, {"rpm", c.rpm}});
    j["violations"] = nlohmann::ordered_json::array();
    for (const Diagnostic& d : path.violations) j["violations"].push_back(to_json(d));
    std::cout << json_text(j) << "\n";
  } else {
    for (const Diagnostic& d : path.violations) fmt::print(stderr, "{}\n", format(d));
    if (!draw) return 1;
    fmt::print("{}: {} moves, {} segments, estimated time {:.3f} s\n", a.file, path.moves,
               path.segments.size(), path.estimated_time_s);
    if (b.isEmpty())
      fmt::print("bounds: none (no motion)\n");
    else
      fmt::print("bounds ({}): X {:.4f} to {:.4f}, Y {:.4f} to {:.4f}, Z {:.4f} to {:.4f}\n", units,
                 b.min().x(), b.max().x(), b.min().y(), b.max().y(), b.min().z(), b.max().z());
    fmt::print("stock ({}): X {:g} to {:g}, Y {:g} to {:g}, Z {:g} to {:g}\n", units,
               stock->min().x(), stock->max().x(), stock->min().y(), stock->max().y(),
               stock->min().z(), stock->max().z());
    for (const Toolpath::CutterChange& c : path.cutter_changes)
      fmt::print("tool change at line {} (segment {}): {}cutter diameter {:g}\n", c.line, c.first,
                 c.tool ? fmt::format("tool {}, ", c.tool) : "", c.diameter);
    for (const Toolpath::SpindleChange& c : path.spindle_changes)
      fmt::print("spindle at line {} (segment {}): {:g} RPM\n", c.line, c.first, c.rpm);
    if (a.play_s || a.play_line)
      fmt::print("played: {} of {} segments, to machine time {:.3f} s\n", path.segments.size(),
                 whole.segments.size(),
                 path.timeline.empty() ? 0.0 : path.timeline.back().end_s);
    if (written)
      fmt::print("wrote {}: {} view{}\n", a.output, a.view, a.material ? ", material" : "");
  }
  return failed || (draw && !written) ? 1 : 0;
}

}  // namespace gantry
