// libFuzzer target: any bytes as a part file, through the parser, the expression evaluator
// and a dry-run interpreter. Must never crash, hang or trip a sanitizer. Every line the fast
// readers (simple commands, common statements) accept must read exactly as the general
// parser reads it.
#include <cstddef>
#include <cstdint>
#include <cstdio>   // the mismatch, before aborting
#include <cstdlib>  // abort
#include <string>

#include "../support/same_statement.hpp"  // simple_command_mismatch

#include "../support/null_sink.hpp"       // NullSink
#include "gantry/interp/interpreter.hpp"  // Interpreter
#include "gantry/lang/script.hpp"         // Script

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const gantry::Settings settings = gantry::default_settings();
  std::string text(reinterpret_cast<const char*>(data), size);
  auto script = gantry::Script::from_text(std::move(text), "/nonexistent/fuzz.sbp");
  gantry::Statement fast, common;  // reused line after line, as the interpreter does
  for (gantry::Cursor c = script->start(); !script->at_end(c);) {
    gantry::Cursor next;
    const std::string line(script->line_at(c, &next));
    if (gantry::parse_simple_command(line, script->name(), c.line, &fast)) {
      const std::string why = gantry::testing::simple_command_mismatch(
          fast, gantry::parse_line(line, script->name(), c.line));
      if (!why.empty()) {
        std::fprintf(stderr, "simple command read differently: %s\n  line: %s\n", why.c_str(),
                     line.c_str());
        std::abort();
      }
    }
    if (gantry::parse_common_statement(line, script->name(), c.line, &common)) {
      const std::string why = gantry::testing::common_statement_mismatch(
          common, gantry::parse_line(line, script->name(), c.line));
      if (!why.empty()) {
        std::fprintf(stderr, "common statement read differently: %s\n  line: %s\n", why.c_str(),
                     line.c_str());
        std::abort();
      }
    }
    c = next;
  }
  gantry::NullSink sink;
  std::string printed;
  gantry::ScriptedIO io(true, {}, &printed);
  gantry::PersistentStore store;  // in memory: never saved
  gantry::InterpreterOptions opt;
  opt.dry_run = true;           // no files written, no programs started
  opt.statement_budget = 2000;  // loops end quickly
  gantry::Interpreter interp(settings, sink, io, store, opt);
  interp.check(script);
  return 0;
}
