// The register seam: everything the driver does to the card goes through a Pci7200Bus, so the
// same driver code runs against the real card (VFIO, or sysfs programmed I/O) or against
// EmulatedPci7200 in CI.
#pragma once

#include <chrono>
#include <cstdint>
#include <span>
#include <string>

#include "pci7200/pci7200_registers.hpp"  // Bar

namespace gantry::pci7200 {

// Host memory the card reads by bus-master DMA, and the address the card must be given for
// its first word (an IOVA under VFIO). 32 bits: the S5933's address registers are 32 bits.
struct DmaBuffer {
  std::span<std::uint32_t> words;  // empty: no DMA, programmed I/O only
  std::uint32_t bus_address = 0;
};

class Pci7200Bus {
 public:
  virtual ~Pci7200Bus() = default;

  // 32-bit register access at a BAR offset. A failed access returns all ones and makes
  // failed() true; the driver treats that as a hardware fault.
  virtual std::uint32_t read32(Bar bar, std::uint32_t offset) = 0;
  virtual void write32(Bar bar, std::uint32_t offset, std::uint32_t value) = 0;
  virtual bool failed() const = 0;

  virtual DmaBuffer dma_buffer() = 0;

  // The feeder thread's wait between passes (a short sleep, or a yield when busy-polling).
  virtual void pause() = 0;
  // Any thread's wait while the card plays (e.g. for its FIFO to empty).
  virtual void sleep_for(std::chrono::nanoseconds duration) = 0;
  // Called before the feeder thread starts and before it is joined, so that a bus that paces
  // the feeder (the emulation) can let it go.
  virtual void attach_feeder() {}
  virtual void detach_feeder() {}

  virtual std::string describe() const = 0;
};

}  // namespace gantry::pci7200
