// The parser of one physical line. Positions are byte offsets into the whole line, so every
// location it reports is the exact column. Errors are thrown as GantryError.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "gantry/lang/statement.hpp"  // Statement and its parts

namespace gantry {

class LineParser {
 public:
  LineParser(std::string_view line, std::shared_ptr<const std::string> file, int line_no)
      : line_(line), file_(std::move(file)), line_no_(line_no) {}

  // One statement from [b, e): the comment is already removed and the range trimmed.
  Statement statement(size_t b, size_t e) const;

 private:
  // parser.cpp: classification, commands, labels, assignment, IF, ON INPUT, jumps.
  Statement assignment(size_t b, size_t e) const;
  Statement command(const std::string& word, size_t b, size_t w, size_t e) const;
  Statement custom_cut(const std::string& word, size_t b, size_t w, size_t e) const;
  Statement computed_custom_cut(size_t b, size_t p, size_t e) const;
  Statement jump(bool gosub, size_t b, size_t w, size_t e) const;
  Statement if_statement(size_t b, size_t w, size_t e) const;
  Statement on_input(size_t b, size_t w, size_t e) const;
  StatementPtr action(size_t b, size_t e, std::string_view owner) const;

  // statement_parser.cpp: the keyword statements. nullopt when `word` is not a keyword.
  std::optional<Statement> program_statement(const std::string& word, size_t b, size_t w,
                                             size_t e) const;
  Statement pause(size_t b, size_t w, size_t e) const;
  Statement print(size_t b, size_t w, size_t e, bool is_write) const;
  Statement input(size_t b, size_t w, size_t e) const;
  Statement msgbox(size_t b, size_t w, size_t e) const;
  Statement dialog(size_t b, size_t w, size_t e) const;
  Statement open(size_t b, size_t w, size_t e) const;
  Statement registry(const std::string& word, size_t b, size_t w, size_t e) const;
  Expr file_number(size_t* p, size_t e) const;  // `#n` or `#(n)` at *p; advances *p
  std::vector<LValue> lvalues(size_t b, size_t e) const;

  // Shared pieces.
  SourceLoc loc(size_t col0) const;
  [[noreturn]] void error(size_t col0, std::string message) const;
  size_t skip_space(size_t i, size_t end) const;
  Arg arg(size_t b, size_t e, bool whole_quotes = true) const;
  Expr expression(size_t b, size_t e, std::string_view what, bool bare_words = false) const;
  LValue lvalue(size_t b, size_t e) const;
  std::vector<std::pair<size_t, size_t>> split_commas(size_t b, size_t e) const;
  std::string label_name(size_t b, size_t e, bool* ok) const;

  std::string_view line_;
  std::shared_ptr<const std::string> file_;
  int line_no_;
};

}  // namespace gantry
