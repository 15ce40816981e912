// The recent part files (session/recent_files): newest first, each once, at most `keep`,
// kept across sessions in a file written atomically; a missing or damaged list is empty.
#include "gantry/session/recent_files.hpp"

#include <gtest/gtest.h>
#include <unistd.h>  // getpid

#include <filesystem>
#include <fstream>

#include "gantry/core/text_file.hpp"  // read_text_file

namespace gantry::session {
namespace {

namespace fs = std::filesystem;

struct RecentFilesTest : ::testing::Test {
  fs::path dir = fs::temp_directory_path() / ("gantry_recent_" + std::to_string(getpid()));
  void SetUp() override { fs::remove_all(dir); }
  void TearDown() override { fs::remove_all(dir); }
};

TEST_F(RecentFilesTest, TheListLivesNextToTheValuesFile) {
  EXPECT_EQ(recent_files_path("/home/op/.config/gantry/values/Desktop.toml"),
            "/home/op/.config/gantry/values/recent_files.txt");
}

TEST_F(RecentFilesTest, NewestFirstEachOnceAndKeptAcrossSessions) {
  const std::string list = (dir / "values" / "recent_files.txt").string();  // no folder yet
  {
    RecentFiles r(list, 3);
    EXPECT_TRUE(r.files().empty());
    std::string why;
    EXPECT_TRUE(r.add("/parts/a.sbp", &why)) << why;
    EXPECT_TRUE(r.add("/parts/b.nc"));
    EXPECT_TRUE(r.add("/parts/a.sbp"));  // again: to the front, not twice
    EXPECT_EQ(r.files(), (std::vector<std::string>{"/parts/a.sbp", "/parts/b.nc"}));
    r.add("/parts/c.sbp");
    r.add("/parts/d.sbp");  // the fourth: the oldest drops off
    EXPECT_EQ(r.files(),
              (std::vector<std::string>{"/parts/d.sbp", "/parts/c.sbp", "/parts/a.sbp"}));
  }
  EXPECT_EQ(read_text_file(list), "/parts/d.sbp\n/parts/c.sbp\n/parts/a.sbp\n");
  // No temporary file is left beside it.
  int entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir / "values")) ++entries;
  EXPECT_EQ(entries, 1);
  const RecentFiles next(list, 3);  // the next session
  EXPECT_EQ(next.files(),
            (std::vector<std::string>{"/parts/d.sbp", "/parts/c.sbp", "/parts/a.sbp"}));
}

TEST_F(RecentFilesTest, ARelativeNameIsKeptAbsolute) {
  RecentFiles r((dir / "recent_files.txt").string());
  r.add("part.sbp");
  EXPECT_EQ(r.files().at(0), (fs::current_path() / "part.sbp").string());
}

TEST_F(RecentFilesTest, AHandEditedListReadsEachFileOnce) {
  fs::create_directories(dir);
  std::ofstream(dir / "recent_files.txt") << "/p/a.sbp\r\n\n/p/a.sbp\n/p/b.sbp";
  const RecentFiles r((dir / "recent_files.txt").string());
  EXPECT_EQ(r.files(), (std::vector<std::string>{"/p/a.sbp", "/p/b.sbp"}));
}

TEST_F(RecentFilesTest, AListThatCannotBeWrittenSaysWhyAndKeepsTheFileInMemory) {
  fs::create_directories(dir);
  std::ofstream(dir / "file") << "x";  // a file where the folder should be
  RecentFiles r((dir / "file" / "recent_files.txt").string());
  std::string why;
  EXPECT_FALSE(r.add("/p/a.sbp", &why));
  EXPECT_FALSE(why.empty());
  EXPECT_EQ(r.files(), (std::vector<std::string>{"/p/a.sbp"}));
}

}  // namespace
}  // namespace gantry::session
