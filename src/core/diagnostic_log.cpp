// A check's log: repeats dropped in constant time, errors beyond the cap counted by kind.
#include "gantry/core/diagnostic_log.hpp"

#include <fmt/format.h>  // keys and the summary

#include <algorithm>  // sort, min

namespace gantry {
namespace {

// What makes two diagnostics the same for a check: for an error, the line it is at (a file
// that cannot be read: the line that called it), whatever its text; for a warning, its text.
std::string repeat_key(const Diagnostic& d) {
  if (d.severity == Severity::Error) {
    const SourceLoc* at = d.loc.line > 0 ? &d.loc : d.via.empty() ? nullptr : &d.via.back();
    if (at) return fmt::format("{}\n{}", at->file ? *at->file : std::string(), at->line);
  }
  return format(d);
}

// 25641 -> "25,641".
std::string with_commas(std::size_t n) {
  std::string digits = std::to_string(n), out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

}  // namespace

bool DiagnosticLog::add(Diagnostic d) {
  if (!seen_.insert(repeat_key(d)).second) return false;
  const bool error = d.severity == Severity::Error;
  if (error && full()) {
    ++omitted_;
    ++omitted_kinds_[diagnostic_kind(d.message)];
    return false;
  }
  if (error) ++errors_;
  kept_.push_back(std::move(d));
  return true;
}

void DiagnosticLog::stop_short(Diagnostic why) {
  if (!stopped_) stopped_ = why;
  const bool error = why.severity == Severity::Error;
  if (add(why) || (error && full())) return;
  // On a line reported already, why the check ended is still said.
  if (error) ++errors_;
  kept_.push_back(std::move(why));
}

std::string DiagnosticLog::summary() const {
  if (omitted_ == 0) return {};
  std::vector<std::pair<std::string, std::size_t>> kinds(omitted_kinds_.begin(),
                                                         omitted_kinds_.end());
  std::sort(kinds.begin(), kinds.end(), [](const auto& a, const auto& b) {
    return a.second != b.second ? a.second > b.second : a.first < b.first;
  });
  constexpr std::size_t kNamed = 4;  // one line: the commonest kinds, the rest counted
  std::string out =
      fmt::format("stopped after {} error{}; {} more not shown: ", with_commas(errors_),
                  errors_ == 1 ? "" : "s", with_commas(omitted_));
  std::size_t rest = omitted_;
  for (std::size_t i = 0; i < kinds.size() && i < kNamed; ++i) {
    out += fmt::format("{}{} '{}'", i ? ", " : "", with_commas(kinds[i].second), kinds[i].first);
    rest -= kinds[i].second;
  }
  if (rest > 0)
    out += fmt::format(", {} of {} other kinds", with_commas(rest), kinds.size() - kNamed);
  return out;
}

std::string diagnostic_kind(std::string_view message) {
  message = message.substr(0, std::min(message.find(';'), message.find(" (")));
  std::string out;
  std::size_t i = 0;
  while (i < message.size()) {
    const char c = message[i];
    if (c == ' ') {
      ++i;
      continue;
    }
    std::size_t end = i + 1;
    if (c == '\'' || c == '"') {  // quoted text names one instance: left out
      const std::size_t close = message.find(c, i + 1);
      i = close == std::string_view::npos ? message.size() : close + 1;
      continue;
    }
    while (end < message.size() && message[end] != ' ') ++end;
    const std::string_view word = message.substr(i, end - i);
    out += out.empty() ? "" : " ";
    if (word.find_first_of("0123456789") == std::string_view::npos) {
      out += word;
    } else {  // a number names one instance: '#', keeping the punctuation after it
      out += '#';
      out += word.substr(word.find_last_not_of(":,)") + 1);
    }
    i = end;
  }
  while (!out.empty() && (out.back() == ',' || out.back() == ':')) out.pop_back();
  return out;
}

}  // namespace gantry
