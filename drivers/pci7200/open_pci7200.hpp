// The entry point the CLI calls for `[card] type = "pci7200"`: finds the card, opens it
// through VFIO (DMA) or sysfs programmed I/O, and returns it as a Card, or nullptr and a
// message that names the fix.
#pragma once

#include <chrono>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>

#include "gantry/hal/card.hpp"           // Card
#include "gantry/settings/settings.hpp"  // Settings
#include "pci7200/pci7200_card.hpp"      // Pci7200Options
#include "pci7200/pci_discovery.hpp"     // kSysfsPciDevices

namespace gantry {

struct Pci7200OpenOptions {
  std::string sysfs_devices = pci7200::kSysfsPciDevices;
  std::string dev_root = "/dev";
  std::size_t card_index = 0;        // which card, in address order, when several are fitted
  std::size_t dma_words = 2 * 8192;  // two halves of 41 ms each at 200 kHz
  // The feeder's wait between passes; zero busy-polls (an isolated CPU, see README.md).
  std::chrono::nanoseconds poll_interval{10'000};
  // The driver's own charge pump: -1 (none) by default, because the step generator puts the
  // profile's charge pump ([outputs]) into the words, which stops with them on every card.
  int charge_pump_bit = -1;  // must not be a step or direction bit
  double charge_pump_hz = 12'500;
  pci7200::RealtimeRequest realtime{80, -1, true};
};

std::unique_ptr<Card> open_pci7200(const Settings& settings, std::string* error);
std::unique_ptr<Card> open_pci7200(const Settings& settings, const Pci7200OpenOptions& options,
                                   std::string* error);

// The card options a profile implies: its idle word, and a charge-pump bit clear of the pin
// map. nullopt and a message when the profile cannot run on this card.
std::optional<pci7200::Pci7200Options> pci7200_options_for(const Settings& settings,
                                                           const Pci7200OpenOptions& options,
                                                           std::string* error);

}  // namespace gantry
