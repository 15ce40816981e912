// Statements that talk to the operator or to files: PAUSE, PRINT, WRITE, INPUT, MSGBOX,
// DIALOG, FAIL, OPEN, CLOSE, SHELL, PLAY, WARNING OFF and the registry statements.
#include <fmt/format.h>  // messages

#include <sys/wait.h>  // WEXITSTATUS
#include <cmath>       // round

#include <cstdlib>     // system, for SHELL
#include <filesystem>  // GetUsrPath, GetAppPath
#include <functional>  // option values

#include "gantry/interp/interpreter.hpp"
#include "gantry/lang/number_literal.hpp"  // parse_number_literal
#include "gantry/lang/scan.hpp"            // upper, trim
#include "interp_private.hpp"

namespace gantry {

namespace {

std::string strip_one_quote_pair(std::string_view t) {
  if (!t.empty() && t.front() == '"') t.remove_prefix(1);
  if (!t.empty() && t.back() == '"') t.remove_suffix(1);
  return std::string(t);
}

// MSGBOX button sets, by the low group of the type value.
const std::vector<std::string>& buttons_for(int group) {
  static const std::vector<std::string> sets[] = {
      {"OK"},        {"OK", "Cancel"},   {"Abort", "Retry", "Ignore"}, {"Yes", "No", "Cancel"},
      {"Yes", "No"}, {"Retry", "Cancel"}};
  return sets[group];
}

int msgbox_type(const Value& v, const SourceLoc& loc) {
  if (v.is_string()) {
    static const std::pair<const char*, int> names[] = {
        {"OKONLY", 0},       {"OKCANCEL", 1},    {"ABORTRETRYIGNORE", 2}, {"YESNOCANCEL", 3},
        {"YESNO", 4},        {"RETRYCANCEL", 5}, {"CRITICAL", 16},        {"QUESTION", 32},
        {"EXCLAMATION", 48}, {"INFORMATION", 64}};
    const std::string u = scan::upper(scan::trim(v.str()));
    for (auto [n, t] : names)
      if (u == n) return t;
    if (!parse_number_literal(u)) return 0;  // an unknown name: OK only, as documented
  }
  const double d = v.to_number(loc, "the MSGBOX button type");
  const int t = static_cast<int>(d);
  // Valid values are one from each group: buttons 0-5, icon 0/16/32/48/64, default 0-768.
  const int b = t % 16, icon = t % 256 - b, def = t - t % 256;
  if (d != t || b > 5 || icon > 64 || def > 768 || t < 0) return 0;  // anything else: OK only
  return t;
}

// FabMo's dialog options (PAUSE and DIALOG): button captions and a title.
struct DialogOptions {
  std::string ok, cancel, title;
};

DialogOptions dialog_options(const std::vector<std::pair<std::string, Arg>>& options,
                             const std::function<Value(const Arg&)>& value) {
  DialogOptions d;
  for (const auto& [name, a] : options) {
    if (name == "OKTEXT")
      d.ok = value(a).to_string();
    else if (name == "CANCELTEXT")
      d.cancel = value(a).to_string();
    else if (name == "TITLE")
      d.title = value(a).to_string();
    else if (name != "DETAIL" && name != "NOBUTTON")
      fail(a.loc, fmt::format("unknown option {}; use OKTEXT, CANCELTEXT or TITLE", name));
  }
  return d;
}

}  // namespace

std::string Interpreter::pause_message(const SourceLoc&) const {
  const Frame& f = frames_.back();
  if (std::optional<std::string_view> prev = f.script->line_before(current_)) {
    LineParse lp = parse_line(*prev, f.script->name(), current_.line - 1);
    if (lp.comment) return *lp.comment;
  }
  return "Continue?";
}

// Waits until input switch `in` (1-12) is `state` (closed: true): PAUSE UNTIL, and Friendly
// Motion's M200-M231 (`what` names the statement in messages).
void Interpreter::wait_for_input(int in, bool state, const SourceLoc& loc, std::string_view what) {
  // Level-triggered: an input already in the state does not wait.
  const int n = in - 1;
  ctx_.sync();
  if (snapshot().inputs[n] == state) return;
  const bool live = gated_sink_->input_switches().has_value();
  if (options_.unattended_inputs) {
    // Nobody is at the machine: only the simulated machine can answer, or the wait never ends.
    const int on = state;
    const std::optional<Vec6> check_at =
        live ? std::nullopt : std::optional<Vec6>(snapshot().table_base + state_.machine_origin);
    if (!options_.unattended_inputs(n + 1, on, check_at))
      fail(
          loc,
          fmt::format(
              "{6} waits for input {0} to {1}, and nothing will {1} it: nobody "
              "is at the machine, and the simulated machine has no event{2} for input "
              "{0}{3}; give it one with --sim-input {0}={4}@SECONDS (at a machine "
              "time){5}, or run from a terminal",
              n + 1, on ? "close" : "open", live ? " still to come" : "",
              live ? ""
                   : fmt::format(", nor a switch that {}s it where the tool rests",
                                 on ? "close" : "open"),
              on,
              live ? "" : fmt::format(" or --sim-input {}={}@x>=POS (while X is there)", n + 1, on),
              what));
    if (!live) return;  // a check: the simulated machine answers, not a person
  }
  if (live) {
    // The live machine: it waits for the switch, in short dwells, so time passes on the
    // card (virtual time too) and a stop ends the wait.
    while ((*gated_sink_->input_switches())[n] != state) {
      ctx_.dwell(0.01, loc);
      ctx_.sync();
    }
    return;
  }
  if (!io_.confirm(fmt::format("{} (waiting for input {} to {})", pause_message(loc), in,
                               state ? "close" : "open"),
                   loc))
    throw OperatorStop({loc, Severity::Error, fmt::format("stopped by the operator at {}", what)});
}

void Interpreter::exec(const PauseStmt& s, const SourceLoc& loc) {
  if (s.kind == PauseStmt::Kind::Until) {
    const double in = evaluate(*s.input, *this).to_number(loc, "the input number");
    const double state = evaluate(*s.state, *this).to_number(loc, "the state");
    if (in != std::round(in) || in < 1 || in > 12)
      fail(loc, fmt::format("input switch {} does not exist; inputs are 1 to 12", in));
    wait_for_input(static_cast<int>(in), state != 0, loc, "PAUSE UNTIL");
    return;
  }
  if (s.kind == PauseStmt::Kind::Operator) {
    if (!io_.confirm(pause_message(loc), loc))
      throw OperatorStop({loc, Severity::Error, "stopped by the operator at PAUSE"});
    return;
  }
  dialog_options(s.options, [&](const Arg& a) { return value_of(a); });  // validated; captions
  const Value v = value_of(*s.value);
  // A number waits; so does text that is a number (INPUT answers are text).
  const std::optional<double> secs =
      v.is_number() ? std::optional<double>(v.num()) : parse_number_literal(v.str());
  if (secs && !s.into) {
    const std::string note = pause_message(loc);  // the comment line above, if any
    if (note != "Continue?") io_.print(note + "\n");
    ctx_.dwell(*secs, loc);
    return;
  }
  const std::string message = v.to_string();
  if (s.into) {
    std::optional<std::string> answer =
        io_.ask(message, (s.into->persistent ? "$" : "&") + s.into->name, "", loc);
    if (!answer) throw OperatorStop({loc, Severity::Error, "stopped by the operator at PAUSE"});
    assign(*s.into, Value::string(*answer));
    return;
  }
  if (!io_.confirm(message, loc))
    throw OperatorStop({loc, Severity::Error, "stopped by the operator at PAUSE"});
}

// PRINT joins items with five spaces (comma form) or nothing (semicolon form); WRITE #n's
// comma form joins with ", " so that `WRITE #1, "M2", &x` writes `M2, 23.5`.
void Interpreter::exec(const PrintStmt& s, const SourceLoc& loc) {
  std::string text;
  const char* joint = s.comma_mode ? (s.file ? ", " : "     ") : "";
  for (size_t i = 0; i < s.items.size(); ++i) {
    const Arg& a = s.items[i];
    if (i) text += joint;
    text += a.is_expression() ? value_of(a).to_string() : strip_one_quote_pair(a.text);
  }
  if (s.newline) text += '\n';
  if (!s.file) {
    io_.print(text);
    return;
  }
  UserFile& f = user_file(*s.file, loc, true);
  if (f.mode == OpenStmt::Mode::Input)
    fail(loc, fmt::format("file #{} was opened FOR INPUT; open it FOR OUTPUT or APPEND to write",
                          f.number));
  *f.out << text << std::flush;
}

void Interpreter::exec(const InputStmt& s, const SourceLoc& loc) {
  std::string answer;
  if (s.file) {
    UserFile& f = user_file(*s.file, loc, true);
    if (f.mode != OpenStmt::Mode::Input)
      fail(loc, fmt::format("file #{} was opened for writing; INPUT # reads files opened FOR "
                            "INPUT",
                            f.number));
    if (!std::getline(*f.in, answer))
      fail(loc, fmt::format("INPUT #{} read past the end of {}", f.number, f.path));
    if (!answer.empty() && answer.back() == '\r') answer.pop_back();
  } else {
    std::string names;
    for (const LValue& v : s.vars)
      names += fmt::format("{}{}{}", names.empty() ? "" : ",", v.persistent ? "$" : "&", v.name);
    const std::string prompt =
        s.prompt ? (s.prompt->is_expression() ? value_of(*s.prompt).to_string()
                                              : strip_one_quote_pair(s.prompt->text))
                 : "";
    std::string def;
    if (s.default_var) {
      const Value* d = s.default_var->persistent ? nullptr : user_variable(s.default_var->name);
      if (d) def = d->to_string();
    }
    std::optional<std::string> a = io_.ask(prompt, names, def, loc);
    if (!a) throw OperatorStop({loc, Severity::Error, "stopped by the operator at INPUT"});
    answer = *a;
  }
  if (s.vars.size() == 1) {
    assign(s.vars[0], Value::string(std::string(scan::trim(answer))));
    return;
  }
  if (scan::trim(answer).empty())  // an empty box with several variables counts as Cancel
    throw OperatorStop({loc, Severity::Error, "stopped by the operator at INPUT"});
  std::vector<std::string> fields;
  size_t start = 0;
  for (size_t i = 0; i <= answer.size(); ++i) {
    if (i < answer.size() && answer[i] != ',') continue;
    fields.push_back(strip_one_quote_pair(scan::trim(answer.substr(start, i - start))));
    start = i + 1;
  }
  if (fields.size() < s.vars.size())
    fail(loc, fmt::format("INPUT needs {} values separated by commas and got {}", s.vars.size(),
                          fields.size()));
  for (size_t i = 0; i < s.vars.size(); ++i) assign(s.vars[i], Value::string(fields[i]));
}

void Interpreter::exec(const MsgBoxStmt& s, const SourceLoc& loc) {
  const std::string body = s.body.blank() ? "" : value_of(s.body).to_string();
  const int type = s.buttons.blank() ? 0 : msgbox_type(value_of(s.buttons), s.buttons.loc);
  const std::string title = s.title.blank() ? "Gantry" : value_of(s.title).to_string();
  const std::vector<std::string>& buttons = buttons_for(type % 16);
  const size_t def = std::min<size_t>(static_cast<size_t>(type / 256), buttons.size() - 1);
  vars_["MSGANSWER"] = Value::string(io_.choose(body, buttons, def, title, loc));
}

// FabMo's DIALOG: a message with OK/Cancel captions; one with only a cancel caption ends the
// run once it is acknowledged.
// TIMER=n closes it by itself after n seconds (FabMo's stock homing macro ends with one): the
// message is shown and the machine waits that long, nobody asked.
void Interpreter::exec(const DialogStmt& s, const SourceLoc& loc) {
  std::string ok, cancel;
  std::optional<double> timer;
  for (const auto& [name, a] : s.options) {
    if (name == "OKTEXT")
      ok = value_of(a).to_string();
    else if (name == "CANCELTEXT")
      cancel = value_of(a).to_string();
    else if (name == "TIMER")
      timer = value_of(a).to_number(a.loc, "the DIALOG's TIMER");
    else if (name != "TITLE" && name != "DETAIL" && name != "NOBUTTON")
      fail(a.loc,
           fmt::format("unknown DIALOG option {}; use OKTEXT, CANCELTEXT, TITLE or TIMER", name));
  }
  const std::string message = s.message.blank() ? "" : value_of(s.message).to_string();
  if (timer) {
    if (!(*timer >= 0)) fail(loc, fmt::format("the DIALOG's TIMER {} is not a time", *timer));
    io_.print(message + "\n");
    ctx_.dwell(*timer, loc);
    return;
  }
  if (!cancel.empty() && ok.empty()) {
    io_.choose(message, {cancel}, 0, "Gantry", loc);
    throw OperatorStop(
        {loc, Severity::Error, fmt::format("the file ended at DIALOG: {}", message)});
  }
  if (!io_.confirm(message, loc))
    throw OperatorStop({loc, Severity::Error, "stopped by the operator at DIALOG"});
}

void Interpreter::exec(const FailStmt& s, const SourceLoc& loc) {
  fail(loc, fmt::format("FAIL: {}", s.message.blank() ? "the file stopped itself"
                                                      : value_of(s.message).to_string()));
}

Interpreter::UserFile& Interpreter::user_file(const Expr& number, const SourceLoc& loc,
                                              bool must_be_open) {
  const double n = evaluate(number, *this).to_number(loc, "the file number");
  if (n != std::round(n) || n < 1 || n > 9)
    fail(loc, fmt::format("file number {} is not 1 to 9", n));
  for (auto& f : files_)  // a number whose OPEN failed (no path) is not open
    if (f->number == static_cast<int>(n) && (!must_be_open || !f->path.empty())) return *f;
  if (must_be_open) fail(loc, fmt::format("file #{} is not open; OPEN it first", n));
  files_.push_back(std::make_unique<UserFile>());
  files_.back()->number = static_cast<int>(n);
  return *files_.back();
}

void Interpreter::exec(const OpenStmt& s, const SourceLoc& loc) {
  const std::string name = value_of(s.path).to_string();
  UserFile& f = user_file(s.number, loc, false);
  if (!f.path.empty())
    fail(loc, fmt::format("file #{} is already open ({}); CLOSE it first", f.number, f.path));
  const std::string path = s.mode == OpenStmt::Mode::Input ? readable_file(name, s.path.loc)
                                                           : writable_path(name, s.path.loc);
  if (s.mode == OpenStmt::Mode::Input) {
    f.in = files_system_->open_read(path);
    if (!f.in) fail(s.path.loc, fmt::format("cannot open {} for reading", path));
  } else {
    forget_called(path);
    f.out = files_system_->open_write(path, s.mode == OpenStmt::Mode::Append);
    if (!f.out) fail(s.path.loc, fmt::format("cannot open {} for writing", path));
  }
  f.path = path;  // open only once it has opened: a failed OPEN leaves the number free
  f.mode = s.mode;
}

void Interpreter::exec(const CloseStmt& s, const SourceLoc& loc) {
  if (!s.number) {
    files_.clear();
    return;
  }
  const double n = evaluate(*s.number, *this).to_number(loc, "the file number");
  const auto it =
      std::find_if(files_.begin(), files_.end(), [&](const auto& f) { return f->number == n; });
  if (it == files_.end()) {
    io_.warn({loc, Severity::Warning, fmt::format("CLOSE #{}: that file is not open", n)});
    return;
  }
  files_.erase(it);
}

void Interpreter::exec(const ShellStmt& s, const SourceLoc& loc) {
  if (!options_.allow_shell)
    fail(loc, "SHELL starts other programs and is disabled; run with --allow-shell to permit it");
  if (options_.dry_run) return;
  const std::string command = value_of(s.command).to_string();
  bool sync = false;
  for (const Arg& a : s.options)
    if (scan::upper(a.text) == "SYNC") sync = true;
  const int status = std::system((sync ? command : command + " &").c_str());
  const int rc = WIFEXITED(status) ? WEXITSTATUS(status) : status;
  if (sync && rc != 0)
    io_.warn(
        {loc, Severity::Warning, fmt::format("SHELL: `{}` exited with status {}", command, rc)});
}

void Interpreter::exec(const WarningOffStmt&, const SourceLoc&) {
  warning_off_ = true;
}

void Interpreter::exec(const PlayStmt& s, const SourceLoc& loc) {
  io_.warn({loc, Severity::Warning,
            fmt::format("PLAY {}: Gantry plays no sounds; the file continues", s.path.text)});
}

void Interpreter::exec(const RegistryStmt& s, const SourceLoc& loc) {
  auto set = [&](const char* key) {  // only writes mark the store changed
    const Value v = value_of(s.arg);
    store_.registry()[key] = v.is_number() ? nlohmann::json(v.num()) : nlohmann::json(v.str());
  };
  auto get = [&](const char* key) {
    const nlohmann::json* j = store_.registry_value(key);
    Value v = Value::string("");
    if (j)
      v = j->is_number() ? Value::number(j->get<double>()) : Value::string(j->get<std::string>());
    assign(*s.target, v);
  };
  if (s.name == "SETUSRVAL")
    set("uValue");
  else if (s.name == "SETUSRVALCLRD")
    set("uValueClrd");
  else if (s.name == "SETSPINDLESTATUS")
    set("SpindleStatus");
  else if (s.name == "GETUSRVAL")
    get("uValue");
  else if (s.name == "GETUSRVALCLRD")
    get("uValueClrd");
  else if (s.name == "GETSPINDLESTATUS")
    get("SpindleStatus");
  else if (s.name == "GETUSRPATH")
    assign(*s.target, Value::string(std::filesystem::path(store_.path()).parent_path().string()));
  else if (s.name == "GETAPPPATH")
    assign(*s.target,
           Value::string(std::filesystem::read_symlink("/proc/self/exe").parent_path().string()));
  else if (s.name == "GETPARTFILENAME")
    assign(*s.target, Value::string(*frames_.front().script->name()));
  else
    fail(loc, fmt::format("unknown registry statement {}", s.name));
}

}  // namespace gantry
