// Keeping and saving the values the runs leave in force.
#include "values_keeper.hpp"

#include "gantry/core/text_file.hpp"        // read_text_file, write_file_atomically
#include "gantry/settings/values_file.hpp"  // values_text

namespace gantry {

void ValuesKeeper::ran(const Settings& s) {
  {
    std::lock_guard lock(m_);
    now_ = s;
  }
  const std::string text = values_text(s, profile_.bare);
  if (read_text_file(profile_.values_path) == text) return;
  if (!write_file_atomically(profile_.values_path, text))
    io_.warn({file_loc(profile_.values_path), Severity::Warning,
              "cannot save the values this line changed; the previous values file is kept"});
}

Settings ValuesKeeper::settings() const {
  std::lock_guard lock(m_);
  return now_;
}

}  // namespace gantry
