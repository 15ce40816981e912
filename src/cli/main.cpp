// gantry: the headless command line. run, check and moves over the same pipeline as the UI.
#include <fmt/format.h>  // output
#include <CLI/CLI.hpp>   // command-line parsing

#include <algorithm>   // clamp
#include <cctype>      // tolower
#include <charconv>    // from_chars
#include <cstdio>      // stdout, stderr
#include <filesystem>  // exists
#include <iostream>    // JSON to stdout
#include <optional>
#include <set>

#include "console.hpp"       // the console subcommand
#include "export_gcode.hpp"  // GcodeWriter
#include "import_wincnc.hpp"  // gantry import-wincnc
#ifdef GANTRY_HAVE_GUI
#include "gui_command.hpp"  // the gui subcommand (ui/)
#endif
#include "gantry/commands/command_docs.hpp"  // help text
#include "gantry/core/any_bytes.hpp"         // json_text
#include "gantry/core/text.hpp"              // upper, lower
#include "gantry/core/text_file.hpp"         // read_text_file
#include "gantry/lang/fm.hpp"                // fm_command_list: `gantry help fm`
#include "gantry/lang/script.hpp"            // Script
#include "gantry/interp/interpreter_options.hpp"  // the macro folders help looks in
#include "gantry/machine/job.hpp"            // run_job, check_program, interpret
#include "gantry/motion/cycle_timer.hpp"     // estimate
#include "gantry/session/machine_memory.hpp"  // MachineMemory: the state kept across sessions
#include "gantry/session/run_log.hpp"         // RunLogger, the part-file log; gantry log
#include "gantry/settings/values_file.hpp"   // the values file
#include "gantry/session/open_card.hpp"       // open_card
#include "machine_profile.hpp"               // MachineProfile, load_machine_profile
#include "preview_command.hpp"               // PreviewArgs, run_preview
#include "man_page.hpp"                      // man_page
#include "progress.hpp"                      // StatusLine
#include "report.hpp"                        // RunReport, to_json, to_text
#include "signal_watch.hpp"                  // SignalWatch
#include "sim/sim_card.hpp"                  // SimCard
#include "svg.hpp"                           // moves_svg
#include "terminal_io.hpp"                   // TerminalIO

#include <unistd.h>  // isatty

namespace gantry {
namespace {

using session::CardChoice;
using session::open_card;
using session::plays_in_real_time;

void print_errors(const std::vector<Diagnostic>& errors) {  // and warnings
  for (const Diagnostic& d : errors) fmt::print(stderr, "{}\n", format(d));
}

// A check's errors and warnings, then the errors beyond its cap in one line.
void print_errors(const DiagnosticLog& found) {
  print_errors(found.kept());
  if (const std::string s = found.summary(); !s.empty()) fmt::print(stderr, "gantry: {}\n", s);
}

// The line of the top-level file where a check stopped short.
int top_line(const Diagnostic& d) {
  return d.via.empty() ? d.loc.line : d.via.front().line;
}

// UV, UD and UR show or load the profile and say where it and the values live; the folders
// part files may reach besides their own are the profile's and --allow-path's.
void describe(const MachineProfile& p, const std::vector<std::string>& allow_paths,
              InterpreterOptions& o) {
  o.allowed_folders = allowed_folders(p, allow_paths);
  o.profile = &p.bare;
  o.profile_path = p.path;
  o.values_path = p.values_path;
  o.profile_name = p.name;
}

// With nobody at the simulated machine: what its events and switches do to an input while
// the tool rests (PAUSE UNTIL). `sim`: the live card, which knows which events are still to
// come; a check (`check_at` given) counts every event, and the switches where the tool is.
std::function<bool(int, bool, const std::optional<Vec6>&)> unattended_inputs(
    const SimWorld& world, const InputSettings& bits, const SimCard* sim = nullptr) {
  return [world, bits, sim](int n, bool closed, const std::optional<Vec6>& check_at) {
    const int bit = bits.switch_bits[static_cast<size_t>(n - 1)];
    if (!check_at && sim) return sim->input_may_change(bit, closed);
    return world.can_set(bit, closed, bits, 0, check_at);
  };
}

struct RunArgs {
  std::string file, profile, card;  // card: empty = the profile's
  bool json = false, realtime = false;
  bool step = false;                         // --step: Friendly Motion starts in STEP mode
  std::string trace;                         // --trace FILE: the simulated card's pin trace
  std::optional<double> estop_at, stall_at;  // simulated operator and producer
  std::optional<double> probe_z;
  std::vector<std::string> limits;      // AXIS-=POS or AXIS+=POS: simulated limit switches
  std::vector<std::string> sim_inputs;  // N=S@SECONDS or N=S@AXIS>=POS / AXIS<=POS

