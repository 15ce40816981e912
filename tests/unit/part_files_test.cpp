// Finding part files as files written on Windows name them (FP's .sbp, case), FP's undefined
// variables, and where C<n> finds its macro: --macros or the parts folder and the operator's
// folder first, then the macros Gantry ships (docs/language.md, §5.1, §5.3, §5.4).
#include <gtest/gtest.h>
#include <unistd.h>  // getpid

#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "../support/recording_sink.hpp"
#include "gantry/core/diagnostic.hpp"
#include "gantry/interp/file_system.hpp"
#include "gantry/interp/interpreter.hpp"
#include "gantry/interp/operator_io.hpp"
#include "gantry/interp/persistent_store.hpp"
#include "gantry/lang/script.hpp"
#include "gantry/settings/settings.hpp"

namespace gantry {
namespace {

namespace fs = std::filesystem;

const std::string kShipped = std::string(GANTRY_SOURCE_DIR) + "/parts/macros";

class PartFilesTest : public ::testing::Test {
 protected:
  PartFilesTest() {
    root_ = fs::temp_directory_path() /
            ("gantry_part_files_" + std::to_string(::getpid()) + "_" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(root_);
    options.user_macro_dir = path("user");  // never the tester's own folder
    options.shipped_macro_dir = kShipped;
  }
  ~PartFilesTest() override { fs::remove_all(root_); }

  std::string path(const std::string& name) const { return (root_ / name).string(); }
  std::string folder() const { return root_.string(); }
  std::string write(const std::string& name, const std::string& text) const {
    const fs::path p = root_ / name;
    fs::create_directories(p.parent_path());
    std::ofstream(p) << text;
    return p.string();
  }
  // Runs the file `name`; the error it stops at, if any.
  std::optional<Diagnostic> run(const std::string& name) {
    ScriptedIO io(true, {}, &printed);
    PersistentStore store;
    Interpreter interp(settings, sink, io, store, options);
    try {
      interp.run(Script::load(path(name)));
    } catch (const GantryError& e) {
      return e.diagnostic();
    }
    warnings = io.warnings();
    return std::nullopt;
  }
  std::string run_error(const std::string& name) {
    const std::optional<Diagnostic> d = run(name);
    return d ? format(*d) : "(no error)";
  }
  std::vector<double> x_targets() const {
    std::vector<double> xs;
    for (const CanonMove& m : sink.moves)
      if (m.kind == MoveKind::Line) xs.push_back(m.to[0]);
    return xs;
  }

  Settings settings = default_settings();
  InterpreterOptions options;
  RecordingSink sink;
  std::string printed;
  std::vector<Diagnostic> warnings;

 private:
  fs::path root_;
};

// ---- find_part_file

TEST_F(PartFilesTest, AnExactNameIsFoundAsItIs) {
  const std::string p = write("Part.sbp", "");
  DiskFileSystem disk;
  EXPECT_EQ(find_part_file(disk, p).path, p);
  EXPECT_EQ(find_part_file(disk, p).error, "");
}

TEST_F(PartFilesTest, AMissingNameIsFoundRegardlessOfCaseFolderAndFileAlike) {
  const std::string p = write("sub/mypart.sbp", "");
  DiskFileSystem disk;
  const PartFileLookup found = find_part_file(disk, path("SUB/MyPart.SBP"));
  EXPECT_EQ(found.path, p);
  EXPECT_EQ(found.error, "");
}

TEST_F(PartFilesTest, NamesThatDifferOnlyInCaseAreRefusedUnlessOneIsExact) {
  write("PART.SBP", "");
  const std::string exact = write("Part.sbp", "");
  DiskFileSystem disk;
  EXPECT_EQ(find_part_file(disk, exact).path, exact);  // the exact one wins
  const PartFileLookup neither = find_part_file(disk, path("part.sbp"));
  EXPECT_EQ(neither.error, "there is no part.sbp but PART.SBP and Part.sbp in " + folder() +
                               ", which differ only in case; name the one to use exactly");
}

TEST_F(PartFilesTest, ANameFoundNowhereIsReturnedAsTried) {
  DiskFileSystem disk;
  const PartFileLookup found = find_part_file(disk, path("none/part.sbp"));
  EXPECT_EQ(found.path, path("none/part.sbp"));
  EXPECT_EQ(found.error, "");
}

// The sandbox of a check finds what the check wrote, in any case, as the run would.
TEST_F(PartFilesTest, TheSandboxListsItsOwnFiles) {
  SandboxFileSystem sandbox;
  *sandbox.open_write(path("Written.sbp"), false) << "MX, 1\n";
  EXPECT_EQ(find_part_file(sandbox, path("written.SBP")).path, path("Written.sbp"));
}

// ---- FP

TEST_F(PartFilesTest, FpAddsSbpToANameWithoutAnExtension) {
  write("sub.sbp", "MX, 2\n");
  write("main.sbp", "FP, sub\n");
  ASSERT_FALSE(run("main.sbp")) << run_error("main.sbp");
  EXPECT_EQ(x_targets(), std::vector<double>{2});
}

TEST_F(PartFilesTest, FpFindsAWindowsNameInAnotherCase) {
  write("jobs/mypart.sbp", "MX, 3\n");
  write("main.sbp", "FP, Jobs\\MyPart.SBP\n");
  ASSERT_FALSE(run("main.sbp")) << run_error("main.sbp");
  EXPECT_EQ(x_targets(), std::vector<double>{3});
}

TEST_F(PartFilesTest, FpRefusesTwoNamesThatDifferOnlyInCase) {
  write("PART.sbp", "MX, 1\n");
  write("part.SBP", "MX, 2\n");
  write("main.sbp", "MY, 1\nFP, Part.sbp\n");
  EXPECT_EQ(run_error("main.sbp"),
            path("main.sbp") + ":2:1: error: there is no Part.sbp but PART.sbp and part.SBP in " +
                folder() + ", which differ only in case; name the one to use exactly");
}

// Before: `cannot open the part file` for a file named &PART in the parts folder.
TEST_F(PartFilesTest, FpWithAnUndefinedVariableSaysSoAtItsColumn) {
  write("main.sbp", "MX, 1\nFP,  &part\n");
  EXPECT_EQ(run_error("main.sbp"), path("main.sbp") +
                                       ":2:6: error: undefined variable &PART; set it before "
                                       "this line");
}

TEST_F(PartFilesTest, FpWithADefinedVariableRunsItsFile) {
  write("cut.sbp", "MX, 4\n");
  write("main.sbp", "&part = \"cut\"\nFP, &part\n");
  ASSERT_FALSE(run("main.sbp")) << run_error("main.sbp");
  EXPECT_EQ(x_targets(), std::vector<double>{4});
}

TEST_F(PartFilesTest, AMissingFpFileNamesThePathTriedAndTheCallingLine) {
  write("main.sbp", "FP, nothere\n");
  EXPECT_EQ(run_error("main.sbp"), path("main.sbp") + ":1:1: error: cannot read " +
                                       path("nothere.sbp") + ": there is no such file");
}

// ---- C<n>

TEST_F(PartFilesTest, TheShippedC6SwitchesTheSpindleOnAndWaitsForSpinUp) {
  write("main.sbp", "C6\n");
  ASSERT_FALSE(run("main.sbp")) << run_error("main.sbp");
  ASSERT_EQ(sink.moves.size(), 3u);
  EXPECT_EQ(sink.moves[0].kind, MoveKind::Output);
  EXPECT_EQ(sink.moves[0].output, 1);
  EXPECT_TRUE(sink.moves[0].output_on);
  EXPECT_EQ(sink.moves[1].kind, MoveKind::Dwell);
  EXPECT_EQ(sink.moves[1].dwell_s, 3);  // &SpinUp's default, C6.sbp's header
  EXPECT_EQ(*sink.moves[1].loc.file, kShipped + "/C6.sbp");
  EXPECT_EQ(sink.moves[2].kind, MoveKind::Output);  // every output goes off at the run's end
  EXPECT_FALSE(sink.moves[2].output_on);
}

TEST_F(PartFilesTest, TheCallersSpinUpVariableIsKept) {
  write("main.sbp", "&SpinUp = 7\nC6\n");
  ASSERT_FALSE(run("main.sbp")) << run_error("main.sbp");
  ASSERT_EQ(sink.moves.size(), 3u);
  EXPECT_EQ(sink.moves[1].dwell_s, 7);
}

TEST_F(PartFilesTest, TheOperatorsFolderComesBeforeTheShippedOne) {
  write("user/C6.sbp", "MX, 6\n");
  write("main.sbp", "C6\n");
  ASSERT_FALSE(run("main.sbp")) << run_error("main.sbp");
  EXPECT_EQ(x_targets(), std::vector<double>{6});
}

TEST_F(PartFilesTest, ThePartsFolderComesBeforeTheOperatorsFolder) {
  write("user/C6.sbp", "MX, 6\n");
  write("c6.sbp", "MX, 5\n");  // lower case, as copied from Windows
  write("main.sbp", "C6\n");
  ASSERT_FALSE(run("main.sbp")) << run_error("main.sbp");
  EXPECT_EQ(x_targets(), std::vector<double>{5});
}

TEST_F(PartFilesTest, MacrosReplacesThePartsAndOperatorsFolders) {
  write("user/C6.sbp", "MX, 6\n");
  write("C6.sbp", "MX, 5\n");
  write("given/C6.sbp", "MX, 4\n");
  options.macro_dir = path("given");
  write("main.sbp", "C6\nC7\n");
  ASSERT_FALSE(run("main.sbp")) << run_error("main.sbp");
  EXPECT_EQ(x_targets(), std::vector<double>{4});                // C6 from --macros,
  EXPECT_EQ(*sink.moves.back().loc.file, kShipped + "/C7.sbp");  // C7 still shipped
}

// C9's change position is in table base coordinates, wherever the part's zero is; the tool
// comes back over the point it left (moves are in table base coordinates too).
TEST_F(PartFilesTest, TheShippedC9ChangesToolsAtATableBasePosition) {
  write("main.sbp", "MX, 5\nMY, 4\nZ2\n&Tool = 3\n&ChangeX = 1\nC9\n");
  ASSERT_FALSE(run("main.sbp")) << run_error("main.sbp");
  std::vector<std::string> lines;
  for (const CanonMove& m : sink.moves)
    if (m.kind == MoveKind::Line && m.loc.file && *m.loc.file == kShipped + "/C9.sbp")
      lines.push_back(std::to_string(m.loc.line) + ": " + std::to_string(m.to[0]) + "," +
                      std::to_string(m.to[1]) + "," + std::to_string(m.to[2]));
  EXPECT_EQ(lines, (std::vector<std::string>{"26: 5.000000,4.000000,1.000000",  // Safe-Z
                                             "28: 1.000000,0.000000,1.000000",  // the change
                                             "33: 5.000000,4.000000,1.000000"}));  // back
}

TEST_F(PartFilesTest, TheShippedC9RefusesAMissingToolNumber) {
  write("main.sbp", "MX, 1\nC9\n");
  EXPECT_EQ(run_error("main.sbp"),
            path("main.sbp") + ":2 -> " + kShipped +
                "/C9.sbp:20:19: error: FAIL: C9 needs the tool to put in: set &Tool first "
                "(&Tool = 2, then C9)");
}

TEST_F(PartFilesTest, ACustomCutFoundNowhereNamesEveryFolderLookedIn) {
  write("main.sbp", "MX, 1\n  C8\n");
  EXPECT_EQ(run_error("main.sbp"),
            path("main.sbp") +
                ":2:3: error: C8 runs custom cut 8, but there is no C8.sbp or macro_8.sbp in " +
                folder() + ", " + path("user") + " or " + kShipped +
                "; put the macro in one of them or give its folder with --macros");
}

}  // namespace
}  // namespace gantry
