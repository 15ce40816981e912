// libFuzzer target: any bytes as the persistent $variables file. Must never crash or trip a
// sanitizer; a file that loads must save as text that loads again to the same values (text
// that is not UTF-8 included).
#include <cstddef>
#include <cstdint>
#include <cstdio>   // the failed check, before aborting
#include <cstdlib>  // abort
#include <string>

#include "gantry/interp/persistent_file.hpp"  // parse_persistent_file, persistent_file_text

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::string why;
  int line = 0;
  const std::optional<nlohmann::json> values = gantry::parse_persistent_file(text, &why, &line);
  if (!values) return 0;
  const std::string saved = gantry::persistent_file_text(*values);
  const std::optional<nlohmann::json> again = gantry::parse_persistent_file(saved, &why, &line);
  if (!again || *again != *values) {
    std::fprintf(stderr, "a saved persistent file does not read back as itself (%s):\n%s\n",
                 why.c_str(), saved.c_str());
    std::abort();
  }
  return 0;
}
