// The machine state kept across sessions (session/machine_memory) and the part-file log
// (session/run_log): their files, a corrupt or missing file, and both on the live controller.
#include "gantry/session/machine_memory.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>  // stat: a file replaced or not
#include <unistd.h>    // getpid

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "gantry/core/text_file.hpp"  // read_text_file, write_file_atomically
#include "gantry/interp/operator_io.hpp"
#include "gantry/lang/script.hpp"
#include "gantry/session/run_log.hpp"
#include "sim/sim_card.hpp"

namespace gantry::session {
namespace {

namespace fs = std::filesystem;

// A fresh folder per test, removed after.
struct Folder {
  fs::path dir;
  Folder() {
    static int n = 0;
    dir = fs::temp_directory_path() / ("gantry_memory_" + std::to_string(getpid()) + "_" +
                                       std::to_string(++n));
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  ~Folder() { fs::remove_all(dir); }
  std::string state() const { return (dir / "profile.state.toml").string(); }
  std::string log() const { return (dir / "part_files.log").string(); }
};

struct Machine {
  Settings settings = default_settings();
  SimCard card{settings};
  ScriptedIO io{true, {}};
  PersistentStore store;
  Controller c{settings, card, io, store};
  std::int64_t steps(double units, int axis = 0) const {
    return std::llround(units * settings.axes[axis].steps_per_unit);
  }
  void run(const std::string& text) {
    ASSERT_TRUE(c.run(Script::from_text(text, "part.sbp")));
    c.wait();
  }
};

SavedMachine sample() {
  SavedMachine m;
  m.moving = true;
  m.confirmed = false;
  m.why = "an E-stop";
  m.units = Units::Millimetres;
  m.table << 1.25, -2.5, 0.125, 90, 0, -45;
  m.zero << 0.5, 0.25, -0.75, 0, 0, 0;
  m.system = 3;
  m.work_origin[3] << 1, 2, 3, 0, 0, 0;
  m.g92 << 0, 0, 0.1, 0, 0, 0;
  m.saved_at = "2026-11-27T01:00:00Z";
  return m;
}

TEST(MachineMemory, TheFileRoundTrips) {
  const SavedMachine m = sample();
  const std::string text = machine_state_text(m);
  EXPECT_NE(text.find("motion = \"moving\""), std::string::npos) << text;
  EXPECT_NE(text.find("units = \"mm\""), std::string::npos) << text;
  std::string why;
  const std::optional<SavedMachine> back = parse_machine_state(text, &why);
  ASSERT_TRUE(back) << why;
  EXPECT_TRUE(back->moving);
  EXPECT_FALSE(back->confirmed);
  EXPECT_EQ(back->why, "an E-stop");
  EXPECT_EQ(back->units, Units::Millimetres);
  EXPECT_EQ(back->table, m.table);
  EXPECT_EQ(back->zero, m.zero);
  EXPECT_EQ(back->system, 3);
  EXPECT_EQ(back->work_origin[3], m.work_origin[3]);
  EXPECT_EQ(back->g92, m.g92);
}

TEST(MachineMemory, ItSitsBesideTheValuesFile) {
  EXPECT_EQ(machine_state_path("/c/gantry/values/Desktop.toml"),
            "/c/gantry/values/Desktop.state.toml");
  EXPECT_EQ(run_log_path("/c/gantry/values/Desktop.toml"), "/c/gantry/values/part_files.log");
}

TEST(MachineMemory, ABadFileIsALocatedMessage) {
  std::string why;
  EXPECT_FALSE(parse_machine_state("motion = \"at rest\"\nconfirmed = tru\n", &why));
  EXPECT_NE(why.find("line 2"), std::string::npos) << why;
  EXPECT_FALSE(parse_machine_state("motion = \"flying\"\nconfirmed = true\n", &why));
  EXPECT_NE(why.find("motion"), std::string::npos) << why;
  EXPECT_FALSE(parse_machine_state(
      "motion = \"at rest\"\nconfirmed = true\nunits = \"in\"\n\n[position]\nq = 1\n", &why));
  EXPECT_NE(why.find("line 6"), std::string::npos) << why;
  EXPECT_FALSE(parse_machine_state("motion = \"at rest\"\nconfirmed = true\nunits = \"in\"\n",
                                   &why));
  EXPECT_NE(why.find("position"), std::string::npos) << why;
}

TEST(MachineMemory, AMissingOrCorruptFileIsAFreshStartNeverACrash) {
  Folder f;
  MachineMemory missing(f.state());
  const std::string fresh = missing.load(Units::Inches);
  EXPECT_NE(fresh.find("no machine state saved yet"), std::string::npos) << fresh;
  EXPECT_FALSE(missing.restoring());
  EXPECT_TRUE(missing.state().table.isZero());

  for (const std::string& junk : {std::string("\x00\xff garbage [[[", 14), std::string("")}) {
    std::ofstream(f.state(), std::ios::binary) << junk;
    MachineMemory bad(f.state());
    const std::string said = bad.load(Units::Inches);
    EXPECT_NE(said.find("not a machine state file"), std::string::npos) << said;
    EXPECT_NE(said.find(f.state()), std::string::npos) << said;
    EXPECT_FALSE(bad.restoring());
    EXPECT_FALSE(bad.state().confirmed);  // the position starts at 0, unconfirmed
    EXPECT_TRUE(bad.state().table.isZero());
  }
  // The next save replaces it with a good one.
  MachineMemory bad(f.state());
  bad.load(Units::Inches);
  ASSERT_TRUE(bad.save());
  std::string why;
  EXPECT_TRUE(parse_machine_state(*read_text_file(f.state()), &why)) << why;
}

TEST(MachineMemory, SavesAtomicallyAndSaysWhenItCannot) {
  Folder f;
  MachineMemory m(f.state());
  m.load(Units::Inches);
  for (int i = 0; i < 20; ++i) ASSERT_TRUE(m.save());
  // Only the file itself: the temporary files were renamed over it.
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(f.dir)) names.push_back(e.path().filename());
  EXPECT_EQ(names, std::vector<std::string>{"profile.state.toml"});
  // Unchanged: not written again (the same inode).
  auto inode = [&] {
    struct stat st {};
    ::stat(f.state().c_str(), &st);
    return st.st_ino;
  };
  const auto before = inode();
  ASSERT_TRUE(m.save());
  EXPECT_EQ(inode(), before);
  m.confirm();  // already confirmed: nothing changes
  EXPECT_EQ(inode(), before);
  // A folder that cannot be made (its parent is a file): false with the reason, no throw.
  std::ofstream(f.dir / "file") << "x";
  MachineMemory nowhere((f.dir / "file" / "s.state.toml").string());
  nowhere.load(Units::Inches);
  std::string why;
  EXPECT_FALSE(nowhere.save(&why));
  EXPECT_FALSE(why.empty());
}

TEST(MachineMemory, KilledMidMoveRestoresUnconfirmed) {
  Folder f;
  SavedMachine m = sample();
  m.units = Units::Inches;
  m.confirmed = true;
  m.why.clear();
  ASSERT_TRUE(write_file_atomically(f.state(), machine_state_text(m)));
  MachineMemory mem(f.state());
  const std::string said = mem.load(Units::Inches);
  EXPECT_NE(said.find("position restored from the last session"), std::string::npos) << said;
  EXPECT_NE(said.find("UNCONFIRMED"), std::string::npos) << said;
  EXPECT_NE(said.find("mid-move"), std::string::npos) << said;
  EXPECT_TRUE(mem.restoring());
  EXPECT_FALSE(mem.state().confirmed);
  // Saved at rest, still unconfirmed; the operator's confirmation clears it.
  ASSERT_TRUE(mem.save());
  std::string why;
  std::optional<SavedMachine> back = parse_machine_state(*read_text_file(f.state()), &why);
  ASSERT_TRUE(back);
  EXPECT_FALSE(back->moving);
  EXPECT_FALSE(back->confirmed);
  mem.confirm();
  back = parse_machine_state(*read_text_file(f.state()), &why);
  EXPECT_TRUE(back->confirmed);
  MachineMemory again(f.state());
  EXPECT_NE(again.load(Units::Inches).find("; home to confirm"), std::string::npos);
}

TEST(MachineMemory, OtherUnitsAreNotRestored) {
  Folder f;
  SavedMachine m = sample();
  m.moving = false;
  ASSERT_TRUE(write_file_atomically(f.state(), machine_state_text(m)));  // mm
  MachineMemory mem(f.state());
  const std::string said = mem.load(Units::Inches);
  EXPECT_NE(said.find("not restored"), std::string::npos) << said;
  EXPECT_FALSE(mem.restoring());
}

// The controller: "moving" is on disk before any motion, "at rest" with the position after.
TEST(MachineMemory, TheControllerSavesBeforeMotionAndAtRest) {
  Folder f;
  Machine m;
  MachineMemory mem(f.state());
  mem.load(m.settings.units);
  std::vector<std::string> seen_before_motion;
  mem.attach(m.c, [&](const Controller::Activity& a) {
    if (a.at_rest) return;
    EXPECT_EQ(m.c.status().steps[0], 0);  // nothing played yet
    std::string why;
    seen_before_motion.push_back(
        parse_machine_state(*read_text_file(f.state()), &why)->moving ? "moving" : "at rest");
  });
  m.run("MX, 1\nZX\nMX, 0.5\nMY, 2\n");
  EXPECT_EQ(seen_before_motion, std::vector<std::string>{"moving"});
  std::string why;
  const std::optional<SavedMachine> s = parse_machine_state(*read_text_file(f.state()), &why);
  ASSERT_TRUE(s) << why;
  EXPECT_FALSE(s->moving);
  EXPECT_TRUE(s->confirmed);
  EXPECT_DOUBLE_EQ(s->table[0], 1.5);  // ZX at table 1, then working 0.5
  EXPECT_DOUBLE_EQ(s->table[1], 2);
  EXPECT_DOUBLE_EQ(s->zero[0], 1);
}

// A new session: the card counts from 0, the tool where the file says; moves go from there.
TEST(MachineMemory, ANewSessionMovesFromTheRestoredPosition) {
  Folder f;
  SavedMachine saved;
  saved.table << 5, 3, 0, 0, 0, 0;
  saved.zero << 2, 1, 0, 0, 0, 0;
  ASSERT_TRUE(write_file_atomically(f.state(), machine_state_text(saved)));
  Machine m;
  MachineMemory mem(f.state());
  mem.load(m.settings.units);
  mem.attach(m.c);
  EXPECT_DOUBLE_EQ(m.c.modal().position[0], 3);  // working = table - zero
  EXPECT_DOUBLE_EQ(m.c.modal().position[1], 2);
  EXPECT_DOUBLE_EQ(m.c.modal().zero[0], 2);
  m.run("MX, 0\n");  // working 0: table 2, three inches towards -X from where it was
  EXPECT_EQ(m.c.status().steps[0], m.steps(-3));
  EXPECT_DOUBLE_EQ(mem.state().table[0], 2);
}

// An E-stop makes the position suspect until it is set again (ZT here; C3 homing alike).
TEST(MachineMemory, AnEStopUnconfirmsAndZTConfirms) {
  Folder f;
  Machine m;
  MachineMemory mem(f.state());
  mem.load(m.settings.units);
  mem.attach(m.c);
  m.c.schedule(Request::EStop, 0.3);
  m.run("MX, 5\n");
  EXPECT_FALSE(mem.state().confirmed);
  EXPECT_NE(mem.state().why.find("E-stop"), std::string::npos);
  ASSERT_TRUE(m.c.acknowledge());
  m.run("MX, 1\n");  // a move does not confirm it
  EXPECT_FALSE(mem.state().confirmed);
  ASSERT_TRUE(m.c.run_typed(Script::from_text("ZT\n", "typed")));
  m.c.wait();
  EXPECT_TRUE(mem.state().confirmed);
  std::string why;
  EXPECT_TRUE(parse_machine_state(*read_text_file(f.state()), &why)->confirmed);
}

TEST(RunLog, ARecordRoundTripsAndReadsAsText) {
  RunRecord r;
  r.file = "parts/sign \"a\".sbp";
  r.start = "2026-11-27T01:50:03Z";
  r.end = "2026-11-27T01:50:15Z";
  r.status = "stopped";
  r.line = 24;
  r.message = "stopped by the operator";
  r.cycle_s = 12.34;
  r.position << 1, 2, 3, 0, 0, 0;
  r.units = "in";
  const std::string line = run_record_line(r);
  EXPECT_EQ(line.find('\n'), std::string::npos);
  const std::optional<RunRecord> back = parse_run_record(line);
  ASSERT_TRUE(back);
  EXPECT_EQ(back->file, r.file);
  EXPECT_EQ(back->line, 24);
  EXPECT_DOUBLE_EQ(back->cycle_s, 12.34);
  EXPECT_EQ(back->position, r.position);
  EXPECT_EQ(run_record_text(r),
            "2026-11-27 01:50:03  0:00:12.3  stopped at line 24     parts/sign \"a\".sbp");
}

TEST(RunLog, AppendsLinesAndReadsTheLastSkippingBadOnes) {
  Folder f;
  RunRecord r;
  r.status = "completed";
  for (int i = 1; i <= 5; ++i) {
    r.file = "f" + std::to_string(i) + ".sbp";
    std::string why;
    ASSERT_TRUE(append_run_record(f.log(), r, &why)) << why;
    if (i == 3) std::ofstream(f.log(), std::ios::app) << "{\"cut\": short\n";
  }
  std::size_t bad = 0;
  const std::vector<RunRecord> last = read_run_log(f.log(), 2, &bad);
  ASSERT_EQ(last.size(), 2u);
  EXPECT_EQ(last[0].file, "f4.sbp");
  EXPECT_EQ(last[1].file, "f5.sbp");
  EXPECT_EQ(bad, 1u);
  EXPECT_EQ(read_run_log(f.log(), 0).size(), 5u);
  EXPECT_TRUE(read_run_log((f.dir / "none.log").string(), 3).empty());
}

// A run's start line goes to the log at once; a run whose process is gone without its end
// line reads as killed, and the next start closes it with where the tool was last known.
TEST(RunLog, AStartLineComesFirstAndAKilledRunIsClosedAtTheNextStart) {
  Folder f;
  RunLogger log(f.log());
  Controller::Activity start;
  start.part_file = true;
  start.file = "live.sbp";
  log.activity(start);
  std::vector<RunRecord> runs = read_run_log(f.log(), 0);
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_EQ(runs[0].status, "running");  // this process is alive
  EXPECT_EQ(runs[0].pid, static_cast<int>(getpid()));
  // A run of a process that is gone (no pid is this large): killed, end unknown.
  RunRecord gone;
  gone.id = "2026-11-27T03:00:00Z-999999999-1";
  gone.pid = 999'999'999;
  gone.file = "gone.sbp";
  gone.start = "2026-11-27T03:00:00Z";
  gone.status = "running";
  std::string why;
  ASSERT_TRUE(append_run_record(f.log(), gone, &why)) << why;
  runs = read_run_log(f.log(), 0);
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[1].status, "killed");
  EXPECT_NE(run_record_text(runs[1]).find("        ?  killed"), std::string::npos)
      << run_record_text(runs[1]);
  SavedMachine last;
  last.table << 2, 3, 0.5, 0, 0, 0;
  last.saved_at = "2026-11-27T03:00:01Z";
  last.confirmed = false;
  EXPECT_EQ(log.close_unfinished(&last), 1u);  // not the live one
  EXPECT_EQ(log.close_unfinished(&last), 0u);  // once
  runs = read_run_log(f.log(), 0);
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[1].status, "killed");
  EXPECT_EQ(runs[1].message,
            "killed/unknown end; last known at X 2.0000 Y 3.0000 Z 0.5000 (in, table base; "
            "saved 2026-11-27T03:00:01Z, mid-move)");
  EXPECT_DOUBLE_EQ(runs[1].position[1], 3);
  // The live run ends: its end line takes its start line's place.
  Controller::Activity end = start;
  end.at_rest = true;
  log.activity(end);
  runs = read_run_log(f.log(), 0);
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[0].status, "completed");
  EXPECT_EQ(runs[0].file, "live.sbp");
}