  // The simulated machine's switches and events: the profile's ([simulator]) and the options';
  // false (after saying why) on a bad --sim-limit or --sim-input.
  bool world(SimWorld& w, const Settings& settings) const {
    w = simulated_world(settings);
    w.estop_at_s = estop_at;
    w.stall_at_s = stall_at;
    if (probe_z) w.probe_z = probe_z;
    for (const std::string& e : sim_inputs)
      if (!add_sim_input(e, settings.inputs, w)) return false;
    for (const std::string& l : limits) {
      const size_t eq = l.find('=');
      const std::string axes = "xyzabc";
      const size_t axis =
          l.empty() ? std::string::npos : axes.find(static_cast<char>(std::tolower(l[0])));
      double pos = 0;
      const bool ok = eq == 2 && axis != std::string::npos && (l[1] == '-' || l[1] == '+') &&
                      std::from_chars(l.data() + 3, l.data() + l.size(), pos).ec == std::errc{};
      if (!ok) {
        fmt::print(stderr, "error: --sim-limit {} must be AXIS-=POS or AXIS+=POS, e.g. x+=23.5\n",
                   l);
        return false;
      }
      (l[1] == '-' ? w.min_switch : w.max_switch)[axis] = pos;
    }
    return true;
  }

  // --sim-input N=S@SECONDS (input switch N reads S from that machine time on) or
  // N=S@AXIS>=POS / AXIS<=POS (it reads S while the axis is there, the other level elsewhere).
  static bool add_sim_input(const std::string& e, const InputSettings& bits, SimWorld& w) {
    auto bad = [&](const std::string& why) {
      fmt::print(stderr,
                 "error: --sim-input {}: {}; write N=S@SECONDS (input switch N, 1-12, reads S, 0 "
                 "or 1, from that machine time on) or N=S@AXIS>=POS / N=S@AXIS<=POS (while the "
                 "axis is there), e.g. --sim-input 5=1@2.5 or --sim-input 3=1@x<=0\n",
                 e, why);
      return false;
    };
    const size_t eq = e.find('='), at = e.find('@');
    int n = 0, level = 0;
    if (eq == std::string::npos || at != eq + 2 ||
        std::from_chars(e.data(), e.data() + eq, n).ptr != e.data() + eq ||
        std::from_chars(e.data() + eq + 1, e.data() + at, level).ptr != e.data() + at)
      return bad("not of that form");
    if (n < 1 || n > 12) return bad(fmt::format("there is no input switch {}", n));
    if (level != 0 && level != 1) return bad("the state is 0 (open) or 1 (closed)");
    const int bit = bits.switch_bits[static_cast<size_t>(n - 1)];
    if (bit < 0)
      return bad(
          fmt::format("input switch {} is not wired in this profile (inputs.switch_bits)", n));
    const std::string when = e.substr(at + 1);
    const char* end = when.data() + when.size();
    const size_t axis = when.empty() ? std::string::npos
                                     : std::string("xyzabc").find(static_cast<char>(
                                           std::tolower(static_cast<unsigned char>(when[0]))));
    double value = 0;
    if (axis != std::string::npos) {
      const bool above = when.compare(1, 2, ">=") == 0;
      if (!above && when.compare(1, 2, "<=") != 0) return bad("the position needs >= or <=");
      if (std::from_chars(when.data() + 3, end, value).ptr != end) return bad("not a position");
      w.position_inputs.push_back({bit, level == 1, static_cast<int>(axis), value, above});
      return true;
    }
    if (std::from_chars(when.data(), end, value).ptr != end || value < 0)
      return bad("not a machine time in seconds");
    w.input_events.push_back({value, bit, level == 1});
    std::stable_sort(
        w.input_events.begin(), w.input_events.end(),
        [](const SimInputEvent& a, const SimInputEvent& b) { return a.at_s < b.at_s; });
    return true;
  }
};

// Options every command that interprets a file shares.
struct LanguageArgs {
  bool yes = false;
  bool allow_shell = false;
  std::vector<std::string> inputs;  // NAME=VALUE
  std::string macros;
  std::vector<std::string> subroutines;  // --subroutines: where o<name> call finds name.ngc
  std::vector<std::string> allow_paths;  // --allow-path: folders part files may reach
  std::string persistent;  // file of $variables; default in the user's config directory
  std::string values;      // the values file; default in the user's config directory
  std::string tool_table;  // --tool-table: G-code's tool table instead of the profile's
  std::size_t budget = 10'000'000;
  std::size_t max_errors = 100;
  double feed_override = 100;  // percent
  int from_line = 0;           // run and moves: the first line to run (0: all)
  std::string language;        // --language: sbp, gcode or fm ("": by the file's name)

  void add_to(CLI::App* cmd) {
    cmd->add_option("--language", language,
                    "Read the file as sbp (OpenSBP), gcode or fm (Friendly Motion) whatever its "
                    "name (default: by its extension and first line)");
    cmd->add_flag("--yes", yes, "Continue every PAUSE and press each MSGBOX's default button");
    cmd->add_option("--input", inputs, "Answer INPUT for a variable: --input '&DEPTH=0.5'");
    cmd->add_flag("--allow-shell", allow_shell, "Let SHELL start programs");
    cmd->add_option("--macros", macros,
                    "Folder C<n> looks in first for C<n>.sbp / macro_<n>.sbp (then the shipped "
                    "macros)");
    add_subroutines_option(cmd, subroutines);
    add_allow_path_option(cmd, allow_paths);
    add_tool_table_option(cmd, tool_table);
    cmd->add_option("--persistent", persistent, "File of persistent $variables (JSON)");
    cmd->add_option("--values", values,
                    "File of the V commands' values (TOML); default: the profile's in "
                    "~/.config/gantry/values");
    cmd->add_option("--budget", budget,
                    "Statements the check may run beyond the file's own lines before it "
                    "calls the file an endless loop, an error (default 10,000,000; 0: no "
                    "limit)");
    cmd->add_option("--max-errors", max_errors,
                    "Stop checking after this many errors and count the rest by kind in one "
                    "line (default 100; 0: no limit)");
  }

