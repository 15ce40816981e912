// G20-G27, Friendly Motion's data files, on a temporary folder (the disk) and in a check's
// sandbox: records written by G26 read back by G27 with and without R, the partial reads the
// manual describes, and every error at the command's location.
#include <gtest/gtest.h>

#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "../support/temp_dir.hpp"
#include "gantry/core/diagnostic.hpp"
#include "gantry/interp/file_system.hpp"
#include "gantry/interp/fm_data_files.hpp"

namespace gantry {
namespace {

const SourceLoc kLoc = file_loc("job.fm", 12, 7);

// The error `f` throws: located at kLoc, its message holding every one of `words`.
template <typename F>
void expect_error(F&& f, const std::vector<std::string>& words) {
  try {
    f();
    ADD_FAILURE() << "no error";
  } catch (const GantryError& e) {
    const Diagnostic& d = e.diagnostic();
    ASSERT_TRUE(d.loc.file);
    EXPECT_EQ(*d.loc.file, "job.fm");
    EXPECT_EQ(d.loc.line, 12);
    EXPECT_EQ(d.loc.column, 7);
    for (const std::string& w : words)
      EXPECT_NE(d.message.find(w), std::string::npos) << d.message << " lacks " << w;
  }
}

struct Files {
  TempDir dir{"fm_data"};
  DiskFileSystem disk;
  // The executor's rule in small: a relative name lands in the data folder (here the temp dir).
  FmDataFiles files{[this](const std::string& name, FileAccess, const SourceLoc&) {
    return name.front() == '/' ? name : dir.path(name);
  }};
};

TEST(FmDataFileName, DatIsAddedWhenTheNameHasNoExtension) {
  EXPECT_EQ(fm_data_file_name("PARTS", kLoc), "PARTS.dat");
  EXPECT_EQ(fm_data_file_name("log.txt", kLoc), "log.txt");
  EXPECT_EQ(fm_data_file_name("run.v2/serials", kLoc), "run.v2/serials.dat");
  EXPECT_EQ(fm_data_file_name("C:\\ncfiles\\LOT", kLoc), "C:\\ncfiles\\LOT.dat");
  EXPECT_EQ(fm_data_file_name(".hidden", kLoc), ".hidden.dat");
  expect_error([] { fm_data_file_name("", kLoc); }, {"empty"});
  expect_error([] { fm_data_file_name("out/", kLoc); }, {"out/", "folder"});
}

TEST(FmDataFiles, G26RecordsReadBackByG27WithAndWithoutR) {
  Files f;
  f.files.create_output(f.disk, "VALUES", kLoc);
  EXPECT_EQ(f.files.output_path(), f.dir.path("VALUES.dat"));
  f.files.write_values(std::vector<double>{1, 2.5, -3}, kLoc);
  f.files.write_values(std::vector<double>{4, 5}, kLoc);
  f.files.write_values(std::vector<double>{6}, kLoc);
  f.files.close_output(kLoc);
  EXPECT_EQ(f.dir.read("VALUES.dat"), "1.0000,2.5000,-3.0000\r\n4.0000,5.0000\r\n6.0000\r\n");

  f.files.open_input(f.disk, "VALUES", kLoc);
  EXPECT_EQ(f.files.input_record(), 1u);
  // R2: the second record; then, without R, on from where it stopped, over the line's end.
  EXPECT_EQ(f.files.read_values(2.0, 1, kLoc), std::vector<double>{4});
  EXPECT_EQ(f.files.read_values(std::nullopt, 2, kLoc), (std::vector<double>{5, 6}));
  // R1 with five values reads on into the second record, and stops after the fifth.
  EXPECT_EQ(f.files.read_values(1.0, 5, kLoc), (std::vector<double>{1, 2.5, -3, 4, 5}));
  EXPECT_EQ(f.files.input_record(), 2u);
  EXPECT_EQ(f.files.read_values(std::nullopt, 1, kLoc), std::vector<double>{6});
  expect_error([&] { f.files.read_values(std::nullopt, 1, kLoc); },
               {"past the end", "VALUES.dat", "value 1 of 1"});
  expect_error([&] { f.files.read_values(4.0, 1, kLoc); },
               {"VALUES.dat", "has 3 records", "record 4 is past its end"});
  f.files.close_input(kLoc);
}

// "The G27 command only reads enough data to fulfill the requirements of the command - it does
// not read an entire line" (seed 004, L542): the next G27 goes on in the same record.
TEST(FmDataFiles, G27ReadsOnlyWhatItNeeds) {
  Files f;
  f.dir.write("row.dat", "10 20,30\n40\n");
  f.files.open_input(f.disk, "row", kLoc);
  EXPECT_EQ(f.files.read_values(std::nullopt, 1, kLoc), std::vector<double>{10});
  EXPECT_EQ(f.files.input_record(), 1u);
  EXPECT_EQ(f.files.input_column(), 3u);
  EXPECT_EQ(f.files.read_values(std::nullopt, 1, kLoc), std::vector<double>{20});
  EXPECT_EQ(f.files.read_values(std::nullopt, 2, kLoc), (std::vector<double>{30, 40}));
  // A record number read from a variable (RV3) arrives as a value: 2.0 is record 2.
  EXPECT_EQ(f.files.read_values(2.0, 1, kLoc), std::vector<double>{40});
}

TEST(FmDataFiles, RecordsAreLinesCountingBlankOnesAndCrLf) {
  Files f;
  f.dir.write("gaps.dat", "1\r\n\r\n+2.5 .5 -1e3\r\n");
  f.files.open_input(f.disk, "gaps", kLoc);
  // Record 2 is blank: reading from it finds the next value, in record 3.
  EXPECT_EQ(f.files.read_values(2.0, 1, kLoc), std::vector<double>{2.5});
  EXPECT_EQ(f.files.read_values(3.0, 3, kLoc), (std::vector<double>{2.5, 0.5, -1000}));
  expect_error([&] { f.files.read_values(4.0, 1, kLoc); }, {"has 3 records"});
}

TEST(FmDataFiles, AFailedReadReadsNothing) {
  Files f;
  f.dir.write("bad.dat", "1,2\n3,abc,5\n");
  f.files.open_input(f.disk, "bad", kLoc);
  expect_error([&] { f.files.read_values(2.0, 3, kLoc); },
               {"record 2 of", "bad.dat", "column 3", "\"abc\" is not a number"});
  EXPECT_EQ(f.files.read_values(std::nullopt, 2, kLoc), (std::vector<double>{1, 2}));
  expect_error([&] { f.files.read_values(std::nullopt, 2, kLoc); }, {"\"abc\""});
  EXPECT_EQ(f.files.read_values(std::nullopt, 1, kLoc), std::vector<double>{3});
  f.files.close_input(kLoc);
  for (const char* word : {"+-4", "+", "-", "nan", "inf", "1e400", "1x", "1,2.3.4"}) {
    f.dir.write("odd.dat", std::string(word) + "\n");
    f.files.open_input(f.disk, "odd.dat", kLoc);
    expect_error([&] { f.files.read_values(std::nullopt, 3, kLoc); }, {"is not a number"});
    f.files.close_input(kLoc);
  }
  f.dir.write("long.dat", std::string(100, 'x'));
  f.files.open_input(f.disk, "long", kLoc);
  expect_error([&] { f.files.read_values(std::nullopt, 1, kLoc); },
               {"\"" + std::string(40, 'x') + "...\" is not a number"});
}

TEST(FmDataFiles, RecordNumbersAndCountsAreChecked) {
  Files f;
  f.dir.write("r.dat", "1\n2\n");
  f.files.open_input(f.disk, "r", kLoc);
  for (double r : {0.0, -1.0, 1.5})
    expect_error([&] { f.files.read_values(r, 1, kLoc); }, {"does not exist", "count from 1"});
  expect_error([&] { f.files.read_values(1.0, 0, kLoc); }, {"1 to 5 values, not 0"});
  expect_error([&] { f.files.read_values(1.0, 6, kLoc); }, {"1 to 5 values, not 6"});
  f.dir.write("empty.dat", "");
  f.files.close_input(kLoc);
  f.files.open_input(f.disk, "empty", kLoc);
  expect_error([&] { f.files.read_values(1.0, 1, kLoc); }, {"has 0 records"});
  expect_error([&] { f.files.read_values(std::nullopt, 1, kLoc); }, {"past the end"});
}

TEST(FmDataFiles, G20EmptiesAFileAndG21AppendsOrCreates) {
  Files f;
  f.dir.write("LOG.dat", "old\r\n");
  f.files.append_output(f.disk, "LOG", kLoc);
  f.files.write_text("RUN 2", kLoc);
  f.files.close_output(kLoc);
  EXPECT_EQ(f.dir.read("LOG.dat"), "old\r\nRUN 2\r\n");
  f.files.create_output(f.disk, "LOG", kLoc);
  EXPECT_EQ(f.dir.read("LOG.dat"), "");  // emptied when it opens, before anything is written
  f.files.close_output(kLoc);
  f.files.append_output(f.disk, "NEW", kLoc);
  EXPECT_TRUE(f.dir.exists("NEW.dat"));
  f.files.write_values(std::vector<double>{-0.00001}, kLoc);
  f.files.close_output(kLoc);
  EXPECT_EQ(f.dir.read("NEW.dat"), "0.0000\r\n");
}

// Each write is flushed: a job stopped with the file still open has lost nothing written.
TEST(FmDataFiles, EveryWriteIsOnTheDiskAtOnce) {
  Files f;
  {
    FmDataFiles files(
        [&](const std::string& n, FileAccess, const SourceLoc&) { return f.dir.path(n); });
    files.create_output(f.disk, "LIVE", kLoc);
    files.write_values(std::vector<double>{1, 2, 3, 4, 5}, kLoc);
    EXPECT_EQ(f.dir.read("LIVE.dat"), "1.0000,2.0000,3.0000,4.0000,5.0000\r\n");
    files.write_text("SERIAL 312A3", kLoc);
    EXPECT_EQ(f.dir.read("LIVE.dat"), "1.0000,2.0000,3.0000,4.0000,5.0000\r\nSERIAL 312A3\r\n");
  }
  EXPECT_EQ(f.dir.read("LIVE.dat"), "1.0000,2.0000,3.0000,4.0000,5.0000\r\nSERIAL 312A3\r\n");
}

// Programs from DOS name their files in any case; an exact name wins.
TEST(FmDataFiles, G23FindsANameInAnotherCase) {
  Files f;
  f.dir.write("lot.dat", "1\n");
  f.files.open_input(f.disk, "LOT", kLoc);
  EXPECT_EQ(f.files.input_path(), f.dir.path("lot.dat"));
  EXPECT_EQ(f.files.read_values(1.0, 1, kLoc), std::vector<double>{1});
  f.files.close_input(kLoc);
  // Two that differ only in case, and no exact one: which was meant is unknown.
  f.dir.write("Dup.dat", "2\n");
  f.dir.write("dUP.dat", "3\n");
  expect_error([&] { f.files.open_input(f.disk, "DUP", kLoc); }, {"G23"});
  EXPECT_FALSE(f.files.input_open());
}

TEST(FmDataFiles, OneOutputAndOneInputAtATime) {
  Files f;
  f.dir.write("IN.dat", "7\n");
  f.files.create_output(f.disk, "A", kLoc);
  expect_error([&] { f.files.create_output(f.disk, "B", kLoc); },
               {"G20", "open already", "A.dat", "G22"});
  expect_error([&] { f.files.append_output(f.disk, "B", kLoc); }, {"G21", "open already", "A.dat"});
  EXPECT_FALSE(f.dir.exists("B.dat"));
  f.files.open_input(f.disk, "IN", kLoc);  // an input beside the output is fine
  expect_error([&] { f.files.open_input(f.disk, "IN", kLoc); },
               {"G23", "open already", "IN.dat", "G24"});
  f.files.close_all();
  EXPECT_FALSE(f.files.output_open());
  EXPECT_FALSE(f.files.input_open());
  f.files.close_all();  // nothing open: no complaint
}

TEST(FmDataFiles, NothingOpenIsALocatedError) {
  Files f;
  expect_error([&] { f.files.close_output(kLoc); }, {"G22", "no output file is open"});
  expect_error([&] { f.files.close_input(kLoc); }, {"G24", "no input file is open"});
  expect_error([&] { f.files.write_text("X", kLoc); }, {"G25", "no output file is open"});
  expect_error([&] { f.files.write_values(std::vector<double>{1}, kLoc); },
               {"G26", "no output file is open"});
  expect_error([&] { f.files.read_values(1.0, 1, kLoc); }, {"G27", "no input file is open"});
}

TEST(FmDataFiles, AMissingInputFileSaysWhereItLooked) {
  Files f;
  expect_error([&] { f.files.open_input(f.disk, "NOPE", kLoc); },
               {"G23: there is no file", f.dir.path("NOPE.dat")});
  EXPECT_FALSE(f.files.input_open());
  // A folder named as the file is no data file either.
  std::filesystem::create_directories(f.dir.path("box.dat"));
  expect_error([&] { f.files.open_input(f.disk, "box", kLoc); }, {"G23", "box.dat"});
  expect_error([&] { f.files.create_output(f.disk, "box", kLoc); }, {"G20", "box.dat"});
}

TEST(FmDataFiles, G26TakesOneToFiveFiniteValues) {
  Files f;
  f.files.create_output(f.disk, "V", kLoc);
  expect_error([&] { f.files.write_values(std::vector<double>{}, kLoc); }, {"1 to 5", "not 0"});
  expect_error([&] { f.files.write_values(std::vector<double>(6, 1.0), kLoc); }, {"not 6"});
  expect_error(
      [&] {
        f.files.write_values(std::vector<double>{1, std::numeric_limits<double>::infinity()}, kLoc);
      },
      {"value 2 is not a number"});
  f.files.close_output(kLoc);
  EXPECT_EQ(f.dir.read("V.dat"), "");
}

// The executor's resolve refuses a name the part file may not reach: nothing is opened.
TEST(FmDataFiles, ANameTheResolveRefusesOpensNothing) {
  TempDir dir("fm_reach");
  DiskFileSystem disk;
  FmDataFiles files([](const std::string& name, FileAccess access,
                       const SourceLoc& loc) -> std::string {
    fail(loc, std::string(access == FileAccess::Write ? "may not write " : "may not read ") + name);
  });
  expect_error([&] { files.create_output(disk, "/etc/x", kLoc); }, {"may not write /etc/x.dat"});
  expect_error([&] { files.open_input(disk, "/etc/passwd", kLoc); },
               {"may not read /etc/passwd.dat"});
  EXPECT_FALSE(files.output_open());
  EXPECT_FALSE(files.input_open());
}

// A check runs on the sandbox: G20 writes nothing to the disk, and G23 reads what it wrote.
TEST(FmDataFiles, ACheckWritesIntoItsSandbox) {
  TempDir dir("fm_sandbox");
  SandboxFileSystem sandbox;
  FmDataFiles files(
      [&](const std::string& n, FileAccess, const SourceLoc&) { return dir.path(n); });
  files.create_output(sandbox, "S", kLoc);
  files.write_values(std::vector<double>{8, 9}, kLoc);
  files.close_output(kLoc);
  EXPECT_FALSE(dir.exists("S.dat"));
  files.open_input(sandbox, "S", kLoc);
  EXPECT_EQ(files.read_values(1.0, 2, kLoc), (std::vector<double>{8, 9}));
}

}  // namespace
}  // namespace gantry
