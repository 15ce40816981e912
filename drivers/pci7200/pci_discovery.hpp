// Finding the PCI-7200 in sysfs, and turning what is found (or missing) into a message that
// names the fix. The sysfs root is a parameter so that tests can use a fake tree.
#pragma once

#include <string>
#include <vector>

#include "pci7200/pci7200_registers.hpp"  // PciId

namespace gantry::pci7200 {

inline constexpr const char* kSysfsPciDevices = "/sys/bus/pci/devices";
inline constexpr const char* kReadmeHint = "see drivers/pci7200/README.md";

struct PciDeviceLocation {
  std::string address;    // "0000:03:00.0"
  std::string directory;  // <sysfs root>/0000:03:00.0
  PciId id{};
  std::string driver;    // bound kernel driver ("vfio-pci", "uio_pci_generic"), "" if none
  int iommu_group = -1;  // -1: the device has no IOMMU group (IOMMU off)
};

struct PciDiscovery {
  std::vector<PciDeviceLocation> cards;  // in address order
  std::string error;                     // set when none is found
};

// Lists every PCI-7200 under `sysfs_devices` (normally /sys/bus/pci/devices).
PciDiscovery find_pci7200(const std::string& sysfs_devices = kSysfsPciDevices);

// How the card will be opened, or why it cannot be.
enum class Transport { None, Vfio, ProgrammedIo };
struct TransportChoice {
  Transport transport = Transport::None;
  std::string error;
};
TransportChoice choose_transport(const PciDeviceLocation& card);

// "<path>: permission denied; add a udev rule or run as root; see ..." and the like.
std::string open_failure_message(const std::string& path, int error_number);

}  // namespace gantry::pci7200
