// Card selection for the live front ends and `gantry run`.
#include "gantry/session/open_card.hpp"

#include "sim/sim_card.hpp"  // SimCard
#ifdef GANTRY_HAVE_GPIOD
#include "gpiod/gpio_map_profile.hpp"  // apply_profile
#include "gpiod/open_gpiod.hpp"        // open_gpiod
#endif
#ifdef GANTRY_HAVE_PCI7200
#include "pci7200/open_pci7200.hpp"  // open_pci7200
#endif

namespace gantry::session {

std::unique_ptr<Card> open_card(const CardChoice& choice, const Settings& settings,
                                std::string* error) {
  if (choice.type == "sim")
    return std::make_unique<SimCard>(settings, choice.realtime, choice.world, choice.trace);
#ifdef GANTRY_HAVE_GPIOD
  if (choice.type == "gpiod") {
    GpioMap map;
    map.chip_path = settings.card.gpiod_chip;
    for (const GpioLineBit& o : settings.card.gpiod_outputs) map.outputs.push_back({o.bit, o.line});
    for (const GpioLineBit& i : settings.card.gpiod_inputs) map.inputs.push_back({i.line, i.bit});
    apply_profile(map, settings);
    return open_gpiod(map, error);
  }
#endif
#ifdef GANTRY_HAVE_PCI7200
  if (choice.type == "pci7200") return open_pci7200(settings, error);
#endif
  *error = "card type \"" + choice.type +
           "\" is not built into this gantry; rebuild with its driver (GANTRY_GPIOD, "
           "GANTRY_PCI7200) or use --card sim";
  return nullptr;
}

}  // namespace gantry::session
