// What runs is what was checked, at the level of a job: a part file the checked file calls
// (FP) is loaded once, and the run reads the check's bytes even if the file is written over
// between the two; a file the job itself writes is called as written.
#include <gtest/gtest.h>
#include <unistd.h>  // getpid

#include <filesystem>
#include <fstream>

#include "gantry/interp/operator_io.hpp"  // ScriptedIO
#include "gantry/lang/script.hpp"         // Script
#include "gantry/machine/job.hpp"         // check_program, interpret
#include "gantry/settings/settings.hpp"   // default_settings
#include "../support/recording_sink.hpp"

namespace gantry {
namespace {

namespace fs = std::filesystem;

struct JobFolder {
  JobFolder() : dir(fs::temp_directory_path() / ("gantry_checked_" + std::to_string(::getpid()))) {
    fs::create_directories(dir);
  }
  ~JobFolder() { fs::remove_all(dir); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(dir / name, std::ios::binary) << text;
    return (dir / name).string();
  }
  fs::path dir;
};

// The Z of every move the run makes.
std::vector<double> run_z(const std::shared_ptr<const Script>& script) {
  const Settings settings = default_settings();
  PersistentStore store;
  RecordingSink sink;
  ScriptedIO io(true, {});
  JobOptions opt;
  opt.interpreter.dry_run = true;
  interpret(script, settings, sink, io, store, opt);
  std::vector<double> z;
  for (const CanonMove& m : sink.moves) z.push_back(m.to[2]);
  return z;
}

TEST(CheckedRun, ACalledFileWrittenOverAfterTheCheckRunsAsChecked) {
  JobFolder job;
  const std::string top = job.write("top.sbp", "FP, sub.sbp\n");
  job.write("sub.sbp", "MZ, 0.5\n");
  const auto script = Script::load(top);
  const Settings settings = default_settings();
  PersistentStore store;
  ASSERT_FALSE(check_program(script, settings, store, {}).has_errors());
  job.write("sub.sbp", "MZ, -3\n");  // a plunge the check never saw
  EXPECT_EQ(run_z(script), std::vector<double>{0.5});
}

TEST(CheckedRun, AFileTheJobWritesIsCalledAsItWasWritten) {
  JobFolder job;
  job.write("sub.sbp", "MZ, 0.5\n");
  const auto script = Script::load(job.write("top.sbp",
                                             "FP, sub.sbp\n"
                                             "OPEN \"sub.sbp\" FOR OUTPUT AS #1\n"
                                             "WRITE #1, \"MZ, 0.25\"\n"
                                             "CLOSE #1\n"
                                             "FP, sub.sbp\n"));
  EXPECT_EQ(run_z(script), (std::vector<double>{0.5, 0.25}));
}

}  // namespace
}  // namespace gantry
