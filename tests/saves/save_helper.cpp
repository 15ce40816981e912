// Saves one kind of file, once or for ever, for the kill-during-save test: the test starts
// it, SIGKILLs it at a random moment and looks at what is on disk.
//   gantry_save_helper KIND FOLDER VARIANT         save variant 0 or 1 once
//   gantry_save_helper KIND FOLDER VARIANT loop    save variants VARIANT, 1-VARIANT, ... for ever,
//                                                  writing a byte to fd 3 after each save
// KIND: writer (write_file_atomically itself, 200 KB), settings (US in a run), values (a
// run's MS, saved in the values file), variables (a run's $variable, saved in the persistent
// file). Each save goes through the same code as `gantry run`'s: run_job on the simulated card.
#include <unistd.h>  // write

#include <cstdio>
#include <string>

#include "gantry/core/text_file.hpp"  // write_file_atomically
#include "gantry/interp/operator_io.hpp"
#include "gantry/lang/script.hpp"
#include "gantry/machine/job.hpp"
#include "sim/sim_card.hpp"

namespace {

using namespace gantry;

// The part file a run of `kind` saves with, variant 0 or 1.
std::string part_file(const std::string& kind, int variant) {
  const std::string speed = variant == 0 ? "1" : "2";
  if (kind == "settings") return "MS, " + speed + "\nUS, settings.toml\n";  // beside the part
  if (kind == "values") return "MS, " + speed + "\n";  // MS stays when the file ends
  // variables: a long text, so that a kill often lands while it is written
  return "$TEXT = \"" + std::string(variant == 0 ? 20000 : 30000, variant == 0 ? 'a' : 'b') +
         "\"\n";
}

bool save(const std::string& kind, const std::string& folder, int variant) {
  if (kind == "writer")
    return write_file_atomically(folder + "/writer.txt",
                                 std::string(variant == 0 ? 200000 : 150000, "ab"[variant]));
  static const Settings profile = default_settings();
  SimCard card(profile);
  ScriptedIO io(true, {}, nullptr, stderr);
  PersistentStore store(folder + "/persistent.json");
  JobOptions options;
  options.values_path = folder + "/values.toml";
  options.profile = &profile;
  const JobResult r = run_job(Script::from_text(part_file(kind, variant), folder + "/save.sbp"),
                              profile, card, io, store, options);
  for (const Diagnostic& d : r.errors) std::fprintf(stderr, "%s\n", format(d).c_str());
  for (const Diagnostic& d : r.warnings) std::fprintf(stderr, "%s\n", format(d).c_str());
  return r.ok() && r.warnings.empty();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: %s writer|settings|values|variables FOLDER 0|1 [loop]\n", argv[0]);
    return 2;
  }
  const std::string kind = argv[1], folder = argv[2];
  int variant = std::stoi(argv[3]) != 0;
  const bool loop = argc > 4 && std::string(argv[4]) == "loop";
  do {
    if (!save(kind, folder, variant)) return 1;
    if (loop && ::write(3, "s", 1) != 1) return 1;  // tells the test (fd 3: its pipe)
    variant = 1 - variant;
  } while (loop);
  return 0;
}
