// Script reading files through its window: lines across the window's edge, CRLF split by
// it, lines longer than it, and the line above a cursor far into a file; jumps anywhere in a
// file through its block store, and its memory.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "gantry/interp/interpreter.hpp"  // GOSUB across the file
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

// ---- the block store: a jump anywhere reads the right line, memory stays bounded ----

// The start of every line, in order.
std::vector<Cursor> cursors_of(const Script& s) {
  std::vector<Cursor> out;
  for (Cursor c = s.start(), next; !s.at_end(c); c = next) {
    out.push_back(c);
    s.line_at(c, &next);
  }
  return out;
}

// Appends a comment line ending with `end` so that `end` starts at `at`.
void comment_to(std::string& text, size_t at, const std::string& end) {
  ASSERT_GT(at, text.size());
  text += "'" + std::string(at - text.size() - 1, 'x') + end;
}

// Lines of every length and terminator around the edges of blocks (64 KiB) and of the old
// window (1 MiB), and lines across several blocks, read from the file in any order give what
// the same text in memory gives: the line and the next line's cursor.
TEST(ScriptStore, JumpsAnywhereBothWaysReadWhatTheTextInMemoryReads) {
  constexpr size_t kBlock = size_t{1} << 16;
  std::string text = "SA\n";
  comment_to(text, kBlock - 1, "\r\nMX, 1\n");    // "\r" ends a block, "\n" starts the next
  comment_to(text, 2 * kBlock - 1, "\rMX, 2\r");  // a lone "\r" ends a block
  comment_to(text, 3 * kBlock, "\nMX, 3\n");      // "\n" starts a block
  comment_to(text, 4 * kBlock - 1, "\n\n");       // an empty line starts a block
  comment_to(text, kMiB - 2, "\r\n\r\n");         // the old window's edge
  text += "'" + std::string(3 * kBlock + 17, 'L') + "\r\n";  // across four blocks
  std::mt19937 rng(27);
  const char* const ends[] = {"\n", "\r\n", "\r"};
  for (int n = 0; text.size() < 5 * kMiB; ++n)
    text += "MX, " + std::to_string(n) + "." + std::string(rng() % 120, '5') + ends[rng() % 3];
  text += "MZ, 9\r";  // the file ends on a lone "\r"
  const auto file = Script::load(write_temp("jumps.sbp", text));
  const auto mem = Script::from_text(text, "jumps.sbp");
  ASSERT_TRUE(file->ok());
  const std::vector<Cursor> all = cursors_of(*mem);
  const std::vector<Cursor> read = cursors_of(*file);
  ASSERT_EQ(read.size(), all.size());
  ASSERT_GT(all.size(), 50000u);
  for (size_t i = 0; i < all.size(); ++i) ASSERT_EQ(read[i].offset, all[i].offset) << i;
  auto same = [&](Cursor c) {
    Cursor a, b;
    const std::string from_file(file->line_at(c, &a));
    ASSERT_EQ(from_file, mem->line_at(c, &b)) << "line " << c.line;
    ASSERT_EQ(a.offset, b.offset) << "line " << c.line;
    ASSERT_EQ(a.line, b.line);
  };
  // A GOSUB far down and its RETURN far up, from both ends towards the middle.
  for (size_t i = 0; i < all.size() / 2; i += 101) {
    same(all[i]);
    same(all[all.size() - 1 - i]);
  }
  // The lines around every edge, then jumps at random.
  for (size_t i = 0; i < 12; ++i) same(all[i]);
  std::uniform_int_distribution<size_t> any(0, all.size() - 1);
  for (int i = 0; i < 20000; ++i) same(all[any(rng)]);
  // The line above, after a jump (a file looks back 64 KiB, text all the way).
  for (int i = 0; i < 2000; ++i) {
    const Cursor c = all[any(rng)];
    const std::optional<std::string_view> in_memory = mem->line_before(c);
    if (in_memory && in_memory->size() > 65000) continue;
    const std::optional<std::string> expected(in_memory);
    const std::optional<std::string_view> above = file->line_before(c);
    EXPECT_EQ(above ? std::optional<std::string>(*above) : std::nullopt, expected)
        << "line " << c.line;
  }
}

// PRINT output of running `script`.
std::string printed_by(const std::shared_ptr<const Script>& script) {
  class Drop : public MotionSink {
   public:
    void move(const CanonMove&) override {}
    void flush() override {}
  } sink;
  std::string printed;
  ScriptedIO io(true, {}, &printed);
  PersistentStore store;
  Interpreter interp(default_settings(), sink, io, store);
  interp.run(script);
  return printed;
}

TEST(ScriptStore, GosubAndReturnAcrossMoreThanAMebibyteBothWays) {
  std::string pad;
  while (pad.size() < 2 * kMiB + 12345) pad += "' between the calls and the subroutine\n";
  const std::string loop =
      "&n = 0\nLOOP:\n&n = &n + 1\nGOSUB SUB\nPRINT &r\nIF &n < 40 THEN GOTO LOOP\nEND\n";
  const std::string sub = "SUB:\n&r = &n * 10\nRETURN\n";
  const std::string below = loop + pad + sub;                              // a GOSUB down
  const std::string above = "GOTO MAIN\n" + sub + pad + "MAIN:\n" + loop;  // a GOSUB up
  for (const std::string& text : {below, above}) {
    const auto file = Script::load(write_temp("gosub.sbp", text));
    ASSERT_TRUE(file->ok());
    const std::string printed = printed_by(file);
    EXPECT_EQ(printed, printed_by(Script::from_text(text, "gosub.sbp")));
    EXPECT_NE(printed.find("400"), std::string::npos) << printed;
  }
}

#if !defined(__SANITIZE_ADDRESS__)  // its quarantine keeps what the parsers free resident
// This process's resident memory in KiB.
long resident_kib() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
  return -1;
}

// A 24 MiB file checked, read through and jumped about in: the script keeps at most 1 MiB of
// blocks and nothing per line (an offset per line would be 6.4 MB here). The 10M-line figure
// against its 200 MB target: bench/script_bench.cpp, BM_ScriptTenMillionLinesPeakRss.
TEST(ScriptStore, MemoryStaysBoundedOnALargeFile) {
  const std::string path = (fs::temp_directory_path() / "gantry_script_large.sbp").string();
  size_t lines = 0;
  {
    std::ofstream out(path, std::ios::binary);
    std::string chunk;
    while (lines < 800000) {
      chunk += "' a comment line of the generated file, number " + std::to_string(lines++) +
               "\nMX, 1.5\n";
      ++lines;
      if (chunk.size() > kMiB) {
        out << chunk;
        chunk.clear();
      }
    }
    out << chunk;
  }
  const long before = resident_kib();
  ASSERT_GT(before, 0);
  const auto s = Script::load(path);
  ASSERT_TRUE(s->ok());
  EXPECT_EQ(s->line_count(), static_cast<int>(lines));
  std::vector<Cursor> some;  // every 100th line's start, to jump to
  size_t bytes = 0;
  Cursor next;
  for (Cursor c = s->start(); !s->at_end(c); c = next) {
    if (c.line % 100 == 0) some.push_back(c);
    bytes += s->line_at(c, &next).size();
  }
  std::mt19937 rng(1);
  for (int i = 0; i < 5000; ++i) bytes += s->line_at(some[rng() % some.size()], &next).size();
  const long grown = resident_kib() - before;
  EXPECT_GT(bytes, 20 * kMiB);
  EXPECT_LT(grown, 4 * 1024) << "KiB more resident after reading the file";
  fs::remove(path);
}
#endif

}  // namespace
}  // namespace gantry
