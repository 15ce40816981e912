// libFuzzer target: any bytes as a whole G-code file (deep nesting, long files), loaded and
// checked by a dry-run interpreter. Must never crash, hang or trip a sanitizer; every error
// it reports must be located in the file and must show as JSON.
#include <cstddef>
#include <cstdint>
#include <cstdio>   // the failed check, before aborting
#include <cstdlib>  // abort
#include <string>

#include <nlohmann/json.hpp>

#include "../support/null_sink.hpp"       // NullSink
#include "gantry/core/any_bytes.hpp"      // json_text
#include "gantry/interp/interpreter.hpp"  // Interpreter
#include "gantry/lang/script.hpp"         // Script

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const gantry::Settings settings = gantry::default_settings();
  std::string text(reinterpret_cast<const char*>(data), size);
  int lines = 1;  // line breaks as a Script reads them: \n, \r\n or a lone \r
  for (std::size_t i = 0; i < text.size(); ++i)
    lines += text[i] == '\n' || (text[i] == '\r' && (i + 1 == text.size() || text[i + 1] != '\n'));
  auto script = gantry::Script::from_text(std::move(text), "/nonexistent/fuzz.nc");
  gantry::NullSink sink;
  std::string printed;
  gantry::ScriptedIO io(true, {}, &printed);
  gantry::PersistentStore store;  // in memory: never saved
  gantry::InterpreterOptions opt;
  opt.dry_run = true;
  opt.statement_budget = 2000;
  gantry::Interpreter interp(settings, sink, io, store, opt);
  for (const gantry::Diagnostic& d : interp.check(script)) {
    if (d.loc.line > lines) {
      std::fprintf(stderr, "error placed on line %d of a %d-line file: %s\n", d.loc.line, lines,
                   gantry::format(d).c_str());
      std::abort();
    }
    (void)gantry::json_text(nlohmann::json{{"message", d.message}});  // must not throw
  }
  return 0;
}
