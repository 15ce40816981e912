// sysfs scanning for the PCI-7200 and the messages for what can go wrong on the way to it.
#include "pci7200/pci_discovery.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace gantry::pci7200 {
namespace fs = std::filesystem;
namespace {

// sysfs writes IDs as "0x144a\n".
bool read_hex_id(const fs::path& file, std::uint16_t* value) {
  std::ifstream in(file);
  std::string text;
  if (!(in >> text)) return false;
  try {
    const unsigned long v = std::stoul(text, nullptr, 16);
    if (v > 0xffff) return false;
    *value = static_cast<std::uint16_t>(v);
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

std::string link_basename(const fs::path& link) {
  std::error_code ec;
  const fs::path target = fs::read_symlink(link, ec);
  return ec ? std::string() : target.filename().string();
}

bool is_pci7200(const PciId& id) {
  return std::any_of(std::begin(kKnownIds), std::end(kKnownIds), [&](const PciId& k) {
    return k.vendor == id.vendor && k.device == id.device;
  });
}

}  // namespace

PciDiscovery find_pci7200(const std::string& sysfs_devices) {
  PciDiscovery found;
  std::error_code ec;
  fs::directory_iterator it(sysfs_devices, ec);
  if (ec) {
    found.error =
        fmt::format("{}: cannot be read ({}); is sysfs mounted?", sysfs_devices, ec.message());
    return found;
  }
  for (const fs::directory_entry& entry : it) {
    PciDeviceLocation card;
    if (!read_hex_id(entry.path() / "vendor", &card.id.vendor) ||
        !read_hex_id(entry.path() / "device", &card.id.device) || !is_pci7200(card.id))
      continue;
    card.address = entry.path().filename().string();
    card.directory = entry.path().string();
    card.driver = link_basename(entry.path() / "driver");
    const std::string group = link_basename(entry.path() / "iommu_group");
    if (!group.empty() && std::all_of(group.begin(), group.end(), ::isdigit))
      card.iommu_group = std::stoi(group);
    found.cards.push_back(card);
  }
  std::sort(found.cards.begin(), found.cards.end(),
            [](const auto& a, const auto& b) { return a.address < b.address; });
  if (found.cards.empty())
    found.error = fmt::format(
        "no PCI-7200 found (vendor {:04x} device {:04x}, or vendor {:04x} device {:04x} on "
        "AMCC-based cards) in {}; is the card fitted?",
        kAdlinkId.vendor, kAdlinkId.device, kAmccId.vendor, kAmccId.device, sysfs_devices);
  return found;
}

TransportChoice choose_transport(const PciDeviceLocation& card) {
  if (card.driver == "vfio-pci") {
    if (card.iommu_group < 0)
      return {Transport::None,
              fmt::format("{} is bound to vfio-pci but has no IOMMU group; enable VT-d/AMD-Vi "
                          "in the firmware and boot with intel_iommu=on (or amd_iommu=on), or "
                          "bind it to uio_pci_generic for the programmed-I/O fallback; {}",
                          card.address, kReadmeHint)};
    return {Transport::Vfio, {}};
  }
  if (card.driver == "uio_pci_generic") return {Transport::ProgrammedIo, {}};
  if (card.driver.empty())
    return {Transport::None,
            fmt::format("{} is bound to no driver; bind it to vfio-pci (DMA{}) or "
                        "uio_pci_generic (programmed I/O); {}",
                        card.address,
                        card.iommu_group < 0 ? ", which needs the IOMMU: no IOMMU group now" : "",
                        kReadmeHint)};
  return {Transport::None,
          fmt::format("{} is bound to {}; unbind it and bind vfio-pci (or uio_pci_generic); {}",
                      card.address, card.driver, kReadmeHint)};
}

std::string open_failure_message(const std::string& path, int error_number) {
  switch (error_number) {
    case EACCES:
    case EPERM:
      return fmt::format("{}: permission denied; add a udev rule or run as root; {}", path,
                         kReadmeHint);
    case ENOENT:
      return fmt::format(
          "{}: does not exist; is the driver (vfio-pci or uio_pci_generic) "
          "loaded and the card bound to it? {}",
          path, kReadmeHint);
    case EBUSY:
      return fmt::format("{}: busy; another program has the card open", path);
    default:
      return fmt::format("{}: {}", path, std::strerror(error_number));
  }
}

}  // namespace gantry::pci7200
