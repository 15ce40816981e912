// An operator for tests who answers every question yes (confirm), gives no text (ask), takes
// each default button (choose), and keeps what the program printed, asked and warned.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "gantry/interp/operator_io.hpp"

namespace gantry {

class AnsweringIO : public OperatorIO {
 public:
  void print(std::string_view text) override { printed += text; }
  bool confirm(std::string_view question, const SourceLoc&) override {
    questions.emplace_back(question);
    return true;
  }
  std::optional<std::string> ask(std::string_view, std::string_view, std::string_view,
                                 const SourceLoc&) override {
    return std::nullopt;
  }
  std::string choose(std::string_view, const std::vector<std::string>& buttons, size_t def,
                     std::string_view, const SourceLoc&) override {
    return buttons.at(def);
  }
  void warn(const Diagnostic& d) override { warnings.push_back(d); }

  std::string printed;
  std::vector<std::string> questions;
  std::vector<Diagnostic> warnings;
};

}  // namespace gantry
