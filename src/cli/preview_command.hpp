// `gantry preview`: a part file's toolpath drawn without a display (PNG or SVG), with its
// bounding box, cycle-time estimate, move count and soft-limit violations (docs/preview.md).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "gantry/interp/persistent_store.hpp"  // PersistentStore
#include "gantry/machine/job.hpp"              // JobOptions
#include "gantry/settings/settings.hpp"        // Settings

namespace CLI {
class App;
}

namespace gantry {

struct PreviewArgs {
  std::string file, output, settings;
  std::string view = "top";
  std::string size = "800x600";
  bool material = false;
  std::string cutter = "flat";  // flat, ball, v or v<angle>
  double stock_top = 0;         // Z of the uncut material's surface
  std::string stock;            // WxHxD[@X,Y,Z]; "": the profile's VP table size at 0,0
  std::optional<double> play_s;          // --play T: as it stands at machine time T
  std::optional<std::uint32_t> play_line;  // --play-line N: after line N's first run
  bool json = false;
};

// Adds the `preview` subcommand with its own options (the interpreting ones, --yes,
// --input, --macros ..., are added by the caller, as for `gantry moves`).
CLI::App* add_preview_command(CLI::App& app, PreviewArgs& args);

// Loads the toolpath, writes the picture and prints the summary. 0, or 1 when the options
// are wrong, the picture cannot be written or the file has errors (they are printed, the
// picture is still written when the file made any move).
int run_preview(const PreviewArgs& args, const Settings& settings, const JobOptions& job,
                const PersistentStore& store);

}  // namespace gantry
