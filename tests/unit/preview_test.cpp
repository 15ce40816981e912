// The preview: the toolpath model, the line pictures (PNG and SVG) and the material map,
// checked on the shipped parts/ files and on small files written here.
#include <gtest/gtest.h>
#include <unistd.h>  // getpid

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>

#include "gantry/motion/cycle_timer.hpp"
#include "gantry/lang/script.hpp"  // Script
#include "gantry/machine/job.hpp"  // check_program, interpret
#include "gantry/preview/material.hpp"
#include "gantry/preview/render.hpp"
#include "gantry/preview/toolpath.hpp"
#include "../support/recording_sink.hpp"

namespace gantry {
namespace {

namespace fs = std::filesystem;

const fs::path kParts = fs::path(GANTRY_SOURCE_DIR) / "parts";

// A part file written for one test, removed after it.
class TempPart {
 public:
  TempPart(const std::string& name, const std::string& text)
      : path_(fs::temp_directory_path() / (std::to_string(getpid()) + "_" + name)) {
    std::ofstream(path_) << text;
  }
  ~TempPart() { fs::remove(path_); }
  std::string path() const { return path_.string(); }

 private:
  fs::path path_;
};

// The moves `gantry moves` lists: a check, then the file interpreted into a sink.
std::vector<CanonMove> listed_moves(const std::string& file, const Settings& settings) {
  auto script = Script::load(file);
  PersistentStore store;
  EXPECT_TRUE(check_program(script, settings, store).kept().empty());
  RecordingSink sink;
  ScriptedIO io(true, {});
  JobOptions opt;
  opt.interpreter.dry_run = true;
  interpret(script, settings, sink, io, store, opt);
  return sink.moves;
}

TEST(Toolpath, DemoHasTheBoundsMovesAndEstimateOfTheCheck) {
  const Settings s = default_settings();
  ToolpathOptions opts;
  opts.estimate = true;
  const Toolpath path = load_toolpath((kParts / "demo.sbp").string(), s, opts);
  EXPECT_TRUE(path.violations.empty());
  EXPECT_FALSE(path.cancelled);
  // Worked out from the file: it starts at 0,0,0, cuts 0.125 deep and parks at 12, 9, 1.
  EXPECT_EQ(path.bounds.min(), Eigen::Vector3f(0, 0, -0.125f));
  EXPECT_EQ(path.bounds.max(), Eigen::Vector3f(12, 9, 1));
  EXPECT_EQ(path.start, Eigen::Vector3f::Zero());
  const ToolpathSegment& last = path.segments.back();
  EXPECT_EQ(Eigen::Vector3f(last.x, last.y, last.z), Eigen::Vector3f(12, 9, 1));
  EXPECT_EQ(last.line, 57u);
  EXPECT_EQ(last.kind, PathKind::Jog);

  // The same moves `gantry moves` lists, one segment per line move (demo has no arcs).
  const std::vector<CanonMove> moves = listed_moves((kParts / "demo.sbp").string(), s);
  EXPECT_EQ(path.moves, moves.size());
  std::size_t lines = 0;
  for (const CanonMove& m : moves) lines += m.kind == MoveKind::Line;
  EXPECT_EQ(path.segments.size(), lines);

  CycleTimer timer(s, 1);
  JobOptions timed;
  timed.check_moves = &timer;
  check_program(Script::load((kParts / "demo.sbp").string()), s, PersistentStore(), timed);
  const double estimate = timer.seconds();
  EXPECT_GT(estimate, 0);
  EXPECT_DOUBLE_EQ(path.estimated_time_s, estimate);
  EXPECT_EQ(load_toolpath((kParts / "demo.sbp").string(), s).estimated_time_s, 0);  // not asked
}

TEST(Toolpath, KindsAndLinesFollowTheMoves) {
  TempPart f("kinds.sbp", "JZ, 0.5\nJ2, 1, 1\nMZ, -0.1\nM2, 2, 1\n");
  const Toolpath path = load_toolpath(f.path(), default_settings());
  ASSERT_EQ(path.segments.size(), 4u);
  const PathKind kinds[] = {PathKind::Jog, PathKind::Jog, PathKind::Cut, PathKind::Cut};
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(path.segments[i].kind, kinds[i]) << i;
    EXPECT_EQ(path.segments[i].line, i + 1);
  }
}

TEST(Toolpath, AGapBetweenMovesIsJoinedByAJog) {
  // A move that does not start where the last ended (the tool was moved outside the file,
  // as a keypad jog on the live machine does): each segment still starts at the last's end.
  Toolpath path;
  CanonMove a;
  a.to << 1, 0, 0, 0, 0, 0;
  CanonMove b = a;
  b.from << 2, 2, 0, 0, 0, 0;
  b.to << 3, 2, 0, 0, 0, 0;
  b.loc.line = 7;
  path.add(a, 0.001);
  path.add(b, 0.001);
  ASSERT_EQ(path.segments.size(), 3u);
  EXPECT_EQ(path.segments[1].kind, PathKind::Jog);
  EXPECT_EQ(Eigen::Vector3f(path.segments[1].x, path.segments[1].y, path.segments[1].z),
            Eigen::Vector3f(2, 2, 0));
  EXPECT_EQ(path.segments[1].line, 7u);
  EXPECT_EQ(path.segments[2].kind, PathKind::Cut);
  EXPECT_EQ(path.moves, 2u);
}

TEST(Toolpath, ArcsAreChordsWithinTheChordTolerance) {
  Settings s = default_settings();
  s.planner.chord_tolerance = 0.001;
  // A full clockwise circle of radius 2 about 7, 5 from 5, 5 (CG: end = start).
  TempPart f("circle.sbp", "J2, 5, 5\nCG, , 5, 5, 2, 0, T, 1\n");
  const Toolpath path = load_toolpath(f.path(), s);
  ASSERT_TRUE(path.violations.empty()) << format(path.violations.front());
  std::size_t on_arc = 0;
  Eigen::Vector2f from = path.start.head<2>();
  for (const ToolpathSegment& seg : path.segments) {
    const Eigen::Vector2f to(seg.x, seg.y), centre(7, 5);
    if (seg.kind == PathKind::Cut && seg.line == 2) {
      ++on_arc;
      EXPECT_NEAR((to - centre).norm(), 2, 1e-5);
      // The chord's middle strays from the arc by at most the tolerance.
      EXPECT_GE(((from + to) / 2 - centre).norm(), 2 - 0.001 - 1e-5);
    }
    from = to;
  }
  // 2 acos(1 - 0.001 / 2) = 0.0633 rad per chord at most: 100 chords or more a turn.
  EXPECT_GE(on_arc, 100u);
}

TEST(Toolpath, SoftLimitViolationNamesItsLineAndIsNotDrawn) {
  TempPart f("limits.sbp", "J2, 1, 1\nM2, 2, 2\nMX, 30\nM2, 3, 3\n");
  const Toolpath path = load_toolpath(f.path(), default_settings());
  ASSERT_EQ(path.violations.size(), 1u);
  const Diagnostic& d = path.violations[0];
  EXPECT_EQ(d.severity, Severity::Error);
  EXPECT_EQ(d.loc.line, 3);
  EXPECT_NE(d.message.find("soft limits"), std::string::npos) << d.message;
  EXPECT_TRUE(path.has_errors());
  // Line 3 is not drawn, but the check goes on from where it meant the tool to be (X=30,
  // docs/language.md 6.2): the model's break to there is a jog, then line 4 from there.
  EXPECT_EQ(path.bounds.max().x(), 30.0f);
  ASSERT_EQ(path.segments.size(), 4u);
  EXPECT_EQ(path.segments[2].kind, PathKind::Jog);
  EXPECT_EQ(path.segments[2].x, 30.0f);
}

TEST(Toolpath, MissingAndBadFilesGiveLocatedErrors) {
  const Toolpath missing = load_toolpath("/nonexistent/nosuch.sbp", default_settings());
  ASSERT_EQ(missing.violations.size(), 1u);
  EXPECT_NE(format(missing.violations[0]).find("nosuch.sbp"), std::string::npos);
  EXPECT_TRUE(missing.segments.empty());

  TempPart f("bad.sbp", "J2, 1, 1\nM2, 2, (3\nM2, 3, 3\n");
  const Toolpath bad = load_toolpath(f.path(), default_settings());
  ASSERT_FALSE(bad.violations.empty());
  EXPECT_EQ(bad.violations[0].loc.line, 2);
  EXPECT_GT(bad.violations[0].loc.column, 0);
  EXPECT_EQ(bad.segments.size(), 2u);  // the check went past the error
}

// A file of `n` cutting moves in a zigzag.
std::string zigzag(int n) {
  std::string text = "MZ, -0.1\n";
  for (int i = 0; i < n; ++i)
    text += "M2, " + std::to_string(1 + (i % 2) * 10) + ", " + std::to_string(1 + i * 1e-4) + "\n";
  return text;
}

TEST(Toolpath, ProgressReportsTheGrowingPathAndCancelStopsTheLoad) {
  TempPart f("long.sbp", zigzag(150'000));
  std::atomic<bool> cancel = false;
  std::vector<std::size_t> seen;
  ToolpathOptions opts;
  opts.progress = [&](const Toolpath& so_far) { seen.push_back(so_far.segments.size()); };
  const Toolpath whole = load_toolpath(f.path(), default_settings(), opts);
  EXPECT_EQ(whole.segments.size(), 150'001u);
  ASSERT_EQ(seen.size(), 2u);  // every 65536 segments
  EXPECT_EQ(seen[0], 65536u);
  EXPECT_EQ(seen[1], 2 * 65536u);

  opts.cancel = &cancel;
  opts.progress = [&](const Toolpath&) { cancel = true; };
  const Toolpath part = load_toolpath(f.path(), default_settings(), opts);
  EXPECT_TRUE(part.cancelled);
  EXPECT_EQ(part.segments.size(), 65536u);
}

// Pictures -------------------------------------------------------------------------------

bool is(Rgb a, Rgb b) {
  return a == b;
}

TEST(Render, LinePicturesHaveTheirSizeAndDrawOnlyInsideTheToolpathsBox) {
  const Settings s = default_settings();
  for (const char* part : {"demo.sbp", "relative_steps.sbp", "speeds.sbp"}) {
    const Toolpath path = load_toolpath((kParts / part).string(), s);
    for (View view : {View::Top, View::Iso, View::Front, View::Side}) {
      SCOPED_TRACE(std::string(part) + " " + view_name(view));
      PreviewOptions opts;
      opts.view = view;
      opts.width = 640;
      opts.height = 400;
      const Image image = render_lines(path, s, opts);
      ASSERT_EQ(image.width, 640);
      ASSERT_EQ(image.height, 400);
      ASSERT_EQ(image.rgb.size(), 640u * 400 * 3);
      // The toolpath's box as the picture projects it, widened by the start dot's radius.
      const Projection proj(view, preview_box(path, s, opts), 640, 400);
      Eigen::AlignedBox2f box;
      for (int c = 0; c < 8; ++c)
        box.extend(
            proj(path.bounds.corner(static_cast<Eigen::AlignedBox3f::CornerType>(c))).head<2>());
      const float slack = 3 * 640 / 400.0f + 2;
      int drawn = 0;
      for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
          const Rgb c = image.at(x, y);
          // The scale bar and the dimensions (issue 25) are text, outside the path's box.
          if (is(c, palette::background) || is(c, palette::table) || is(c, palette::text))
            continue;
          ++drawn;
          const Eigen::Vector2f p(x + 0.5f, y + 0.5f);
          EXPECT_LE(box.exteriorDistance(p), slack) << x << "," << y;
        }
      // The side view of demo sees its lines edge on; every view still draws lines.
      EXPECT_GT(drawn, 200);
    }
  }
}

TEST(Render, CutsJogsAndTheTableHaveTheirOwnColours) {
  const Settings s = default_settings();
  const Toolpath path = load_toolpath((kParts / "demo.sbp").string(), s);
  const Image image = render_lines(path, s, PreviewOptions{});
  std::map<Rgb, int> count;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) ++count[image.at(x, y)];
  EXPECT_GT(count[palette::cut_deep], 1000);
  EXPECT_GT(count[palette::cut_upper], 20);  // the chamfers' slopes
  EXPECT_GT(count[palette::jog], 200);
  EXPECT_GT(count[palette::table], 800);  // 24 x 18 in at 30 px/in: its outline
  EXPECT_EQ(count[palette::keypad], 0);
  // The table's corner 0, 0 and a border cut at 5, 1 (top view: Y up).
  const Projection proj(View::Top, preview_box(path, s, PreviewOptions{}), 800, 600);
  const Eigen::Vector3f corner = proj({24, 18, 0}), border = proj({5, 1, -0.125f});
  EXPECT_EQ(image.at(static_cast<int>(corner.x()) - 1, static_cast<int>(corner.y())),
            palette::table);
  EXPECT_EQ(image.at(static_cast<int>(border.x()), static_cast<int>(border.y())),
            palette::cut_deep);
}

int count_paths(const std::string& svg) {
  const std::regex path("<path ");
  return static_cast<int>(
      std::distance(std::sregex_iterator(svg.begin(), svg.end(), path), std::sregex_iterator()));
}

TEST(Render, SvgHasOnePathPerRunOfOneStyle) {
  // Runs: jogs (1-2), plunge (3, above its own bottom), cuts (4-5), jogs (6-7), plunge (8),
  // cut (9).
  TempPart f("runs.sbp",
             "JZ, 0.5\nJ2, 1, 1\nMZ, -0.1\nM2, 2, 1\nM2, 2, 2\nJZ, 0.5\nJ2, 3, 3\nMZ, -0.1\n"
             "M2, 4, 3\n");
  const Settings s = default_settings();
  const Toolpath path = load_toolpath(f.path(), s);
  PreviewOptions opts;
  const std::string svg = render_svg(path, s, opts);
  EXPECT_EQ(count_paths(svg), 6);
  EXPECT_NE(svg.find("width=\"800\" height=\"600\""), std::string::npos);
  EXPECT_NE(svg.find("<polygon"), std::string::npos);  // the table
  opts.leading_jogs = false;  // as `gantry moves --svg` draws: the first run is left out
  opts.table = false;
  const std::string figure = render_svg(path, s, opts);
  EXPECT_EQ(count_paths(figure), 5);
  EXPECT_EQ(figure.find("<polygon"), std::string::npos);
}

TEST(Render, ViewsAndCuttersParse) {
  EXPECT_EQ(parse_view("iso"), View::Iso);
  EXPECT_EQ(parse_view("ISO"), std::nullopt);
  ASSERT_TRUE(parse_cutter("v60", 0.5));
  EXPECT_EQ(parse_cutter("v60", 0.5)->v_angle, 60);
  EXPECT_EQ(parse_cutter("ball", 0.5)->shape, CutterShape::Ball);
  EXPECT_EQ(parse_cutter("v", 0.5)->v_angle, 90);
  for (const char* bad : {"", "v0", "v180", "vx", "round", "v60x"})
    EXPECT_FALSE(parse_cutter(bad, 0.5)) << bad;
}

// Material ------------------------------------------------------------------------------

// Two grooves along X: 0.1 deep at Y 1 and 0.3 deep at Y 3, from X 1 to 5.
const char* kGrooves =
    "JZ, 0.5\nJ2, 1, 1\nMZ, -0.1\nMX, 5\nJZ, 0.5\nJ2, 1, 3\nMZ, -0.3\nMX, 5\nJZ, 0.5\n";

TEST(Material, CuttersLeaveTheirProfile) {
  TempPart f("grooves.sbp", kGrooves);
  const Toolpath path = load_toolpath(f.path(), default_settings());
  const float cell_slack = 0.01f;
  for (const char* shape : {"flat", "ball", "v90"}) {
    SCOPED_TRACE(shape);
    const Cutter cutter = *parse_cutter(shape, 0.25);
    const HeightMap map = carve(path, cutter, 0, 1000);
    ASSERT_LE(map.cell, cell_slack);
    // On the groove's axis (to the nearest cell, half a cell off at most).
    EXPECT_NEAR(*map.height(3, 1), -0.1f, map.cell);
    EXPECT_NEAR(*map.height(3, 3), -0.3f, map.cell);
    EXPECT_EQ(*map.height(3, 2), 0.0f);     // between the grooves: uncut
    EXPECT_EQ(*map.height(3, 1.2f), 0.0f);  // beyond the cutter's radius
    // 0.1 off the axis: flat at full depth; ball r - sqrt(r^2 - 0.1^2) = 0.05 higher; a
    // 90-degree V as high as it is far out.
    const float rise = cutter.shape == CutterShape::Flat   ? 0
                       : cutter.shape == CutterShape::Ball ? 0.05f
                                                           : 0.1f;
    EXPECT_NEAR(*map.height(3, 3.1f), -0.3f + rise, cell_slack);
  }
}

TEST(Material, SlopedCutsAreDeepAtTheirLowEndOnly) {
  // Down 0.1 per unit along X: a flat cutter of radius 0.125 leaves at X the depth its tip
  // reached 0.125 further on, down to the end's -0.4 (within a cell).
  TempPart f("ramp.sbp", "JZ, 0\nJ2, 1, 1\nM3, 5, 1, -0.4\n");
  const HeightMap map = carve(load_toolpath(f.path(), default_settings()),
                              Cutter{CutterShape::Flat, 0.25, 90}, 0, 1000);
  EXPECT_NEAR(*map.height(1.5f, 1), -0.0625f, map.cell);
  EXPECT_NEAR(*map.height(3, 1), -0.2125f, map.cell);
  EXPECT_NEAR(*map.height(5, 1), -0.4f, map.cell);
  EXPECT_NEAR(*map.height(5.1f, 1), -0.4f, map.cell);
  EXPECT_EQ(*map.height(0.8f, 1), 0.0f);  // behind the start: uncut
}

// The scale bar's and the dimensions' pixels (palette::text) in [x0, x1) x [y0, y1).
int text_pixels(const Image& image, int x0, int y0, int x1, int y1) {
  int n = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) n += image.at(x, y) == palette::text;
  return n;
}

float luminance(Rgb c) {
  return 0.299f * c[0] + 0.587f * c[1] + 0.114f * c[2];
}

TEST(Material, DeeperCutsAreDarkerInThePicture) {
  // A 1 in cutter: grooves wide enough for the iso view to see their floors past the near
  // wall.
  TempPart f("grooves.sbp", kGrooves);
  const HeightMap map = carve(load_toolpath(f.path(), default_settings()),
                              Cutter{CutterShape::Flat, 1.0, 90}, 0, 800);
  for (View view : {View::Top, View::Iso}) {
    SCOPED_TRACE(view_name(view));
    PreviewOptions opts;
    opts.view = view;
    const Image image = render_material(map, opts);
    ASSERT_EQ(image.width, 800);
    ASSERT_EQ(image.height, 600);
    const Projection proj = material_projection(map, opts);
    auto sample = [&](float x, float y) {
      const Eigen::Vector3f p = proj({x, y, *map.height(x, y)});
      return luminance(image.at(static_cast<int>(p.x()), static_cast<int>(p.y())));
    };
    const float stock = sample(3, 2), shallow = sample(3, 1), deep = sample(3, 3);
    EXPECT_LT(shallow, stock);
    EXPECT_LT(deep, shallow);
    EXPECT_EQ(image.at(2, 2), palette::background);  // the corner is outside the stock
  }
}

TEST(Material, DemoCutIsDarkerThanItsStock) {
  const Toolpath path = load_toolpath((kParts / "demo.sbp").string(), default_settings());
  const HeightMap map = carve(path, Cutter{}, 0, 800);
  EXPECT_NEAR(*map.height(5, 1), -0.125f, 1e-6);  // the border's second pass
  EXPECT_EQ(*map.height(5.2f, 4), 0.0f);          // between the H and the I
  const Image image = render_material(map, PreviewOptions{});
  const Projection proj = material_projection(map, PreviewOptions{});
  const Eigen::Vector3f cut = proj({5, 1, -0.125f}), stock = proj({5.2f, 4, 0});
  EXPECT_LT(luminance(image.at(static_cast<int>(cut.x()), static_cast<int>(cut.y()))),
            luminance(image.at(static_cast<int>(stock.x()), static_cast<int>(stock.y()))));
}

// Issue 25: the material picture had no scale; it has the line picture's scale bar and
// dimensions (black text on the light background), and none without the path.
TEST(Material, ThePictureHasTheScaleBarAndTheDimensions) {
  const Toolpath path = load_toolpath((kParts / "demo.sbp").string(), default_settings());
  const HeightMap map = carve(path, Cutter{}, 0, 400);
  PreviewOptions opts;
  const Image with = render_material(map, opts, &path);
  const int h = with.height;
  EXPECT_GT(text_pixels(with, 8, 8, 400, 15), 300);      // "X 0.0000 to ..." at the top left
  EXPECT_GT(text_pixels(with, 8, h - 16, 200, h), 20);  // the bar and its label
  const Image without = render_material(map, opts);
  EXPECT_EQ(text_pixels(without, 0, 0, without.width, without.height), 0);
}

// Issue 25: stock, tool changes, units and play ------------------------------------------

TEST(Material, StockIsTheBlockGivenNotFittedToTheCuts) {
  // Two grooves from X 1 to 5 in a 10 x 8 x 0.5 block at the origin: the map covers the
  // block (its far corner uncut), not the grooves plus a margin.
  TempPart f("grooves.sbp", kGrooves);
  const Toolpath path = load_toolpath(f.path(), default_settings());
  const Eigen::AlignedBox3f stock(Eigen::Vector3f(0, 0, -0.5f), Eigen::Vector3f(10, 8, 0));
  const HeightMap map = carve(path, Cutter{}, stock, 801);
  EXPECT_FLOAT_EQ(map.x0, 0);
  EXPECT_FLOAT_EQ(map.y0, 0);
  EXPECT_NEAR(map.x0 + map.cell * static_cast<float>(map.nx - 1), 10, map.cell);
  EXPECT_NEAR(map.y0 + map.cell * static_cast<float>(map.ny - 1), 8, map.cell);
  EXPECT_FLOAT_EQ(map.bottom, -0.5f);
  EXPECT_EQ(*map.height(9.9f, 7.9f), 0.0f);  // the block's far corner: uncut stock
  EXPECT_NEAR(*map.height(3, 3), -0.3f, map.cell);
  EXPECT_FALSE(map.height(10.5f, 4));  // off the block
}

TEST(Render, SvgDrawsTheStockRectangleAtItsCorners) {
  // Top view, 800 x 600, a 10 x 8 block with the path inside it and no table: the view fits
  // the block, 67.5 pixels a unit (90 % of 600 / 8), centred.
  TempPart f("grooves.sbp", kGrooves);
  const Settings s = default_settings();
  const Toolpath path = load_toolpath(f.path(), s);
  PreviewOptions opts;
  opts.table = false;
  opts.stock = Eigen::AlignedBox3f(Eigen::Vector3f(0, 0, -0.5f), Eigen::Vector3f(10, 8, 0));
  const std::string svg = render_svg(path, s, opts);
  EXPECT_NE(svg.find("<polygon class=\"stock\" stroke=\"#a06428\" "
                     "points=\"62.50,570.00 737.50,570.00 737.50,30.00 62.50,30.00\"/>"),
            std::string::npos)
      << svg;
  // The scale bar: 2 in (at most a quarter of the width: 200 / 67.5 = 2.96 in), 135 pixels,
  // and the path's bounding dimensions.
  EXPECT_NE(svg.find("points=\"8,586.00 8,592.00 143.00,592.00 143.00,586.00\""),
            std::string::npos);
  EXPECT_NE(svg.find(">2 in</text>"), std::string::npos);
  EXPECT_NE(svg.find("X 0.0000 to 5.0000 (5.0000 in), Y 0.0000 to 3.0000 (3.0000 in), "
                     "Z -0.3000 to 0.5000 (0.8000 in)"),
            std::string::npos);
  // The PNG draws the same rectangle: its right side is stock-coloured.
  const Image image = render_lines(path, s, opts);
  EXPECT_EQ(image.at(737, 300), palette::stock);
}


// The units the file sets (VD, G20/G21) and its cutters (VC) ----------------------------

TEST(Toolpath, AfterVdMillimetresTheBoundsAndTheTableAreInMillimetres) {
  TempPart f("vd_mm.sbp", "VD, , , 1\nJZ, 10\nJ2, 10, 10\nMZ, -3\nMX, 100\nMY, 50\nJZ, 10\n");
  const Settings s = default_settings();  // inches
  const Toolpath path = load_toolpath(f.path(), s);
  ASSERT_FALSE(path.has_errors()) << format(path.violations.front());
  EXPECT_EQ(path.units, Units::Millimetres);
  EXPECT_NEAR(path.bounds.max().x(), 100, 1e-3);
  EXPECT_NEAR(path.bounds.max().y(), 50, 1e-3);
  EXPECT_NEAR(path.bounds.min().z(), -3, 1e-3);
  EXPECT_NEAR(path.cutter_diameter, 0.25 * 25.4, 1e-9);  // VC's, converted with the units
  EXPECT_TRUE(path.cutter_changes.empty());              // the same cutter
  for (const ToolpathSegment& g : path.segments)
    EXPECT_EQ(g.units, static_cast<std::uint8_t>(Units::Millimetres));
  // The table (24 x 18 in) is drawn in millimetres too, and the SVG says mm.
  PreviewOptions opts;
  EXPECT_NEAR(preview_box(path, s, opts).max().x(), 24 * 25.4, 1e-2);
  const std::string svg = render_svg(path, s, opts);
  EXPECT_NE(svg.find("X 0.0000 to 100.0000 (100.0000 mm)"), std::string::npos) << svg;
}

TEST(Toolpath, AGcodeFileInG21IsDrawnInMillimetres) {
  TempPart f("g21.nc", "G21 G90\nG0 Z5\nG0 X10 Y10\nG1 Z-2 F300\nG1 X100 F600\nG1 Y50\n"
                       "G0 Z5\nM2\n");
  const Toolpath path = load_toolpath(f.path(), default_settings());
  ASSERT_FALSE(path.has_errors()) << format(path.violations.front());
  EXPECT_EQ(path.units, Units::Millimetres);
  EXPECT_NEAR(path.bounds.max().x(), 100, 1e-3);
  EXPECT_NEAR(path.bounds.max().y(), 50, 1e-3);
  EXPECT_NEAR(path.bounds.min().z(), -2, 1e-3);
  // G20 stays in inches, as the profile is.
  TempPart g("g20.nc", "G20 G90\nG0 Z0.2\nG1 X4 F20\nM2\n");
  const Toolpath inches = load_toolpath(g.path(), default_settings());
  EXPECT_EQ(inches.units, Units::Inches);
  EXPECT_NEAR(inches.bounds.max().x(), 4, 1e-5);
}

TEST(Toolpath, EachVcInTheFileIsACutterOfItsSegments) {
  TempPart f("two_vc.sbp", "VC, 0.125\nJZ, 0.5\nMZ, -0.1\nMX, 2\nJZ, 0.5\nVC, 0.5\nJ2, 0, 1\n"
                           "MZ, -0.1\nMX, 2\nJZ, 0.5\n");
  const Toolpath path = load_toolpath(f.path(), default_settings());
  ASSERT_FALSE(path.has_errors()) << format(path.violations.front());
  EXPECT_DOUBLE_EQ(path.cutter_diameter, 0.125);  // set before the first move: the first cutter
  ASSERT_EQ(path.cutter_changes.size(), 1u);
  EXPECT_DOUBLE_EQ(path.cutter_changes[0].diameter, 0.5);
  EXPECT_EQ(path.cutter_changes[0].line, 7u);  // the first move after it
  EXPECT_EQ(path.segments.front().tool, 0);
  EXPECT_EQ(path.segments.back().tool, 1);
  EXPECT_EQ(path.segments[path.cutter_changes[0].first].tool, 1);
  EXPECT_EQ(path.segments[path.cutter_changes[0].first - 1].tool, 0);
  const std::string svg = render_svg(path, default_settings(), PreviewOptions{});
  EXPECT_NE(svg.find(">cutters 0.125 in, 0.5 in from line 7</text>"), std::string::npos) << svg;
}

TEST(Toolpath, AToolChangeMacroThatSetsVcChangesTheCutter) {
  // &Tool = n, then C9: this shop's C9 sets the cutter of each tool.
  const fs::path macros = fs::temp_directory_path() / (std::to_string(getpid()) + "_macros");
  fs::create_directories(macros);
  std::ofstream(macros / "C9.sbp") << "IF &Tool = 2 THEN VC, 0.5\nIF &Tool = 1 THEN VC, 0.25\n";
  TempPart f("toolchange.sbp", "&Tool = 1\nC9\nJZ, 0.5\nMX, 1\n&Tool = 2\nC9\nMX, 2\n");
  ToolpathOptions topts;
  topts.job.interpreter.macro_dir = macros.string();
  const Toolpath path = load_toolpath(f.path(), default_settings(), topts);
  fs::remove_all(macros);
  ASSERT_FALSE(path.has_errors()) << format(path.violations.front());
  ASSERT_EQ(path.cutter_changes.size(), 1u);
  EXPECT_DOUBLE_EQ(path.cutter_changes[0].diameter, 0.5);
  EXPECT_EQ(path.cutter_changes[0].line, 6u);  // the C9 line (issue 25: it was the next move's)
}

// Issue 25: a tool change whose macro sets VC and then moves (to the safe Z) is told at the
// calling file's C9 line, not at the line of the macro's own file (the preview's report and
// legend name lines of the file previewed); a TR in a file FP calls, at the FP line.
TEST(Toolpath, AToolChangeIsToldAtTheCallingFilesC9Line) {
  const fs::path macros = fs::temp_directory_path() / (std::to_string(getpid()) + "_macros9");
  fs::create_directories(macros);
  std::ofstream(macros / "C9.sbp") << "'change\n'the cutter\nVC, 0.5\nJZ, 1\n";
  std::ofstream(macros / "spin.sbp") << "'sub\nTR, 12000\nMX, 3\n";
  TempPart f("toolchange9.sbp", "JZ, 0.5\nMX, 1\n'next\n&Tool = 2\nC9\nMX, 2\n"
                                "FP, \"" + (macros / "spin.sbp").string() + "\"\n");
  ToolpathOptions topts;
  topts.job.interpreter.macro_dir = macros.string();
  const Toolpath path = load_toolpath(f.path(), default_settings(), topts);
  fs::remove_all(macros);
  ASSERT_FALSE(path.has_errors()) << format(path.violations.front());
  ASSERT_EQ(path.cutter_changes.size(), 1u);
  EXPECT_DOUBLE_EQ(path.cutter_changes[0].diameter, 0.5);
  EXPECT_EQ(path.cutter_changes[0].tool, 2);
  EXPECT_EQ(path.cutter_changes[0].line, 5u);  // C9's, not the macro's JZ (its line 4) or VC (3)
  ASSERT_FALSE(path.spindle_changes.empty());
  EXPECT_EQ(path.spindle_changes.back().rpm, 12000);
  EXPECT_EQ(path.spindle_changes.back().line, 7u);  // the FP line, not the sub's TR (its 2)
}

TEST(Render, ThePngHasAScaleBarAndTheDimensions) {
  // The SVG's scale bar test's picture: 2 in, 135 pixels, from X 8 to 143 at Y 592.
  TempPart f("grooves.sbp", kGrooves);
  const Settings s = default_settings();
  const Toolpath path = load_toolpath(f.path(), s);
  PreviewOptions opts;
  opts.table = false;
  opts.stock = Eigen::AlignedBox3f(Eigen::Vector3f(0, 0, -0.5f), Eigen::Vector3f(10, 8, 0));
  const Image image = render_lines(path, s, opts);
  for (int x = 8; x <= 143; x += 5) EXPECT_EQ(image.at(x, 592), palette::text) << x;
  EXPECT_EQ(image.at(8, 587), palette::text);    // its ends rise 6 pixels
  EXPECT_EQ(image.at(143, 587), palette::text);
  EXPECT_EQ(image.at(75, 587), palette::background);
  // "2 in" right of the bar, on its line: the 2's 13 pixels and the i's and n's.
  EXPECT_GT(text_pixels(image, 147, 585, 147 + 4 * 6, 592), 25);
  // The dimensions at the top left: "X 0.0000 to 5.0000 (5.0000 in), Y ...", 7 pixels tall.
  EXPECT_GT(text_pixels(image, 8, 8, 400, 15), 300);
  EXPECT_EQ(text_pixels(image, 8, 16, 400, 24), 0);  // one line: it fits 800 pixels
  // The X: its corners at (8, 8) and (12, 8).
  EXPECT_EQ(image.at(8, 8), palette::text);
  EXPECT_EQ(image.at(12, 8), palette::text);
  // Without them (a figure): no text.
  opts.dimensions = false;
  const Image plain = render_lines(path, s, opts);
  for (int y = 0; y < plain.height; ++y)
    for (int x = 0; x < plain.width; ++x) ASSERT_NE(plain.at(x, y), palette::text);
}

TEST(Toolpath, SpindleSpeedsAreListedWithTheirSegment) {
  TempPart f("tr.sbp", "TR, 12000\nMX, 1\nTR, 18000\nMX, 2\n");
  Settings s = default_settings();
  s.spindle.pwm_bit = 5;  // TR sends the speed only to a machine with a speed output
  const Toolpath path = load_toolpath(f.path(), s);
  ASSERT_EQ(path.spindle_changes.size(), 2u);
  EXPECT_EQ(path.spindle_changes[0].rpm, 12000);
  EXPECT_EQ(path.spindle_changes[0].first, 0u);
  EXPECT_EQ(path.spindle_changes[1].rpm, 18000);
  EXPECT_EQ(path.spindle_changes[1].line, 3u);
  EXPECT_EQ(path.spindle_changes[1].first, 1u);
}

TEST(Toolpath, PlayAtHalfTheCycleTimeLeavesTheSecondHalfUncut) {
  // Two equal grooves along X, one after the other: at half the cycle time the first is cut
  // (about), the second not begun.
  TempPart f("halves.sbp", "JZ, 0.5\nJ2, 1, 1\nMZ, -0.2\nMX, 4\nJZ, 0.5\nJ2, 1, 3\n"
                           "MZ, -0.2\nMX, 4\nJZ, 0.5\n");
  ToolpathOptions topts;
  topts.estimate = true;
  const Toolpath path = load_toolpath(f.path(), default_settings(), topts);
  ASSERT_GT(path.estimated_time_s, 0);
  ASSERT_FALSE(path.timeline.empty());
  EXPECT_EQ(path.timeline.back().end, path.segments.size());
  EXPECT_NEAR(path.timeline.back().end_s, path.estimated_time_s, 1e-6);
  const Toolpath half = played_to_time(path, path.estimated_time_s / 2);
  EXPECT_LT(half.segments.size(), path.segments.size());
  const Eigen::AlignedBox3f stock(Eigen::Vector3f(0, 0, -1), Eigen::Vector3f(5, 4, 0));
  const HeightMap map = carve(half, Cutter{}, stock, 501);
  EXPECT_NEAR(*map.height(2, 1), -0.2f, map.cell);  // the first groove: cut
  EXPECT_EQ(*map.height(2, 3), 0.0f);                // the second: not yet
  EXPECT_EQ(*map.height(3.5f, 3), 0.0f);
  // The whole time: both cut; line 4 (the first MX): the first groove and no more.
  const HeightMap all = carve(played_to_time(path, 1e9), Cutter{}, stock, 501);
  EXPECT_NEAR(*all.height(2, 3), -0.2f, all.cell);
  const Toolpath line4 = played_to_line(path, 4);
  EXPECT_EQ(line4.segments.back().line, 4u);
  EXPECT_FLOAT_EQ(line4.segments.back().x, 4);
  const HeightMap at4 = carve(line4, Cutter{}, stock, 501);
  EXPECT_NEAR(*at4.height(3.9f, 1), -0.2f, at4.cell);
  EXPECT_EQ(*at4.height(2, 3), 0.0f);
}

TEST(Toolpath, RotaryAMovesAreWrappedOnACylinderAboutX) {
  // At Z 1 on the axis' centre line, A turns 90 degrees: drawn as a quarter circle of
  // radius 1 about the X axis, in pieces of 2 degrees, ending at (0, 1, 0).
  TempPart f("rotary.sbp", "JZ, 1\nMA, 90\nMX, 2\n");
  Settings s = default_settings();
  s.axes[3].min = -1000;
  s.axes[3].max = 1000;
  const Toolpath path = load_toolpath(f.path(), s);
  ASSERT_TRUE(path.violations.empty()) << format(path.violations.front());
  ASSERT_TRUE(path.wrap_a);
  ASSERT_EQ(path.segments.size(), 1u + 45 + 1);
  for (std::size_t i = 1; i <= 45; ++i) {
    const ToolpathSegment& p = path.segments[i];
    EXPECT_NEAR(std::hypot(p.y, p.z), 1.0f, 1e-5f) << i;  // on the cylinder
    EXPECT_FLOAT_EQ(p.x, 0);
  }
  EXPECT_NEAR(path.segments[45].y, 1.0f, 1e-5f);
  EXPECT_NEAR(path.segments[45].z, 0.0f, 1e-5f);
  EXPECT_NEAR(path.segments[23].y, std::sin(46 * 3.14159265f / 180), 1e-5f);  // 23 pieces in
  // Then X at A 90: along the cylinder's side at (x, 1, 0).
  EXPECT_FLOAT_EQ(path.segments[46].x, 2);
  EXPECT_NEAR(path.segments[46].y, 1.0f, 1e-5f);
  // With A in inches (VD's rotary unit a length) it is a flat axis: Z stays 1.
  s.display.rotary_units[0] = AxisUnit::Inches;
  const Toolpath flat = load_toolpath(f.path(), s);
  EXPECT_FALSE(flat.wrap_a);
  EXPECT_FLOAT_EQ(flat.segments.back().z, 1);
  EXPECT_FLOAT_EQ(flat.segments.back().y, 0);
}

}  // namespace
}  // namespace gantry
