// The load pass over O-words (gcode_oword.hpp): one stack of open blocks, scoped per
// subroutine as LinuxCNC 2.9 scopes its control-flow numbers.
#include <fmt/format.h>  // messages

#include "gcode_oword.hpp"

namespace gantry {
namespace {

std::string shown(const std::string& name) {
  return !name.empty() && name[0] >= '0' && name[0] <= '9' ? "o" + name : "o<" + name + ">";
}

}  // namespace

SourceLoc OwordIndexer::loc(const Cursor& at, int column) const {
  return SourceLoc{s_.name_, at.line, column};
}

void OwordIndexer::error(const SourceLoc& at, std::string what) {
  s_.errors_.push_back({at, Severity::Error, std::move(what)});
}

// A new control-flow block: its number is free in this scope.
void OwordIndexer::declare(const GcodeOword& o, const SourceLoc& at) {
  const auto [it, fresh] = used_.emplace(o.name, at.line);
  if (!fresh)
    error(at, fmt::format("{} is used for another block already, at line {}; give each if, "
                          "while, do and repeat its own number (LinuxCNC refuses this too)",
                          shown(o.name), it->second));
}

// The end of an `opener` block named o.name: false (and reported) when the innermost open
// block is another.
bool OwordIndexer::close(const GcodeOword& o, OwordKind opener, const SourceLoc& at) {
  const char* kw = oword_keyword(o.kind);
  if (!open_.empty() && open_.back().kind == opener && open_.back().name == o.name) return true;
  // Which block is it then? Say what is open instead.
  if (open_.empty() || (open_.back().kind == OwordKind::Sub && opener != OwordKind::Sub)) {
    error(at, fmt::format("{} {} ends no {} {}: none is open here", shown(o.name), kw,
                          shown(o.name), oword_keyword(opener)));
    return false;
  }
  const Open& top = open_.back();
  error(at, fmt::format("{} {} does not match the innermost open block, {} {} at line {}; close "
                        "that one first (the O numbers of a block's lines must be the same)",
                        shown(o.name), kw, shown(top.name), oword_keyword(top.kind), top.loc.line));
  // Recover: if the block named is open further out, what is inside it ends here too.
  for (size_t i = open_.size(); i-- > 0;)
    if (open_[i].kind == opener && open_[i].name == o.name) {
      open_.resize(i + 1);
      return true;
    }
  return false;
}

void OwordIndexer::add(const GcodeBlock& b, Cursor at, Cursor next) {
  const GcodeOword& o = b.oword;
  const SourceLoc here = loc(at, o.column);
  auto& links = s_.oword_links_;
  switch (o.kind) {
    case OwordKind::None:
      return;
    case OwordKind::Program:
      // Fanuc: `O1234` names the program, or starts subprogram 1234 (M98 P1234 ... M99).
      if (!open_.empty())
        error(here, fmt::format("O{} starts a program inside {} {} (line {}); close that "
                                "first",
                                o.name, shown(open_.back().name), oword_keyword(open_.back().kind),
                                open_.back().loc.line));
      s_.gcode_programs_.emplace(o.name, next);
      return;
    case OwordKind::Sub:
      if (sub_) {
        error(here, fmt::format("{} sub is inside the definition of {}: subroutines cannot "
                                "be nested; end {} with endsub first",
                                shown(o.name), shown(*sub_), shown(*sub_)));
        return;
      }
      if (!open_.empty()) {
        error(here, fmt::format("{} sub is inside {} {} (line {}): define subroutines outside "
                                "any if or loop",
                                shown(o.name), shown(open_.back().name),
                                oword_keyword(open_.back().kind), open_.back().loc.line));
        return;
      }
      if (const auto it = s_.gcode_subs_.find(o.name); it != s_.gcode_subs_.end())
        error(here, fmt::format("{} is defined twice: first at line {}; give each subroutine "
                                "its own name",
                                shown(o.name), it->second.line - 1));
      else
        s_.gcode_subs_.emplace(o.name, next);
      sub_ = o.name;
      main_used_.swap(used_);
      used_.clear();
      open_.push_back({o.kind, o.name, at, next, here, {}, false, {}, {}});
      return;
    case OwordKind::Endsub:
    case OwordKind::Return: {
      const char* kw = oword_keyword(o.kind);
      if (!sub_) {
        error(here, fmt::format("{} {} is outside any subroutine definition (o... sub)",
                                shown(o.name), kw));
        return;
      }
      if (o.name != *sub_) {
        error(here, fmt::format("{} {} is inside {} sub: {} {} ends the subroutine it is in",
                                shown(o.name), kw, shown(*sub_), shown(*sub_), kw));
        if (o.kind == OwordKind::Return) return;
      }
      if (o.kind == OwordKind::Return) return;
      while (!open_.empty() && open_.back().kind != OwordKind::Sub) {
        const Open& inner = open_.back();
        error(inner.loc,
              fmt::format(
                  "{} {} is not closed before the end of {}: add {} end{}", shown(inner.name),
                  oword_keyword(inner.kind), shown(*sub_), shown(inner.name),
                  inner.kind == OwordKind::Do ? "... while [...]" : oword_keyword(inner.kind)));
        open_.pop_back();
      }
      if (!open_.empty()) {
        OwordLink& l = links[open_.back().at.offset];
        l.end = next;
        l.complete = true;
        open_.pop_back();
      }
      sub_.reset();
      used_.swap(main_used_);
      return;
    }
    case OwordKind::Call:
      return;  // subroutines are found when called: in this file, or in a file of their name
    case OwordKind::If:
      declare(o, here);
      open_.push_back({o.kind, o.name, at, next, here, {at.offset}, false, {}, {}});
      return;
    case OwordKind::Elseif:
    case OwordKind::Else:
      if (!close(o, OwordKind::If, here)) return;
      if (open_.back().had_else) {
        error(here, fmt::format("{} {} comes after {} else: else is the last branch", shown(o.name),
                                oword_keyword(o.kind), shown(o.name)));
        return;
      }
      links[open_.back().branches.back()].jump = at;
      open_.back().branches.push_back(at.offset);
      open_.back().had_else = o.kind == OwordKind::Else;
      return;
    case OwordKind::Endif:
      if (!close(o, OwordKind::If, here)) return;
      links[open_.back().branches.back()].jump = at;
      for (size_t branch : open_.back().branches) {
        links[branch].end = next;
        links[branch].complete = true;
      }
      open_.pop_back();
      return;
    case OwordKind::Do:
    case OwordKind::Repeat:
      declare(o, here);
      open_.push_back({o.kind, o.name, at, next, here, {}, false, {}, {}});
      return;
    case OwordKind::While:
      if (!open_.empty() && open_.back().kind == OwordKind::Do && open_.back().name == o.name) {
        Open& d = open_.back();
        OwordLink& l = links[at.offset];
        l.jump = d.next;
        l.closes_do = true;
        l.complete = true;
        for (size_t br : d.breaks) links[br] = {next, {}, false, true};
        for (size_t c : d.continues) links[c] = {at, {}, false, true};
        open_.pop_back();
        return;
      }
      declare(o, here);
      open_.push_back({o.kind, o.name, at, next, here, {}, false, {}, {}});
      return;
    case OwordKind::Endwhile:
    case OwordKind::Endrepeat: {
      const OwordKind opener = o.kind == OwordKind::Endwhile ? OwordKind::While : OwordKind::Repeat;
      if (!close(o, opener, here)) return;
      Open& w = open_.back();
      links[w.at.offset].jump = next;
      links[w.at.offset].complete = true;
      OwordLink& l = links[at.offset];
      l.complete = true;
      if (opener == OwordKind::While) {
        l.jump = w.at;
        for (size_t br : w.breaks) links[br] = {next, {}, false, true};
        for (size_t c : w.continues) links[c] = {w.at, {}, false, true};
      } else {
        l.jump = w.next;
        l.end = w.at;
      }
      open_.pop_back();
      return;
    }
    case OwordKind::Break:
    case OwordKind::Continue:
      for (size_t i = open_.size(); i-- > 0;) {
        Open& loop = open_[i];
        if (loop.kind == OwordKind::Sub) break;
        if (loop.name != o.name) continue;
        if (loop.kind == OwordKind::While || loop.kind == OwordKind::Do) {
          (o.kind == OwordKind::Break ? loop.breaks : loop.continues).push_back(at.offset);
          return;
        }
        if (loop.kind == OwordKind::Repeat) {
          error(here, fmt::format("{} {} is inside {} repeat: break and continue work in while "
                                  "and do loops only (as in LinuxCNC 2.9)",
                                  shown(o.name), oword_keyword(o.kind), shown(o.name)));
          return;
        }
      }
      error(here, fmt::format("{} {}: no {} while or do loop is open here", shown(o.name),
                              oword_keyword(o.kind), shown(o.name)));
      return;
  }
}

void OwordIndexer::finish() {
  for (const Open& b : open_) {
    const std::string end = b.kind == OwordKind::Do
                                ? shown(b.name) + " while [...]"
                                : shown(b.name) + " end" + oword_keyword(b.kind);
    error(b.loc,
          fmt::format("{} {} is never closed: add {}", shown(b.name), oword_keyword(b.kind), end));
  }
}

}  // namespace gantry
