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
// a subroutine's (a line numbered with a K call's target starts the subroutines, which the
// main program's M0 ends before, as the manual's "All programs should include an M0 or M2").
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
    return !(line.sequence && called.count(*line.sequence));
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

void Interpreter::exec(const FmStmt& s, const SourceLoc& loc) {
  FmFlow& flow = *fm_flow_;
  const FmLine& line = s.line;
  size_t k = 0;
  if (flow.resume_offset == current_.offset) {  // back from a subroutine: after its K
    k = flow.resume_index;
    flow.resume_offset = SIZE_MAX;
  } else if (flow.step && !ctx_.checking_) {
    const std::string answer = io_.choose(fmt::format("STEP: line {} next", current_.line),
                                          {"Step", "Auto", "Stop"}, 0, "Friendly Motion", loc);
    if (answer == "Stop") throw OperatorStop({loc, Severity::Error, "stopped by the operator"});
    flow.step = answer == "Step";
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
                         {"Step", "Auto", "Stop"}, 1, "Friendly Motion", at);
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
