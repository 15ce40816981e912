// The machine's state kept across sessions: position, zero offsets and units, saved at every
// rest and at exit, restored at start (docs/machine_state.md).
#pragma once

#include <array>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>

#include "gantry/core/axes.hpp"           // Vec6
#include "gantry/machine/controller.hpp"  // Controller
#include "gantry/settings/settings.hpp"   // Units

namespace gantry::session {

// What the state file holds.
struct SavedMachine {
  bool moving = false;     // written before each motion, cleared at rest: true = killed mid-move
  // False once the position is suspect (a kill mid-move, an E-stop or card fault, an
  // unreadable file) until it is homed, set by ZT, or the operator confirms it.
  bool confirmed = true;
  std::string why;         // unconfirmed: why, for the operator
  Units units = Units::Inches;
  Vec6 table = Vec6::Zero();  // where the tool is, table base coordinates
  Vec6 zero = Vec6::Zero();   // where working 0 is, table base coordinates (Z2, ZX, ZZ...)
  int system = 0;             // G-code's work system, G54 (0) .. G59.3 (8)
  std::array<Vec6, 9> work_origin{};  // their origins, table base coordinates
  Vec6 g92 = Vec6::Zero();            // G92's axis offset
  std::string saved_at;               // UTC, ISO 8601 (for the operator)
  SavedMachine() {
    for (Vec6& v : work_origin) v.setZero();
  }
};

// The state file next to the values file: values/NAME.toml -> values/NAME.state.toml.
std::string machine_state_path(const std::string& values_path);
// The file's text (TOML), and back: nullopt with `why` (located: line and column) when it is
// not a state file.
std::string machine_state_text(const SavedMachine& m);
std::optional<SavedMachine> parse_machine_state(std::string_view text, std::string* why);

// Keeps one live machine's state file. load() at start, attach() to the controller (it
// restores and then saves at every start of motion and every rest), save() at exit.
class MachineMemory {
 public:
  explicit MachineMemory(std::string path) : path_(std::move(path)) {}
  // Reads the file: the operator's message (restored, unconfirmed and why, or a fresh start
  // and why). A missing or unreadable file is a fresh start, never an error.
  std::string load(Units units_now);
  // load() found no file (the first start): the position starts at 0 as it always did, and
  // the front ends say nothing.
  bool first_start() const {
    std::lock_guard lock(m_);
    return first_start_;
  }
  // The loaded position and offsets written into `st`, the card's counts at `machine` (the
  // check before a run starts from them too). Nothing when nothing was loaded.
  void restore(ModalState& st, const Vec6& machine) const;
  // Restores the loaded position into the controller (idle) and saves from then on.
  // `also`: told each activity too (the part-file log), after the save.
  void attach(Controller& c, std::function<void(const Controller::Activity&)> also = {});
  // Writes the last state at rest (exit). False (with `why`) when it cannot be written.
  bool save(std::string* why = nullptr);
  SavedMachine state() const;
  bool restoring() const {  // load() found a position that attach() has yet to restore
    std::lock_guard lock(m_);
    return loaded_.has_value();
  }
  const std::string& path() const { return path_; }
  // The operator's confirmation: the position is right (SB3: "keep the location").
  // Returns what to tell the operator (the console and the window say the same).
  std::string confirm();

 private:
  void activity(const Controller::Activity& a);
  bool write(const SavedMachine& m, std::string* why);

  std::string path_;
  mutable std::mutex m_;
  SavedMachine now_;
  std::optional<SavedMachine> loaded_;  // to restore at attach
  bool first_start_ = false;
  std::string last_written_;  // the last save's text without its time (unchanged: no write)
  Vec6 origin_at_start_ = Vec6::Zero();  // the activity's machine_origin when it began
  Units units_at_start_ = Units::Inches;  // ... and its units
};

// CONFIRM typed at a front end: `memory`'s confirm(), or, when no state is kept (null), that
// there is nothing to confirm.
std::string confirm_position(MachineMemory* memory);

}  // namespace gantry::session
