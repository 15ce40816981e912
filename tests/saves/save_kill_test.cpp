// Kill-during-save: each kind of save runs in a child process (gantry_save_helper, saving in
// a loop through the same code as `gantry run`), which is SIGKILLed at a random moment, 200
// times per kind. The file must always be the old or the new content, complete (never empty
// or partial), keep its mode, and a later save must leave no temporary file behind.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <thread>

namespace {

namespace fs = std::filesystem;

struct Kind {
  const char* name;
  const char* file;  // in the folder
};

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The file's content without US's date line, which changes from minute to minute.
std::string content(const fs::path& p) {
  std::string text = read(p);
  if (text.rfind("# Gantry settings saved by US on ", 0) == 0) text.erase(0, text.find('\n') + 1);
  return text;
}

// `saved`: the write end of a pipe on which a looping helper writes a byte after each save.
pid_t start_helper(const std::string& kind, const fs::path& folder, int variant, bool loop,
                   int saved = -1) {
  const pid_t pid = fork();
  if (pid == 0) {
    const int null = open("/dev/null", O_WRONLY);  // US says what it saved, 200 times
    dup2(null, STDOUT_FILENO);
    if (saved >= 0) dup2(saved, 3);
    const std::string v = std::to_string(variant);
    execl(GANTRY_SAVE_HELPER, GANTRY_SAVE_HELPER, kind.c_str(), folder.c_str(), v.c_str(),
          loop ? "loop" : nullptr, static_cast<char*>(nullptr));
    _exit(127);
  }
  return pid;
}

int run_helper(const std::string& kind, const fs::path& folder, int variant) {
  int status = 0;
  waitpid(start_helper(kind, folder, variant, false), &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::vector<std::string> temp_files(const fs::path& folder) {
  std::vector<std::string> out;
  for (const fs::directory_entry& e : fs::directory_iterator(folder))
    if (e.path().filename().string().find(".gantry-save-") != std::string::npos)
      out.push_back(e.path().filename().string());
  return out;
}

class KillDuringSave : public ::testing::TestWithParam<Kind> {};

TEST_P(KillDuringSave, FileIsAlwaysOldOrNewAndNoTempFileRemains) {
  const Kind kind = GetParam();
  const fs::path folder = fs::temp_directory_path() / ("gantry_kill_" + std::string(kind.name) +
                                                       "_" + std::to_string(getpid()));
  fs::remove_all(folder);
  fs::create_directories(folder);
  const fs::path file = folder / kind.file;
  ASSERT_EQ(run_helper(kind.name, folder, 1), 0);
  const std::string b = content(file);
  ASSERT_EQ(run_helper(kind.name, folder, 0), 0);
  const std::string a = content(file);
  ASSERT_NE(a, b);
  ASSERT_FALSE(a.empty());
  ASSERT_EQ(chmod(file.c_str(), 0600), 0);

  const unsigned seed = std::random_device{}();
  std::mt19937 rng(seed);
  int saw_old = 0, saw_new = 0;
  for (int kill_no = 0; kill_no < 200; ++kill_no) {
    int saved[2];
    ASSERT_EQ(pipe(saved), 0);
    const auto started = std::chrono::steady_clock::now();
    const pid_t pid = start_helper(kind.name, folder, 1, true, saved[1]);  // B, A, B, ...
    close(saved[1]);
    // Once its first save is done the helper is saving in its loop: the kill lands at a
    // random moment within the time that first save took (start-up included), so in the
    // middle of the saves that follow, whatever the machine's load.
    char c = 0;
    const bool first_done = ::read(saved[0], &c, 1) == 1;
    const auto first = std::chrono::steady_clock::now() - started;
    if (first_done) {
      const auto us = std::chrono::duration_cast<std::chrono::microseconds>(first).count();
      std::this_thread::sleep_for(
          std::chrono::microseconds(std::uniform_int_distribution<long>(0, us)(rng)));
    }
    kill(pid, SIGKILL);
    int status = 0;
    waitpid(pid, &status, 0);
    close(saved[0]);
    ASSERT_TRUE(first_done && WIFSIGNALED(status))
        << "the helper ended by itself (a save failed); seed " << seed;
    const std::string now = content(file);
    ASSERT_TRUE(now == a || now == b) << "kill " << kill_no << " left " << now.size()
                                      << " bytes that are neither the old nor the new content; "
                                      << "seed " << seed;
    (now == a ? saw_old : saw_new) += 1;
    struct stat st {};
    ASSERT_EQ(stat(file.c_str(), &st), 0);
    ASSERT_EQ(st.st_mode & 07777, 0600u) << "kill " << kill_no;
  }
  // A later save cleans what the kills left. It must change the file: a run whose values are
  // unchanged writes nothing (and so cleans nothing until the next save that does).
  const bool was_a = content(file) == a;
  ASSERT_EQ(run_helper(kind.name, folder, was_a ? 1 : 0), 0);
  EXPECT_EQ(content(file), was_a ? b : a);
  EXPECT_EQ(temp_files(folder), std::vector<std::string>{});
  std::printf(
      "[ figures  ] %s: 200 kills, never a torn file; then %d times the first loop "
      "save's content, %d times a later one's\n",
      kind.name, saw_new, saw_old);
  fs::remove_all(folder);
}

INSTANTIATE_TEST_SUITE_P(EveryKindOfSave, KillDuringSave,
                         ::testing::Values(Kind{"writer", "writer.txt"},
                                           Kind{"settings", "settings.toml"},
                                           Kind{"values", "values.toml"},
                                           Kind{"variables", "persistent.json"}),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace
