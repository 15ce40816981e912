// libFuzzer target: any bytes as the persistent $variables file. Must never crash or trip a
// sanitizer; a file that loads must save as text that loads again to the same values (text
// that is not UTF-8 included).
#include <cstddef>
#include <cstdint>
#include <cstdio>   // the failed check, before aborting
#include <cstdlib>  // abort
#include <string>

#include "gantry/interp/persistent_store.hpp"  // PersistentStore::parse, text

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::string why;
  int line = 0;
  const std::optional<gantry::PersistentStore> store =
      gantry::PersistentStore::parse(text, &why, &line);
  if (!store) return 0;
  const std::string saved = store->text();
  const std::optional<gantry::PersistentStore> again =
      gantry::PersistentStore::parse(saved, &why, &line);
  if (!again || again->text() != saved) {
    std::fprintf(stderr, "a saved persistent file does not read back as itself (%s):\n%s\n",
                 why.c_str(), saved.c_str());
    std::abort();
  }
  return 0;
}
