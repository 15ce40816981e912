// The machine's state kept across sessions: the state file's text, its reading, and saving
// it at every start of motion and every rest.
#include "gantry/session/machine_memory.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <sstream>
#include <toml++/toml.h>

#include "gantry/core/text_file.hpp"  // read_text_file, write_file_atomically
#include "gantry/core/utc_time.hpp"   // utc_timestamp

namespace gantry::session {
namespace {

constexpr std::array<const char*, 9> kSystems{"g54", "g55", "g56", "g57", "g58",
                                              "g59", "g59_1", "g59_2", "g59_3"};

toml::table axes_table(const Vec6& v) {  // { x = 1.0, y = 0.0, ... } on one line
  toml::table t;
  for (int i = 0; i < kAxisCount; ++i) t.insert(std::string(1, kAxisLetters[i]), v[i]);
  t.is_inline(true);
  return t;
}

// `t[key]`: six axes x..c, each a number (missing: 0).
bool read_axes(const toml::table& t, std::string_view key, Vec6& out, std::string* why) {
  out.setZero();
  const toml::node* n = t.get(key);
  if (!n) return true;
  const toml::table* axes = n->as_table();
  if (!axes) {
    *why = fmt::format("line {}: [{}] must be a table of axes x, y, z, a, b, c",
                       n->source().begin.line, key);
    return false;
  }
  for (const auto& [k, v] : *axes) {
    const std::string name(k.str());
    const std::size_t i = std::string_view(kAxisLetters.data(), kAxisCount).find(name);
    const std::optional<double> d = v.value<double>();
    if (name.size() != 1 || i == std::string_view::npos || !d || !std::isfinite(*d)) {
      *why = fmt::format("line {}: {}.{} must be an axis x, y, z, a, b or c with a number",
                         v.source().begin.line, key, name);
      return false;
    }
    out[static_cast<int>(i)] = *d;
  }
  return true;
}

std::string axes_text(const Vec6& v) {
  return fmt::format("X {:.4f} Y {:.4f} Z {:.4f}", v[0], v[1], v[2]) +
         (v.tail<3>().isZero() ? "" : fmt::format(" A {:.4f} B {:.4f} C {:.4f}", v[3], v[4], v[5]));
}

}  // namespace

std::string machine_state_path(const std::string& values_path) {
  std::filesystem::path p(values_path);
  if (p.extension() == ".toml") p.replace_extension();
  return p.string() + ".state.toml";
}

std::string machine_state_text(const SavedMachine& m) {
  toml::table t;
  t.insert("motion", m.moving ? "moving" : "at rest");
  t.insert("confirmed", m.confirmed);
  if (!m.confirmed && !m.why.empty()) t.insert("why", m.why);
  t.insert("units", units_name(m.units));
  t.insert("saved_at", m.saved_at);
  t.insert("position", axes_table(m.table));
  t.insert("zero", axes_table(m.zero));
  toml::table g;
  g.insert("system", kSystems[static_cast<std::size_t>(std::clamp(m.system, 0, 8))]);
  for (std::size_t i = 0; i < kSystems.size(); ++i) g.insert(kSystems[i], axes_table(m.work_origin[i]));
  g.insert("g92", axes_table(m.g92));
  t.insert("gcode", g);
  std::ostringstream out;
  out << "# Gantry's machine state, kept across sessions (docs/machine_state.md). Written\n"
         "# before each motion (motion: moving) and at every rest (at rest); lengths in\n"
         "# `units`, positions in table base coordinates. Delete it to start at 0.\n"
      << toml::toml_formatter(t, toml::format_flags::none) << "\n";
  return out.str();
}

std::optional<SavedMachine> parse_machine_state(std::string_view text, std::string* why) {
  toml::table t;
  try {
    t = toml::parse(text);
  } catch (const toml::parse_error& e) {
    *why = fmt::format("line {}, column {}: {}", e.source().begin.line, e.source().begin.column,
                       e.description());
    return std::nullopt;
  }
  SavedMachine m;
  const std::optional<std::string> motion = t["motion"].value<std::string>();
  if (!motion || (*motion != "moving" && *motion != "at rest")) {
    *why = "motion must be \"moving\" or \"at rest\"";
    return std::nullopt;
  }
  m.moving = *motion == "moving";
  const std::optional<bool> confirmed = t["confirmed"].value<bool>();
  if (!confirmed) {
    *why = "confirmed must be true or false";
    return std::nullopt;
  }
  m.confirmed = *confirmed;
  m.why = t["why"].value_or(std::string());
  const std::optional<std::string> units = t["units"].value<std::string>();
  if (units != "in" && units != "mm") {
    *why = "units must be \"in\" or \"mm\"";
    return std::nullopt;
  }
  m.units = *units == "mm" ? Units::Millimetres : Units::Inches;
  m.saved_at = t["saved_at"].value_or(std::string());
  if (!t.contains("position")) {
    *why = "no [position]";
    return std::nullopt;
  }
  if (!read_axes(t, "position", m.table, why) || !read_axes(t, "zero", m.zero, why))
    return std::nullopt;
  if (const toml::table* g = t["gcode"].as_table()) {
    const std::string system = (*g)["system"].value_or(std::string("g54"));
    const auto it = std::find(kSystems.begin(), kSystems.end(), system);
    if (it == kSystems.end()) {
      *why = fmt::format("gcode.system {} is no work system (g54 .. g59_3)", system);
      return std::nullopt;
    }
    m.system = static_cast<int>(it - kSystems.begin());
    for (std::size_t i = 0; i < kSystems.size(); ++i)
      if (!read_axes(*g, kSystems[i], m.work_origin[i], why)) return std::nullopt;
    if (!read_axes(*g, "g92", m.g92, why)) return std::nullopt;
  }
  return m;
}

std::string MachineMemory::load(Units units_now) {
  std::lock_guard lock(m_);
  now_ = SavedMachine{};
  now_.units = units_now;
  now_.confirmed = true;  // nothing suspect: the tool is where the operator left it, at 0
  std::error_code ec;
  first_start_ = !std::filesystem::exists(path_, ec);
  if (first_start_)
    return fmt::format("no machine state saved yet ({}): the position starts at 0; home (C3) "
                       "to set it",
                       path_);
  const std::optional<std::string> text = read_text_file(path_);
  std::string why = "cannot read it";
  const std::optional<SavedMachine> m = text ? parse_machine_state(*text, &why) : std::nullopt;
  if (!m) {
    now_.confirmed = false;
    now_.why = "the state file was unreadable";
    return fmt::format("{}: not a machine state file ({}); starting afresh: the position starts "
                       "at 0, unconfirmed; home (C3) to set it (the file is replaced at the "
                       "next rest)",
                       path_, why);
  }
  if (m->units != units_now) {
    now_.confirmed = false;
    now_.why = "the state file's units were not the machine's";
    return fmt::format("{}: the position was saved in {} but the machine is in {}: not "
                       "restored; the position starts at 0; home (C3) to set it",
                       path_, units_name(m->units), units_name(units_now));
  }
  loaded_ = *m;
  now_ = *m;
  SavedMachine as_read = *m;
  as_read.saved_at.clear();
  last_written_ = machine_state_text(as_read);  // an exit with nothing changed writes nothing
  if (m->moving) {
    now_.confirmed = false;
    now_.why = "the last session ended mid-move (killed, crashed or powered off while moving)";
  }
  now_.moving = false;
  const std::string where = fmt::format("{} ({}, table base; zero at {})", axes_text(m->table),
                                        units_name(m->units), axes_text(m->zero));
  if (now_.confirmed)
    return fmt::format("position restored from the last session: {}; home to confirm", where);
  return fmt::format("position restored from the last session: {}; UNCONFIRMED: {}; home (C3) "
                     "or set it (ZT) before cutting",
                     where, now_.why);
}

void MachineMemory::restore(ModalState& st, const Vec6& machine) const {
  std::lock_guard lock(m_);
  if (!loaded_) return;
  const SavedMachine& m = *loaded_;
  st.zero = m.zero;
  st.machine_origin = machine - m.table;  // the card counts from where it was opened
  st.position = m.table - st.zero - st.applied_offset;
  st.gcode.system = m.system;
  st.gcode.origin = m.work_origin;
  st.gcode.axis_offset = m.g92;
}

void MachineMemory::attach(Controller& c, std::function<void(const Controller::Activity&)> also) {
  c.restore([&](ModalState& st, const Vec6& machine) { restore(st, machine); });
  {
    std::lock_guard lock(m_);
    loaded_.reset();  // restored once
  }
  c.on_activity([this, also = std::move(also)](const Controller::Activity& a) {
    activity(a);
    if (also) also(a);
  });
}

void MachineMemory::activity(const Controller::Activity& a) {
  SavedMachine m;
  {
    std::lock_guard lock(m_);
    const ModalState& st = a.modal;
    now_.moving = !a.at_rest;
    now_.units = a.units;
    now_.table = st.position + st.zero + st.applied_offset;
    now_.zero = st.zero;
    now_.system = st.gcode.system;
    now_.work_origin = st.gcode.origin;
    now_.g92 = st.gcode.axis_offset;
    if (!a.at_rest) {
      origin_at_start_ = st.machine_origin;
      units_at_start_ = a.units;
    } else if (a.estop) {
      now_.confirmed = false;
      now_.why = "an E-stop (or a card fault) stopped the pulses at once";
    } else if (!a.error && !st.machine_origin.isApprox(origin_at_start_, 1e-12) &&
               a.units == units_at_start_) {  // a change of units scales the origin
      now_.confirmed = true;  // homed, or table base set (ZT, VA): the operator placed it
      now_.why.clear();
    }
    m = now_;
  }
  std::string why;
  write(m, &why);  // a failure leaves the last file: the next rest tries again
}

bool MachineMemory::save(std::string* why) {
  SavedMachine m;
  {
    std::lock_guard lock(m_);
    now_.moving = false;
    m = now_;
  }
  std::string w;
  return write(m, why ? why : &w);
}

bool MachineMemory::write(const SavedMachine& m, std::string* why) {
  SavedMachine out = m;
  out.saved_at.clear();
  std::string same = machine_state_text(out);
  {
    std::lock_guard lock(m_);
    if (same == last_written_) return true;  // unchanged since the last save: no write
  }
  out.saved_at = utc_timestamp();
  std::error_code ec;
  std::filesystem::create_directories(std::filesystem::path(path_).parent_path(), ec);
  if (!write_file_atomically(path_, machine_state_text(out), why)) return false;
  std::lock_guard lock(m_);
  last_written_ = std::move(same);
  return true;
}

SavedMachine MachineMemory::state() const {
  std::lock_guard lock(m_);
  return now_;
}

std::string MachineMemory::confirm() {
  bool was;
  {
    std::lock_guard lock(m_);
    was = now_.confirmed;
    now_.confirmed = true;
    now_.why.clear();
  }
  save();
  return was ? "the position was confirmed already"
             : "the position is confirmed: the tool is where the readout says";
}

std::string confirm_position(MachineMemory* memory) {
  return memory ? memory->confirm() : "nothing to confirm: no machine state is kept";
}

}  // namespace gantry::session