  // Options for the job; false (after printing why) when an --input is malformed.
  bool job_options(const Settings& settings, JobOptions& out) const {
    out.interpreter.allow_shell = allow_shell;
    out.interpreter.macro_dir = macros;
    out.interpreter.subroutine_dirs = subroutines;  // the Interpreter adds the profile's after
    out.interpreter.trig_in_degrees = out.interpreter.plus_joins_text =
        settings.dialect == Dialect::FabMo;
    out.check_budget = budget;
    out.max_errors = max_errors;
    out.feed_override = feed_override / 100;
    // The profile's bounds (feed_override.min, max), as the live override keeps to them; the
    // default, 100 %, is taken to the nearer bound when they leave it out.
    const double lo = settings.feed_override.min, hi = settings.feed_override.max;
    if (feed_override == 100 && (feed_override < lo || feed_override > hi))
      out.feed_override = std::clamp(feed_override, lo, hi) / 100;
    else if (feed_override < lo || feed_override > hi) {
      fmt::print(stderr,
                 "error: --feed-override {} is outside the profile's feed override bounds, {} % "
                 "to {} % (feed_override.min, max)\n",
                 feed_override, settings.feed_override.min, settings.feed_override.max);
      return false;
    }
    out.yes = yes;
    out.interpreter.start_line = from_line;
    if (!language.empty()) {
      out.interpreter.language = language_named(language);
      if (!out.interpreter.language) {
        fmt::print(stderr, "error: --language {} is not sbp, gcode or fm\n", language);
        return false;
      }
    }
    for (const std::string& kv : inputs) {
      const size_t eq = kv.find('=');
      if (eq == std::string::npos || eq == 0) {
        fmt::print(stderr, "error: --input {} must be NAME=VALUE, e.g. --input '&DEPTH=0.5'\n", kv);
        return false;
      }
      std::string name = ascii::upper(kv.substr(0, eq));
      if (name[0] != '&' && name[0] != '$') name = "&" + name;
      out.inputs[name] = kv.substr(eq + 1);
    }
    return true;
  }

