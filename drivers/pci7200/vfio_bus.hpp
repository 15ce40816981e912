// The real card through VFIO: registers by pread/pwrite on the device's BAR regions, and a
// DMA buffer mapped through the IOMMU at a 32-bit IOVA the S5933 can address. The preferred
// transport: the IOMMU confines the card's bus mastering to that buffer.
#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "pci7200/pci7200_bus.hpp"    // Pci7200Bus
#include "pci7200/pci_discovery.hpp"  // PciDeviceLocation

namespace gantry::pci7200 {

struct VfioBusSettings {
  std::string dev_root = "/dev";  // where vfio/<group> and vfio/vfio live
  std::size_t dma_words = 2 * 8192;
  // The feeder's wait between passes; zero busy-polls (give it an isolated CPU).
  std::chrono::nanoseconds poll_interval{10'000};
};

class VfioBus final : public Pci7200Bus {
 public:
  // Opens the card's IOMMU group, container and device; nullptr and a message naming the fix
  // on failure.
  static std::unique_ptr<VfioBus> open(const PciDeviceLocation& card,
                                       const VfioBusSettings& settings, std::string* error);
  ~VfioBus() override;
  VfioBus(const VfioBus&) = delete;
  VfioBus& operator=(const VfioBus&) = delete;

  std::uint32_t read32(Bar bar, std::uint32_t offset) override;
  void write32(Bar bar, std::uint32_t offset, std::uint32_t value) override;
  bool failed() const override { return failed_.load(std::memory_order_acquire); }
  DmaBuffer dma_buffer() override;
  void pause() override;
  void sleep_for(std::chrono::nanoseconds duration) override;
  std::string describe() const override { return description_; }

 private:
  VfioBus() = default;

  int container_ = -1;
  int group_ = -1;
  int device_ = -1;
  std::uint64_t bar_offset_[2] = {0, 0};
  std::uint32_t* dma_ = nullptr;
  std::size_t dma_bytes_ = 0;
  std::size_t dma_words_ = 0;
  bool dma_mapped_ = false;
  std::chrono::nanoseconds poll_interval_{0};
  std::atomic<bool> failed_{false};
  std::string description_;
};

}  // namespace gantry::pci7200
