// VFIO group/container/device setup, BAR access and the IOMMU-mapped DMA buffer.
#include "pci7200/vfio_bus.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <linux/pci_regs.h>
#include <linux/vfio.h>
#include <sched.h>
#include <sys/ioctl.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "pci7200/monotonic_sleep.hpp"

namespace gantry::pci7200 {
namespace {

// Below 4 GiB, since MRAR is 32 bits; any free IOVA will do, the IOMMU translates it.
constexpr std::uint32_t kDmaIova = 0x1000'0000;

std::string os_error(const std::string& what) {
  return fmt::format("{}: {}", what, std::strerror(errno));
}

}  // namespace

std::unique_ptr<VfioBus> VfioBus::open(const PciDeviceLocation& card,
                                       const VfioBusSettings& settings, std::string* error) {
  std::unique_ptr<VfioBus> bus(new VfioBus());
  bus->poll_interval_ = settings.poll_interval;
  auto fail = [&](std::string message) {
    *error = std::move(message);
    return nullptr;
  };

  const std::string group_path = fmt::format("{}/vfio/{}", settings.dev_root, card.iommu_group);
  bus->group_ = ::open(group_path.c_str(), O_RDWR | O_CLOEXEC);
  if (bus->group_ < 0) return fail(open_failure_message(group_path, errno));
  vfio_group_status status{};
  status.argsz = sizeof(status);
  if (ioctl(bus->group_, VFIO_GROUP_GET_STATUS, &status) < 0)
    return fail(fmt::format("{}: not a VFIO group ({}); {}", group_path, std::strerror(errno),
                            kReadmeHint));
  if (!(status.flags & VFIO_GROUP_FLAGS_VIABLE))
    return fail(fmt::format(
        "IOMMU group {0} is not viable: every device in /sys/kernel/iommu_groups/{0}/devices "
        "must be bound to vfio-pci (a PCI card behind a PCIe-to-PCI bridge shares its group); "
        "{1}",
        card.iommu_group, kReadmeHint));

  const std::string container_path = settings.dev_root + "/vfio/vfio";
  bus->container_ = ::open(container_path.c_str(), O_RDWR | O_CLOEXEC);
  if (bus->container_ < 0) return fail(open_failure_message(container_path, errno));
  if (ioctl(bus->container_, VFIO_GET_API_VERSION) != VFIO_API_VERSION)
    return fail(fmt::format("{}: unknown VFIO API version", container_path));
  if (ioctl(bus->container_, VFIO_CHECK_EXTENSION, VFIO_TYPE1_IOMMU) <= 0)
    return fail(fmt::format("{}: no type-1 IOMMU support; {}", container_path, kReadmeHint));
  if (ioctl(bus->group_, VFIO_GROUP_SET_CONTAINER, &bus->container_) < 0)
    return fail(os_error(group_path + ": joining the VFIO container"));
  if (ioctl(bus->container_, VFIO_SET_IOMMU, VFIO_TYPE1_IOMMU) < 0)
    return fail(os_error(container_path + ": selecting the type-1 IOMMU"));
  bus->device_ = ioctl(bus->group_, VFIO_GROUP_GET_DEVICE_FD, card.address.c_str());
  if (bus->device_ < 0) return fail(os_error(group_path + ": getting device " + card.address));

  const std::uint32_t bar_bytes[2] = {kAmccBarBytes, kCardBarBytes};
  for (int bar = 0; bar < 2; ++bar) {
    vfio_region_info region{};
    region.argsz = sizeof(region);
    region.index = VFIO_PCI_BAR0_REGION_INDEX + static_cast<std::uint32_t>(bar);
    if (ioctl(bus->device_, VFIO_DEVICE_GET_REGION_INFO, &region) < 0)
      return fail(os_error(fmt::format("{}: BAR{} region", card.address, bar)));
    const std::uint32_t rw = VFIO_REGION_INFO_FLAG_READ | VFIO_REGION_INFO_FLAG_WRITE;
    if ((region.flags & rw) != rw || region.size < bar_bytes[bar])
      return fail(fmt::format("{}: BAR{} is {} bytes, not the PCI-7200's {}; is this the card?",
                              card.address, bar, region.size, bar_bytes[bar]));
    bus->bar_offset_[bar] = region.offset;
  }

  // The card must answer I/O cycles and may master the bus.
  vfio_region_info config{};
  config.argsz = sizeof(config);
  config.index = VFIO_PCI_CONFIG_REGION_INDEX;
  std::uint16_t command = 0;
  if (ioctl(bus->device_, VFIO_DEVICE_GET_REGION_INFO, &config) < 0 ||
      pread(bus->device_, &command, 2, static_cast<off_t>(config.offset + PCI_COMMAND)) != 2)
    return fail(os_error(card.address + ": reading the PCI command register"));
  command |= PCI_COMMAND_IO | PCI_COMMAND_MASTER;
  if (pwrite(bus->device_, &command, 2, static_cast<off_t>(config.offset + PCI_COMMAND)) != 2)
    return fail(os_error(card.address + ": enabling I/O and bus mastering"));

  const std::size_t page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
  bus->dma_bytes_ = (settings.dma_words * 4 + page - 1) / page * page;
  void* memory = mmap(nullptr, bus->dma_bytes_, PROT_READ | PROT_WRITE,
                      MAP_SHARED | MAP_ANONYMOUS | MAP_POPULATE, -1, 0);
  if (memory == MAP_FAILED) return fail(os_error("allocating the DMA buffer"));
  bus->dma_ = static_cast<std::uint32_t*>(memory);
  bus->dma_words_ = settings.dma_words;
  vfio_iommu_type1_dma_map map{};
  map.argsz = sizeof(map);
  map.flags = VFIO_DMA_MAP_FLAG_READ | VFIO_DMA_MAP_FLAG_WRITE;
  map.vaddr = reinterpret_cast<std::uint64_t>(memory);
  map.iova = kDmaIova;
  map.size = bus->dma_bytes_;
  if (ioctl(bus->container_, VFIO_IOMMU_MAP_DMA, &map) < 0)
    return fail(
        fmt::format("mapping the DMA buffer through the IOMMU failed ({}); VFIO pins it "
                    "against the locked-memory limit: raise `ulimit -l`; {}",
                    std::strerror(errno), kReadmeHint));
  bus->dma_mapped_ = true;
  bus->description_ =
      fmt::format("PCI-7200 {} via VFIO (IOMMU group {}, {}-word DMA buffer at IOVA {:#x})",
                  card.address, card.iommu_group, settings.dma_words, kDmaIova);
  return bus;
}

VfioBus::~VfioBus() {
  if (dma_mapped_) {
    vfio_iommu_type1_dma_unmap unmap{};
    unmap.argsz = sizeof(unmap);
    unmap.iova = kDmaIova;
    unmap.size = dma_bytes_;
    ioctl(container_, VFIO_IOMMU_UNMAP_DMA, &unmap);
  }
  if (dma_ != nullptr) munmap(dma_, dma_bytes_);
  if (device_ >= 0) ::close(device_);
  if (group_ >= 0) ::close(group_);
  if (container_ >= 0) ::close(container_);
}

std::uint32_t VfioBus::read32(Bar bar, std::uint32_t offset) {
  std::uint32_t value = 0;
  const auto at = static_cast<off_t>(bar_offset_[static_cast<int>(bar)] + offset);
  if (pread(device_, &value, sizeof(value), at) != sizeof(value)) {
    failed_.store(true, std::memory_order_release);
    return 0xffffffff;
  }
  return value;
}

void VfioBus::write32(Bar bar, std::uint32_t offset, std::uint32_t value) {
  const auto at = static_cast<off_t>(bar_offset_[static_cast<int>(bar)] + offset);
  if (pwrite(device_, &value, sizeof(value), at) != sizeof(value))
    failed_.store(true, std::memory_order_release);
}

DmaBuffer VfioBus::dma_buffer() {
  return {std::span(dma_, dma_words_), kDmaIova};
}

void VfioBus::pause() {
  if (poll_interval_.count() <= 0)
    sched_yield();  // busy-poll: under SCHED_FIFO on an isolated CPU this returns at once
  else
    sleep_monotonic(poll_interval_);
}

void VfioBus::sleep_for(std::chrono::nanoseconds duration) {
  sleep_monotonic(duration);
}

}  // namespace gantry::pci7200
