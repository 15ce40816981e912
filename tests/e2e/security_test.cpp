// A part file's reach (docs/security.md): hostile files through `gantry check` and `gantry
// run`, refused where they are written, with nothing outside the job's folder changed; the
// folders the operator allows; every file error check and run raise alike; FIFOs never hang.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/stat.h>  // mkfifo
#include <unistd.h>    // getpid, geteuid

#include <cstdlib>  // setenv
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "../support/run_gantry.hpp"

namespace {

namespace fs = std::filesystem;
using e2e::gantry;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Every entry under `root` (links as their targets' text, not followed), with its content.
std::map<std::string, std::string> snapshot(const fs::path& root) {
  std::map<std::string, std::string> out;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(root, ec); !ec && it != fs::end(it);
       it.increment(ec)) {
    const fs::path p = it->path();
    const fs::file_status s = fs::symlink_status(p);
    out[p.string()] = fs::is_symlink(s)        ? "-> " + fs::read_symlink(p).string()
                      : fs::is_regular_file(s) ? slurp(p)
                                               : "(other)";
  }
  return out;
}

// A folder of its own: job/ holds the part files, outside/ is what they must not reach.
class Reach : public ::testing::Test {
 protected:
  Reach() {
    static int n = 0;
    root_ = fs::temp_directory_path() / fmt::format("gantry_security_{}_{}", getpid(), n++);
    fs::remove_all(root_);
    fs::create_directories(job());
    fs::create_directories(outside());
    write(outside() / "existing.sbp", "MX, 1\n");
    write(outside() / "notes.txt", "outside\n");
  }
  ~Reach() override {
    std::error_code ec;
    fs::permissions(job() / "locked.txt", fs::perms::owner_all, ec);
    fs::remove_all(root_, ec);
  }
  fs::path job() const { return root_ / "job"; }
  fs::path outside() const { return root_ / "outside"; }
  static void write(const fs::path& p, const std::string& text) {
    std::ofstream(p, std::ios::binary) << text;
  }
  // The part file hostile.sbp: a move first, so a run that got past the check would move.
  std::string part(const std::string& line) const {
    const fs::path p = job() / "hostile.sbp";
    write(p, "MX, 0.5\n" + line + "\n");
    return p.string();
  }
  // The error line (FILE:LINE:COL: error: ...) for line 2 of hostile.sbp, or "".
  static std::string located(const std::string& err) {
    std::smatch m;
    static const std::regex line(R"(\S*hostile\.sbp:2:[0-9]+: error: [^\n]*)");
    return std::regex_search(err, m, line) ? m.str() : "";
  }
  // `line` refused alike by check and run, at line 2 of the file, with nothing moved and
  // nothing outside the job's folder changed. Returns the message.
  std::string refused(const std::string& line, const std::string& options = "") {
    const std::string file = part(line);
    const auto before = snapshot(root_);
    const e2e::GantryResult check = gantry(fmt::format("check '{}' {}", file, options), 60);
    const e2e::GantryResult run = gantry(fmt::format("run '{}' --yes {}", file, options), 60);
    EXPECT_EQ(check.exit_code, 1) << line << "\n" << check.err;
    EXPECT_EQ(run.exit_code, 1) << line << "\n" << run.err;
    const std::string said = located(check.err);
    EXPECT_NE(said, "") << line << "\ncheck said:\n" << check.err;
    EXPECT_EQ(located(run.err), said) << line << "\nrun said:\n" << run.err;
    EXPECT_NE(run.out.find("steps      X=0 Y=0 Z=0"), std::string::npos) << run.out;
    EXPECT_EQ(snapshot(root_), before) << line;
    return said;
  }

