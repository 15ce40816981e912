// The console window's operator: questions handed from the job thread to the window's.
#include "window_io.hpp"

#include <fmt/format.h>

#include <utility>

namespace gantry::ui {
namespace {

std::string where(const SourceLoc& loc) {
  return loc.file && *loc.file != "console" ? fmt::format("{}:{}", *loc.file, loc.line)
                                            : std::string("console");
}

}  // namespace

void WindowIO::print(std::string_view text) {
  std::lock_guard lock(m_);
  output_ += text;
}

void WindowIO::warn(const Diagnostic& d) {
  print(format(d) + "\n");
}

bool WindowIO::confirm(std::string_view message, const SourceLoc& loc) {
  try {
    return scripted_.confirm(message, loc);
  } catch (const NeedsOperator&) {
  }
  Question q;
  q.kind = Question::Kind::Pause;
  q.where = where(loc);
  q.text = std::string(message);
  return wait_for(std::move(q)).has_value();
}

std::optional<std::string> WindowIO::ask(std::string_view prompt, std::string_view variable,
                                         std::string_view default_value, const SourceLoc& loc) {
  try {
    return scripted_.ask(prompt, variable, default_value, loc);
  } catch (const NeedsOperator&) {
  }
  Question q;
  q.kind = Question::Kind::Input;
  q.where = where(loc);
  q.text = prompt.empty() ? "Input" : std::string(prompt);
  q.variable = std::string(variable);
  q.default_value = std::string(default_value);
  return wait_for(std::move(q));
}

std::string WindowIO::choose(std::string_view text, const std::vector<std::string>& buttons,
                             std::size_t default_button, std::string_view title,
                             const SourceLoc& loc) {
  try {
    return scripted_.choose(text, buttons, default_button, title, loc);
  } catch (const NeedsOperator&) {
  }
  Question q;
  q.kind = Question::Kind::MsgBox;
  q.where = where(loc);
  q.title = std::string(title);
  q.text = std::string(text);
  q.buttons = buttons;
  q.default_button = default_button;
  const std::optional<std::string> a = wait_for(std::move(q));
  return a ? *a : buttons.back();  // cancelled: the last button (Cancel or No)
}

KeypadAnswer WindowIO::keypad(std::string_view message, const SourceLoc&) {
  std::lock_guard lock(m_);
  keypad_message_ =
      message.empty() ? std::string("SK: the file waits while you jog") : std::string(message);
  return KeypadAnswer::Jog;
}

std::string WindowIO::take_keypad_message() {
  std::lock_guard lock(m_);
  return std::exchange(keypad_message_, {});
}

std::optional<std::string> WindowIO::wait_for(Question q) {
  std::unique_lock lock(m_);
  q.id = next_id_++;
  question_ = std::move(q);
  answer_.reset();
  cv_.wait(lock, [&] { return !question_; });
  return answer_;
}

std::string WindowIO::take_output() {
  std::lock_guard lock(m_);
  return std::exchange(output_, {});
}

std::optional<Question> WindowIO::question() const {
  std::lock_guard lock(m_);
  return question_;
}

void WindowIO::answer(std::string a) {
  {
    std::lock_guard lock(m_);
    if (!question_) return;
    answer_ = std::move(a);
    question_.reset();
  }
  cv_.notify_all();
}

void WindowIO::cancel() {
  {
    std::lock_guard lock(m_);
    if (!question_) return;
    answer_.reset();
    question_.reset();
  }
  cv_.notify_all();
}

}  // namespace gantry::ui