  PersistentStore store() const {
    return PersistentStore(persistent.empty() ? PersistentStore::default_path() : persistent);
  }
};

// What the commands that read a part file share: the profile, the job's options and the
// file, checked (every statement run dry). Filled in place: `opt` points into `profile`.
struct CheckedFile {
  MachineProfile profile;
  JobOptions opt;
  std::shared_ptr<const Script> script;
  DiagnosticLog found;  // errors and warnings
  double estimate_s = 0;
};

// A part file as every command loads it: the load pass reports unknown commands too.
std::shared_ptr<const Script> load_part_file(const std::string& file,
                                             std::optional<Language> language) {
  return Script::load(file, CommandTable::standard().is_command(), language);
}

// False (after saying why) when the profile or an --input is malformed. `estimate`: the
// check also plans the motion and gives the cycle time, as the preview does: an operator
// answers at the run (a wait for them counts no time) and an INPUT takes its default.
// Nobody is at a check: on the simulated card, its machine answers PAUSE UNTIL or nothing does.
// `control`: stops the check from another thread (a signal).
bool load_and_check(const std::string& file, const std::string& settings_path,
                    const LanguageArgs& lang, CheckedFile& out, bool estimate = false,
                    RunControl* control = nullptr) {
  if (!load_machine_profile(settings_path, lang.values, out.profile, lang.tool_table)) return false;
  if (!lang.job_options(out.profile.settings, out.opt)) return false;
  describe(out.profile, lang.allow_paths, out.opt.interpreter);
  const Settings& settings = out.profile.settings;
  if (settings.card.type == "sim")
    out.opt.interpreter.unattended_inputs =
        unattended_inputs(simulated_world(settings), settings.inputs);
  if (estimate) out.opt.input_defaults = true;  // --input still answers first
  if (control) out.opt.stop = &control->stopped();
  out.script = load_part_file(file, out.opt.interpreter.language);
  std::optional<CycleTimer> timer;
  JobOptions check = out.opt;
  if (estimate) check.check_moves = &timer.emplace(settings, check.feed_override, check.check_moves);
  out.found = check_program(out.script, settings, lang.store(), check);
  if (timer) out.estimate_s = timer->seconds();
  return true;
}

int cmd_run(const RunArgs& a, const LanguageArgs& lang) {
  MachineProfile profile;
  RunReport report;
  if (!load_machine_profile(a.profile, lang.values, profile, lang.tool_table)) return 1;
  const Settings& settings = profile.settings;
  JobOptions opt;
  if (!lang.job_options(settings, opt)) return 1;
  describe(profile, lang.allow_paths, opt.interpreter);
  PersistentStore store = lang.store();
  report.units = settings.units;
  report.axis_names = axis_names(settings);
  std::shared_ptr<const Script> script = load_part_file(a.file, opt.interpreter.language);
  if (a.step && !script->fm()) {
    fmt::print(stderr,
               "error: --step is Friendly Motion's STEP mode, and {} is not a Friendly Motion "
               "program (the console's STEP single-steps OpenSBP and G-code)\n",
               a.file);
    return 1;
  }
  opt.interpreter.fm_step = a.step;
  // A person at a terminal answers the file's questions, unless --yes/--input do. With
  // --json, stdout holds only the report: PRINT goes to stderr.
  std::FILE* const print_to = a.json ? stderr : stdout;
  ScriptedIO scripted(lang.yes, opt.inputs, nullptr, print_to);
  TerminalIO terminal(opt.inputs, print_to);
  const bool interactive = !lang.yes && isatty(STDIN_FILENO) && isatty(STDERR_FILENO);
  opt.operator_present = interactive;
  OperatorIO& io = interactive ? static_cast<OperatorIO&>(terminal) : scripted;

  CardChoice choice;
  choice.type = a.card.empty() ? settings.card.type : a.card;
  choice.realtime = a.realtime;
  choice.trace = a.trace;
  opt.interpreter.warn_before_motion = plays_in_real_time(choice.type, choice.realtime);
  if (!a.world(choice.world, settings)) return 1;
  std::string why;
  const std::unique_ptr<Card> card = open_card(choice, settings, &why);
  if (!card) {
    fmt::print(stderr, "error: cannot open the {} card: {}\n", choice.type, why);
    return 1;
  }
  auto* sim = dynamic_cast<SimCard*>(card.get());  // the simulated card reports more
  // Nobody at the simulated machine: its events and switches answer PAUSE UNTIL, or nothing.
  if (sim && !interactive)
    opt.interpreter.unattended_inputs = unattended_inputs(choice.world, settings.inputs, sim);
  // The position, zero and units the last session left (docs/machine_state.md), and the
  // part-file log (VD), both next to the values file: on a live machine only (a real card,
  // or the simulated one in real time). A run in virtual time is an off-machine check of the
  // file, the same from the same inputs: it neither starts where another left nor is logged.
  const bool live = opt.interpreter.warn_before_motion;
  session::MachineMemory memory(session::machine_state_path(profile.values_path));
  if (live)
    if (const std::string said = memory.load(settings.units); !memory.first_start())
      fmt::print(stderr, "gantry: {}\n", said);
  ModalState restored;  // the check starts from it too
  restored.speeds = settings.speeds;
  const Vec6 start_table = memory.state().table;  // the card counts from here (0: a fresh start)
  if (live && memory.restoring()) {
    memory.restore(restored, Vec6::Zero());  // the card counts from 0
    opt.start_state = &restored;
  }
  session::RunLogger part_log(session::run_log_path(profile.values_path));
  if (const session::SavedMachine last = memory.state(); live)
    part_log.close_unfinished(&last);  // runs a kill cut short get their end line
  const bool logging = settings.display.part_file_log;
  std::function<void(Controller&)> keep;
  if (live)
    keep = [&](Controller& c) {
      memory.attach(c, [&](const Controller::Activity& act) {
        if (logging) part_log.activity(act);
      });
    };
  if (!a.json)
    fmt::print(stderr, "gantry: running {} on the {} card, profile \"{}\"\n", a.file,
               sim ? "simulated" : choice.type, settings.name);
  JobResult job;
  int stops = 0;  // the operator's: 1 a stop, 2 or more an E-stop
  {
    // At a terminal, a progress line under the file's output; its questions and PRINT text
    // clear it and it comes back after them.
    StatusLine line(stderr);
    const bool show_progress = line.enabled() && !a.json;
    StatusLineIO around_line(io, line);
    std::function<void(const ControllerStatus&)> watch;
    if (show_progress)
      watch = [&](const ControllerStatus& st) { line.show(progress_line(session::run_progress(st))); };
    opt.profile = &profile.bare;
    opt.values_path = profile.values_path;
    // Ctrl-C (or SIGTERM, a closed terminal) stops the run in order: the check before it
    // ends at its next statement and nothing moves, or the tool ramps down along the path,
    // a question waiting at the terminal ends, and the report says where the tool is. A
    // second one E-stops. Blocked before the controller's threads start.
    RunControl control;
    SignalWatch signals;
    signals.start([&](int sig) {
      fmt::print(stderr, "\ngantry: signal {}: stopping the run{}\n", sig,
                 control.stop() ? " (again: E-stop)" : ": E-stop");
      terminal.cancel();
    });
    struct StopFirst {  // the watcher ends before the controller it stops
      SignalWatch& w;
      ~StopFirst() { w.stop(); }
    } stop_first{signals};
    job = run_job(script, settings, *card, show_progress ? around_line : io, store, opt, &control,
                  watch, keep);
    stops = control.stops();
  }
  if (std::string why; live && !memory.save(&why))  // at exit
    fmt::print(stderr, "gantry: cannot save the machine state to {}: {}\n", memory.path(), why);
  if (const std::string why = part_log.failure(); !why.empty())
    fmt::print(stderr, "gantry: cannot append to the part-file log {}: {}\n", part_log.path(), why);
  for (const Diagnostic& w : job.warnings) fmt::print(stderr, "{}\n", format(w));
  for (const Diagnostic& w : scripted.warnings()) fmt::print(stderr, "{}\n", format(w));
  report.errors = job.errors;
  report.error_summary = job.error_summary;
  report.check_stopped = job.check_stopped;
  report.lines = job.lines;
  report.moves = job.moves;
  report.cut = job.cut;
  report.stopped_by = stops == 0 ? "none" : stops == 1 ? "stop" : "E-stop";
  report.commanded_steps = job.commanded_steps;
  report.played_steps = job.played_steps;
  report.fault = job.fault == CardFault::None ? "none" : fault_name(job.fault);
  // The operator's E-stop stopped the pulses at once, as the card's own would.
  if (stops > 1 && job.cut && job.fault == CardFault::None) report.fault = "E-stop";
  report.planned_time_s = job.planned_time_s;
  report.estimated_time_s = job.estimated_time_s;
  // A real card counts nothing itself: its steps are the generator's count of those played.
  report.steps = sim ? sim->steps() : job.played_steps;
  // In the calibration and units the run left in force (VU, VD may have changed them).
  report.units = job.settings.units;
  // The load's position (the card's count is the motors': backlash takeup, slaved channels),
  // a rotary axis with a wrap modulo it.
  for (int i = 0; i < kAxisCount; ++i)
    report.position[i] = reported_position(
        job.settings.axes[i],
        start_table[i] + static_cast<double>(job.played_steps[i]) / job.settings.axes[i].steps_per_unit);
  report.time_s = static_cast<double>(card->ticks_played()) / settings.card.pacer_hz();
  if (sim) add_card_checks(report, *sim);
  if (sim && choice.realtime && !a.json)  // how the feeder kept up (bench/soak.sh reads it)
    if (const SimCard::FeedFigures f = sim->feed_figures(); f.blocks > 0)
      fmt::print(stderr,
                 "gantry: real time: lead {:.0f} ms; {} blocks; the card's queue held at least "
                 "{:.2f} ms; the feeder's worst lateness {:.2f} ms\n",
                 job.lead_s * 1e3, f.blocks, f.least_queue_s * 1e3, f.worst_late_s * 1e3);
  if (sim && choice.realtime && !a.json)  // where the worst lateness came from (issue 26)
    fmt::print(stderr,
               "gantry: real time: feeder {}; worst block: woke {:.2f} ms late, waited {:.2f} ms "
               "for moves, {:.2f} ms generating; latest wake-up {:.2f} ms; lead grew {} times; "
               "{} blocks released early (no move in time)\n",
               job.feeder_realtime ? "SCHED_FIFO, memory locked" : "not real-time",
               job.lead.worst_woke_late_s * 1e3, job.lead.worst_starved_s * 1e3,
               job.lead.worst_work_s * 1e3, job.lead.most_woke_late_s * 1e3, job.lead.grown,
               job.starved_releases);

  print_errors(report.errors);
  if (!report.error_summary.empty()) fmt::print(stderr, "gantry: {}\n", report.error_summary);
  if (a.json) {
    std::cout << json_text(to_json(report)) << "\n";
  } else {
    fmt::print("{}", to_text(report));
  }
  return exit_code(report);
}

// Exit status: 0 the whole file checked without an error, 1 errors (a stop by a signal
// included), 2 no error but the check stopped short (an INPUT it cannot answer, the budget).
int cmd_check(const std::string& file, const std::string& settings_path, const LanguageArgs& lang) {
  CheckedFile c;
  // Ctrl-C or SIGTERM ends the check at its next statement, with what it found so far.
  RunControl control;
  SignalWatch signals;
  signals.start([&](int sig) {
    fmt::print(stderr, "\ngantry: signal {}: stopping the check\n", sig);
    control.stop();
  });
  const bool loaded = load_and_check(file, settings_path, lang, c, false, &control);
  signals.stop();
  if (!loaded) return 1;
  print_errors(c.found);
  if (c.found.has_errors()) return 1;
  if (const std::optional<Diagnostic>& why = c.found.stopped_short()) {
    fmt::print(
        "{}: NOT fully checked: the check stopped at line {} of {} (see above); the "
        "lines after it were not checked\n",
        file, top_line(*why), c.script->line_count());
    return 2;
  }
  fmt::print("{}: ok, {} lines\n", file, c.script->line_count());
  return 0;
}

// The cycle time of a file, from the same check and planner a run uses.
int cmd_estimate(const std::string& file, const std::string& settings_path, bool json,
                 const LanguageArgs& lang) {
  CheckedFile c;
  if (!load_and_check(file, settings_path, lang, c, /*estimate=*/true)) return 1;
  print_errors(c.found);
  if (c.found.has_errors()) return 1;
  const double seconds = c.estimate_s;
  const char* mode = planner_mode_name(c.profile.settings.planner.mode);
  if (json) {
    nlohmann::ordered_json j;
    j["file"] = file;
    j["planner"] = mode;
    j["estimated_time_s"] = seconds;
    std::cout << json_text(j) << "\n";
  } else {
    const long whole = static_cast<long>(seconds);
    fmt::print("{}: {}:{:02}:{:06.3f} ({:.3f} s) with the {} planner\n", file, whole / 3600,
               whole / 60 % 60, seconds - static_cast<double>(whole - whole % 60), seconds, mode);
  }
  return 0;
}

class PrintingSink : public MotionSink {
 public:
  explicit PrintingSink(bool jsonl) : jsonl_(jsonl) {}
  void move(const CanonMove& m) override {
    if (jsonl_)
      std::cout << json_text(to_json(m)) << "\n";
    else
      std::cout << to_text(m) << "\n";
  }
  void flush() override { std::cout.flush(); }

