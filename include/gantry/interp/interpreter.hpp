// Runs a parsed program: modal state, dispatch through the command table, moves to a sink.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "gantry/commands/command_table.hpp"  // CommandTable, CommandCall
#include "gantry/lang/statement.hpp"          // Program
#include "gantry/motion/canon_move.hpp"       // CanonMove, MotionSink
#include "gantry/settings/settings.hpp"       // Settings

namespace gantry {

// The state the language defines and commands change.
struct ModalState {
  Vec6 position = Vec6::Zero();  // commanded position, units
  bool absolute = true;          // SA (true) or SR (false)
  SpeedSettings speeds;          // MS / JS / VS
};

// What a command handler may touch: the modal state, the profile, and the move stream.
class CommandContext {
 public:
  CommandContext(ModalState& state, const Settings& settings, MotionSink& sink)
      : state_(state), settings_(settings), sink_(sink) {}

  ModalState& state() { return state_; }
  const Settings& settings() const { return settings_; }

  // Emits a straight move from the current position to `target` and makes it current.
  // A target outside the soft limits is an error located at `loc`; nothing is emitted.
  void line_to(const Vec6& target, SpeedClass cls, const SourceLoc& loc);

  std::size_t moves() const { return moves_; }

 private:
  ModalState& state_;
  const Settings& settings_;
  MotionSink& sink_;
  std::size_t moves_ = 0;
};

class Interpreter {
 public:
  Interpreter(const Settings& settings, MotionSink& sink,
              const CommandTable& table = CommandTable::standard());

  // Runs the program to END or its last line; throws GantryError at the first error.
  void run(const Program& program);

  // Runs the program without stopping at errors: returns every error found, each statement
  // that fails being skipped. Used by `check` and before any motion.
  std::vector<Diagnostic> check(const Program& program);

  // Called after each statement with (statements done, statements in the program).
  void on_progress(std::function<void(std::size_t, std::size_t)> f) { progress_ = std::move(f); }

  const ModalState& state() const { return state_; }
  std::size_t statements_executed() const { return executed_; }
  std::size_t moves_emitted() const { return ctx_.moves(); }

 private:
  // Executes one statement; returns false at END.
  bool execute(const Statement& st);
  void execute_command(const CommandStmt& cmd, const SourceLoc& loc);

  const CommandTable& table_;
  MotionSink& sink_;
  ModalState state_;
  CommandContext ctx_;
  std::size_t executed_ = 0;
  std::function<void(std::size_t, std::size_t)> progress_;
};

// Parameter text to a number: OpenSBP numerals (`5`, `-.45`, `+3.`, `1e-3`).
// Anything else is an error at the parameter, naming what was expected.
double evaluate_number(const Param& p, std::string_view what);

}  // namespace gantry
