// Every code of the SB3 and FabMo references has a table entry (issue 6), and a code Gantry
// cannot honour yet says so by name and does nothing else.
#include <gtest/gtest.h>

#include <memory>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "gantry/commands/command_table.hpp"
#include "gantry/core/diagnostic.hpp"
#include "gantry/interp/interpreter.hpp"
#include "gantry/lang/script.hpp"
#include "gantry/motion/canon_move.hpp"
#include "gantry/settings/settings.hpp"

namespace gantry {
namespace {

// shared/spec/commands.md §1: the 125 distinct codes (SB3 entries, FabMo entries and index,
// and the codes only referenced: C3, VK, VV), written out here so the table cannot define them.
constexpr std::string_view kCodes[] = {
    "CA", "CC", "CG", "CP", "CR", "C3",                                            // Cuts
    "FC", "FE", "FG", "FP", "FS",                                                  // File
    "HA", "HB", "HC", "HE", "HN", "HQ", "HR", "HT", "HU", "HW",                    // Help
    "J2", "J3", "J4", "J5", "J6", "JA", "JB", "JC", "JH", "JS", "JX", "JY", "JZ",  // Jog
    "M2", "M3", "M4", "M5", "M6", "MA", "MB", "MC", "MD", "MH", "MI", "MN", "MO",  // Move
    "MS", "MX", "MY", "MZ",                                                        //
    "PX", "PY", "PZ", "PA", "PB", "PC", "P2", "P3", "P4", "P5", "P6",              // Probe
    "RA", "RI", "RP", "RR", "RS", "RZ",                                            // Record
    "SA", "SC", "SF", "SI", "SK", "SL", "SM", "SO", "SP", "SR", "ST", "SV", "SW",  // Settings
    "TC", "TD", "TF", "TH", "TI", "TS", "TT", "TU",                                // Tools
    "UD", "UI", "UL", "UN", "UR", "US", "UU", "UV", "UZ",                          // Utilities
    "VA", "VB", "VC", "VD", "VH", "VI", "VK", "VL", "VN", "VO", "VP", "VR", "VS",  // Values
    "VU", "VV",                                                                    //
    "Z2", "Z3", "Z4", "Z5", "Z6", "ZA", "ZB", "ZC", "ZT", "ZX", "ZY", "ZZ"};       // Zero

TEST(CommandCatalogue, TheListHas125DistinctCodes) {
  EXPECT_EQ(std::size(kCodes), 125u);
  EXPECT_EQ(std::set<std::string_view>(std::begin(kCodes), std::end(kCodes)).size(), 125u);
}

TEST(CommandCatalogue, EveryCodeOfTheReferencesHasATableEntry) {
  const CommandTable& table = CommandTable::standard();
  for (std::string_view code : kCodes) EXPECT_NE(table.find(code), nullptr) << code;
  // M0 is MO's other spelling (SB3: "either a numeric zero or the letter 'O'").
  EXPECT_NE(table.find("M0"), nullptr);
  EXPECT_EQ(table.all().size(), 126u);  // the 125 and M0, each once
}

TEST(CommandCatalogue, GroupsAreTheSpecs) {
  const CommandTable& table = CommandTable::standard();
  const std::pair<std::string_view, CommandGroup> sample[] = {
      {"CR", CommandGroup::Cuts},     {"FG", CommandGroup::File},     {"HW", CommandGroup::Help},
      {"JH", CommandGroup::Jog},      {"MD", CommandGroup::Move},     {"P3", CommandGroup::Probe},
      {"RR", CommandGroup::Record},   {"SW", CommandGroup::Settings}, {"TU", CommandGroup::Tools},
      {"UZ", CommandGroup::Utilities}};
  for (const auto& [code, group] : sample) {
    const CommandSpec* spec = table.find(code);
    ASSERT_NE(spec, nullptr) << code;
    EXPECT_EQ(group_name(spec->group), std::string(group_name(group))) << code;
  }
}

TEST(CommandCatalogue, EveryIncompleteEntrySaysWhatIsMissing) {
  for (const CommandSpec& s : CommandTable::standard().all()) {
    EXPECT_FALSE(s.name.empty()) << s.code;
    if (s.handler == CommandTable::standard().find("VR")->handler) {
      EXPECT_EQ(s.coverage, "not implemented") << s.code;
    }
  }
}

// ---- running one

class RecordingSink : public MotionSink {
 public:
  void move(const CanonMove& m) override { moves.push_back(m); }
  void flush() override {}
  std::vector<CanonMove> moves;
};

class CatalogueRunTest : public ::testing::Test {
 protected:
  Diagnostic run_error(std::string_view text) {
    script_ = Script::from_text(std::string(text), "part.sbp");
    try {
      if (!script_->ok()) throw GantryError(script_->errors().front());
      interp().run(script_);
    } catch (const GantryError& e) {
      return e.diagnostic();
    }
    ADD_FAILURE() << "no error from:\n" << text;
    return {};
  }
  std::vector<Diagnostic> check(std::string_view text) {
    script_ = Script::from_text(std::string(text), "part.sbp");
    return interp().check(script_);
  }
  Interpreter& interp() {
    if (!interp_) interp_.emplace(settings, sink, io, store);
    return *interp_;
  }

  Settings settings = default_settings();
  RecordingSink sink;
  std::string printed;
  ScriptedIO io{true, {}, &printed};
  PersistentStore store;

 private:
  std::shared_ptr<const Script> script_;
  std::optional<Interpreter> interp_;
};

TEST_F(CatalogueRunTest, ANotImplementedCodeIsNamedAtItsLineAndChangesNothing) {
  const ModalState before = interp().state();
  const Diagnostic d = run_error("SA\n  VR, .5, .5\nMX, 1\n");
  EXPECT_EQ(d.loc.line, 2);
  EXPECT_EQ(d.loc.column, 3);
  EXPECT_EQ(d.message,
            "VR (values for ramps) is not implemented yet in Gantry; the ramps come from "
            "[ramps] in the machine profile (docs/settings.md)");
  EXPECT_TRUE(sink.moves.empty());  // the file stopped there: MX never ran
  EXPECT_EQ(interp().state().position, before.position);
  EXPECT_EQ(interp().state().speeds.move.xy, before.speeds.move.xy);
}

TEST_F(CatalogueRunTest, TextParametersReachTheMessage) {
  // O/I/T is a word; the line still fails only because CR is not implemented.
  EXPECT_EQ(
      run_error("CR, 10, 5, O\n").message.rfind("CR (cut rectangle) is not implemented yet", 0),
      0u);
  EXPECT_EQ(run_error("M0\n").message.rfind("M0 (motors off", 0), 0u);
}

TEST_F(CatalogueRunTest, CheckCountsEachSuchLineAndEveryOtherError) {
  const std::vector<Diagnostic> errors = check("MX, 1\nVC, .25\nQQ\nTD\nMY, 2\n");
  ASSERT_EQ(errors.size(), 3u);
  EXPECT_EQ(errors[0].loc.line, 2);
  EXPECT_EQ(errors[0].message.rfind("VC (values for the cutter) is not implemented yet", 0), 0u);
  EXPECT_EQ(errors[1].loc.line, 3);
  EXPECT_EQ(errors[1].message.rfind("unknown command 'QQ'", 0), 0u);
  EXPECT_EQ(errors[2].loc.line, 4);
  EXPECT_EQ(errors[2].message.rfind("TD (tools: drill press) is not implemented yet", 0), 0u);
  EXPECT_EQ(sink.moves.size(), 2u);  // the good lines still ran dry
}

}  // namespace
}  // namespace gantry