 private:
  bool jsonl_;
};

// Keeps the moves, for the SVG view.
class KeepingSink : public MotionSink {
 public:
  void move(const CanonMove& m) override { moves.push_back(m); }
  void flush() override {}
  std::vector<CanonMove> moves;
};

int cmd_moves(const std::string& file, const std::string& settings_path, const std::string& format,
              const std::string& svg, const LanguageArgs& lang) {
  CheckedFile c;
  if (!load_and_check(file, settings_path, lang, c)) return 1;
  if (c.found.has_errors()) {
    print_errors(c.found);
    return 1;
  }
  const Settings& settings = c.profile.settings;
  const std::shared_ptr<const Script>& script = c.script;
  JobOptions& opt = c.opt;
  // Moves are a preview: PRINT output and operator questions are answered as in a check.
  PrintingSink sink(format == "jsonl");
  std::string printed;
  ScriptedIO io(true, opt.inputs, &printed);
  opt.interpreter.dry_run = true;
  PersistentStore preview = lang.store().scratch_copy();  // a preview saves nothing
  // --svg: a picture instead of the list.
  if (!svg.empty()) {
    KeepingSink kept;
    interpret(script, settings, kept, io, preview, opt);
    if (!write_file_atomically(svg, moves_svg(kept.moves, settings))) {
      fmt::print(stderr, "error: cannot write {}\n", svg);
      return 1;
    }
    return 0;
  }
  interpret(script, settings, sink, io, preview, opt);
  return 0;
}

// A program's canonical moves as G-code (docs/gcode.md, "Exporting"): checked first, as
// `moves` does; the file is written only when the whole program ran.
int cmd_export_gcode(const std::string& file, const std::string& out_path,
                     const std::string& settings_path, const LanguageArgs& lang) {
  CheckedFile c;
  if (!load_and_check(file, settings_path, lang, c)) return 1;
  print_errors(c.found);
  if (c.found.has_errors()) return 1;
  GcodeWriter writer(c.profile.settings, std::filesystem::path(file).filename().string());
  std::string printed;
  ScriptedIO io(true, c.opt.inputs, &printed);
  c.opt.interpreter.dry_run = true;
  PersistentStore preview = lang.store().scratch_copy();  // an export saves nothing
  interpret(c.script, c.profile.settings, writer, io, preview, c.opt);
  const std::string text = writer.finish();
  if (out_path.empty()) {
    std::cout << text;
    return 0;
  }
  if (!write_file_atomically(out_path, text)) {
    fmt::print(stderr, "error: cannot write {}\n", out_path);
    return 1;
  }
  return 0;
}

// The toolpath drawn to a picture, with its bounds, estimate and violations.
int cmd_preview(const PreviewArgs& args, const LanguageArgs& lang) {
  MachineProfile profile;
  if (!load_machine_profile(args.settings, lang.values, profile, lang.tool_table)) return 1;
  JobOptions opt;
  if (!lang.job_options(profile.settings, opt)) return 1;
  opt.input_defaults = true;  // a preview goes on past INPUT (--input still answers first)
  describe(profile, lang.allow_paths, opt.interpreter);
  return run_preview(args, profile.settings, opt, lang.store());
}

// The command table, whole or one menu group, as text or JSON (for scripts and front ends).
int cmd_commands(const std::string& group, bool json) {
  const CommandTable& table = CommandTable::standard();
  const auto lower = [](std::string_view t) { return ascii::lower(t); };
  std::vector<const CommandSpec*> chosen;
  std::set<std::string> groups;
  for (const CommandSpec& s : table.all()) {
    groups.insert(group_name(s.group));
    if (group.empty() || lower(group_name(s.group)) == lower(group)) chosen.push_back(&s);
  }
  if (chosen.empty()) {
    std::string names;
    for (const std::string& g : groups) names += (names.empty() ? "" : ", ") + g;
    fmt::print(stderr, "error: no command group '{}'; the groups are {}\n", group, names);
    return 1;
  }
  if (!json) {
    for (const CommandSpec* s : chosen)
      fmt::print("{}  {:<10} {}{}\n", s->code, group_name(s->group), s->name,
                 s->coverage.empty() ? "" : fmt::format(" [{}]", s->coverage));
    return 0;
  }
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const CommandSpec* s : chosen) out.push_back(to_json(*s));
  std::cout << json_text(out) << "\n";
  return 0;
}

int cmd_help(const std::string& code, bool markdown) {
  const CommandTable& table = CommandTable::standard();
  if (ascii::lower(code) == "fm" || ascii::lower(code) == "friendlymotion") {
    // the third language's own table (docs/friendlymotion.md's, with --markdown)
    fmt::print("{}", markdown ? fm_commands_markdown() : fm_command_list());
    return 0;
  }
  if (markdown) {
    fmt::print("{}", commands_markdown(table));
    return 0;
  }
  if (code.empty()) {
    fmt::print("{}", command_list(table));
    return 0;
  }
  const InterpreterOptions defaults;  // the folders a part file's C<n> looks in, --macros aside
  if (const std::optional<std::string> help = help_topic(
          code, {defaults.user_macro_dir, defaults.shipped_macro_dir})) {
    fmt::print("{}", *help);
    return 0;
  }
  fmt::print(stderr, "error: unknown command '{}': no command, statement or custom cut is called so; `gantry help` lists them all\n", code);
  return 1;
}

// The part-file log (VD): the last runs, oldest first (docs/machine_state.md).
int cmd_log(const std::string& profile_arg, const std::string& values, std::size_t last,
            bool json) {
  MachineProfile profile;
  if (!load_machine_profile(profile_arg, values, profile)) return 1;
  const std::string path = session::run_log_path(profile.values_path);
  std::size_t bad = 0;
  const std::vector<session::RunRecord> runs = session::read_run_log(path, last, &bad);
  if (json) {
    nlohmann::ordered_json out = nlohmann::ordered_json::array();
    for (const session::RunRecord& r : runs)
      out.push_back(nlohmann::ordered_json::parse(session::run_record_line(r)));
    std::cout << json_text(out) << "\n";
  } else if (runs.empty()) {
    fmt::print("no part file runs logged in {}\n", path);
  } else {
    for (const session::RunRecord& r : runs) fmt::print("{}\n", session::run_record_text(r));
  }
  if (bad)
    fmt::print(stderr, "gantry: {} line{} of {} {} not a run record (skipped)\n", bad,
               bad == 1 ? "" : "s", path, bad == 1 ? "is" : "are");
  return 0;
}

// The machine state kept across sessions; --confirm: the operator vouches for the position.
int cmd_state(const std::string& profile_arg, const std::string& values, bool confirm) {
  MachineProfile profile;
  if (!load_machine_profile(profile_arg, values, profile)) return 1;
  session::MachineMemory memory(session::machine_state_path(profile.values_path));
  fmt::print("{}\n", memory.load(profile.settings.units));
  if (!confirm) return 0;
  if (!memory.restoring()) {
    fmt::print(stderr, "error: no position to confirm in {}\n", memory.path());
    return 1;
  }
  memory.confirm();
  fmt::print("the position is confirmed in {}\n", memory.path());
  return 0;
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
  run_cmd->add_option("file", run.file, "Part file (.sbp, or G-code: .nc .tap .gcode .ngc)")
      ->required();
  add_profile_option(run_cmd, run.profile);
  run_cmd->add_option("--card", run.card, "Card to run on (default: the profile's card.type)")
      ->check(CLI::IsMember({"sim", "pci7200", "gpiod"}));
  run_cmd->add_flag("--json", run.json, "Print the report as one JSON object on stdout");
  run_cmd->add_flag("--realtime", run.realtime, "Play the simulated card in real time");
  run_cmd->add_flag("--step", run.step,
                    "A Friendly Motion program starts in STEP mode: the operator starts each "
                    "line (Step), or runs on (Auto), as after an M0");
  run_cmd->add_option("--trace", run.trace, "Write the simulated card's pin trace to FILE");
  run_cmd->add_option("--sim-estop-at", run.estop_at, "Simulate E-stop at this machine time, s");
  run_cmd->add_option("--sim-stall-at", run.stall_at,
                      "Simulate the pulse producer stalling at this machine time, s");
  run_cmd->add_option("--sim-limit", run.limits,
                      "Simulate a limit switch: AXIS-=POS (low side) or AXIS+=POS (high side)");
  run_cmd->add_option(
      "--sim-probe-z", run.probe_z,
      "Simulate a probe surface at this Z (default: the profile's simulator.plate_z)");
  run_cmd->add_option("--sim-input", run.sim_inputs,
                      "Simulate input switch N reading S: N=S@SECONDS from that machine time on, "
                      "or N=S@AXIS>=POS / AXIS<=POS while the axis is there");
  LanguageArgs run_lang, check_lang, moves_lang;
  run_lang.add_to(run_cmd);
  run_cmd
      ->add_option("--from-line", run_lang.from_line,
                   "Start at this line: the lines before it set modes, values and the location "
                   "without moving, then the tool goes there by Safe-Z")
      ->check(CLI::Range(1, 1'000'000'000));
  run_cmd
      ->add_option("--feed-override", run_lang.feed_override,
                   "Percent of the file's speeds (within the profile's feed_override.min and max)")
      ->check(CLI::Range(1.0, 200.0));

  std::string check_file, check_settings;
  CLI::App* check_cmd = app.add_subcommand("check", "Check a part file without motion");
  check_cmd->add_option("file", check_file, "Part file (.sbp, or G-code)")->required();
  add_profile_option(check_cmd, check_settings);
  check_lang.add_to(check_cmd);

  std::string moves_file, moves_settings, moves_format = "text";
  CLI::App* moves_cmd = app.add_subcommand("moves", "Print the canonical moves of a part file");
  moves_cmd->add_option("file", moves_file, "Part file (.sbp, or G-code)")->required();
  add_profile_option(moves_cmd, moves_settings);
  moves_cmd->add_option("--format", moves_format, "text or jsonl")
      ->check(CLI::IsMember({"text", "jsonl"}));
  std::string moves_svg_file;
  moves_cmd->add_option("--svg", moves_svg_file,
                        "Write a top view of the moves to this SVG file instead of listing them");
  moves_lang.add_to(moves_cmd);
  moves_cmd
      ->add_option("--from-line", moves_lang.from_line,
                   "List the moves of a run that starts at this line (the approach first)")
      ->check(CLI::Range(1, 1'000'000'000));

  std::string estimate_file, estimate_settings;
  bool estimate_json = false;
  LanguageArgs estimate_lang;
  CLI::App* estimate_cmd =
      app.add_subcommand("estimate", "Predict a part file's cycle time without running it");
  estimate_cmd->add_option("file", estimate_file, "Part file (.sbp, or G-code)")->required();
  add_profile_option(estimate_cmd, estimate_settings);
  estimate_cmd->add_flag("--json", estimate_json, "Print the estimate as one JSON object");
  estimate_lang.add_to(estimate_cmd);
  estimate_cmd
      ->add_option("--feed-override", estimate_lang.feed_override,
                   "Percent of the file's speeds (within the profile's feed_override.min and max)")
      ->check(CLI::Range(1.0, 200.0));

  std::string export_file, export_out, export_settings;
  LanguageArgs export_lang;
  CLI::App* export_cmd = app.add_subcommand(
      "export-gcode", "Write a part file's canonical moves as G-code for another controller");
  export_cmd->add_option("file", export_file, "Part file (.sbp, or G-code)")->required();
  export_cmd->add_option("-o,--output", export_out, "The G-code file to write; default: stdout");
  add_profile_option(export_cmd, export_settings);
  export_lang.add_to(export_cmd);

  ImportWincncArgs import_args;
  CLI::App* import_cmd = add_import_wincnc_command(app, import_args);

  std::string commands_group;
  bool commands_json = false;
  CLI::App* commands_cmd = app.add_subcommand("commands", "List the command table");
  commands_cmd->add_option("--group", commands_group, "Only this menu group, e.g. Move or Values");
  commands_cmd->add_flag("--json", commands_json,
                         "One JSON array: codes, names, groups, coverage, parameters");

  std::string help_code;
  bool help_markdown = false;
  CLI::App* help_cmd = app.add_subcommand("help", "List the commands, or describe one");
  help_cmd->add_option("code", help_code,
                       "A two-letter command (MX), a statement (PAUSE), a custom cut (C2), or fm "
                       "for the Friendly Motion commands");
  help_cmd->add_flag("--markdown", help_markdown, "Print the command reference (docs/commands.md)");
  bool help_man = false;
  help_cmd->add_flag("--man", help_man, "Print the manual page gantry(1), in roff");

  ConsoleArgs console_args;
  CLI::App* console_cmd = add_console_command(app, console_args);
  PreviewArgs preview_args;
  LanguageArgs preview_lang;
  CLI::App* preview_cmd = add_preview_command(app, preview_args);
  preview_lang.add_to(preview_cmd);
  std::string log_profile, log_values;
  std::size_t log_last = 20;
  bool log_json = false;
  CLI::App* log_cmd =
      app.add_subcommand("log", "List the part files run: start, cycle time, how each ended");
  add_profile_option(log_cmd, log_profile);
  log_cmd->add_option("--values", log_values,
                      "The values file the log sits beside (default: the profile's)");
  log_cmd->add_option("--last", log_last, "Show the last N runs (default 20; 0: all)");
  log_cmd->add_flag("--json", log_json, "Print the runs as one JSON array");

  std::string state_profile, state_values;
  bool state_confirm = false;
  CLI::App* state_cmd = app.add_subcommand(
      "state", "Show the machine state kept from the last session (position, zero, units)");
  add_profile_option(state_cmd, state_profile);
  state_cmd->add_option("--values", state_values,
                        "The values file the state sits beside (default: the profile's)");
  state_cmd->add_flag("--confirm", state_confirm,
                      "The tool is where the state says: mark the position confirmed");
#ifdef GANTRY_HAVE_GUI
  GuiArgs gui_args;
  CLI::App* gui_cmd = add_gui_command(app, gui_args);
#endif

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 1;
  }
  try {
    if (*run_cmd) return cmd_run(run, run_lang);
    if (*check_cmd) return cmd_check(check_file, check_settings, check_lang);
    if (*moves_cmd)
      return cmd_moves(moves_file, moves_settings, moves_format, moves_svg_file, moves_lang);
    if (*estimate_cmd)
      return cmd_estimate(estimate_file, estimate_settings, estimate_json, estimate_lang);
    if (*help_cmd && help_man) return fmt::print("{}", man_page(app)), 0;
    if (*help_cmd) return cmd_help(help_code, help_markdown);
    if (*export_cmd) return cmd_export_gcode(export_file, export_out, export_settings, export_lang);
    if (*import_cmd) return run_import_wincnc(import_args);
    if (*console_cmd) return run_console(console_args);
    if (*preview_cmd) return cmd_preview(preview_args, preview_lang);
#ifdef GANTRY_HAVE_GUI
    if (*gui_cmd) return run_gui_command(gui_args);
#endif
    if (*commands_cmd) return cmd_commands(commands_group, commands_json);
    if (*log_cmd) return cmd_log(log_profile, log_values, log_last, log_json);
    if (*state_cmd) return cmd_state(state_profile, state_values, state_confirm);
  } catch (const GantryError& e) {
    fmt::print(stderr, "{}\n", e.what());
    return 1;
  }
  return 1;
}
