// Fill-in sheets from the command table.
#include "fill_sheet.hpp"

#include <fmt/format.h>

#include <cctype>
#include <charconv>
#include <cmath>

#include "gantry/lang/scan.hpp"  // trim

namespace gantry::ui {
namespace {

// The parameters of a line after its code, split at the commas outside quotes, with the
// column (1-based, in `line`) each starts at.
struct Piece {
  std::string text;
  int column;
};
std::vector<Piece> split_params(std::string_view line) {
  std::vector<Piece> out;
  std::size_t i = line.find_first_not_of(' ');
  if (i == std::string_view::npos || line.size() < i + 2) return out;
  i += 2;
  while (i < line.size() && line[i] == ' ') ++i;
  if (i < line.size() && line[i] == ',') ++i;
  if (i >= line.size()) return out;
  std::size_t start = i;
  bool quoted = false;
  for (; i <= line.size(); ++i) {
    if (i < line.size() && line[i] == '"') quoted = !quoted;
    if (i == line.size() || (line[i] == ',' && !quoted)) {
      out.push_back(
          {std::string(scan::trim(line.substr(start, i - start))), static_cast<int>(start) + 1});
      start = i + 1;
    }
  }
  return out;
}

std::optional<double> plain_number(std::string_view s) {
  double v = 0;
  const char* b = s.data();
  if (!s.empty() && *b == '+') ++b;
  const auto r = std::from_chars(b, s.data() + s.size(), v);
  if (r.ec != std::errc{} || r.ptr != s.data() + s.size()) return std::nullopt;
  return v;
}

std::string unit_text(std::string_view unit, std::string_view units) {
  if (unit == "units") return std::string(units);
  if (unit == "units/s") return fmt::format("{}/s", units);
  return std::string(unit);
}

}  // namespace

std::string field_error(const ParamSpec& p, std::string_view value) {
  const std::string v(scan::trim(value));
  if (v.empty()) return p.required ? "required: this parameter has no default" : "";
  if (p.kind == ParamKind::Text) {
    if (p.choices.empty()) return "";
    std::string_view rest = p.choices;
    while (!rest.empty()) {
      const std::size_t sp = rest.find(' ');
      const std::string_view w = rest.substr(0, sp);
      bool same = w.size() == v.size();
      for (std::size_t i = 0; same && i < w.size(); ++i)
        same = std::toupper(static_cast<unsigned char>(w[i])) ==
               std::toupper(static_cast<unsigned char>(v[i]));
      if (same) return "";
      rest = sp == std::string_view::npos ? std::string_view{} : rest.substr(sp + 1);
    }
    return fmt::format("must be {}", param_range(p));
  }
  const std::optional<double> n = plain_number(v);
  if (!n) {
    // An expression or a variable is the controller's to evaluate; anything else is wrong.
    const char c = v[0];
    const bool expr = c == '&' || c == '%' || c == '$' || c == '(' || c == '-' || c == '.' ||
                      std::isdigit(static_cast<unsigned char>(c)) ||
                      std::isalpha(static_cast<unsigned char>(c));
    return expr ? "" : "must be a number";
  }
  if (p.whole && *n != std::floor(*n)) return "must be a whole number";
  if ((p.min && *n < *p.min) || (p.max && *n > *p.max))
    return fmt::format("out of range: {}", param_range(p));
  return "";
}

FillSheet::FillSheet(const CommandSpec& spec, Dialect dialect, std::string_view units_name)
    : spec_(&spec) {
  for (const ParamSpec& p : spec.params_for(dialect)) {
    SheetField f;
    f.spec = &p;
    f.label = std::string(p.name);
    f.type = std::string(param_type(p));
    f.unit = unit_text(p.unit, units_name);
    f.range = param_range(p);
    f.hint = p.default_value ? fmt::format("{}", *p.default_value)
             : p.required    ? "required"
                             : "blank: unchanged";
    fields_.push_back(std::move(f));
  }
}

void FillSheet::fill_from(std::string_view line) {
  const std::vector<Piece> pieces = split_params(line);
  for (std::size_t i = 0; i < pieces.size() && i < fields_.size(); ++i)
    fields_[i].value = pieces[i].text;
}

bool FillSheet::validate() {
  bool ok = true;
  for (SheetField& f : fields_) {
    f.error = field_error(*f.spec, f.value);
    ok = ok && f.error.empty();
  }
  return ok;
}

std::string FillSheet::line() const {
  std::size_t last = 0;  // fields written: up to the last one not blank
  for (std::size_t i = 0; i < fields_.size(); ++i)
    if (!scan::trim(fields_[i].value).empty()) last = i + 1;
  std::string out(spec_->code);
  for (std::size_t i = 0; i < last; ++i) out += ", " + std::string(scan::trim(fields_[i].value));
  return out;
}

std::vector<std::string> FillSheet::place_errors(const std::vector<Diagnostic>& errors) {
  std::vector<std::string> rest;
  const std::string text = line();
  const std::vector<Piece> pieces = split_params(text);
  for (const Diagnostic& d : errors) {
    std::size_t field = fields_.size();
    if (d.loc.line == 1 && d.via.empty())
      for (std::size_t i = 0; i < pieces.size() && i < fields_.size(); ++i)
        if (d.loc.column >= pieces[i].column) field = i;
    if (field < fields_.size() && d.loc.column > 0)
      fields_[field].error = d.message;
    else
      rest.push_back(d.loc.line == 1 && d.via.empty() ? d.message : format(d));
  }
  return rest;
}

}  // namespace gantry::ui
