// Fixtures for tests that run programs on an interpreter into a RecordingSink: the default
// profile, an operator, the $variables, and either a fresh interpreter per run or check (the
// G-code front end's golden tests) or one kept across runs; and the helpers they share.
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "answering_io.hpp"
#include "gantry/core/diagnostic.hpp"
#include "gantry/core/vec6.hpp"
#include "gantry/interp/interpreter.hpp"
#include "gantry/interp/operator_io.hpp"
#include "gantry/interp/persistent_store.hpp"
#include "gantry/lang/script.hpp"
#include "gantry/settings/settings.hpp"
#include "recording_sink.hpp"

namespace gantry {

// X, Y and Z (A, B and C 0), as golden end points are written.
inline Vec6 v6(double x, double y, double z = 0) {
  Vec6 v = Vec6::Zero();
  v << x, y, z, 0, 0, 0;
  return v;
}

// The lines and arcs of `moves`, in order.
inline std::vector<CanonMove> lines_and_arcs(const std::vector<CanonMove>& moves) {
  std::vector<CanonMove> out;
  for (const CanonMove& m : moves)
    if (m.kind == MoveKind::Line || m.kind == MoveKind::Arc) out.push_back(m);
  return out;
}

// The errors of `found` (warnings left out), first first.
inline std::vector<Diagnostic> errors_of(const std::vector<Diagnostic>& found) {
  std::vector<Diagnostic> out;
  for (const Diagnostic& d : found)
    if (d.severity == Severity::Error) out.push_back(d);
  return out;
}

// The first error of `found`; a test failure naming the program `text` when there is none.
inline Diagnostic first_error_of(const std::vector<Diagnostic>& found, const std::string& text) {
  for (const Diagnostic& d : found)
    if (d.severity == Severity::Error) return d;
  ADD_FAILURE() << "no error for:\n" << text;
  return {};
}

template <class IO = AnsweringIO>
class InterpreterFixture : public ::testing::Test {
 protected:
  // Runs `script` on an interpreter of its own into a fresh `sink`: every move it made.
  // `state` receives the modal state it ends in, `after` (when given) its settings.
  const std::vector<CanonMove>& run_script(std::shared_ptr<const Script> script,
                                           const InterpreterOptions& o = {},
                                           Settings* after = nullptr) {
    sink = RecordingSink();
    Interpreter interp(settings, sink, io, store, o);
    interp.run(std::move(script));
    state = interp.state();
    if (after) *after = interp.settings();
    return sink.moves;
  }
  // What a check (a dry run) of `script` finds, the load pass's errors included; its moves go
  // to `into`, by default a fresh `sink`.
  std::vector<Diagnostic> check_script(std::shared_ptr<const Script> script,
                                       InterpreterOptions o = {}, MotionSink* into = nullptr) {
    if (!into) {
      sink = RecordingSink();
      into = &sink;
    }
    o.dry_run = true;
    Interpreter interp(settings, *into, io, store, o);
    return interp.check(std::move(script));
  }

  Settings settings = default_settings();
  RecordingSink sink;
  IO io;
  PersistentStore store;
  ModalState state;
};

// One interpreter, made at its first use with `settings` and `options`, runs program after
// program and keeps its state; the operator answers yes and its PRINT text goes to `printed`.
// The hooks a test may use: `options` (its files, the profile), `profile` (a second Settings,
// the machine's profile when options.profile points to it), fresh_interp() for a test that
// runs each program on a new interpreter, operator_io() for another operator, `Sink` for a
// sink that records more.
template <class Sink = RecordingSink>
class BasicKeptInterpreterFixture : public ::testing::Test {
 protected:
  Interpreter& interp() {
    if (!interp_) interp_.emplace(settings, sink, operator_io(), store, options);
    return *interp_;
  }
  // The operator the interpreter is made with (when it is made): `io` unless overridden.
  virtual OperatorIO& operator_io() { return io; }
  // A new interpreter in place of the kept one (made now, with `settings` and `options` now).
  Interpreter& fresh_interp() {
    interp_.reset();
    return interp();
  }
  const ModalState& state() { return interp().state(); }
  const std::vector<CanonMove>& moves() const { return sink.moves; }

  // Runs `script` on interp(); a script that did not load, or an error, fails the test.
  void run_program(const std::shared_ptr<const Script>& script) {
    ASSERT_TRUE(script->ok()) << format(script->errors().front());
    try {
      interp().run(script);
    } catch (const GantryError& e) {
      FAIL() << format(e.diagnostic());
    }
  }
  // Runs `script` on interp() expecting an error: returns it; a test failure naming the
  // program `text` when there is none.
  Diagnostic program_error(const std::shared_ptr<const Script>& script, std::string_view text) {
    try {
      interp().run(script);
    } catch (const GantryError& e) {
      return e.diagnostic();
    }
    ADD_FAILURE() << "no error from:\n" << text;
    return {};
  }
  // run_program and program_error for program text, as part.sbp; a load-pass error is the
  // error run_error returns.
  void run(std::string_view text) { run_program(Script::from_text(std::string(text), "part.sbp")); }
  Diagnostic run_error(std::string_view text) {
    const auto script = Script::from_text(std::string(text), "part.sbp");
    if (!script->ok()) return script->errors().front();
    return program_error(script, text);
  }
  // The warnings the operator was given, one a line.
  std::string warnings() const {
    std::string out;
    for (const Diagnostic& d : io.warnings()) out += format(d) + "\n";
    return out;
  }

  Settings settings = default_settings();
  Settings profile = default_settings();
  InterpreterOptions options;
  Sink sink;
  std::string printed;
  ScriptedIO io{true, {}, &printed};
  PersistentStore store;
  std::optional<Interpreter> interp_;
};
using KeptInterpreterFixture = BasicKeptInterpreterFixture<>;

}  // namespace gantry
