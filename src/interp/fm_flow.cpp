// Friendly Motion's lines and flow (docs/friendlymotion.md, "Flow"): the commands of a line
// run left to right; J jumps and K calls go to the line that starts with their sequence
// number; M6 returns to the command after the K, on its line; M0 stops for the operator (who
// goes on line by line, STEP, or runs on, AUTO); M2 runs the program again from its top.
#include <fmt/format.h>  // messages

#include <cmath>    // trunc
#include <cstdint>  // SIZE_MAX
#include <set>

#include "gantry/interp/fm_executor.hpp"
#include "interp_private.hpp"

namespace gantry {
namespace {

constexpr size_t kMaxCalls = 10;  // "Subroutines may be nested up to 10 deep"

// Whether the program goes on after an M0 at `c`: a line with a command follows that is not
// a subroutine's (a line numbered with a K call's target, or a hot key's N10001-N10010, starts
// the subroutines, which the main program's M0 ends before, as the manual's "All programs
// should include an M0 or M2").
bool program_follows(const Script& script, Cursor c) {
  FmLine line;
  Diagnostic error;
  std::set<int> called;
  for (Cursor k = script.start(), next; !script.at_end(k); k = next) {
    if (parse_fm_line(script.line_at(k, &next), script.name(), k.line, &line, &error))
      for (const FmCommand& cmd : line.commands)
        if (cmd.op == FmOp::Call) called.insert(cmd.target);
  }
  for (Cursor next; !script.at_end(c); c = next) {
    const std::string_view text = script.line_at(c, &next);
    if (!parse_fm_line(text, script.name(), c.line, &line, &error)) return true;
    if (line.commands.empty()) continue;
    // N10001-N10010 are the Alt-F keys' subroutines, which only the keyboard calls.
    return !(line.sequence &&
             (called.count(*line.sequence) || (*line.sequence > 10000 && *line.sequence <= 10010)));
  }
  return false;
}

}  // namespace

void Interpreter::fm_go_to(int sequence, const SourceLoc& loc) {
  Frame& f = frames_.back();
  const std::optional<Cursor> target = f.script->label(fmt::format("N{}", sequence));
  if (!target)
    fail(loc, fmt::format("no line in this file starts with N{}; J and K go to a sequence "
                          "number written first on its line",
                          sequence));
  f.pc = *target;
}

// M200-M231 test input (code - 200) + 1: Gantry's inputs are 1 to 12 (M200-M211). "Active"
// (the manual's logic low) is the switch closed, whatever its wiring's level.
bool Interpreter::fm_input_active(int code, const SourceLoc& loc) {
  const int n = code - 200 + 1;
  if (n > 12)
    fail(loc, fmt::format("M{} is input {}, and Gantry has input switches 1 to 12 (M200-M211)",
                          code, n));
  ctx_.sync();
  return snapshot().inputs[static_cast<size_t>(n - 1)];
}

void Interpreter::fm_wait_input(int code, const SourceLoc& loc) {
  const int n = code - 200 + 1;
  if (n > 12)
    fail(loc, fmt::format("M{} is input {}, and Gantry has input switches 1 to 12 (M200-M211)",
                          code, n));
  wait_for_input(n, true, loc, fmt::format("M{}", code));
}

bool Interpreter::in_friendly_motion() const {
  return !frames_.empty() && frames_.back().script->fm();
}

// "The Alternate Function Keys (Alt-F1 to Alt-F-10) directly call and execute the subroutines
// N10001 to N10010 ... When subroutine execution is completed, the system returns to the STEP
// mode." The key is taken before a line: the subroutine runs (on its own, in AUTO), and its
// M6 comes back to the start of that line, which then waits for the operator (STEP). A key
// whose subroutine the program lacks is the manual's error message: a warning, and the run
// goes on (a stray key does not end a part).
bool Interpreter::fm_hot_call(int key, const SourceLoc& loc) {
  FmFlow& flow = *fm_flow_;
  Frame& f = frames_.back();
  const int n = 10000 + key;
  const std::optional<Cursor> target = f.script->label(fmt::format("N{}", n));
  if (!target) {
    io_.warn({loc, Severity::Warning,
              fmt::format("Alt-F{} calls subroutine N{}, which this program does not have; "
                          "nothing was called",
                          key, n)});
    return false;
  }
  if (flow.calls.size() >= kMaxCalls)
    fail(loc, fmt::format("Alt-F{}: subroutines already nest 10 deep (the manual's limit)", key));
  io_.print(fmt::format("Alt-F{}: N{}\n", key, n));
  flow.calls.push_back({current_, 0, *target, 0, true});
  f.pc = *target;
  flow.step = false;
  return true;
}

void Interpreter::exec(const FmStmt& s, const SourceLoc& loc) {
  FmFlow& flow = *fm_flow_;
  const FmLine& line = s.line;
  size_t k = 0;
  auto hot_key = [&] { return options_.fm_hot_key ? options_.fm_hot_key() : 0; };
  if (flow.resume_offset == current_.offset) {  // back from a subroutine: after its K
    k = flow.resume_index;
    flow.resume_offset = SIZE_MAX;
  } else if (!ctx_.checking_) {
    if (const int key = hot_key(); key > 0 && fm_hot_call(key, loc)) return;
    while (flow.step) {
      const std::string answer = io_.choose(fmt::format("STEP: line {} next", current_.line),
                                            {"Step", "Auto", "Stop"}, 0, kFmStepTitle, loc);
      if (answer == "Stop") throw OperatorStop({loc, Severity::Error, "stopped by the operator"});
      flow.step = answer == "Step";
      // A hot key pressed at the question answered it (session::press_fm_hot_key): its
      // subroutine runs first and this line asks again when it returns; a key with no
      // subroutine asks again at once.
      const int key = hot_key();
      if (key == 0) break;
      if (fm_hot_call(key, loc)) return;
      flow.step = true;
    }
  }
  for (; k < line.commands.size(); ++k) {
    const FmCommand& c = line.commands[k];
    const SourceLoc at{loc.file, loc.line, c.column};
    Frame& f = frames_.back();
    switch (c.op) {
      case FmOp::Sequence:
        continue;
      case FmOp::Jump:
      case FmOp::Call: {
        const bool go = c.axis == 'M'   ? fm_input_active(c.cond, at)
                        : c.axis == 'V' ? fm_->variable(c.cond) > 0
                                        : true;
        if (!go) continue;  // the next command (on this line or the next)
        if (c.op == FmOp::Jump) return fm_go_to(c.target, at);
        long repeats = 0;
        if (c.repeat >= 0) {
          const double r = fm_->value(line, c.repeat, at);
          if (r != std::trunc(r) || r < 0 || r > 1e6)
            fail(at, fmt::format("R{} is not a repeat count: a whole number from 0", r));
          repeats = static_cast<long>(r);
        }
        if (flow.calls.size() >= kMaxCalls)
          fail(at,
               "subroutines nest more than 10 deep (the manual's limit); a subroutine may "
               "be calling itself");
        fm_go_to(c.target, at);
        flow.calls.push_back({current_, k + 1, f.pc, repeats});
        return;
      }
      case FmOp::M:
        if (c.expr >= 0) break;
        if (c.code == 6) {
          if (flow.calls.empty())
            fail(at,
                 "M6 returns from a subroutine, and none was called (K); end the main "
                 "program with M0 or M2 before the subroutines");
          FmFlow::Call& call = flow.calls.back();
          if (call.hot) {  // an Alt-F key's: the line it came before runs next, in STEP
            f.pc = call.line;
            flow.calls.pop_back();
            flow.step = true;
            return;
          }
          if (call.left > 0) {  // R: the subroutine again
            --call.left;
            f.pc = call.target;
            return;
          }
          f.pc = call.line;
          flow.resume_offset = call.line.offset;
          flow.resume_index = call.next;
          flow.calls.pop_back();
          return;
        }
        if (c.code == 0) {
          ctx_.come_to_rest(at);
          const bool last = k + 1 == line.commands.size() && !program_follows(*f.script, f.pc);
          if (last) {  // nothing after it but subroutines: the program ends here
            f.pc = Cursor{std::string::npos, f.pc.line};
            return;
          }
          const std::string answer =
              io_.choose("M0: program stop. Step runs a line at a time, Auto runs on, Stop ends",
                         {"Step", "Auto", "Stop"}, 1, kFmStepTitle, at);
          if (answer == "Stop")
            throw OperatorStop({at, Severity::Error, "stopped by the operator at M0"});
          flow.step = answer == "Step";
          continue;
        }
        if (c.code == 2) {
          ctx_.come_to_rest(at);
          flow.calls.clear();
          // A check passes once; so does a run nobody attends, which would repeat for ever.
          if (ctx_.checking_ || !options_.operator_present) {
            if (!ctx_.checking_)
              io_.warn({at, Severity::Warning,
                        "M2 repeats the program until the operator stops it; nobody attends "
                        "this run, so it ran once"});
            f.pc = Cursor{std::string::npos, f.pc.line};
            return;
          }
          f.pc = f.script->start();
          return;
        }
        if (c.code >= 200 && c.code <= 231) {
          fm_wait_input(c.code, at);
          continue;
        }
        break;
      default:
        break;
    }
    fm_->execute(c, line, at);
  }
}

}  // namespace gantry
