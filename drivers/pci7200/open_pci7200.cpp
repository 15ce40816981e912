// Profile checks, card discovery and transport selection for the PCI-7200.
#include "pci7200/open_pci7200.hpp"

#include <fmt/format.h>

#include <algorithm>  // max
#include <cmath>      // llround

#include "gantry/hal/input_roles.hpp"  // input_roles
#include "gantry/hal/pin_map.hpp"
#include "pci7200/pacer_divisor.hpp"
#include "pci7200/sysfs_pio_bus.hpp"
#include "pci7200/vfio_bus.hpp"

namespace gantry {

using pci7200::Pci7200Bus;

std::optional<pci7200::Pci7200Options> pci7200_options_for(const Settings& settings,
                                                           const Pci7200OpenOptions& options,
                                                           std::string* error) {
  const CardSettings& card = settings.card;
  if (card.clock_hz != pci7200::i8254::kClockHz) {
    *error = fmt::format(
        "card.clock_hz is {} but the PCI-7200's 8254 counts a {} Hz clock; "
        "set clock_hz = 4000000",
        card.clock_hz, pci7200::i8254::kClockHz);
    return std::nullopt;
  }
  const pci7200::PacerDivisor divisor = pci7200::pacer_divisor(card.clock_hz, card.pacer_hz());
  if (!divisor.ok()) {
    *error = "card.pacer_divisor: " + divisor.error;
    return std::nullopt;
  }
  const PinMap pins = PinMap::from(settings.pins);
  std::uint32_t used = 0;
  for (const AxisPins& axis : pins.axes) used |= axis.step_mask | axis.dir_mask;
  if (options.charge_pump_bit >= 32 ||
      (options.charge_pump_bit >= 0 && (used >> options.charge_pump_bit) & 1)) {
    *error = fmt::format(
        "the charge-pump output bit {} is also a step or direction bit in "
        "[pins], or not a bit of the 32-bit word; choose another",
        options.charge_pump_bit);
    return std::nullopt;
  }
  pci7200::Pci7200Options out;
  out.clock_hz = card.clock_hz;
  out.charge_pump_bit = options.charge_pump_bit;
  out.charge_pump_hz = options.charge_pump_hz;
  out.idle_word = pins.idle_word();
  // The step generator keeps at most card.lead_ms queued (docs/controller.md): output starts
  // with half of it, so the lead (never below this plus one block) can fill it.
  out.prime_words = std::max<std::size_t>(
      64, static_cast<std::size_t>(std::llround(card.lead_ms * 1e-3 * card.pacer_hz() / 2)));
  out.realtime = options.realtime;
  // The E-stop and limit inputs stop the pacer in the feeder, tick-exact.
  const InputRoles roles = input_roles(settings);
  out.estop = roles.estop;
  out.limits = roles.limits;
  out.limit_rule = LimitFilter(settings, card.pacer_hz());
  out.cushion = CushionRule(settings);  // played by the feeder thread
  return out;
}

std::unique_ptr<Card> open_pci7200(const Settings& settings, std::string* error) {
  return open_pci7200(settings, Pci7200OpenOptions{}, error);
}

std::unique_ptr<Card> open_pci7200(const Settings& settings, const Pci7200OpenOptions& options,
                                   std::string* error) {
  std::optional<pci7200::Pci7200Options> card_options =
      pci7200_options_for(settings, options, error);
  if (!card_options) return nullptr;

  const pci7200::PciDiscovery found = pci7200::find_pci7200(options.sysfs_devices);
  if (found.cards.empty()) {
    *error = found.error;
    return nullptr;
  }
  if (options.card_index >= found.cards.size()) {
    *error = fmt::format("PCI-7200 number {} asked for, but {} found in {}", options.card_index + 1,
                         found.cards.size(), options.sysfs_devices);
    return nullptr;
  }
  const pci7200::PciDeviceLocation& location = found.cards[options.card_index];
  const pci7200::TransportChoice choice = pci7200::choose_transport(location);
  std::shared_ptr<Pci7200Bus> bus;
  switch (choice.transport) {
    case pci7200::Transport::Vfio:
      bus = pci7200::VfioBus::open(
          location, {options.dev_root, options.dma_words, options.poll_interval}, error);
      break;
    case pci7200::Transport::ProgrammedIo:
      bus = pci7200::SysfsPioBus::open(location, options.poll_interval, error);
      break;
    case pci7200::Transport::None:
      *error = choice.error;
      return nullptr;
  }
  if (!bus) return nullptr;
  auto card = std::make_unique<pci7200::Pci7200Card>(bus, *card_options);
  if (bus->failed()) {
    *error = fmt::format("{}: register access failed while quiescing the card; {}", bus->describe(),
                         pci7200::kReadmeHint);
    return nullptr;
  }
  return card;
}

}  // namespace gantry
