// The live machine's assembly for the console and the window, and keeping the values the
// runs leave in force.
#include "gantry/session/live_machine.hpp"

#include <fmt/format.h>  // the error

#include "gantry/core/text_file.hpp"        // read_text_file, write_file_atomically
#include "gantry/session/open_card.hpp"     // open_card, plays_in_real_time
#include "gantry/session/pendant_profile.hpp"  // pendant_profile
#include "gantry/settings/values_file.hpp"  // values_text

namespace gantry::session {

void ValuesKeeper::ran(const Settings& s) {
  {
    std::lock_guard lock(m_);
    now_ = s;
  }
  const std::string text = values_text(s, profile_.bare);
  if (read_text_file(profile_.values_path) == text) return;
  if (std::string why; !write_file_atomically(profile_.values_path, text, &why))
    io_.warn({file_loc(profile_.values_path), Severity::Warning,
              fmt::format("cannot save the values this line changed ({}); the previous values "
                          "file is kept",
                          why)});
}

Settings ValuesKeeper::settings() const {
  std::lock_guard lock(m_);
  return now_;
}

InterpreterOptions live_interpreter_options(const MachineProfile& p, ValuesKeeper& values,
                                            const LiveMachineOptions& a, bool real_time) {
  InterpreterOptions opt;
  opt.allow_shell = a.allow_shell;
  opt.macro_dir = a.macros;
  opt.subroutine_dirs = a.subroutines;  // the Interpreter adds the profile's after
  opt.allowed_folders = allowed_folders(p, a.allow_paths);
  opt.warn_before_motion = real_time;
  opt.trig_in_degrees = opt.plus_joins_text = p.settings.dialect == Dialect::FabMo;
  opt.profile = &p.bare;
  opt.profile_path = p.path;
  opt.values_path = p.values_path;
  opt.save_values = [&values](const Settings& s) { values.ran(s); };
  return opt;
}

std::unique_ptr<Card> open_live_card(const LiveMachineOptions& a, const Settings& settings,
                                     std::string* type) {
  CardChoice choice;
  choice.type = a.card.empty() ? settings.card.type : a.card;
  choice.realtime = a.realtime;
  choice.world = simulated_world(settings);  // the profile's switches and Z zero plate
  *type = choice.type;
  std::string why;
  std::unique_ptr<Card> card = open_card(choice, settings, &why);
  if (!card) fmt::print(stderr, "error: cannot open the {} card: {}\n", choice.type, why);
  return card;
}

std::unique_ptr<LiveMachine> LiveMachine::open(const LiveMachineOptions& a, const MachineProfile& p,
                                               OperatorIO& io) {
  auto m = std::unique_ptr<LiveMachine>(new LiveMachine{
      PersistentStore(a.persistent.empty() ? PersistentStore::default_path() : a.persistent),
      ValuesKeeper(p, io),
      {},
      nullptr,
      false,
      nullptr,
      nullptr,
      {},
      nullptr,
      nullptr,
      nullptr,
      {}});
  m->card = open_live_card(a, p.settings, &m->card_type);
  if (!m->card) return nullptr;
  m->real_time = plays_in_real_time(m->card_type, a.realtime);
  m->controller = std::make_unique<Controller>(
      p.settings, *m->card, io, m->store, live_interpreter_options(p, m->values, a, m->real_time));
  m->memory = std::make_unique<MachineMemory>(machine_state_path(p.values_path));
  m->part_log = std::make_unique<RunLogger>(run_log_path(p.values_path));
  m->restored = m->memory->load(p.settings.units);
  const session::SavedMachine last = m->memory->state();
  m->part_log->close_unfinished(&last);  // runs a kill cut short get their end line
  if (!m->memory->first_start()) io.warn({SourceLoc{}, Severity::Warning, m->restored});
  LiveMachine& live = *m;
  m->memory->attach(*m->controller, [&live](const Controller::Activity& act) {
    if (live.values.settings().display.part_file_log) live.part_log->activity(act);
  });
  std::vector<Diagnostic> problems;  // bad key bindings, at their line: told, then left out
  PendantProfile pp = pendant_profile(p.settings, p.path, &problems);
  for (const Diagnostic& d : problems) io.warn(d);
  m->keys = std::move(pp.keys);
  m->pendant = std::make_unique<PendantService>(
      *m->controller, [&live] { return live.values.settings(); }, std::move(pp.buttons),
      [&io](const std::string& text) { io.warn({SourceLoc{}, Severity::Warning, "pendant: " + text}); },
      pendant::open_libusb_port(nullptr));
  if (const PendantSettings& ps = p.settings.pendant; ps.gamepad != "off") {
    std::string error;
    if (auto b = GamepadBindings::parse(ps.gamepad_jog, ps.gamepad_buttons, &error))
      m->gamepad = std::make_unique<GamepadService>(
          ps.gamepad, std::move(*b),
          [&live](const PendantEvent& e) { live.pendant->input().handle(e); },
          [&io](const std::string& text) {
            io.warn({SourceLoc{}, Severity::Warning, "pendant: " + text});
          });
    else
      io.warn({SourceLoc{}, Severity::Error,
               "profile: " + error + "; the gamepad is not used until this is put right"});
  }
  return m;
}

LiveMachine::~LiveMachine() {
  gamepad.reset();  // the gamepad sends into the pendant's input: it goes first
  pendant.reset();  // no pendant event reaches the controller as it goes
  controller.reset();  // its threads end: nothing moves after the last save
  if (memory) memory->save();
}

}  // namespace gantry::session
