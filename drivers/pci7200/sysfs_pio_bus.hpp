// The programmed-I/O fallback for machines without an IOMMU: the card bound to
// uio_pci_generic (so no other driver touches it), its two I/O-port BARs read and written
// through sysfs resource files, and no DMA: the feeder writes words into the bridge's FIFO.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>

#include "pci7200/pci7200_bus.hpp"    // Pci7200Bus
#include "pci7200/pci_discovery.hpp"  // PciDeviceLocation

namespace gantry::pci7200 {

class SysfsPioBus final : public Pci7200Bus {
 public:
  // nullptr and a message naming the fix on failure. `poll_interval` zero busy-polls, which
  // this transport needs at high pacer rates (the FIFO holds 8 words).
  static std::unique_ptr<SysfsPioBus> open(const PciDeviceLocation& card,
                                           std::chrono::nanoseconds poll_interval,
                                           std::string* error);
  ~SysfsPioBus() override;
  SysfsPioBus(const SysfsPioBus&) = delete;
  SysfsPioBus& operator=(const SysfsPioBus&) = delete;

  std::uint32_t read32(Bar bar, std::uint32_t offset) override;
  void write32(Bar bar, std::uint32_t offset, std::uint32_t value) override;
  bool failed() const override { return failed_.load(std::memory_order_acquire); }
  DmaBuffer dma_buffer() override { return {}; }
  void pause() override;
  void sleep_for(std::chrono::nanoseconds duration) override;
  std::string describe() const override { return description_; }

 private:
  SysfsPioBus() = default;

  int resource_[2] = {-1, -1};
  std::chrono::nanoseconds poll_interval_{0};
  std::atomic<bool> failed_{false};
  std::string description_;
};

}  // namespace gantry::pci7200
