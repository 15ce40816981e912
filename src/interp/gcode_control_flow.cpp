// G-code's O-words (docs/gcode.md, "O-words"): subroutines, if, loops, with LinuxCNC 2.9's
// semantics; Fanuc's M98/M99 subprograms and WinCNC's `M98 file`. The load pass paired every
// block's lines (Script::oword_link), so each jump here is one lookup.
#include <fmt/format.h>  // messages

#include <cmath>       // lround
#include <filesystem>  // the subroutine files' folders

#include "gantry/core/file_problem.hpp"  // shown_path
#include "gantry/interp/gcode_executor.hpp"
#include "interp_private.hpp"  // Frame, GcodeFlow

namespace gantry {
namespace {

// LinuxCNC's INTERP_SUB_ROUTINE_LEVELS: the main program and 9 nested calls.
constexpr size_t kMaxCallDepth = 9;

std::string shown(const std::string& name) {
  return !name.empty() && name[0] >= '0' && name[0] <= '9' ? "o" + name : "o<" + name + ">";
}

SourceLoc at_column(const SourceLoc& loc, int column) {
  SourceLoc l = loc;
  l.column = column;
  return l;
}

}  // namespace

// Calls whose frame has ended (M2 in a subroutine, a file's end) are closed.
void Interpreter::gcode_drop_stale_calls() {
  GcodeFlow& g = *gcode_flow_;
  while (!g.calls.empty() && g.calls.back().frame >= frames_.size()) {
    g.repeats.resize(std::min(g.repeats.size(), g.calls.back().repeats_base));
    g.calls.pop_back();
    gcode_->leave_call();
  }
}

void Interpreter::push_gcode_frame(std::shared_ptr<const Script> script, Cursor pc,
                                   const SourceLoc& from, bool restore_g92) {
  if (static_cast<int>(frames_.size()) >= options_.max_file_depth)
    fail(from, fmt::format("files are nested {} deep, the most allowed; a file may be calling "
                           "itself",
                           options_.max_file_depth));
  // The G-code modes go on: a subroutine's file is part of its caller's program.
  Frame f;
  f.script = std::move(script);
  f.pc = pc;
  f.called_from = from;
  f.saved_speeds = state_.speeds;
  f.transform = frames_.back().transform;
  f.plunge_start_z = state_.position[2];
  frames_.push_back(std::move(f));
  gcode_->enter_file(restore_g92);  // end_file's leave_file pops what this pushes
}

void Interpreter::gcode_flow(const GcodeBlock& b, const SourceLoc& loc) {
  if (!b.call_file.empty()) return gcode_call_file(b, loc);
  Frame& f = frames_.back();
  const GcodeOword& o = b.oword;
  const SourceLoc at = at_column(loc, o.column);
  if (!f.script->gcode())
    fail(at, "O-words work in G-code files only; in an OpenSBP file use IF, GOTO and GOSUB");
  gcode_drop_stale_calls();
  GcodeFlow& g = *gcode_flow_;
  const OwordLink* link = f.script->oword_link(current_.offset);
  const bool linked = link && link->complete;
  auto test = [&] { return gcode_->value(b, 0, o.args.at(0), loc) != 0; };
  auto branch_to = [&](Cursor c) {
    g.branch_script = f.script.get();
    g.branch_offset = c.offset;
    f.pc = c;
  };
  const bool branch_here = g.branch_script == f.script.get() && g.branch_offset == current_.offset;
  if (branch_here) g.branch_script = nullptr;
  switch (o.kind) {
    case OwordKind::None:
    case OwordKind::Program:  // Fanuc's program number: reached, it does nothing (as rs274)
    case OwordKind::Do:
    case OwordKind::Endif:
      return;
    case OwordKind::Sub:  // a definition: skipped until called
      if (linked) f.pc = link->end;
      return;
    case OwordKind::Endsub:
    case OwordKind::Return:
      return gcode_return(b, loc);
    case OwordKind::Call:
      return gcode_call(b, loc);
    case OwordKind::If:
      if (linked && !test()) branch_to(link->jump);
      return;
    case OwordKind::Elseif:
      if (!linked) return;
      if (!branch_here)
        f.pc = link->end;  // the branch before it ran
      else if (!test())
        branch_to(link->jump);
      return;
    case OwordKind::Else:
      if (linked && !branch_here) f.pc = link->end;
      return;
    case OwordKind::While:
      if (!linked) return;
      if (link->closes_do ? test() : !test()) {
        f.pc = link->jump;
        g.hot = link->closes_do || !g.calls.empty();
      } else if (link->closes_do) {
        g.hot = !g.calls.empty();  // the do loop ends
      }
      return;
    case OwordKind::Endwhile:
    case OwordKind::Continue:
      if (linked) f.pc = link->jump;
      g.hot = true;
      return;
    case OwordKind::Break:
      if (linked) f.pc = link->jump;
      g.hot = !g.calls.empty();
      return;
    case OwordKind::Repeat: {
      if (!linked) return;
      const double n = gcode_->value(b, 0, o.args.at(0), loc);
      const size_t base = g.calls.empty() ? 0 : g.calls.back().repeats_base;
      // Entered again (a loop around it went on without it ending): the old count goes.
      for (size_t i = g.repeats.size(); i-- > base;)
        if (g.repeats[i].script == f.script.get() && g.repeats[i].offset == current_.offset) {
          g.repeats.resize(i);
          break;
        }
      const long count = std::isfinite(n) ? std::lround(n) : 0;
      if (count <= 0) {
        f.pc = link->jump;
        return;
      }
      g.hot = true;
      g.repeats.push_back({f.script.get(), current_.offset, count - 1});
      return;
    }
    case OwordKind::Endrepeat: {
      if (!linked) return;
      const size_t base = g.calls.empty() ? 0 : g.calls.back().repeats_base;
      for (size_t i = g.repeats.size(); i-- > base;) {
        GcodeFlow::Repeat& r = g.repeats[i];
        if (r.script != f.script.get() || r.offset != link->end.offset) continue;
        if (r.left > 0) {
          --r.left;
          g.repeats.resize(i + 1);
          f.pc = link->jump;
        } else {
          g.repeats.resize(i);
          g.hot = !g.calls.empty();
        }
        return;
      }
      return;
    }
  }
}

// The file `name`.ngc in the calling file's folder or a subroutine folder; "" when none has it.
std::string Interpreter::gcode_sub_file(const std::string& name, const SourceLoc& loc) const {
  std::vector<std::string> dirs;
  const Frame& f = frames_.back();
  dirs.push_back(f.script->name() ? std::filesystem::path(*f.script->name()).parent_path().string()
                                  : parts_dir_);
  dirs.insert(dirs.end(), options_.subroutine_dirs.begin(), options_.subroutine_dirs.end());
  for (const std::string& dir : dirs) {
    const PartFileLookup found =
        find_part_file(*files_system_, (std::filesystem::path(dir) / (name + ".ngc")).string());
    if (!found.error.empty()) fail(loc, found.error);
    if (files_system_->is_file(found.path)) {
      check_reach(found.path, FileAccess::Read, loc);
      return found.path;
    }
  }
  return "";
}

void Interpreter::gcode_call(const GcodeBlock& b, const SourceLoc& loc) {
  const GcodeOword& o = b.oword;
  const SourceLoc at = at_column(loc, o.column);
  GcodeFlow& g = *gcode_flow_;
  // The arguments are the caller's values.
  std::vector<double> args;
  for (int e : o.args) args.push_back(gcode_->value(b, 0, e, loc));
  if (gcode_->call_depth() >= kMaxCallDepth)
    fail(at, fmt::format("subroutines are nested {} deep, the most LinuxCNC allows; a "
                         "subroutine may be calling itself without end",
                         kMaxCallDepth));
  Frame* f = &frames_.back();
  std::optional<Cursor> body = f->script->gcode_sub(o.name);
  std::shared_ptr<const Script> file;
  // Subroutines are global, as in LinuxCNC: one a calling file defines serves its callees.
  for (size_t k = frames_.size() - 1; !body && k-- > 0;)
    if (frames_[k].script->gcode() && (body = frames_[k].script->gcode_sub(o.name)))
      file = frames_[k].script;
  if (!body) {
    const std::string path = gcode_sub_file(o.name, at);
    if (path.empty()) {
      std::string where = "the calling file's folder";
      for (const std::string& d : options_.subroutine_dirs) where += ", " + d;
      fail(at, fmt::format("{} call: no {} sub in this file, and no {}.ngc in {}; define it "
                           "(o... sub ... o... endsub), or give its folder with --subroutines or "
                           "the profile's subroutines",
                           shown(o.name), shown(o.name), o.name, where));
    }
    file = frames_.front().script->called(
        path, [&] { return files_system_->load_script(path, table_.is_command()); });
    if (!file->ok())
      for (Diagnostic d : file->errors())
        if (d.severity == Severity::Error) {
          d = located(std::move(d));
          d.via.push_back(at);
          throw GantryError(std::move(d));
        }
    if (!file->gcode() || !(body = file->gcode_sub(o.name)))
      fail(at, fmt::format("{} does not define {} sub: a subroutine file holds {} sub ... {} "
                           "endsub",
                           shown_path(path), shown(o.name), shown(o.name), shown(o.name)));
  }
  GcodeFlow::Call c;
  c.back = f->pc;
  c.repeats_base = g.repeats.size();
  if (file) {
    push_gcode_frame(std::move(file), *body, at, /*restore_g92=*/false);
    c.own_frame = true;
  } else {
    f->pc = *body;
  }
  c.frame = frames_.size() - 1;
  g.calls.push_back(c);
  g.hot = true;
  gcode_->enter_call(args, /*numbered_local=*/true);
}

void Interpreter::gcode_return(const GcodeBlock& b, const SourceLoc& loc) {
  const GcodeOword& o = b.oword;
  GcodeFlow& g = *gcode_flow_;
  if (g.calls.empty() || g.calls.back().frame + 1 != frames_.size() || g.calls.back().fanuc)
    fail(at_column(loc, o.column),
         fmt::format("{} {} is reached without a call of {}: a subroutine runs only when "
                     "called",
                     shown(o.name), oword_keyword(o.kind), shown(o.name)));
  std::optional<double> value;  // evaluated with the subroutine's own parameters
  if (!o.args.empty()) value = gcode_->value(b, 0, o.args[0], loc);
  const GcodeFlow::Call c = g.calls.back();
  g.calls.pop_back();
  g.repeats.resize(std::min(g.repeats.size(), c.repeats_base));
  gcode_->leave_call();
  gcode_->set_returned(value);
  g.hot = !g.calls.empty();
  if (c.own_frame) end_file();
  frames_.back().pc = c.back;
}

void Interpreter::gcode_m98_m99(const GcodeBlock& b, const SourceLoc& loc) {
  gcode_drop_stale_calls();
  GcodeFlow& g = *gcode_flow_;
  Frame& f = frames_.back();
  auto word = [&](char letter) -> const GcodeWord* {
    for (const GcodeWord& w : b.words)
      if (w.letter == letter) return &w;
    return nullptr;
  };
  if (b.flow_m == 99) {
    if (!g.calls.empty() && g.calls.back().frame + 1 == frames_.size()) {
      GcodeFlow::Call& c = g.calls.back();
      if (!c.fanuc)
        fail(loc,
             "M99 ends a subprogram called with M98; an o-word subroutine ends with its "
             "endsub");
      if (c.loops_left > 0) {
        --c.loops_left;
        f.pc = c.body;
        return;
      }
      const Cursor back = c.back;
      g.repeats.resize(std::min(g.repeats.size(), c.repeats_base));
      g.calls.pop_back();
      gcode_->leave_call();
      f.pc = back;
      return;
    }
    // Not in a subprogram: a called file (WinCNC's M98 file) ends; the main program ends as
    // at M2, as LinuxCNC's rs274 does (not the endless restart of a Fanuc control).
    if (frames_.size() > 1 && !frames_[frames_.size() - 2].call.lines)
      f.pc = Cursor{std::string::npos, f.pc.line};
    else
      gcode_->end_program(loc);
    return;
  }
  // M98 P<n> [L<count>]: subprogram O<n>, further down this file.
  const GcodeWord* p = word('P');
  if (!p) return;  // the executor refused it already
  const SourceLoc p_at = at_column(loc, p->column);
  const double pn = gcode_->value(b, p->number, p->expr, loc);
  if (pn != std::round(pn) || pn < 0)
    fail(p_at,
         fmt::format("M98 P{} is not a program number: P is a whole number, as in M98 P100", pn));
  const std::string name = fmt::format("{}", static_cast<long long>(pn));
  long loops = 1;
  if (const GcodeWord* l = word('L')) {
    const double ln = gcode_->value(b, l->number, l->expr, loc);
    if (ln != std::round(ln) || ln < 0)
      fail(at_column(loc, l->column),
           fmt::format("M98 L{} is not a count: L is how many times to run, 0 or more", ln));
    loops = static_cast<long>(ln);
  }
  const std::optional<Cursor> body = f.script->gcode_program(name);
  if (!body)
    fail(p_at, fmt::format("M98 P{0}: this file has no subprogram O{0}; write it after the main "
                           "program's M30, from O{0} to M99",
                           name));
  if (loops == 0) return;
  if (gcode_->call_depth() >= kMaxCallDepth)
    fail(loc, fmt::format("subprograms are nested {} deep, the most LinuxCNC allows; a "
                          "subprogram may be calling itself without end",
                          kMaxCallDepth));
  GcodeFlow::Call c;
  c.back = f.pc;
  c.fanuc = true;
  c.loops_left = loops - 1;
  c.body = *body;
  c.repeats_base = g.repeats.size();
  c.frame = frames_.size() - 1;
  gcode_->enter_call({}, /*numbered_local=*/false);
  g.calls.push_back(c);
  g.hot = true;
  f.pc = *body;
}

// WinCNC's `M98 file.tap`: runs another program file, then goes on after the line.
void Interpreter::gcode_call_file(const GcodeBlock& b, const SourceLoc& loc) {
  const SourceLoc at = at_column(loc, b.call_file_column);
  if (ctx_.settings().gcode_dialect != GcodeDialect::WinCNC)
    fail(at, fmt::format("M98 {} calls a program file, as WinCNC does: set gcode_dialect = "
                         "\"wincnc\" in the profile; in standard G-code call O subprograms "
                         "(M98 P100) or o<name> call",
                         b.call_file));
  for (const GcodeWord& w : b.words)
    if (w.letter != 'M')
      fail(at_column(loc, w.column), "M98 with a file name takes no other words on its line");
  const std::string path = readable_file(b.call_file, at);
  std::shared_ptr<const Script> file = frames_.front().script->called(
      path, [&] { return files_system_->load_script(path, table_.is_command()); });
  if (!file->ok())
    for (Diagnostic d : file->errors())
      if (d.severity == Severity::Error) {
        d = located(std::move(d));
        d.via.push_back(at);
        throw GantryError(std::move(d));
      }
  push_gcode_frame(file, file->start(), at, /*restore_g92=*/true);
}

}  // namespace gantry
