// libFuzzer target: any bytes as a part file, through the parser, the expression evaluator
// and a dry-run interpreter. Must never crash, hang or trip a sanitizer.
#include <cstddef>
#include <cstdint>
#include <string>

#include "gantry/interp/interpreter.hpp"  // Interpreter
#include "gantry/lang/script.hpp"         // Script

namespace {

class NullSink : public gantry::MotionSink {
 public:
  void move(const gantry::CanonMove&) override {}
  void flush() override {}
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const gantry::Settings settings = gantry::default_settings();
  std::string text(reinterpret_cast<const char*>(data), size);
  auto script = gantry::Script::from_text(std::move(text), "/nonexistent/fuzz.sbp");
  NullSink sink;
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
