// Register access through /sys/bus/pci/devices/<card>/resource0 and resource1.
#include "pci7200/sysfs_pio_bus.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sched.h>
#include <unistd.h>

#include <cerrno>
#include <fstream>
#include <sstream>

#include "pci7200/monotonic_sleep.hpp"

namespace gantry::pci7200 {
namespace {

constexpr unsigned long kIoResourceFlag = 0x100;  // IORESOURCE_IO in the "resource" file

}  // namespace

std::unique_ptr<SysfsPioBus> SysfsPioBus::open(const PciDeviceLocation& card,
                                               std::chrono::nanoseconds poll_interval,
                                               std::string* error) {
  std::unique_ptr<SysfsPioBus> bus(new SysfsPioBus());
  bus->poll_interval_ = poll_interval;
  // "resource" has one line per BAR: start end flags. Only I/O BARs are readable as files.
  std::ifstream resources(card.directory + "/resource");
  const std::uint32_t bar_bytes[2] = {kAmccBarBytes, kCardBarBytes};
  for (int bar = 0; bar < 2; ++bar) {
    std::string line;
    unsigned long long start = 0, end = 0, flags = 0;
    if (!std::getline(resources, line) ||
        !(std::istringstream(line) >> std::hex >> start >> end >> flags) ||
        !(flags & kIoResourceFlag) || end + 1 - start < bar_bytes[bar]) {
      *error = fmt::format("{}: BAR{} is not a {}-byte I/O-port BAR; is this the PCI-7200?",
                           card.address, bar, bar_bytes[bar]);
      return nullptr;
    }
    const std::string path = fmt::format("{}/resource{}", card.directory, bar);
    bus->resource_[bar] = ::open(path.c_str(), O_RDWR | O_CLOEXEC);
    if (bus->resource_[bar] < 0) {
      *error = open_failure_message(path, errno);
      return nullptr;
    }
  }
  bus->description_ = fmt::format("PCI-7200 {} via sysfs programmed I/O (no DMA; {})", card.address,
                                  card.driver.empty() ? "no driver bound" : card.driver);
  return bus;
}

SysfsPioBus::~SysfsPioBus() {
  for (int fd : resource_)
    if (fd >= 0) ::close(fd);
}

std::uint32_t SysfsPioBus::read32(Bar bar, std::uint32_t offset) {
  std::uint32_t value = 0;
  if (pread(resource_[static_cast<int>(bar)], &value, sizeof(value), offset) != sizeof(value)) {
    failed_.store(true, std::memory_order_release);
    return 0xffffffff;
  }
  return value;
}

void SysfsPioBus::write32(Bar bar, std::uint32_t offset, std::uint32_t value) {
  if (pwrite(resource_[static_cast<int>(bar)], &value, sizeof(value), offset) != sizeof(value))
    failed_.store(true, std::memory_order_release);
}

void SysfsPioBus::pause() {
  if (poll_interval_.count() <= 0)
    sched_yield();
  else
    sleep_monotonic(poll_interval_);
}

void SysfsPioBus::sleep_for(std::chrono::nanoseconds duration) {
  sleep_monotonic(duration);
}

}  // namespace gantry::pci7200
