// gantry: the headless command line. run, check and moves over the same pipeline as the UI.
#include <fmt/format.h>  // output
#include <CLI/CLI.hpp>   // command-line parsing

#include <cctype>    // toupper
#include <cstdio>    // stdout, stderr
#include <iostream>  // JSON to stdout

#include "gantry/commands/command_docs.hpp"  // help text
#include "gantry/lang/parser.hpp"            // parse_file
#include "gantry/machine/job.hpp"            // run_job, check_program, interpret
#include "progress.hpp"                      // ProgressBar
#include "report.hpp"                        // RunReport, to_json, to_text
#include "sim/sim_card.hpp"                  // SimCard

namespace gantry {
namespace {

void print_errors(const std::vector<Diagnostic>& errors) {
  for (const Diagnostic& d : errors) fmt::print(stderr, "{}\n", format(d));
}

// Loads --settings, or the compiled-in default profile.
bool load_profile(const std::string& path, Settings& out) {
  SettingsLoad load = path.empty() ? parse_settings(default_profile_text(), "settings/default.toml")
                                   : load_settings_file(path);
  if (!load.ok()) {
    print_errors(load.errors);
    return false;
  }
  out = load.settings;
  return true;
}

struct RunArgs {
  std::string file, settings, card = "sim";
  bool json = false, realtime = false;
};

int cmd_run(const RunArgs& a) {
  Settings settings;
  RunReport report;
  Program program;
  if (!load_profile(a.settings, settings)) return 1;
  report.units = settings.units;
  program = parse_file(a.file);

  if (!a.json)
    fmt::print(stderr, "gantry: running {} on the simulated card, profile \"{}\"\n", a.file,
               settings.name);
  SimCard card(settings, a.realtime);
  JobResult job;
  {
    ProgressBar bar;
    JobOptions opt;
    if (bar.enabled() && !a.json) opt.progress = [&](size_t d, size_t t) { bar.update(d, t); };
    job = run_job(program, settings, card, opt);
  }
  report.errors = job.errors;
  report.lines = job.lines;
  report.moves = job.moves;
  report.commanded_steps = job.commanded_steps;
  report.planned_time_s = job.planned_time_s;
  report.steps = card.steps();
  for (int i = 0; i < kAxisCount; ++i)
    report.position[i] = static_cast<double>(card.steps()[i]) / settings.axes[i].steps_per_unit;
  report.time_s = card.time_s();
  report.timing_violations = card.timing_violations();
  for (const TimingViolation& v : card.first_violations())
    report.violation_notes.push_back(fmt::format("tick {} axis {}: {}", v.tick,
                                                 static_cast<char>(kAxisLetters[v.axis] - 32),
                                                 rule_name(v.rule)));
  report.max_velocity_ratio = card.kinematics().max_velocity_ratio();
  report.max_accel_ratio = card.kinematics().max_accel_ratio();

  print_errors(report.errors);
  if (a.json) {
    std::cout << to_json(report).dump() << "\n";
  } else {
    fmt::print("{}", to_text(report));
  }
  return report.errors.empty() && report.timing_violations == 0 ? 0 : 1;
}

int cmd_check(const std::string& file, const std::string& settings_path) {
  Settings settings;
  if (!load_profile(settings_path, settings)) return 1;
  const Program program = parse_file(file);
  const std::vector<Diagnostic> errors = check_program(program, settings);
  print_errors(errors);
  if (errors.empty()) fmt::print("{}: ok, {} statements\n", file, program.statements.size());
  return errors.empty() ? 0 : 1;
}

class PrintingSink : public MotionSink {
 public:
  explicit PrintingSink(bool jsonl) : jsonl_(jsonl) {}
  void move(const CanonMove& m) override {
    if (jsonl_)
      std::cout << to_json(m).dump() << "\n";
    else
      std::cout << to_text(m) << "\n";
  }
  void flush() override { std::cout.flush(); }

 private:
  bool jsonl_;
};

int cmd_moves(const std::string& file, const std::string& settings_path,
              const std::string& format) {
  Settings settings;
  if (!load_profile(settings_path, settings)) return 1;
  const Program program = parse_file(file);
  const std::vector<Diagnostic> errors = check_program(program, settings);
  if (!errors.empty()) {
    print_errors(errors);
    return 1;
  }
  PrintingSink sink(format == "jsonl");
  interpret(program, settings, sink);
  return 0;
}

int cmd_help(const std::string& code, bool markdown) {
  const CommandTable& table = CommandTable::standard();
  if (markdown) {
    fmt::print("{}", commands_markdown(table));
    return 0;
  }
  if (code.empty()) {
    fmt::print("{}", command_list(table));
    return 0;
  }
  std::string upper = code;
  for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  if (const CommandSpec* spec = table.find(upper)) {
    fmt::print("{}", command_help(*spec));
    return 0;
  }
  fmt::print(stderr, "error: unknown command '{}'; `gantry help` lists them all\n", code);
  return 1;
}

}  // namespace
}  // namespace gantry

int main(int argc, char** argv) {
  using namespace gantry;
  CLI::App app{
      "Gantry: an OpenSBP CNC controller. Runs part files on a step card or the "
      "simulated card."};
  app.set_version_flag("--version", std::string("gantry ") + GANTRY_VERSION);
  app.require_subcommand(1);

  RunArgs run;
  CLI::App* run_cmd = app.add_subcommand("run", "Run a part file on the card");
  run_cmd->add_option("file", run.file, "Part file (.sbp)")->required();
  run_cmd->add_option("--settings", run.settings, "Machine profile (TOML); default: built-in");
  run_cmd->add_option("--card", run.card, "Card to run on")
      ->check(CLI::IsMember({"sim"}))
      ->default_str("sim");
  run_cmd->add_flag("--json", run.json, "Print the report as one JSON object on stdout");
  run_cmd->add_flag("--realtime", run.realtime, "Play the simulated card in real time");

  std::string check_file, check_settings;
  CLI::App* check_cmd = app.add_subcommand("check", "Check a part file without motion");
  check_cmd->add_option("file", check_file, "Part file (.sbp)")->required();
  check_cmd->add_option("--settings", check_settings, "Machine profile (TOML)");

  std::string moves_file, moves_settings, moves_format = "text";
  CLI::App* moves_cmd = app.add_subcommand("moves", "Print the canonical moves of a part file");
  moves_cmd->add_option("file", moves_file, "Part file (.sbp)")->required();
  moves_cmd->add_option("--settings", moves_settings, "Machine profile (TOML)");
  moves_cmd->add_option("--format", moves_format, "text or jsonl")
      ->check(CLI::IsMember({"text", "jsonl"}));

  std::string help_code;
  bool help_markdown = false;
  CLI::App* help_cmd = app.add_subcommand("help", "List the commands, or describe one");
  help_cmd->add_option("code", help_code, "A two-letter command, such as MX");
  help_cmd->add_flag("--markdown", help_markdown, "Print the command reference (docs/commands.md)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 1;
  }
  try {
    if (*run_cmd) return cmd_run(run);
    if (*check_cmd) return cmd_check(check_file, check_settings);
    if (*moves_cmd) return cmd_moves(moves_file, moves_settings, moves_format);
    if (*help_cmd) return cmd_help(help_code, help_markdown);
  } catch (const GantryError& e) {
    fmt::print(stderr, "{}\n", e.what());
    return 1;
  }
  return 1;
}
