// bench/preview: loading and drawing a million-segment toolpath with the software renderer.
// Prints the load time, the time to the first frame (whole and progressive), the steady
// frame time and the memory per segment; the targets are a first frame under 2 s and under
// 200 bytes a segment (issue 9).
#include <fmt/format.h>
#include <unistd.h>  // getpid, sysconf

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>

#include "gantry/preview/material.hpp"
#include "gantry/preview/render.hpp"
#include "gantry/preview/toolpath.hpp"

#ifdef GANTRY_BENCH_GL
// The console window's GL figures for the same toolpath (bench/CMakeLists.txt).
void gl_preview_figures(const gantry::Toolpath& path);
#endif

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Resident memory now, bytes (/proc/self/statm's second field, in pages).
std::size_t resident_bytes() {
  std::ifstream statm("/proc/self/statm");
  std::size_t size = 0, resident = 0;
  statm >> size >> resident;
  return resident * static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
}

// A 3D relief carving: `rows` raster rows of `per_row` short M3 moves over a wavy surface
// on a 10 x 10 in blank, the kind of file that reaches a million segments.
void write_relief(const std::string& path, int rows, int per_row) {
  std::ofstream out(path);
  out << "MS, 4, 2\nJZ, 0.5\nJ2, 1, 1\n";
  for (int r = 0; r < rows; ++r) {
    const double y = 1 + 10.0 * r / rows;
    for (int i = 0; i <= per_row; ++i) {
      const int k = r % 2 ? per_row - i : i;  // back and forth
      const double x = 1 + 10.0 * k / per_row;
      const double z = -0.25 + 0.1 * std::sin(x * 1.3) * std::cos(y * 0.9);
      out << fmt::format("M3, {:.4f}, {:.4f}, {:.4f}\n", x, y, z);
    }
  }
  out << "JZ, 0.5\n";
}

}  // namespace

int main() {
  using namespace gantry;
  const std::string file = (std::filesystem::temp_directory_path() /
                            fmt::format("gantry_preview_bench_{}.sbp", getpid()))
                               .string();
  write_relief(file, 1000, 999);  // 1000 x 1000 moves
  const Settings settings = default_settings();
  PreviewOptions view;
  view.view = View::Iso;

  // Progressive: a viewer draws the first batch the loader hands over.
  std::optional<double> first_batch_s;
  ToolpathOptions opts;
  const std::size_t before = resident_bytes();
  const auto t0 = Clock::now();
  opts.progress = [&](const Toolpath& so_far) {
    if (first_batch_s) return;
    const Image image = render_lines(so_far, settings, view);
    first_batch_s = seconds_since(t0);
  };
  const Toolpath path = load_toolpath(file, settings, opts);
  const double load_s = seconds_since(t0);
  const std::size_t after = resident_bytes();
  auto t1 = Clock::now();
  Image image = render_lines(path, settings, view);
  const double first_frame_s = seconds_since(t1);

  constexpr int kFrames = 5;
  t1 = Clock::now();
  for (int i = 0; i < kFrames; ++i) image = render_lines(path, settings, view);
  const double steady_s = seconds_since(t1) / kFrames;

  t1 = Clock::now();
  ToolpathOptions with_estimate;
  with_estimate.estimate = true;
  const double estimate = load_toolpath(file, settings, with_estimate).estimated_time_s;
  const double estimate_load_s = seconds_since(t1);

  t1 = Clock::now();
  const HeightMap map = carve(path, Cutter{}, 0, 800);
  const double carve_s = seconds_since(t1);
  t1 = Clock::now();
  image = render_material(map, view);
  const double material_s = seconds_since(t1);
  std::filesystem::remove(file);

  const double n = static_cast<double>(path.segments.size());
  fmt::print("toolpath: {} segments from {} moves ({} violations)\n", path.segments.size(),
             path.moves, path.violations.size());
  fmt::print("load (interpret, no estimate):  {:.3f} s\n", load_s);
  fmt::print("first frame, whole file:        {:.3f} s (load + {:.3f} s render, {}x{} iso)\n",
             load_s + first_frame_s, first_frame_s, view.width, view.height);
  if (first_batch_s)
    fmt::print("first frame, progressive:       {:.3f} s (the first 65536 segments)\n",
               *first_batch_s);
  fmt::print("steady frame (software):        {:.1f} ms\n", steady_s * 1e3);
  fmt::print("bytes per segment:              {:.1f} (segment vector), {:.1f} (resident growth)\n",
             static_cast<double>(path.segments.capacity() * sizeof(ToolpathSegment)) / n,
             static_cast<double>(after > before ? after - before : 0) / n);
  fmt::print("load with the cycle-time estimate: {:.3f} s (estimate {:.1f} s)\n", estimate_load_s,
             estimate);
  fmt::print("material map: carve {:.3f} s ({} x {} cells), render {:.3f} s\n", carve_s, map.nx,
             map.ny, material_s);
#ifdef GANTRY_BENCH_GL
  gl_preview_figures(path);
#endif
  return 0;
}
