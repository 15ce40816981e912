// Restart persistence (issue 25): gantry killed with SIGKILL mid-move starts again with the
// position restored from the last rest and marked unconfirmed; clean restarts restore it.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "../support/run_gantry.hpp"

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

std::string slurp(const fs::path& p) {
  std::stringstream s;
  s << std::ifstream(p).rdbuf();
  return s.str();
}

// One config folder for every start of the test: the sessions share the state file.
struct Sessions {
  fs::path dir = fs::temp_directory_path() / fmt::format("gantry_state_e2e_{}", getpid());
  Sessions() {
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  ~Sessions() { fs::remove_all(dir); }
  fs::path state() const { return dir / "config/gantry/values/Desktop_24x18__inches_.state.toml"; }
  std::string part(const std::string& name, const std::string& text) const {
    std::ofstream(dir / name) << text;
    return (dir / name).string();
  }
  // `gantry ARGS` to the end: exit code, stdout, stderr.
  e2e::GantryResult gantry(const std::string& args, const std::string& stdin_text = "") const {
    const fs::path in = dir / "stdin", err = dir / "stderr";
    std::ofstream(in) << stdin_text;
    const std::string cmd =
        fmt::format("cd '{}' && XDG_CONFIG_HOME='{}/config' '{}' {} <'{}' 2>'{}'",
                    GANTRY_SOURCE_DIR, dir.string(), GANTRY_BIN, args, in.string(), err.string());
    e2e::GantryResult r;
    FILE* p = popen(cmd.c_str(), "r");
    char buf[4096];
    for (size_t n; (n = fread(buf, 1, sizeof buf, p)) > 0;) r.out.append(buf, n);
    const int status = pclose(p);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.err = slurp(err);
    return r;
  }
};

TEST(MachineState, SigkillMidMoveRestoresThePositionUnconfirmed) {
  Sessions s;
  // Session 1: ends at rest at table X 1.5 with working 0 at table X 1.
  const auto first = s.gantry(fmt::format("run '{}' --realtime", s.part("first.sbp", "SW, 0\nMX, 1\nZX\nMX, 0.5\n")));
  ASSERT_EQ(first.exit_code, 0) << first.err;
  EXPECT_EQ(first.err.find("position restored"), std::string::npos) << "nothing to restore yet";
  std::string state = slurp(s.state());
  EXPECT_NE(state.find("\nmotion = \"at rest\""), std::string::npos) << state;
  EXPECT_NE(state.find("confirmed = true"), std::string::npos) << state;

  // Session 2: a 9 in move at 1 in/s in real time, killed 3 s after "moving" reached the disk
  // (after SW's 2 s warning: the tool is on its way).
  const std::string long_move = s.part("long.sbp", "MS, 1\nMX, 10\n");
  const std::string cmd =
      fmt::format("cd '{}' && XDG_CONFIG_HOME='{}/config' exec '{}' run '{}' --realtime "
                  ">/dev/null 2>'{}'",
                  GANTRY_SOURCE_DIR, s.dir.string(), GANTRY_BIN, long_move,
                  (s.dir / "killed.err").string());
  pid_t pid = 0;
  const char* argv[] = {"/bin/sh", "-c", cmd.c_str(), nullptr};
  ASSERT_EQ(posix_spawn(&pid, "/bin/sh", nullptr, nullptr, const_cast<char**>(argv), environ), 0);
  const auto spawned = Clock::now();
  bool moving = false;
  while (!moving && Clock::now() - spawned < std::chrono::seconds(20)) {
    moving = slurp(s.state()).find("\nmotion = \"moving\"") != std::string::npos;
    if (!moving) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_TRUE(moving) << "the state file never said moving";
  const double moving_after_s = std::chrono::duration<double>(Clock::now() - spawned).count();
  std::this_thread::sleep_for(std::chrono::milliseconds(3000));
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, WNOHANG), 0) << "the run ended before the kill";
  kill(pid, SIGKILL);
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
  std::fprintf(stderr, "[ figures ] 'moving' on disk %.3f s after the start; killed 3 s later\n",
               moving_after_s);
  state = slurp(s.state());
  EXPECT_NE(state.find("\nmotion = \"moving\""), std::string::npos) << state;
  EXPECT_NE(state.find("x = 1.5"), std::string::npos) << state;  // where the move started
  // The part-file log has the run's start line; its process is gone, so it reads as killed.
  const auto killed_log = s.gantry("log --json");
  const nlohmann::json killed_runs = nlohmann::json::parse(killed_log.out);
  ASSERT_EQ(killed_runs.size(), 2u) << killed_log.out;
  EXPECT_EQ(killed_runs[1]["file"], long_move);
  EXPECT_EQ(killed_runs[1]["status"], "killed") << killed_log.out;

  // Session 3 (gantry state): restored, unconfirmed, and why.
  const auto shown = s.gantry("state");
  EXPECT_EQ(shown.exit_code, 0);
  EXPECT_NE(shown.out.find("position restored from the last session: X 1.5000 Y 0.0000"),
            std::string::npos)
      << shown.out;
  EXPECT_NE(shown.out.find("zero at X 1.0000"), std::string::npos) << shown.out;
  EXPECT_NE(shown.out.find("UNCONFIRMED: the last session ended mid-move"), std::string::npos)
      << shown.out;

  // Session 4 (the console): says so at start; its readout is the restored position.
  const auto console = s.gantry("console", "status\n");
  EXPECT_EQ(console.exit_code, 0) << console.err;
  EXPECT_NE(console.out.find("warning: position restored from the last session"),
            std::string::npos)
      << console.out;
  EXPECT_NE(console.out.find("UNCONFIRMED"), std::string::npos) << console.out;
  // Its status says so too, until homed or confirmed (WinCNC's last known position).
  EXPECT_NE(console.out.find("the position is UNCONFIRMED until homed (C3, G28) or confirmed"),
            std::string::npos)
      << console.out;
  EXPECT_NE(console.out.find("idle     X 0.5000  Y 0.0000"), std::string::npos) << console.out;
  EXPECT_NE(console.out.find("table base X 1.5000"), std::string::npos) << console.out;

  // Session 5 (gantry run): moves from the restored position: working 0 is table X 1, half an
  // inch towards -X; still unconfirmed at rest afterwards.
  const auto back = s.gantry(fmt::format("run '{}' --realtime --json", s.part("back.sbp", "SW, 0\nMX, 0\n")));
  ASSERT_EQ(back.exit_code, 0) << back.err;
  EXPECT_NE(back.err.find("gantry: position restored from the last session"), std::string::npos)
      << back.err;
  EXPECT_NE(back.err.find("UNCONFIRMED"), std::string::npos) << back.err;
  const nlohmann::json j = nlohmann::json::parse(back.out);
  EXPECT_EQ(j["steps"]["x"].get<long>(), std::lround(-0.5 * e2e::kStepsPerUnit[0])) << back.out;
  // The report's position is the table base position: the restored one plus the steps played.
  EXPECT_NEAR(j["position"]["x"].get<double>(), 1.0, 1e-3) << back.out;
  state = slurp(s.state());
  EXPECT_NE(state.find("\nmotion = \"at rest\""), std::string::npos) << state;
  EXPECT_NE(state.find("confirmed = false"), std::string::npos) << state;
  EXPECT_NE(state.find("x = 1.0"), std::string::npos) << state;

  // The operator confirms: the next start restores it without the warning.
  EXPECT_EQ(s.gantry("state --confirm").exit_code, 0);
  const auto after = s.gantry("state");
  EXPECT_NE(after.out.find("X 1.0000 Y 0.0000 Z 0.0000 (in, table base; zero at X 1.0000"),
            std::string::npos)
      << after.out;
  EXPECT_NE(after.out.find("; home to confirm"), std::string::npos) << after.out;
  EXPECT_EQ(after.out.find("UNCONFIRMED"), std::string::npos) << after.out;

