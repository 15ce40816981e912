// How an Interpreter runs: dialect, dry run, files and their reach, budgets, the operator.
#pragma once

#include <atomic>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "gantry/core/vec6.hpp"          // Vec6
#include "gantry/core/text_file.hpp"     // user_config_dir
#include "gantry/interp/file_system.hpp"  // FileSystem, user_macro_folder
#include "gantry/lang/script.hpp"         // Language
#include "gantry/settings/settings.hpp"   // Settings

namespace gantry {

struct InterpreterOptions {
  // --language: the top-level file is read as this language whatever its name (nullopt: by
  // its extension and first line, file_language). Files it calls go by their own names.
  std::optional<Language> language;
  bool trig_in_degrees = false;  // dialect "fabmo"
  bool plus_joins_text = false;  // dialect "fabmo": "Offset: " + &z is text
  bool allow_shell = false;      // SHELL runs programs only when allowed
  bool dry_run = false;          // check: no programs started; files (unless `files`
                                 // is given) in a sandbox, so nothing is written
  FileSystem* files = nullptr;   // where files are read and written; null: the disk
  bool operator_present = true;  // check: someone will answer PAUSE/INPUT in the run
  // SW's warning before a run's first motion (the wait, and switch 4 in its automatic modes):
  // where someone may stand at the machine (a real card, the simulated one in real time).
  // Virtual time has nobody to warn, and its cycle times leave the wait out.
  bool warn_before_motion = false;
  // 0: unlimited. A check runs at most this many statements more than the file has lines;
  // past them the file loops (an error).
  std::size_t statement_budget = 0;
  // Set from another thread (a signal, the operator's stop): a check or a run stops before
  // its next statement, so even a loop that moves nothing ends.
  const std::atomic<bool>* stop_check = nullptr;
  // Where C<n> finds its files (docs/language.md, "Custom cuts"): `macro_dir` (--macros),
  // else the parts folder and then `user_macro_dir`; last `shipped_macro_dir`, Gantry's own
  // C6, C7, C9... ("" leaves a folder out).
  std::string macro_dir;
  std::string user_macro_dir = user_macro_folder();
  std::string shipped_macro_dir = shipped_macro_folder();
  // A part file's reach (docs/security.md): besides its job's folder, it reads and writes in
  // `data_dir` (Gantry's data folder) and `allowed_folders` (the profile's [files] allow and
  // --allow-path), and reads the macro folders above.
  std::string data_dir = user_config_dir();
  std::vector<std::string> allowed_folders;
  int max_file_depth = 8;  // FP nesting, the top-level file included
  // The top-level file's first line to run (0 or 1: all of it): the lines before it run
  // without motion, output or questions, then the tool approaches where they leave it
  // (docs/language.md, "Starting at a line").
  int start_line = 0;
  int max_gosub_depth = 256;
  // Where `o<name> call` finds name.ngc when the calling file does not define the subroutine:
  // the calling file's folder, then these (--subroutines), then the profile's `subroutines`;
  // a part file reads them as it reads the macro folders (docs/security.md).
  std::vector<std::string> subroutine_dirs;
  // Called when a run ends (not in a dry run) with the settings as the run leaves them:
  // file-scoped values undone, the speeds MS/JS left in force. The job saves the values.
  std::function<void(const Settings&)> save_values;
  // What UV and UD show and UR loads: the machine profile without the operator's values
  // (null: the built-in default), the file it came from ("": built in), the values file.
  const Settings* profile = nullptr;
  std::string profile_path;
  std::string values_path;
  // The profile's name, for the soft limits' message, which then also lists the shipped
  // profiles whose table holds the move ("": the message names no profile).
  std::string profile_name;
  // With nobody at the machine (--yes, a check): whether anything but a person brings input
  // switch `n` (1-12) to `closed` while the tool rests: the simulated machine's events, and in
  // a check (`check_at`: where the dry run has the tool, machine coordinates) its switches
  // there. On the live machine (nullopt) only an event still to come. Null: the machine's
  // inputs are unknown (a real card's sensors may change them): PAUSE UNTIL waits.
  std::function<bool(int n, bool closed, const std::optional<Vec6>& check_at)> unattended_inputs;
  // Friendly Motion (docs/friendlymotion.md, "Flow"): a run starts in STEP mode, the operator
  // starting each line, as after an M0 (`gantry run --step`).
  bool fm_step = false;
  // Friendly Motion's hot keys: the Alt-F key (1-10) the operator pressed since the last
  // call, 0 for none (taken once). A run polls it before each line and calls N10001-N10010.
  std::function<int()> fm_hot_key;
};

}  // namespace gantry
