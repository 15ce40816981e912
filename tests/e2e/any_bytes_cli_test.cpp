// Any bytes through the gantry binary (issue 22): a message with Latin-1 bytes in a --json
// report, and a $variable holding them, saved by one run and read by the next.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "../support/run_gantry.hpp"

namespace {

namespace fs = std::filesystem;
using e2e::gantry;

class AnyBytes : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("gantry_any_bytes_" + std::to_string(getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string file(const std::string& name, const std::string& text) const {
    const fs::path p = dir_ / name;
    std::ofstream(p, std::ios::binary) << text;
    return p.string();
  }
  fs::path dir_;
};

TEST_F(AnyBytes, RunJsonReportsAMessageWithLatin1BytesEscaped) {
  // A Latin-1 file: the text in the error message is not UTF-8.
  const std::string part = file("latin1.sbp", "MX, 1\nMY, caf\xe9\n");
  const e2e::GantryResult r = gantry("run '" + part + "' --json");
  EXPECT_EQ(r.exit_code, 1) << r.err;  // an error, not an abort (134) with no report
  const nlohmann::json report = nlohmann::json::parse(r.out);
  ASSERT_EQ(report["errors"].size(), 1u) << r.out;
  const std::string message = report["errors"][0]["message"];
  EXPECT_NE(message.find("caf\\xE9"), std::string::npos) << message;
  EXPECT_EQ(report["status"], "error");
  EXPECT_NE(r.err.find("caf\\xE9"), std::string::npos) << r.err;  // gantry check's text too
}

TEST_F(AnyBytes, Latin1PersistentVariableSurvivesASaveAndTheNextRun) {
  const std::string store = (dir_ / "persistent.json").string();
  const std::string set = file("set.sbp", "$name = \"caf\xe9\"\nMX, 1\n");
  const e2e::GantryResult first = gantry("run '" + set + "' --persistent '" + store + "'");
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const std::string get = file("get.sbp", "PRINT \"[\"; $name; \"]\"\n");
  const e2e::GantryResult second = gantry("run '" + get + "' --persistent '" + store + "'");
  ASSERT_EQ(second.exit_code, 0) << second.err;
  EXPECT_NE(second.out.find("[caf\xe9]"), std::string::npos) << second.out;  // the exact bytes
}

}  // namespace
