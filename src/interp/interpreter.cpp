// Statement execution: modal state, parameter evaluation and dispatch through the table.
#include "gantry/interp/interpreter.hpp"

#include <fmt/format.h>  // messages

#include <cmath>  // isfinite

namespace gantry {

void CommandContext::line_to(const Vec6& target, SpeedClass cls, const SourceLoc& loc) {
  const char* unit = units_name(settings_.units);
  for (int i = 0; i < kAxisCount; ++i) {
    if (target[i] == state_.position[i]) continue;  // only axes that move are checked
    const AxisSettings& ax = settings_.axes[i];
    if (!std::isfinite(target[i]) || target[i] < ax.min || target[i] > ax.max)
      fail(loc, fmt::format("move to {}={:.4f} is outside the soft limits {:.4f} to {:.4f} {} "
                            "(axes.{}.min/max in the profile); nothing was moved",
                            static_cast<char>(std::toupper(kAxisLetters[i])), target[i], ax.min,
                            ax.max, unit, kAxisLetters[i]));
  }
  if (target == state_.position) return;  // no motion, no move
  CanonMove m;
  m.speed_class = cls;
  m.from = state_.position;
  m.to = target;
  m.speeds = cls == SpeedClass::Move ? state_.speeds.move : state_.speeds.jog;
  m.loc = loc;
  sink_.move(m);
  state_.position = target;
  ++moves_;
}

Interpreter::Interpreter(const Settings& settings, MotionSink& sink, const CommandTable& table)
    : table_(table), sink_(sink), ctx_(state_, settings, sink) {
  state_.speeds = settings.speeds;
}

void Interpreter::run(const Program& program) {
  if (!program.ok()) throw GantryError(program.errors.front());
  const size_t total = program.statements.size();
  for (const Statement& st : program.statements) {
    const bool go_on = execute(st);
    if (progress_) progress_(executed_, total);
    if (!go_on) break;
  }
  sink_.flush();
}

std::vector<Diagnostic> Interpreter::check(const Program& program) {
  std::vector<Diagnostic> errors = program.errors;
  for (const Statement& st : program.statements) {
    try {
      if (!execute(st)) break;
    } catch (const GantryError& e) {
      errors.push_back(e.diagnostic());
    }
  }
  sink_.flush();
  return errors;
}

bool Interpreter::execute(const Statement& st) {
  ++executed_;
  return std::visit(
      [&](const auto& body) -> bool {
        using T = std::decay_t<decltype(body)>;
        if constexpr (std::is_same_v<T, CommandStmt>) {
          execute_command(body, st.loc);
          return true;
        } else if constexpr (std::is_same_v<T, EndStmt>) {
          return false;
        } else {
          return true;  // a label does nothing when reached
        }
      },
      st.body);
}

void Interpreter::execute_command(const CommandStmt& cmd, const SourceLoc& loc) {
  const CommandSpec* spec = table_.find(cmd.code);
  if (!spec)
    fail(loc, fmt::format("unknown command '{}'; see docs/commands.md for the commands Gantry "
                          "knows",
                          cmd.code));
  if (cmd.params.size() > spec->params.size()) {
    fail(cmd.params[spec->params.size()].loc,
         fmt::format("{} takes {} parameter{}; this is parameter {}", spec->code,
                     spec->params.size(), spec->params.size() == 1 ? "" : "s",
                     spec->params.size() + 1));
  }
  CommandCall call{*spec, loc, cmd.params, {}};
  call.values.resize(spec->params.size());
  for (size_t i = 0; i < spec->params.size(); ++i) {
    const ParamSpec& ps = spec->params[i];
    if (i < cmd.params.size() && !cmd.params[i].blank()) {
      call.values[i] = evaluate_number(cmd.params[i], fmt::format("{} ({})", ps.name, spec->code));
    } else if (ps.required) {
      fail(call.param_loc(i),
           fmt::format("{} needs its parameter {} ({})", spec->code, i + 1, ps.name));
    } else {
      call.values[i] = ps.default_value;
    }
  }
  spec->handler(ctx_, call);
}

}  // namespace gantry
