// Lines typed at the console: the command record (RA, RI, RP, RR, RS, RZ) and SI, which
// sends lines as if they were typed. Played lines run as typed lines do (CommandContext::
// run_typed): values they change stay, and they are not recorded again.
#include "gantry/commands/command_recorder.hpp"

#include <fmt/format.h>  // messages

#include <algorithm>  // min
#include <charconv>   // from_chars
#include <cmath>      // floor
#include <filesystem>
#include <variant>

#include "gantry/commands/command_table.hpp"
#include "gantry/core/text.hpp"  // trim
#include "gantry/interp/command_context.hpp"
#include "gantry/lang/parser.hpp"  // parse_line

namespace gantry {

// ---- CommandRecorder -----------------------------------------------------------------------

bool CommandRecorder::record(std::string_view line) {
  if (!active_) return false;
  line = ascii::trim(line, " \t\n\v\f\r");  // what isspace calls a space
  static const std::shared_ptr<const std::string> kNoFile;
  const LineParse parsed = parse_line(line, kNoFile, 1);
  if (parsed.error || !parsed.statement) return false;  // a broken, blank or comment line
  const auto& body = parsed.statement->body;
  if (std::holds_alternative<LabelStmt>(body)) return false;
  if (const auto* cmd = std::get_if<CommandStmt>(&body)) {
    const CommandSpec* spec = CommandTable::standard().find(cmd->code);
    if (spec && spec->group == CommandGroup::Record) return false;
  }
  if (lines_.size() == kCapacity) lines_.pop_front();
  lines_.emplace_back(line);
  return true;
}

std::vector<std::string> CommandRecorder::last(std::size_t n) const {
  n = std::min(n, lines_.size());
  return {lines_.end() - static_cast<std::ptrdiff_t>(n), lines_.end()};
}

namespace {

// The name the played record's lines are located in ("(record):2:4: error: ...").
constexpr const char* kRecordName = "(record)";

std::string joined(const std::vector<std::string>& lines) {
  std::string out;
  for (const std::string& l : lines) out += l + "\n";
  return out;
}

std::string commands(std::size_t n) {
  return fmt::format("{} command{}", n, n == 1 ? "" : "s");
}

// How many commands back (RR's and RS's parameter): a whole number from 1 to what is kept.
std::size_t how_many_back(const CommandRecorder& rec, double n, const CommandCall& call,
                          size_t param) {
  if (n > static_cast<double>(rec.size()))
    fail(call.param_loc(param),
         fmt::format("{}: {} back, but the record holds {}; nothing was done ({})", call.spec.code,
                     commands(static_cast<std::size_t>(n)), commands(rec.size()),
                     call.spec.code == "RR" ? "RR, A plays them all" : "a blank saves them all"));
  return static_cast<std::size_t>(n);
}

// Plays the last `n` recorded lines `repetitions` times, as typed.
void play(CommandContext& ctx, std::size_t n, int repetitions, const SourceLoc& loc) {
  const std::vector<std::string> lines = ctx.recorder().last(n);
  ctx.run_typed(Script::from_text(joined(lines), kRecordName), repetitions, loc);
}

void record_on(CommandContext& ctx, const CommandCall&) {
  ctx.recorder().set_active(true);
  ctx.print(fmt::format("Recording typed commands ({} kept)\n", ctx.recorder().size()));
}

void record_off(CommandContext& ctx, const CommandCall&) {
  ctx.recorder().set_active(false);
  ctx.print(fmt::format("Recording paused ({} kept; RA resumes)\n", ctx.recorder().size()));
}

void record_clear(CommandContext& ctx, const CommandCall&) {
  ctx.recorder().clear();
  ctx.print(fmt::format("Record cleared; recording is {}\n",
                        ctx.recorder().active() ? "on" : "paused (RA resumes)"));
}

void record_play_all(CommandContext& ctx, const CommandCall& call) {
  if (ctx.recorder().size() == 0) {
    ctx.print("RP: the record is empty; nothing was played\n");
    return;
  }
  play(ctx, ctx.recorder().size(), 1, call.loc);
}

void record_replay(CommandContext& ctx, const CommandCall& call) {
  const CommandRecorder& rec = ctx.recorder();
  const std::string back = *call.text(0);
  std::size_t n = rec.size();
  if (back != "A" && back != "a") {
    double v = 0;
    const auto [end, ec] = std::from_chars(back.data(), back.data() + back.size(), v);
    if (ec != std::errc() || end != back.data() + back.size() || v < 1 || v != std::floor(v))
      fail(call.param_loc(0),
           fmt::format("RR parameter 1 (commands back) is '{}'; give a whole number from 1, "
                       "or A for all of them",
                       back));
    n = how_many_back(rec, v, call, 0);
  } else if (n == 0) {
    ctx.print("RR: the record is empty; nothing was played\n");
    return;
  }
  play(ctx, n, static_cast<int>(*call.number(1)), call.loc);
}

// RS: the name as given; SBTEMP.SBP when blank, `.sbp` added when it has no extension.
std::string save_name(const CommandCall& call) {
  const std::optional<std::string> name = call.text(0);
  if (!name) return "SBTEMP.SBP";
  if (std::filesystem::path(*name).has_extension()) return *name;
  return *name + ".sbp";
}

void record_save(CommandContext& ctx, const CommandCall& call) {
  const CommandRecorder& rec = ctx.recorder();
  const std::size_t n = call.number(1) ? how_many_back(rec, *call.number(1), call, 1) : rec.size();
  if (n == 0) {
    ctx.print("RS: the record is empty; no file was written\n");
    return;
  }
  const std::string text =
      fmt::format("' {} typed at the Gantry console, oldest first (saved by RS)\n{}", commands(n),
                  joined(rec.last(n)));
  const std::string path = ctx.write_file(save_name(call), text, call.param_loc(0));
  ctx.set_last_file(path);
  ctx.print(
      fmt::format("RS saved {} in {}; FE opens it in the editor, FP runs it\n", commands(n), path));
}

// ---- SI ------------------------------------------------------------------------------------

constexpr int kSendLines = 12;
constexpr const char* kSendFile = "temp_code.sbp";

void send_lines(CommandContext& ctx, const CommandCall& call) {
  std::string text;
  for (int i = 0; i < kSendLines; ++i)
    if (const std::optional<std::string> line = call.text(static_cast<size_t>(i)))
      text += *line + "\n";
  if (text.empty()) {  // SB3 recalls the last lines sent into its pad; here they are shown
    std::string path;
    const std::optional<std::string> last = ctx.read_file(kSendFile, call.loc, &path);
    if (!last || last->empty()) {
      ctx.print(
          "SI sends the lines given as its parameters, e.g. SI, \"MX, 1\", \"JY, 2\"; none "
          "were given, and none were sent before\n");
      return;
    }
    ctx.print(
        fmt::format("SI: no lines given. The last lines sent ({}):\n{}"
                    "FP, {} sends them again\n",
                    path, *last, kSendFile));
    return;
  }
  const std::string path = ctx.write_file(kSendFile, text, call.loc);
  ctx.run_typed(Script::from_text(text, path), 1, call.loc);
}

std::vector<ParamSpec> send_params() {
  static const std::string names[kSendLines] = {"line 1", "line 2",  "line 3",  "line 4",
                                                "line 5", "line 6",  "line 7",  "line 8",
                                                "line 9", "line 10", "line 11", "line 12"};
  std::vector<ParamSpec> out;
  for (const std::string& n : names)
    out.push_back({n, "", false, std::nullopt,
                   "A line to run; in double quotes when it holds commas or an expression "
                   "(\"M2, 1, 2\").",
                   ParamKind::Text});
  return out;
}

}  // namespace

void add_record_commands(std::vector<CommandSpec>& out) {
  const auto R = CommandGroup::Record;
  out.push_back({"RA",
                 "Record: activate",
                 R,
                 "Turns the command record on (it is on when Gantry starts): each line typed at "
                 "the console is kept, up to the last 100. Lines run from part files and Record "
                 "commands are not kept.",
                 {},
                 record_on});
  out.push_back({"RI",
                 "Record: inactivate",
                 R,
                 "Pauses the command record: what it holds stays, and lines typed from now on "
                 "are not kept until RA.",
                 {},
                 record_off});
  out.push_back({"RP",
                 "Record: play all",
                 R,
                 "Runs every line in the record again, oldest first, as if typed once more "
                 "(relative moves under SR move on from where the tool is).",
                 {},
                 record_play_all});
  out.push_back(
      {"RR",
       "Record: replay last commands",
       R,
       "Runs the most recent lines of the record again, oldest first and as they were typed, "
       "the whole group as many times as asked. `RR, A, 20` under SR repeats a typed drilling "
       "step 20 times.",
       {ParamSpec{"commands back", "", false, 1.0,
                  "How many of the latest lines to run: a whole number, or A for all.",
                  ParamKind::Text},
        ParamSpec{"repetitions", "", false, 1.0, "How many times the group runs."}.integer(1, 1e6)},
       record_replay});
  out.push_back(
      {"RS",
       "Record: save to a file",
       R,
       "Writes the most recent lines of the record to a part file in the parts folder (FS), "
       "oldest first under a comment line, replacing the file at once (never half written). "
       "FE then opens it, FP runs it.",
       {ParamSpec{"file name", "", false, std::nullopt,
                  "Where to save (blank: SBTEMP.SBP); .sbp is added when it has no extension.",
                  ParamKind::Text},
        ParamSpec{"commands back", "", false, std::nullopt,
                  "How many of the latest lines (blank: all)."}
            .integer(1, static_cast<double>(CommandRecorder::kCapacity))},
       record_save,
       "opening the editor by itself (FE with a blank name opens the saved file)"});
  out.push_back({"RZ",
                 "Record: zero the memory",
                 R,
                 "Empties the command record; whether recording is on stays as RA or RI left it.",
                 {},
                 record_clear});
  out.push_back({"SI", "Send command lines", CommandGroup::Settings,
                 "Runs up to 12 lines given as its parameters, in order, as if typed at the "
                 "console, after saving them in temp_code.sbp in the parts folder. A syntax "
                 "error in any line stops them all before the first runs. Without lines it "
                 "shows the ones sent last.",
                 send_params(), send_lines,
                 "the pad that recalls the last lines for editing (FE, temp_code.sbp edits "
                 "them)"});
}

}  // namespace gantry
