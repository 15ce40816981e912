// Terminal prompts on stderr, answers from stdin. End of input counts as Cancel.
#include "terminal_io.hpp"

#include <fmt/format.h>  // prompts

#include <poll.h>    // poll
#include <unistd.h>  // STDIN_FILENO
#include <cctype>    // tolower

#include <iostream>  // getline

namespace gantry {
namespace {

std::string where(const SourceLoc& loc) {
  return loc.file ? fmt::format("{}:{}", *loc.file, loc.line) : std::string("console");
}

}  // namespace

// Waits for a whole line in short polls, so a stop from another thread ends the wait.
std::optional<std::string> TerminalIO::read_line(const SourceLoc& loc) {
  pollfd in{STDIN_FILENO, POLLIN, 0};
  while (!cancelled_ && poll(&in, 1, 100) == 0) {
  }
  if (cancelled_) {
    fmt::print(stderr, "\n");
    throw OperatorStop(Diagnostic{loc, Severity::Error, "stopped by the operator"});
  }
  std::string line;
  if (!std::getline(std::cin, line)) return std::nullopt;
  if (!line.empty() && line.back() == '\r') line.pop_back();
  return line;
}

void TerminalIO::print(std::string_view text) {
  fmt::print(stream_, "{}", text);
}

bool TerminalIO::confirm(std::string_view message, const SourceLoc& loc) {
  fmt::print(stderr, "\n[{}] {}\n  Enter to continue, c then Enter to cancel: ", where(loc),
             message);
  const std::optional<std::string> a = read_line(loc);
  return a && (a->empty() || std::tolower(static_cast<unsigned char>((*a)[0])) != 'c');
}

std::optional<std::string> TerminalIO::ask(std::string_view prompt, std::string_view variable,
                                           std::string_view default_value, const SourceLoc& loc) {
  // `variable` lists the receiving variables ("&W,&H"). Each one --input gives is taken from
  // there; the terminal is asked only for the others. A single variable keeps its default.
  const std::string names(variable);
  const bool several = names.find(',') != std::string::npos;
  std::string answer;
  bool first = true;
  for (size_t start = 0; start <= names.size();) {
    size_t comma = names.find(',', start);
    if (comma == std::string::npos) comma = names.size();
    const std::string name = names.substr(start, comma - start);
    start = comma + 1;
    std::optional<std::string> value;
    if (auto it = inputs_.find(name); it != inputs_.end()) {
      value = it->second;
    } else {
      fmt::print(stderr, "\n[{}] {} ({}){}: ", where(loc), prompt.empty() ? "Input" : prompt, name,
                 !several && !default_value.empty() ? fmt::format(" [{}]", default_value) : "");
      value = read_line(loc);
      if (!value) return std::nullopt;  // end of input: Cancel
      if (!several && value->empty() && !default_value.empty()) value = std::string(default_value);
    }
    if (!first) answer += ',';
    answer += *value;
    first = false;
  }
  return answer;
}

std::string TerminalIO::choose(std::string_view text, const std::vector<std::string>& buttons,
                               size_t default_button, std::string_view title,
                               const SourceLoc& loc) {
  while (true) {
    fmt::print(stderr, "\n[{}] {}: {}\n", where(loc), title, text);
    for (size_t i = 0; i < buttons.size(); ++i)
      fmt::print(stderr, "  {}) {}{}\n", i + 1, buttons[i], i == default_button ? " (Enter)" : "");
    fmt::print(stderr, "  choice: ");
    const std::optional<std::string> a = read_line(loc);
    if (!a) return buttons.back();  // end of input: the last button (Cancel or No)
    if (a->empty()) return buttons[default_button];
    for (size_t i = 0; i < buttons.size(); ++i)
      if (*a == std::to_string(i + 1)) return buttons[i];
  }
}

void TerminalIO::warn(const Diagnostic& d) {
  fmt::print(stderr, "{}\n", format(d));
}

}  // namespace gantry
