// Script reading files through its window: lines across the window's edge, CRLF split by
// it, lines longer than it, and the line above a cursor far into a file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "gantry/lang/script.hpp"

namespace gantry {
namespace {

namespace fs = std::filesystem;

std::string write_temp(const std::string& name, const std::string& text) {
  const fs::path p = fs::temp_directory_path() / ("gantry_script_" + name);
  std::ofstream(p, std::ios::binary) << text;
  return p.string();
}

// Every line of a loaded script, in order.
std::vector<std::string> lines_of(const Script& s) {
  std::vector<std::string> out;
  for (Cursor c = s.start(); !s.at_end(c);) {
    Cursor next;
    out.emplace_back(s.line_at(c, &next));
    c = next;
  }
  return out;
}

constexpr size_t kMiB = size_t{1} << 20;

TEST(ScriptFile, LinesAcrossTheWindowEdgeReadWhole) {
  // Lines of 37 bytes: the 1 MiB edge falls inside one of them.
  std::string text;
  int n = 0;
  while (text.size() < 3 * kMiB)
    text += "MX, " + std::to_string(1000000 + n++) + ".123456789012345\n";
  const auto s = Script::load(write_temp("edge.sbp", text));
  ASSERT_TRUE(s->ok());
  const std::vector<std::string> lines = lines_of(*s);
  ASSERT_EQ(lines.size(), static_cast<size_t>(n));
  for (int i = 0; i < n; i += 997)
    EXPECT_EQ(lines[i], "MX, " + std::to_string(1000000 + i) + ".123456789012345");
  EXPECT_EQ(s->line_count(), n);
}

TEST(ScriptFile, CrLfSplitByTheWindowIsOneTerminator) {
  std::string text(kMiB - 1, 'x');  // the "\r" is the window's last byte, "\n" the next one
  text = "'" + text.substr(1) + "\r\nMX, 1\r\n";
  const auto s = Script::load(write_temp("crlf.sbp", text));
  ASSERT_TRUE(s->ok());
  const std::vector<std::string> lines = lines_of(*s);
  ASSERT_EQ(lines.size(), 2u);  // not 3: no empty line between \r and \n
  EXPECT_EQ(lines[1], "MX, 1");
}

TEST(ScriptFile, ALineLongerThanTheWindowReadsWhole) {
  const std::string comment = "'" + std::string(3 * kMiB, 'c');
  const auto s = Script::load(write_temp("long.sbp", "SA\n" + comment + "\nMX, 2\n"));
  ASSERT_TRUE(s->ok());
  const std::vector<std::string> lines = lines_of(*s);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[1].size(), comment.size());
  EXPECT_EQ(lines[2], "MX, 2");
}

TEST(ScriptFile, LabelsFarIntoTheFileAreFoundAndTheLineAboveIsRead) {
  std::string text = "GOTO FAR\n";
  while (text.size() < 2 * kMiB) text += "MX, 1\n";
  text += "' the comment above\nFAR:\nMY, 3\n";
  const auto s = Script::load(write_temp("far.sbp", text));
  ASSERT_TRUE(s->ok());
  const std::optional<Cursor> far = s->label("FAR");
  ASSERT_TRUE(far);
  Cursor next;
  EXPECT_EQ(s->line_at(*far, &next), "MY, 3");
  const std::optional<std::string_view> above = s->line_before(*far);
  ASSERT_TRUE(above);
  EXPECT_EQ(*above, "FAR:");
  // Back at the start after reading the far end.
  EXPECT_EQ(s->line_at(s->start(), &next), "GOTO FAR");
}

TEST(ScriptFile, ByteOrderMarkIsSkippedAndADirectoryIsNotAFile) {
  const auto s = Script::load(write_temp("bom.sbp", "\xEF\xBB\xBFMX, 1\n"));
  Cursor next;
  EXPECT_EQ(s->line_at(s->start(), &next), "MX, 1");
  const auto dir = Script::load(fs::temp_directory_path().string());
  ASSERT_EQ(dir->errors().size(), 1u);
  EXPECT_FALSE(dir->ok());
}

// What runs is what was checked: a file written over in place after its load (a CAM
// program exporting again to the same name while it runs) is refused at the next read from
// the disk (its modification time, size or a block's hash differ), never run. Replacing the file (a new file renamed over it) changes nothing.

// Overwrites `len` bytes at `at` in place (the same inode), as an editor's in-place save does.
void overwrite_in_place(const std::string& path, size_t at, const std::string& bytes) {
  std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
  f.seekp(static_cast<std::streamoff>(at));
  f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

std::string three_mib_file() {
  std::string text;
  while (text.size() < 3 * kMiB) text += "MX, 1.000\n";
  return text + "MZ, 0.000\n";
}

TEST(ScriptChecked, AFileWrittenOverInPlaceIsRefusedWhereTheChangeIsRead) {
  const std::string path = write_temp("changed.sbp", three_mib_file());
  const auto s = Script::load(path);
  ASSERT_TRUE(s->ok());
  const size_t last = fs::file_size(path) - 10;
  overwrite_in_place(path, last, "MZ, -3.00\n");  // same size: only the bytes differ
  try {
    lines_of(*s);
    FAIL() << "the changed last line was read";
  } catch (const GantryError& e) {
    EXPECT_NE(e.diagnostic().message.find("changed on disk after it was checked"),
              std::string::npos);
    EXPECT_GE(e.diagnostic().loc.line, 1);  // located at the line being read
  }
}

TEST(ScriptChecked, AChangeInTheWindowAlreadyReadIsNeverSeenAndANewFileIsNoChange) {
  const std::string path = write_temp("renamed.sbp", three_mib_file());
  const auto s = Script::load(path);
  const std::string other = write_temp("renamed.new", "MZ, -3\n");
  fs::rename(other, path);  // the loaded file is still open: its bytes are what runs
  const std::vector<std::string> lines = lines_of(*s);
  EXPECT_EQ(lines.back(), "MZ, 0.000");
}

TEST(ScriptChecked, ATruncatedFileIsRefusedToo) {
  const std::string path = write_temp("shrunk.sbp", three_mib_file());
  const auto s = Script::load(path);
  fs::resize_file(path, kMiB);
  EXPECT_THROW(lines_of(*s), GantryError);
}

TEST(ScriptChecked, ACalledFileIsLoadedOnceForTheCheckAndTheRun) {
  const auto top = Script::from_text("FP, sub.sbp\n", "top.sbp");
  int loads = 0;
  auto load = [&] {
    ++loads;
    return Script::load(write_temp("called.sbp", "MX, 1\n"));
  };
  const auto first = top->called("sub.sbp", load);
  EXPECT_EQ(top->called("sub.sbp", load), first);  // the run reads the check's file
  EXPECT_EQ(loads, 1);
  top->forget_called("sub.sbp");  // the job wrote it: what it wrote is called next
  EXPECT_NE(top->called("sub.sbp", load), first);
  EXPECT_EQ(loads, 2);
}

// The load pass reads every line: given the command table's predicate it reports an unknown
// command wherever it is, reached by a run or not; without one (lang alone) it cannot.

TEST(ScriptLoadPass, ReportsUnknownCommandsOnEveryLineGivenWhichAreCommands) {
  const IsCommand known = [](std::string_view code) { return code == "MX" || code == "JY"; };
  const std::string text = "MX, 1\nEND\nQQ, 2\nIF 1 THEN ZZ\n  jy 3\nPRINT \"QQ\"\n'QQ\n";
  const auto s = Script::from_text(text, "part.sbp", known);
  ASSERT_EQ(s->errors().size(), 2u);
  EXPECT_EQ(format(s->errors()[0]),
            "part.sbp:3:1: error: unknown command 'QQ'; see docs/commands.md for the commands "
            "Gantry knows");
  EXPECT_EQ(s->errors()[1].loc.line, 4);
  EXPECT_EQ(s->errors()[1].message, unknown_command_message("ZZ"));
  EXPECT_TRUE(Script::from_text(text, "part.sbp")->ok());
  const std::string path = write_temp("unknown.sbp", text);
  EXPECT_EQ(Script::load(path, known)->errors().size(), 2u);
  fs::remove(path);
}

}  // namespace
}  // namespace gantry
