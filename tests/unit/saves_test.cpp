// Saves and any bytes (issue 22): the atomic writer keeps modes and symlinks and cleans its
// temporary files; a damaged persistent file is reported and kept; $variables hold any
// bytes; values are saved in shortest round-trip form; text that is not UTF-8 is shown
// escaped; G-code nesting is bounded; echoed source text is capped.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "../support/null_sink.hpp"  // NullSink
#include "gantry/core/any_bytes.hpp"
#include "gantry/core/text_file.hpp"
#include "gantry/interp/interpreter.hpp"
#include "gantry/interp/operator_io.hpp"
#include "gantry/interp/persistent_file.hpp"  // parse_persistent_file, persistent_file_text
#include "gantry/interp/persistent_store.hpp"
#include "gantry/lang/expression.hpp"
#include "gantry/lang/gcode.hpp"
#include "gantry/lang/script.hpp"
#include "gantry/settings/values_file.hpp"

namespace gantry {
namespace {

namespace fs = std::filesystem;

class Saves : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("gantry_saves_" + std::to_string(getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  static std::string read(const std::string& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  static void write(const std::string& p, const std::string& text) {
    std::ofstream(p, std::ios::binary) << text;
  }
  std::vector<std::string> entries() const {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(dir_)) out.push_back(e.path().filename());
    std::sort(out.begin(), out.end());
    return out;
  }
  fs::path dir_;
};

// Runs `text` with the persistent file at `store_path` and saves it as a run's end does.
void run_with_store(const std::string& store_path, const std::string& text) {
  static const Settings settings = default_settings();
  PersistentStore store(store_path);
  NullSink sink;
  ScriptedIO io(true, {}, nullptr, stderr);
  Interpreter interp(settings, sink, io, store);
  interp.run(Script::from_text(text, "part.sbp"));
}

// ---- the atomic writer ------------------------------------------------------------------

TEST_F(Saves, AtomicWriteKeepsThePrivateModeOfTheTarget) {
  const std::string p = path("persistent.json");
  write(p, "{}");
  ASSERT_EQ(chmod(p.c_str(), 0600), 0);
  ASSERT_TRUE(write_file_atomically(p, "{\"variables\": {}}\n"));
  struct stat st {};
  ASSERT_EQ(stat(p.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0600u);  // was widened to 0644
  EXPECT_EQ(read(p), "{\"variables\": {}}\n");
}

TEST_F(Saves, AtomicWriteGoesThroughASymlinkAndKeepsIt) {
  fs::create_directories(dir_ / "real");
  write(path("real/values.toml"), "old\n");
  fs::create_symlink("real/values.toml", dir_ / "values.toml");
  ASSERT_TRUE(write_file_atomically(path("values.toml"), "new\n"));
  EXPECT_TRUE(fs::is_symlink(dir_ / "values.toml"));  // was replaced by a plain file
  EXPECT_EQ(read(path("real/values.toml")), "new\n");
  EXPECT_EQ(read(path("values.toml")), "new\n");
}

TEST_F(Saves, AtomicWriteLeavesNoTemporaryFileAndRemovesThoseOfKilledSaves) {
  const std::string stale = path(".values.toml.gantry-save-0123456789abcdef");
  write(stale, "half a save");  // what a SIGKILL between create and rename leaves
  write(path("values.toml.999999999.tmp"), "what earlier versions left");  // *.PID.tmp
  const std::string live = path(".other.toml.gantry-save-fedcba9876543210");
  write(live, "a save in progress");
  const int held = open(live.c_str(), O_RDONLY);
  ASSERT_EQ(flock(held, LOCK_EX), 0);  // as a writer that is still alive holds it
  ASSERT_TRUE(write_file_atomically(path("values.toml"), "x = 1.0\n"));
  close(held);
  EXPECT_EQ(entries(),
            (std::vector<std::string>{".other.toml.gantry-save-fedcba9876543210", "values.toml"}));
  ASSERT_TRUE(write_file_atomically(path("values.toml"), "x = 2.0\n"));
  EXPECT_EQ(entries(), std::vector<std::string>{"values.toml"});
}

TEST_F(Saves, AtomicWriteSaysWhyItFailedAndLeavesNoTemporaryFile) {
  fs::create_directories(dir_ / "values.toml" / "inside");  // a folder where the file should be
  std::string why;
  EXPECT_FALSE(write_file_atomically(path("values.toml"), "x = 1.0\n", &why));
  EXPECT_NE(why.find("cannot write"), std::string::npos) << why;
  EXPECT_NE(why.find("directory"), std::string::npos) << why;  // the system's reason
  EXPECT_TRUE(fs::is_directory(dir_ / "values.toml" / "inside"));
  EXPECT_EQ(entries(), std::vector<std::string>{"values.toml"});
}

// ---- a damaged persistent file ----------------------------------------------------------

TEST_F(Saves, PersistentFileWhoseVariablesIsNotAnObjectIsReportedAndKept) {
  const std::string p = path("persistent.json");
  const std::string text = "{\"variables\": [1, 2], \"registry\": {}}\n";
  write(p, text);
  try {
    PersistentStore store(p);
    FAIL() << "a damaged file was accepted (and its variables silently dropped)";
  } catch (const GantryError& e) {
    const std::string m = e.diagnostic().message;
    EXPECT_NE(m.find("damaged (its \"variables\" is not an object)"), std::string::npos) << m;
    EXPECT_NE(m.find("nothing ran"), std::string::npos) << m;
    EXPECT_EQ(*e.diagnostic().loc.file, p);
  }
  const std::vector<std::string> now = entries();
  ASSERT_EQ(now.size(), 1u);
  EXPECT_EQ(now[0].rfind("persistent.json.damaged-", 0), 0u) << now[0];
  EXPECT_EQ(read(path(now[0])), text);  // kept byte for byte
  // The next run starts with no $variables and saves a new file beside the kept one.
  run_with_store(p, "$runs := 1\n");
  EXPECT_EQ(entries().size(), 2u);
  EXPECT_EQ(PersistentStore(p).variable("RUNS")->get<int>(), 1);
}

TEST_F(Saves, PersistentFileWithAnUnknownKeyIsReportedAndKept) {
  const std::string p = path("persistent.json");
  write(p, "{\"variables\": {\"A\": 1}, \"notes\": \"mine\"}\n");
  EXPECT_THROW(
      {
        try {
          PersistentStore store(p);
        } catch (const GantryError& e) {
          EXPECT_NE(e.diagnostic().message.find("it has a key \"notes\""), std::string::npos)
              << e.diagnostic().message;
          throw;
        }
      },
      GantryError);
  EXPECT_FALSE(fs::exists(p));
  EXPECT_EQ(entries().size(), 1u);
}

TEST_F(Saves, PersistentFileThatIsNotJsonIsReportedWithItsLine) {
  const std::string p = path("persistent.json");
  write(p, "{\n  \"variables\": {\n    \"A\": 1,\n  }\n");
  try {
    PersistentStore store(p);
    FAIL();
  } catch (const GantryError& e) {
    EXPECT_EQ(e.diagnostic().loc.line, 4);
    EXPECT_NE(e.diagnostic().message.find("not valid JSON"), std::string::npos);
  }
}

// ---- any bytes ----------------------------------------------------------------------------

TEST_F(Saves, PersistentVariableHoldsLatin1BytesAcrossASave) {
  const std::string p = path("persistent.json");
  run_with_store(p, "$name = \"caf\xe9\"\n$mixed = \"c:\\dir\xe9\\x41\"\n$ok = \"caf\xc3\xa9\"\n");
  const PersistentStore reloaded(p);
  EXPECT_EQ(reloaded.variable("NAME")->get<std::string>(), "caf\xe9");
  EXPECT_EQ(reloaded.variable("MIXED")->get<std::string>(), "c:\\dir\xe9\\x41");
  EXPECT_EQ(reloaded.variable("OK")->get<std::string>(), "caf\xc3\xa9");
  const std::string saved = read(p);
  EXPECT_NE(saved.find("\"$bytes\": \"caf\\\\xE9\""), std::string::npos) << saved;
  EXPECT_NE(saved.find("\"OK\": \"caf\xc3\xa9\""), std::string::npos) << saved;  // UTF-8 as is
}

// The persistent fuzzer's find: a "registry" (or "variables") whose only key is "$bytes" read
// back as a text and saved as one, which no load accepts. Its members are decoded, not it.
TEST(PersistentFile, ATableWhoseOnlyKeyIsBytesStaysATableAcrossASave) {
  const std::string text = R"({"registry": {"$bytes": "oak"}, "variables": {"N": 3}})";
  std::string why;
  int line = 0;
  const std::optional<nlohmann::json> first = parse_persistent_file(text, &why, &line);
  ASSERT_TRUE(first) << why;
  EXPECT_TRUE((*first)["registry"].is_object());
  const std::optional<nlohmann::json> again =
      parse_persistent_file(persistent_file_text(*first), &why, &line);
  ASSERT_TRUE(again) << why;
  EXPECT_EQ(*again, *first);
}

TEST(AnyBytes, TextThatIsNotUtf8IsShownEscaped) {
  EXPECT_TRUE(is_utf8("caf\xc3\xa9"));
  EXPECT_FALSE(is_utf8("caf\xe9"));
  EXPECT_FALSE(is_utf8("\xc0\xaf"));      // overlong
  EXPECT_FALSE(is_utf8("\xed\xa0\x80"));  // a surrogate
  EXPECT_EQ(escaped_bytes("caf\xe9 ok"), "caf\\xE9 ok");
  EXPECT_EQ(escaped_bytes(std::string_view("\xff\xfeM\0X", 5)), std::string("\\xFF\\xFEM\0X", 11));
  EXPECT_EQ(escaped_bytes("caf\xc3\xa9"), "caf\xc3\xa9");
}

TEST(AnyBytes, JsonWithLatin1BytesInAMessageDumpsEscaped) {
  nlohmann::ordered_json j = {{"status", "error"},
                              {"errors", {{{"message", "unknown command 'caf\xe9'"}}}}};
  EXPECT_THROW(j.dump(), nlohmann::json::type_error);  // what `gantry run --json` died of
  EXPECT_EQ(json_text(j),
            R"({"status":"error","errors":[{"message":"unknown command 'caf\\xE9'"}]})");
}

TEST(AnyBytes, DiagnosticShowsBytesEscaped) {
  const Diagnostic d{file_loc("caf\xe9.sbp", 2, 1), Severity::Error, "bad 'caf\xe9'"};
  EXPECT_EQ(format(d), "caf\\xE9.sbp:2:1: error: bad 'caf\\xE9'");
}

TEST(AnyBytes, AHugeNumberIsNotEchoedWhole) {
  const std::string digits(10'000'000, '9');
  const ExprParse p = parse_expression(digits + "e999", file_loc("part.sbp", 1, 6));
  ASSERT_TRUE(p.error);
  EXPECT_LT(p.error->message.size(), 200u);
  EXPECT_NE(p.error->message.find("... (10000004 characters)"), std::string::npos)
      << p.error->message.substr(0, 200);
}

// ---- values in shortest round-trip form ---------------------------------------------------

TEST(ValuesFile, NumbersAreSavedInShortestRoundTripForm) {
  const Settings profile = default_settings();
  Settings now = profile;
  now.speeds.move.xy = 0.3;
  now.speeds.move.z = 0.1 + 0.2;  // 0.30000000000000004: kept exact
  now.ramps.threshold_3d = 2;
  const std::string text = values_text(now, profile);
  EXPECT_NE(text.find("xy = 0.3\n"), std::string::npos) << text;
  EXPECT_NE(text.find("z = 0.30000000000000004\n"), std::string::npos) << text;
  EXPECT_EQ(text.find("0.29999"), std::string::npos) << text;
  const SettingsLoad back = parse_settings(settings_text(profile), "profile", text, "values.toml");
  ASSERT_TRUE(back.errors.empty()) << format(back.errors[0]);
  EXPECT_EQ(back.settings.speeds.move.xy, 0.3);
  EXPECT_EQ(back.settings.speeds.move.z, 0.1 + 0.2);
  // A whole profile reads back as itself, every number exact.
  const SettingsLoad whole = parse_settings(settings_text(now), "us.toml");
  ASSERT_TRUE(whole.errors.empty()) << format(whole.errors[0]);
  EXPECT_EQ(settings_text(whole.settings), settings_text(now));
}

// ---- G-code nesting -----------------------------------------------------------------------

TEST(GcodeNesting, DeepBracketsAreALocatedErrorNotAStackOverflow) {
  const std::string deep = "G1 X" + std::string(33000, '[') + "1" + std::string(33000, ']');
  GcodeBlock block;
  Diagnostic error;
  const auto file = std::make_shared<const std::string>("deep.nc");
  EXPECT_FALSE(parse_gcode_block(deep, file, 3, &block, &error));
  EXPECT_EQ(error.loc.line, 3);
  EXPECT_EQ(error.loc.column, 5 + 200);  // the 201st '['
  EXPECT_NE(error.message.find("nested more than 200 deep"), std::string::npos) << error.message;
  for (const char* sign : {"-", "#"}) {
    const std::string chain = "G1 X" + std::string(50000, *sign) + "1";
    EXPECT_FALSE(parse_gcode_block(chain, file, 1, &block, &error)) << sign;
  }
  const std::string fine = "G1 X" + std::string(150, '[') + "1" + std::string(150, ']');
  EXPECT_TRUE(parse_gcode_block(fine, file, 1, &block, &error)) << error.message;
}

}  // namespace
}  // namespace gantry
