// G-code subroutines' parameters (docs/gcode.md, "O-words"): as LinuxCNC 2.9 scopes them,
// #1-#30 and named parameters belong to the call that set them, `#<_name>` to everyone, and
// #31-#5000 are shared.
#include <iterator>  // next

#include "gantry/interp/gcode_executor.hpp"

namespace gantry {
namespace {

bool global_name(const std::string& name) {
  return !name.empty() && name[0] == '_';
}

}  // namespace

void GcodeExecutor::enter_call(const std::vector<double>& args, bool numbered_local) {
  Scope s;
  s.numbered_local = numbered_local;
  if (numbered_local)
    for (size_t n = 1; n <= 30; ++n) {
      s.numbered[n - 1] = params_[n];
      params_[n] = n - 1 < args.size() ? args[n - 1] : 0;
    }
  for (auto it = named_.begin(); it != named_.end();) {
    if (global_name(it->first)) {
      ++it;
      continue;
    }
    s.named.emplace_back(it->first, it->second);
    it = named_.erase(it);
  }
  scopes_.push_back(std::move(s));
  set_returned(std::nullopt);
}

void GcodeExecutor::leave_call() {
  if (scopes_.empty()) return;
  Scope& s = scopes_.back();
  if (s.numbered_local)
    for (size_t n = 1; n <= 30; ++n) params_[n] = s.numbered[n - 1];
  for (auto it = named_.begin(); it != named_.end();)
    it = global_name(it->first) ? std::next(it) : named_.erase(it);
  for (auto& [name, v] : s.named) named_[name] = v;
  scopes_.pop_back();
}

void GcodeExecutor::reset_calls() {
  while (!scopes_.empty()) leave_call();
  set_returned(std::nullopt);
}

void GcodeExecutor::set_returned(std::optional<double> value) {
  named_["_value"] = value.value_or(0);
  named_["_value_returned"] = value ? 1 : 0;
}

}  // namespace gantry
