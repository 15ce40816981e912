// libFuzzer target: any bytes as a machine profile, and as a values file over the default
// profile. Must never crash or trip a sanitizer; a file that loads must save (US's writer,
// the values writer) as text that loads again to the same settings.
#include <cstddef>
#include <cstdint>
#include <cstdio>   // the failed check, before aborting
#include <cstdlib>  // abort
#include <string>

#include "gantry/settings/values_file.hpp"  // parse_settings, settings_text, values_text

namespace {

[[noreturn]] void mismatch(const char* what, const std::string& a, const std::string& b) {
  std::fprintf(stderr, "%s does not read back as itself:\n%s\n---\n%s\n", what, a.c_str(),
               b.c_str());
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const gantry::Settings profile = gantry::default_settings();
  static const std::string profile_text = gantry::settings_text(profile);
  const std::string text(reinterpret_cast<const char*>(data), size);

  const gantry::SettingsLoad whole = gantry::parse_settings(text, "fuzz.toml");
  if (whole.ok()) {
    const std::string saved = gantry::settings_text(whole.settings);
    const gantry::SettingsLoad again = gantry::parse_settings(saved, "saved.toml");
    if (!again.ok() || gantry::settings_text(again.settings) != saved)
      mismatch("a profile US saved", saved, again.ok() ? settings_text(again.settings) : "");
  }

  const gantry::SettingsLoad over =
      gantry::parse_settings(profile_text, "profile.toml", text, "values.toml");
  if (over.ok()) {
    const std::string saved = gantry::values_text(over.settings, profile);
    const gantry::SettingsLoad again =
        gantry::parse_settings(profile_text, "profile.toml", saved, "values.toml");
    if (!again.ok() || gantry::settings_text(again.settings) != settings_text(over.settings))
      mismatch("a saved values file", saved, again.ok() ? settings_text(again.settings) : "");
  }
  return 0;
}
