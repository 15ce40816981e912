// DMA double buffer and programmed-I/O FIFO feeding for the PCI-7200's output.
#include "pci7200/output_feeder.hpp"

#include <algorithm>
#include <array>

namespace gantry::pci7200 {
namespace {

constexpr std::uint32_t kCountMask = amcc::kMaxTransferBytes * 2 - 1;  // MRTC's 26 bits

}  // namespace

OutputFeeder::OutputFeeder(Pci7200Bus& bus) : bus_(bus), dma_(bus.dma_buffer()) {
  // The bridge counts bytes in 26 bits; a half never needs to be longer than that.
  const std::size_t max_half = amcc::kMaxTransferBytes / sizeof(std::uint32_t);
  half_words_ = std::min(dma_.words.size() / 2, max_half);
}

void OutputFeeder::reset() {
  bus_.write32(Bar::Amcc, amcc::kMcsr, amcc::kMcsrP2aFifoReset | amcc::kMcsrReadPriority);
  bus_.write32(Bar::Amcc, amcc::kMcsr, amcc::kMcsrReadPriority);
  bus_.write32(Bar::Amcc, amcc::kMrtc, 0);
  bus_.write32(Bar::Amcc, amcc::kIntcsr, amcc::kIntcsrStatusBits);
  read_enabled_ = false;
  staged_[0] = staged_[1] = 0;
  in_flight_ = -1;
  in_flight_words_ = 0;
  stage_half_ = 0;
  completed_ = 0;
  in_flight_fetched_ = 0;
}

FeederSnapshot OutputFeeder::poll() {
  FeederSnapshot s;
  if (in_flight_ >= 0) {
    const std::uint32_t left_bytes = bus_.read32(Bar::Amcc, amcc::kMrtc) & kCountMask;
    const std::size_t left = std::min<std::size_t>(left_bytes / 4, in_flight_words_);
    in_flight_fetched_ = in_flight_words_ - left;
    if (left == 0) {
      completed_ += in_flight_words_;
      in_flight_fetched_ = 0;
      in_flight_words_ = 0;
      in_flight_ = -1;
    }
  }
  const std::uint32_t mcsr = bus_.read32(Bar::Amcc, amcc::kMcsr);
  constexpr std::uint32_t kFullAndEmpty = amcc::kMcsrP2aFifoFull | amcc::kMcsrP2aFifoEmpty;
  s.device_lost = bus_.failed() || (mcsr & kFullAndEmpty) == kFullAndEmpty;
  s.fifo_empty = (mcsr & amcc::kMcsrP2aFifoEmpty) != 0;
  if (uses_dma()) {
    const std::uint32_t intcsr = bus_.read32(Bar::Amcc, amcc::kIntcsr);
    s.dma_error = (intcsr & (amcc::kIntcsrMasterAbort | amcc::kIntcsrTargetAbort)) != 0;
  }
  s.in_flight = in_flight_ >= 0;
  s.words_staged = staged_[0] + staged_[1] > 0;
  return s;
}

void OutputFeeder::feed(WordSource& source) {
  if (!uses_dma()) {
    write_fifo_directly(source);
    return;
  }
  if (in_flight_ < 0) start_staged_transfer();
  stage(source);
  if (in_flight_ < 0) start_staged_transfer();
}

void OutputFeeder::stage(WordSource& source) {
  const int h = stage_half_;
  const std::size_t begin = static_cast<std::size_t>(h) * half_words_ + staged_[h];
  staged_[h] += source.take(dma_.words.subspan(begin, half_words_ - staged_[h]));
}

void OutputFeeder::start_staged_transfer() {
  const int h = stage_half_;
  if (staged_[h] == 0) return;
  const auto offset_bytes = static_cast<std::uint32_t>(h * half_words_ * sizeof(std::uint32_t));
  bus_.write32(Bar::Amcc, amcc::kMrar, dma_.bus_address + offset_bytes);
  // With reads enabled, writing the count starts the transfer.
  bus_.write32(Bar::Amcc, amcc::kMrtc, static_cast<std::uint32_t>(staged_[h] * 4));
  if (!read_enabled_) {
    bus_.write32(Bar::Amcc, amcc::kMcsr, amcc::kMcsrReadEnable | amcc::kMcsrReadPriority);
    read_enabled_ = true;
  }
  in_flight_ = h;
  in_flight_words_ = staged_[h];
  in_flight_fetched_ = 0;
  staged_[h] = 0;
  stage_half_ = 1 - h;
}

void OutputFeeder::write_fifo_directly(WordSource& source) {
  std::array<std::uint32_t, amcc::kFifoWords> words{};
  for (std::uint32_t pass = 0; pass < 2 * amcc::kFifoWords; ++pass) {
    const std::uint32_t mcsr = bus_.read32(Bar::Amcc, amcc::kMcsr);
    if (bus_.failed() || (mcsr & amcc::kMcsrP2aFifoFull)) return;
    // An empty FIFO takes a whole FIFO's worth; otherwise one word at a time, checking.
    const std::size_t room = (mcsr & amcc::kMcsrP2aFifoEmpty) ? words.size() : 1;
    const std::size_t n = source.take(std::span(words).first(room));
    for (std::size_t i = 0; i < n; ++i) bus_.write32(Bar::Amcc, amcc::kFifo, words[i]);
    completed_ += n;
    if (n < room || room == words.size()) return;
  }
}

void OutputFeeder::stop_transfers() {
  if (!uses_dma()) return;
  bus_.write32(Bar::Amcc, amcc::kMcsr, amcc::kMcsrReadPriority);
  read_enabled_ = false;
  if (in_flight_ >= 0) {
    const std::uint32_t left_bytes = bus_.read32(Bar::Amcc, amcc::kMrtc) & kCountMask;
    completed_ += in_flight_words_ - std::min<std::size_t>(left_bytes / 4, in_flight_words_);
    in_flight_fetched_ = 0;
    in_flight_words_ = 0;
    in_flight_ = -1;
  }
  staged_[0] = staged_[1] = 0;
}

bool OutputFeeder::fifo_empty() {
  return (bus_.read32(Bar::Amcc, amcc::kMcsr) & amcc::kMcsrP2aFifoEmpty) != 0;
}

}  // namespace gantry::pci7200
