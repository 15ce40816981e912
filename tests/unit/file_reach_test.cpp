// A part file's reach (docs/security.md), through the interpreter: the job's folder, the
// data folder, the operator's folders and the read-only macro folders; links resolved.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>  // getpid

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "../support/recording_sink.hpp"
#include "gantry/core/diagnostic.hpp"
#include "gantry/interp/file_reach.hpp"
#include "gantry/interp/interpreter.hpp"
#include "gantry/lang/script.hpp"
#include "gantry/settings/settings.hpp"

namespace gantry {
namespace {

namespace fs = std::filesystem;

class FileReachTest : public ::testing::Test {
 protected:
  FileReachTest() {
    static int n = 0;
    root_ = fs::temp_directory_path() / fmt::format("gantry_file_reach_{}_{}", getpid(), n++);
    fs::remove_all(root_);
    for (const char* d : {"job", "data", "allowed", "macros", "outside"})
      fs::create_directories(root_ / d);
    options.data_dir = (root_ / "data").string();
    options.macro_dir = (root_ / "macros").string();
    options.user_macro_dir = options.shipped_macro_dir = "";
    std::ofstream(root_ / "macros/C50.sbp") << "MX, 1\n";
    std::ofstream(root_ / "outside/C51.sbp") << "MX, 1\n";
  }
  ~FileReachTest() override {
    std::error_code ec;
    fs::remove_all(root_, ec);
  }
  std::string at(const std::string& name) const { return (root_ / name).string(); }

  // Checks `text` as job/part.sbp (a check: writes stay in memory); its errors, formatted.
  std::string check(const std::string& text) {
    const Settings settings = default_settings();
    RecordingSink sink;
    ScriptedIO io(true, {});
    PersistentStore store;
    InterpreterOptions o = options;
    o.dry_run = true;
    Interpreter interp(settings, sink, io, store, o);
    std::string out;
    for (const Diagnostic& d : interp.check(Script::from_text(text, at("job/part.sbp"))))
      out += format(d) + "\n";
    return out;
  }

  fs::path root_;
  InterpreterOptions options;
};

TEST_F(FileReachTest, TheJobAndDataFoldersAreReachedAndNothingElse) {
  const std::string out = check(fmt::format(
      "OPEN \"{0}/job/a.txt\" FOR OUTPUT AS #1\nOPEN \"{0}/data/b.txt\" FOR OUTPUT AS #2\n"
      "OPEN \"{0}/allowed/c.txt\" FOR OUTPUT AS #3\n",
      root_.string()));
  EXPECT_EQ(out, at("job/part.sbp") + ":3:6: error: " + at("allowed/c.txt") +
                     " is outside the job's folder " + at("job") +
                     ": a part file writes files only there, in the Gantry data folder and in "
                     "the folders the operator allows; to allow it, add \"" +
                     at("allowed") +
                     "\" to [files] allow in the machine profile or run with --allow-path " +
                     at("allowed") + "\n");
  options.allowed_folders = {at("allowed")};
  EXPECT_EQ(check(fmt::format("OPEN \"{}/allowed/c.txt\" FOR OUTPUT AS #3\n", root_.string())), "");
}

TEST_F(FileReachTest, MacroFoldersAreReadNotWritten) {
  EXPECT_EQ(check("C50\n"), "");
  EXPECT_EQ(check(fmt::format("FP, {}/macros/C50.sbp\n", root_.string())), "");
  const std::string out = check(fmt::format("US, {}/macros/x.toml\n", root_.string()));
  EXPECT_NE(
      out.find("part.sbp:1:5: error: " + at("macros/x.toml") + " is outside the job's folder"),
      std::string::npos)
      << out;
}

TEST_F(FileReachTest, AMacroThatIsALinkOutIsRefused) {
  fs::create_symlink(at("outside/C51.sbp"), at("macros/C51.sbp"));
  const std::string out = check("C51\n");
  EXPECT_NE(
      out.find("part.sbp:1:1: error: " + at("macros/C51.sbp") + " is outside the job's folder " +
               at("job") + " (it leads to " + at("outside/C51.sbp") + "): a part file reads"),
      std::string::npos)
      << out;
}

TEST_F(FileReachTest, LinksAndDotDotResolveBeforeTheyAreCompared) {
  fs::create_directory_symlink(at("outside"), at("job/out"));
  fs::create_symlink(at("outside/new.txt"), at("job/dangling"));  // its target is missing
  fs::create_symlink("../job", at("data/back"));                  // relative, and inside
  EXPECT_EQ(resolved_path(at("job/out/x.txt")), fs::path(at("outside/x.txt")));
  EXPECT_EQ(resolved_path(at("job/dangling")), fs::path(at("outside/new.txt")));
  EXPECT_EQ(resolved_path(at("job/../job/./a")), fs::path(at("job/a")));
  EXPECT_EQ(resolved_path(at("data/back/a")), fs::path(at("job/a")));
  const FileReach none;
  EXPECT_NE(reach_refusal(at("job/dangling"), FileAccess::Write, at("job"), none), "");
  EXPECT_NE(reach_refusal(at("job/out/x.txt"), FileAccess::Read, at("job"), none), "");
  EXPECT_NE(reach_refusal(at("job/../jobs/x"), FileAccess::Read, at("job"), none), "");
  EXPECT_EQ(reach_refusal(at("data/back/a"), FileAccess::Write, at("job"), none), "");
  EXPECT_EQ(reach_refusal("", FileAccess::Read, "", none), "");  // the working directory
}

}  // namespace
}  // namespace gantry
