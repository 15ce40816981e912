// export-gcode's round trip (docs/gcode.md, "Exporting"): every part in parts/ and in the
// shared corpus that runs without an operator, written as G-code and read back, gives the
// same canonical moves within 1e-6.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include <algorithm>  // sort
#include <iostream>   // the count of files compared

#include "../support/recording_sink.hpp"
#include "cli/export_gcode.hpp"
#include "gantry/interp/operator_io.hpp"       // ScriptedIO
#include "gantry/interp/persistent_store.hpp"  // PersistentStore
#include "gantry/lang/script.hpp"              // Script
#include "gantry/machine/job.hpp"              // check_program, interpret
#include "gantry/motion/path_limits.hpp"       // nominal_path_speed

namespace gantry {
namespace {

// Sends each move both to a recording and to the G-code writer. A file that changes the
// machine's units (VD) makes its later moves in the new units, which the exported G21 or
// G20 brings back to the profile's when read: the recording keeps each move in the
// profile's units, so both compare.
class Tee : public MotionSink {
 public:
  Tee(RecordingSink& a, MotionSink& b, Units profile) : a_(a), b_(b), profile_(profile) {}
  void move(const CanonMove& m) override {
    CanonMove c = m;
    const double k = units_factor(units_, profile_);
    for (Vec6* v : {&c.from, &c.to}) v->head<3>() *= k;
    c.center_x *= k;
    c.center_y *= k;
    for (double* v : {&c.speeds.xy, &c.speeds.z}) *v *= k;
    a_.move(c);
    b_.move(m);
  }
  void flush() override {}
  void settings_changed(const Settings& s) override {
    units_ = s.units;
    b_.settings_changed(s);
  }

 private:
  RecordingSink& a_;
  MotionSink& b_;
  Units profile_, units_ = profile_;
};

// What the machine is told: kinds, ends, arcs, dwells, outputs and the path speed of feeds.
std::string mismatch(const CanonMove& a, const CanonMove& b) {
  constexpr double tol = 1e-6;
  if (a.kind != b.kind) return "kind";
  if (a.speed_class != b.speed_class) return "speed class";
  if ((a.to - b.to).cwiseAbs().maxCoeff() > tol) return "end point";
  if ((a.from - b.from).cwiseAbs().maxCoeff() > tol) return "start point";
  if (a.kind == MoveKind::Arc &&
      (a.plane != b.plane || std::abs(a.center_x - b.center_x) > tol ||
       std::abs(a.center_y - b.center_y) > tol || std::abs(a.sweep - b.sweep) > tol))
    return "arc";
  if (a.kind == MoveKind::Line && a.speed_class == SpeedClass::Move &&
      std::abs(nominal_path_speed(a.to - a.from, a.speeds) -
               nominal_path_speed(b.to - b.from, b.speeds)) > tol)
    return "feed";
  if (a.kind == MoveKind::Arc && std::abs(a.speeds.xy - b.speeds.xy) > tol) return "arc feed";
  if (std::abs(a.dwell_s - b.dwell_s) > tol) return "dwell";
  if (a.output != b.output || a.output_on != b.output_on) return "output";
  return {};
}

TEST(GcodeRoundTrip, ExportedPartsReadBackAsTheSameMoves) {
  std::vector<std::filesystem::path> files;
  for (const char* dir : {GANTRY_SOURCE_DIR "/parts", GANTRY_SOURCE_DIR "/../shared/corpus"}) {
    std::error_code ec;
    for (const auto& e : std::filesystem::directory_iterator(dir, ec))
      if (e.path().extension() == ".sbp" || e.path().extension() == ".fm")
        files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  const Settings settings = default_settings();
  int compared = 0;
  for (const auto& path : files) {
    JobOptions opt;
    opt.operator_present = false;
    opt.interpreter.macro_dir = path.parent_path().string();
    const auto script = Script::load(path.string());
    const PersistentStore store;
    bool clean = true;
    const DiagnosticLog found = check_program(script, settings, store, opt);
    for (const Diagnostic& d : found.kept()) clean = clean && d.severity != Severity::Error;
    if (!clean) continue;  // needs an operator, or a file it does not have
    RecordingSink original;
    GcodeWriter writer(settings, path.filename().string());
    Tee tee(original, writer, settings.units);
    ScriptedIO io(true, {});
    opt.interpreter.dry_run = true;
    PersistentStore scratch = store.scratch_copy();
    interpret(script, settings, tee, io, scratch, opt);
    const auto again = Script::from_text(writer.finish(), path.stem().string() + ".nc");
    ASSERT_TRUE(again->gcode());
    ASSERT_TRUE(again->ok()) << path << ": " << format(again->errors().front());
    RecordingSink read_back;
    PersistentStore scratch2 = store.scratch_copy();
    interpret(again, settings, read_back, io, scratch2, opt);
    ASSERT_EQ(original.moves.size(), read_back.moves.size()) << path;
    for (size_t i = 0; i < original.moves.size(); ++i) {
      const std::string why = mismatch(original.moves[i], read_back.moves[i]);
      ASSERT_TRUE(why.empty()) << path << " move " << i << ": " << why << " (line "
                               << original.moves[i].loc.line << ")";
    }
    ++compared;
  }
  EXPECT_GE(compared, 5);
  std::cout << "round trip: " << compared << " of " << files.size() << " part files\n";
}

}  // namespace
}  // namespace gantry
