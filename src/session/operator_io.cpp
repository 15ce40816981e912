// The operator's mailbox: questions handed from the job thread to the front end's thread.
#include "gantry/session/operator_io.hpp"

#include <utility>

#include "gantry/session/source_place.hpp"  // where

namespace gantry::session {

void OperatorMailbox::print(std::string_view text) {
  if (direct_) return direct_(text);
  std::lock_guard lock(m_);
  output_ += text;
}

void OperatorMailbox::warn(const Diagnostic& d) {
  print(format(d) + "\n");
}

bool OperatorMailbox::confirm(std::string_view message, const SourceLoc& loc) {
  try {
    return scripted_.confirm(message, loc);
  } catch (const NeedsOperator&) {
    if (!has_operator()) throw;
  }
  Question q;
  q.kind = Question::Kind::Pause;
  q.where = where(loc);
  q.text = std::string(message);
  return wait_for(std::move(q)).has_value();
}

std::optional<std::string> OperatorMailbox::ask(std::string_view prompt, std::string_view variable,
                                                std::string_view default_value,
                                                const SourceLoc& loc) {
  try {
    return scripted_.ask(prompt, variable, default_value, loc);
  } catch (const NeedsOperator&) {
    if (!has_operator()) throw;
  }
  Question q;
  q.kind = Question::Kind::Input;
  q.where = where(loc);
  q.text = prompt.empty() ? "Input" : std::string(prompt);
  q.variable = std::string(variable);
  q.default_value = std::string(default_value);
  return wait_for(std::move(q));
}

std::string OperatorMailbox::choose(std::string_view text, const std::vector<std::string>& buttons,
                                    std::size_t default_button, std::string_view title,
                                    const SourceLoc& loc) {
  try {
    return scripted_.choose(text, buttons, default_button, title, loc);
  } catch (const NeedsOperator&) {
    if (!has_operator()) throw;
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

KeypadAnswer OperatorMailbox::keypad(std::string_view message, const SourceLoc& loc) {
  if (!has_operator()) return scripted_.keypad(message, loc);
  std::lock_guard lock(m_);
  keypad_message_ = std::string(message);
  return KeypadAnswer::Jog;
}

std::string OperatorMailbox::take_keypad_message() {
  std::lock_guard lock(m_);
  return std::exchange(keypad_message_, {});
}

std::optional<std::string> OperatorMailbox::wait_for(Question q) {
  std::unique_lock lock(m_);
  q.id = next_id_++;
  question_ = std::move(q);
  answer_.reset();
  cv_.wait(lock, [&] { return !question_; });
  return answer_;
}

std::string OperatorMailbox::take_output() {
  std::lock_guard lock(m_);
  return std::exchange(output_, {});
}

std::optional<Question> OperatorMailbox::question() const {
  std::lock_guard lock(m_);
  return question_;
}

void OperatorMailbox::answer(std::string a) {
  {
    std::lock_guard lock(m_);
    if (!question_) return;
    answer_ = std::move(a);
    question_.reset();
  }
  cv_.notify_all();
}

void OperatorMailbox::cancel() {
  {
    std::lock_guard lock(m_);
    if (!question_) return;
    answer_.reset();
    question_.reset();
  }
  cv_.notify_all();
}

}  // namespace gantry::session