  // The part-file log: the runs that ended, and the killed one, closed by the console's start
  // (session 4) with where the state file last knew the tool.
  const auto log = s.gantry("log");
  EXPECT_NE(log.out.find("completed              " + s.part("first.sbp", "MX, 1\nZX\nMX, 0.5\n")),
            std::string::npos)
      << log.out;
  EXPECT_NE(log.out.find("        ?  killed                 " + long_move +
                         " (killed/unknown end; last known at X 1.5000 Y 0.0000 Z 0.0000 (in, "
                         "table base; saved "),
            std::string::npos)
      << log.out;
  EXPECT_NE(log.out.find(", mid-move)"), std::string::npos) << log.out;
  const std::string raw = slurp(s.state().parent_path() / "part_files.log");
  EXPECT_NE(raw.find("\"status\":\"killed\""), std::string::npos) << raw;  // on disk too
  const auto last = s.gantry("log --last 1 --json");
  const nlohmann::json runs = nlohmann::json::parse(last.out);
  ASSERT_EQ(runs.size(), 1u) << last.out;
  EXPECT_EQ(runs[0]["status"], "completed");
  EXPECT_EQ(runs[0]["position"]["x"], 1.0);
}

// The runs here are live (--realtime): only a live `gantry run` keeps the machine's state.
// One in virtual time is an off-machine check: the same file, the same report, every time.
TEST(MachineState, ARunInVirtualTimeNeitherRestoresNorSaves) {
  Sessions s;
  const std::string file = s.part("rel.sbp", "SR\nMX, 1\n");
  for (int run = 0; run < 2; ++run) {
    const auto r = s.gantry(fmt::format("run '{}' --json", file));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(nlohmann::json::parse(r.out)["steps"]["x"].get<long>(),
              std::lround(1 * e2e::kStepsPerUnit[0]))
        << "run " << run;
  }
  EXPECT_FALSE(fs::exists(s.state()));
  EXPECT_FALSE(fs::exists(s.state().parent_path() / "part_files.log"));
}

// A corrupt state file: a clear message and a fresh start at 0, never a crash.
TEST(MachineState, ACorruptFileIsAMessageAndAFreshStart) {
  Sessions s;
  fs::create_directories(s.state().parent_path());
  std::ofstream(s.state()) << "motion = \"at rest\"\nposition = { x = oops }\n";
  const auto r = s.gantry(fmt::format("run '{}' --realtime --json", s.part("m.sbp", "SW, 0\nMX, 1\n")));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("not a machine state file (line 2"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("starting afresh"), std::string::npos) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["steps"]["x"].get<long>(), std::lround(1 * e2e::kStepsPerUnit[0]));
  const std::string state = slurp(s.state());
  EXPECT_NE(state.find("x = 1.0"), std::string::npos) << state;  // replaced at the rest
}

// VD's part_file_log off: no line.
TEST(MachineState, NoLogLineWhenVdTurnsItOff) {
  Sessions s;
  fs::create_directories(s.dir / "config/gantry/values");
  std::ofstream(s.dir / "values.toml") << "[display]\npart_file_log = false\n";
  const auto r = s.gantry(fmt::format("run '{}' --realtime --values '{}'", s.part("m.sbp", "SW, 0\nMX, 1\n"),
                                      (s.dir / "values.toml").string()));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(fs::exists(s.dir / "part_files.log"));
  EXPECT_TRUE(fs::exists(s.dir / "values.state.toml"));  // beside the values file
}

}  // namespace

// The console's CONFIRM vouches for a restored position as `gantry state --confirm` does.
TEST(MachineState, TheConsolesConfirmMarksTheRestoredPositionConfirmed) {
  Sessions s;
  fs::create_directories(s.state().parent_path());
  std::ofstream(s.state()) << "motion = \"moving\"\nconfirmed = true\nunits = \"in\"\n"
                              "position = { x = 3.0, y = 2.0 }\n";
  const auto console = s.gantry("console --card sim --realtime", "confirm\nconfirm\n");
  ASSERT_EQ(console.exit_code, 0) << console.err << console.out;
  EXPECT_NE(console.out.find("the position is confirmed: the tool is where the readout says"),
            std::string::npos)
      << console.out;
  EXPECT_NE(console.out.find("the position was confirmed already"), std::string::npos)
      << console.out;
  const std::string state = slurp(s.state());
  EXPECT_NE(state.find("confirmed = true"), std::string::npos) << state;
  EXPECT_EQ(s.gantry("state").out.find("UNCONFIRMED"), std::string::npos);
}