// The controller's runs: completed, stopped at a line, E-stop; jogs and typed lines are not runs.
TEST(RunLog, TheControllerLogsEachPartFileRun) {
  Folder f;
  Machine m;
  RunLogger log(f.log());
  m.c.on_activity([&](const Controller::Activity& a) { log.activity(a); });
  m.run("MX, 1\nMY, 1\n");
  m.c.schedule(Request::Stop, 0.2);
  m.run("MX, 0\nMX, 5\nMX, 0\n");
  m.c.schedule(Request::EStop, 0.2);
  m.run("MX, 1\nMX, 5\n");
  ASSERT_TRUE(m.c.acknowledge());
  ASSERT_TRUE(m.c.run_typed(Script::from_text("MX, 2\n", "typed")));
  m.c.wait();
  EXPECT_EQ(log.failure(), "");
  const std::vector<RunRecord> runs = read_run_log(f.log(), 0);
  ASSERT_EQ(runs.size(), 3u);
  EXPECT_EQ(runs[0].status, "completed");
  EXPECT_EQ(runs[0].file, "part.sbp");
  EXPECT_GT(runs[0].cycle_s, 0);
  EXPECT_DOUBLE_EQ(runs[0].position[1], 1);
  EXPECT_EQ(runs[1].status, "stopped");
  EXPECT_GE(runs[1].line, 1);
  EXPECT_EQ(runs[2].status, "E-stop");
  EXPECT_GE(runs[2].line, 1);
  EXPECT_NEAR(runs[2].cycle_s, 0.2, 0.05);
  for (const RunRecord& r : runs) EXPECT_FALSE(r.start.empty() || r.end.empty());
}

}  // namespace
}  // namespace gantry::session
