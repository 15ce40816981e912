// Runs the gantry binary for the end-to-end tests (GANTRY_BIN, GANTRY_SOURCE_DIR come from
// tests/CMakeLists.txt), and the shipped profile's steps per unit.
#pragma once

#include <fmt/format.h>
#include <sys/wait.h>
#include <unistd.h>  // getpid

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace e2e {

struct GantryResult {
  int exit_code = -1;
  std::string out, err;
};

// Runs `gantry ARGS` in the source folder, capturing stdout and stderr. Each call gets a
// fresh config folder, so no run sees the values (or $variables) another run saved.
// `limit_s`: killed after that many seconds (exit code 137), for a test of a hang.
// `runner`: a command gantry runs under (e.g. setpriv, to run as another user).
inline GantryResult gantry(const std::string& args, int limit_s = 0,
                           const std::string& runner = "") {
  namespace fs = std::filesystem;
  static int calls = 0;
  ++calls;
  const fs::path tmp = fs::temp_directory_path();
  const fs::path err = tmp / fmt::format("gantry_e2e_{}_{}.err", getpid(), calls);
  const fs::path config = tmp / fmt::format("gantry_e2e_config_{}_{}", getpid(), calls);
  const std::string cmd = fmt::format(
      "cd '{}' && XDG_CONFIG_HOME='{}' {}{}'{}' {} 2>'{}'", GANTRY_SOURCE_DIR, config.string(),
      limit_s ? fmt::format("timeout -s KILL {} ", limit_s) : "", runner, GANTRY_BIN, args,
      err.string());
  GantryResult r;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf{};
  for (size_t n; (n = fread(buf.data(), 1, buf.size(), p)) > 0;) r.out.append(buf.data(), n);
  const int status = pclose(p);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::stringstream text;
  text << std::ifstream(err).rdbuf();
  r.err = text.str();
  fs::remove_all(config);
  fs::remove(err);
  return r;
}

// Steps per unit of the shipped profile (settings/default.toml), written out here so that a
// test does not trust the code under test to convert positions.
constexpr std::array<double, 6> kStepsPerUnit{916.7324, 916.7324, 1018.5916,
                                              13.8889,  13.8889,  13.8889};
constexpr std::array<const char*, 6> kAxes{"x", "y", "z", "a", "b", "c"};

}  // namespace e2e