  fs::path root_;
};

// ---- the reach ------------------------------------------------------------------------------

TEST_F(Reach, HostileWritesOutsideTheJobFolderAreRefusedByCheckAndRun) {
  fs::create_directory_symlink(outside(), job() / "escape");       // a folder link out
  fs::create_symlink(outside() / "planted.txt", job() / "plant");  // dangling: writing creates it
  write(job() / "drawing.plt", "IN;PU0,0;PD400,0;");
  const std::string abs = outside().string();
  const std::vector<std::string> hostile = {
      R"(OPEN "../outside/notes.txt" FOR APPEND AS #1)",
      fmt::format(R"(OPEN "{}/new.txt" FOR OUTPUT AS #1)", abs),
      R"(OPEN "escape/notes.txt" FOR OUTPUT AS #1)",
      R"(OPEN "plant" FOR APPEND AS #1)",
      R"(OPEN "escape/../../outside/notes.txt" FOR INPUT AS #1)",
      "US, ../outside/settings.toml",
      fmt::format("US, {}/settings.toml", abs),
      "TH, ../outside/existing.sbp",
      "FC, drawing.plt, ../outside/drawing.sbp",
      "FC, drawing.plt, escape/drawing.sbp",
      "UD, ../outside/PROBLEM.LOG",
      "FP, ../outside/existing.sbp",
      "FS, ../outside",
      "FE, ../outside/notes.txt",
  };
  for (const std::string& line : hostile) {
    const std::string said = refused(line);
    EXPECT_NE(said.find("is outside the job's folder " + job().string()), std::string::npos)
        << said;
    EXPECT_NE(said.find("[files] allow in the machine profile or run with --allow-path"),
              std::string::npos)
        << said;
  }
  EXPECT_FALSE(fs::exists(outside() / "planted.txt"));
}

TEST_F(Reach, TheLinkAMessageFollowsIsNamed) {
  fs::create_directory_symlink(outside(), job() / "escape");
  const std::string said = refused(R"(OPEN "escape/notes.txt" FOR APPEND AS #1)");
  EXPECT_NE(said.find("hostile.sbp:2:6: error: " + (job() / "escape/notes.txt").string() +
                      " is outside the job's folder " +
                      job().string() + " (it leads to " + (outside() / "notes.txt").string() +
                      "): a part file writes files only there"),
            std::string::npos)
      << said;
}

TEST_F(Reach, UnCannotNameAnEditorSoFeRunsNothingInjected) {
  const fs::path pwned = outside() / "pwned";
  const std::string said = refused(fmt::format("UN, touch {} ;\nFE, notes.txt", pwned.string()));
  EXPECT_NE(said.find("hostile.sbp:2:5: error: UN cannot change the editor from a part file: "
                      "set it in the machine profile, [machine] editor"),
            std::string::npos)
      << said;
  EXPECT_FALSE(fs::exists(pwned));
  // An editor a values file holds (an older UN saved it there) is not the one FE starts.
  ::setenv("VISUAL", "gantry-test-visual", 1);
  const fs::path values = job() / "values.toml";
  write(values, fmt::format("[machine]\neditor = \"touch {}\"\n", pwned.string()));
  write(job() / "edit.sbp", "FE, notes.txt\n");
  const e2e::GantryResult r = gantry(
      fmt::format("run '{}' --yes --values '{}'", (job() / "edit.sbp").string(), values.string()));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("FE would open " + (job() / "notes.txt").string() +
                       " in gantry-test-visual;"),
            std::string::npos)
      << r.out << r.err;
  EXPECT_FALSE(fs::exists(pwned));
}

TEST_F(Reach, ShellStaysOffWithoutAllowShell) {
  const fs::path pwned = outside() / "pwned";
  const std::string said = refused(fmt::format("SHELL, \"touch {}\", 1, SYNC", pwned.string()));
  EXPECT_NE(said.find("SHELL starts other programs and is disabled; run with --allow-shell"),
            std::string::npos)
      << said;
}

TEST_F(Reach, TheProfileAndAllowPathLetAFolderIn) {
  const std::string line = R"(OPEN "../outside/log.txt" FOR APPEND AS #1
WRITE #1, "cut"
CLOSE #1)";
  const std::string file = part(line);
  // The profile's [files] allow.
  std::string profile = slurp(fs::path(GANTRY_SOURCE_DIR) / "settings/default.toml");
  const std::string empty = "allow = []";
  ASSERT_NE(profile.find(empty), std::string::npos);
  profile.replace(profile.find(empty), empty.size(),
                  fmt::format("allow = [\"{}\"]", outside().string()));
  write(root_ / "allowing.toml", profile);
  e2e::GantryResult r =
      gantry(fmt::format("check '{}' --profile '{}'", file, (root_ / "allowing.toml").string()));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  r = gantry(
      fmt::format("run '{}' --yes --profile '{}'", file, (root_ / "allowing.toml").string()));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(slurp(outside() / "log.txt"), "cut\n");
  // --allow-path, as many as needed.
  r = gantry(fmt::format("run '{}' --yes --allow-path /nowhere --allow-path '{}'", file,
                         outside().string()));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(slurp(outside() / "log.txt"), "cut\ncut\n");
  // A values file cannot allow it: only the profile's own list counts.
  write(root_ / "values.toml", fmt::format("[files]\nallow = [\"{}\"]\n", outside().string()));
  r = gantry(fmt::format("check '{}' --values '{}'", file, (root_ / "values.toml").string()));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("is outside the job's folder"), std::string::npos) << r.err;
}

// ---- check = run: every file error, located, with its own words ------------------------------

TEST_F(Reach, EveryFileErrorIsRaisedByCheckAsByRunAtItsLine) {
  fs::create_directory(job() / "folder");
  ASSERT_EQ(::mkfifo((job() / "pipe").c_str(), 0600), 0);
  ASSERT_EQ(::mkfifo((job() / "fifo.sbp").c_str(), 0600), 0);
  const std::string long_path(6000, 'a');
  const std::string long_name(300, 'n');
  const std::map<std::string, std::string> cases = {
      {R"(OPEN "nofolder/x.txt" FOR OUTPUT AS #1)",
       "hostile.sbp:2:6: error: cannot write " + (job() / "nofolder/x.txt").string() +
           ": there is no folder " + (job() / "nofolder").string()},
      {R"(OPEN "absent.txt" FOR INPUT AS #1)", "hostile.sbp:2:6: error: cannot read " +
                                                   (job() / "absent.txt").string() +
                                                   ": there is no such file"},
      {R"(OPEN "folder" FOR INPUT AS #1)", "hostile.sbp:2:6: error: cannot read " +
                                               (job() / "folder").string() +
                                               ": it is a folder, not a file"},
      {R"(OPEN "folder" FOR OUTPUT AS #1)", "hostile.sbp:2:6: error: cannot write " +
                                                (job() / "folder").string() +
                                                ": it is a folder, not a file"},
      {R"(OPEN "pipe" FOR INPUT AS #1)",
       "hostile.sbp:2:6: error: cannot read " + (job() / "pipe").string() +
           ": it is a named pipe (FIFO), not a file; Gantry opens only regular files"},
      {R"(OPEN "pipe" FOR APPEND AS #1)",
       "hostile.sbp:2:6: error: cannot write " + (job() / "pipe").string() +
           ": it is a named pipe (FIFO), not a file; Gantry opens only regular files"},
      {"FP, fifo.sbp", "hostile.sbp:2:1: error: cannot read " + (job() / "fifo.sbp").string() +
                           ": it is a named pipe (FIFO), not a file"},
      {"FP, absent.sbp", "hostile.sbp:2:1: error: cannot read " + (job() / "absent.sbp").string() +
                             ": there is no such file"},
      {"US, nofolder/settings.toml", "hostile.sbp:2:5: error: cannot write " +
                                         (job() / "nofolder/settings.toml").string() +
                                         ": there is no folder"},
      {fmt::format(R"(OPEN "{}" FOR OUTPUT AS #1)", long_path),
       "hostile.sbp:2:6: error: cannot write " + job().string() + "/aaaa"},
      {fmt::format(R"(OPEN "{}" FOR OUTPUT AS #1)", long_name),
       "hostile.sbp:2:6: error: cannot write "},
  };
  for (const auto& [line, message] : cases) {
    const std::string said = refused(line);
    EXPECT_NE(said.find(message), std::string::npos) << said << "\nwanted: " << message;
  }
  const std::string too_long = refused(fmt::format(R"(OPEN "{}" FOR OUTPUT AS #1)", long_path));
  EXPECT_NE(too_long.find("characters long, and this system allows at most 4095"),
            std::string::npos);
  EXPECT_LT(too_long.size(), 600u);  // the path is shown shortened, not whole
  EXPECT_NE(refused(fmt::format(R"(OPEN "{}" FOR OUTPUT AS #1)", long_name))
                .find("is 300 characters long, and a file or folder name may have at most 255"),
            std::string::npos);
}

// Root reads every file, so as root (CI) gantry runs as the user nobody, under setpriv.
TEST_F(Reach, AnUnreadableFileSaysSo) {
  write(job() / "locked.txt", "secret\n");
  fs::permissions(job() / "locked.txt", fs::perms::none);
  const std::string runner =
      ::geteuid() == 0 ? "setpriv --reuid=65534 --regid=65534 --clear-groups " : "";
  const std::string file = part(R"(OPEN "locked.txt" FOR INPUT AS #1)");
  for (const std::string cmd : {"check", "run --yes"}) {
    const e2e::GantryResult r = gantry(fmt::format("{} '{}'", cmd, file), 60, runner);
    EXPECT_EQ(r.exit_code, 1) << cmd << "\n" << r.err;
    EXPECT_NE(r.err.find(file + ":2:6: error: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("locked.txt: it cannot be read: permission denied"), std::string::npos)
        << r.err;
  }
}

// ---- a FIFO as the part file ------------------------------------------------------------------

TEST_F(Reach, AFifoPartFileIsRefusedWithoutWaiting) {
  const fs::path pipe = job() / "pipe.sbp";
  ASSERT_EQ(::mkfifo(pipe.c_str(), 0600), 0);
  for (const std::string cmd : {"check", "run --yes"}) {
    const e2e::GantryResult r = gantry(fmt::format("{} '{}'", cmd, pipe.string()), 60);
    EXPECT_EQ(r.exit_code, 1) << cmd << ": killed (137) means it waited on the FIFO\n" << r.err;
    EXPECT_NE(r.err.find(pipe.string() +
                         ": error: cannot open the part file: it is a named pipe (FIFO), not a "
                         "file; Gantry opens only regular files"),
              std::string::npos)
        << r.err;
  }
  // FP and C<n> of one: refused at their line.
  EXPECT_NE(refused("FP, pipe.sbp").find("it is a named pipe (FIFO)"), std::string::npos);
  ASSERT_EQ(::mkfifo((job() / "C77.sbp").c_str(), 0600), 0);
  const e2e::GantryResult r = gantry(fmt::format("check '{}'", part("C77")), 60);
  EXPECT_EQ(r.exit_code, 1) << r.err;  // not run as a macro: a FIFO is not a file
}

}  // namespace
