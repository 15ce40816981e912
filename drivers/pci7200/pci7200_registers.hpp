// Every register fact the driver relies on, in one place, so that a wrong one is corrected
// once. Sources are cited in drivers/pci7200/README.md ("Register facts"). Facts that public
// sources do not settle are marked UNVERIFIED here and listed in the README.
#pragma once

#include <cstdint>

namespace gantry::pci7200 {

struct PciId {
  std::uint16_t vendor;
  std::uint16_t device;
};

// The ADLINK ID is the one the project was given; pci.ids (2023) has no such entry.
inline constexpr PciId kAdlinkId{0x144a, 0x7200};  // UNVERIFIED
// Cards built around the AMCC S5933 bridge carry AMCC's vendor ID (pci.ids, public driver).
inline constexpr PciId kAmccId{0x10e8, 0x80d8};
inline constexpr PciId kKnownIds[] = {kAdlinkId, kAmccId};

// Both BARs are I/O-port BARs: BAR0 the S5933 bridge's operation registers (0x40 bytes), BAR1
// the card's own registers (0x20 bytes).
enum class Bar : int { Amcc = 0, Card = 1 };
inline constexpr std::uint32_t kAmccBarBytes = 0x40;
inline constexpr std::uint32_t kCardBarBytes = 0x20;

// AMCC S5933 operation registers (BAR0). The output path is "PCI to add-on" (P2A): the
// bridge's bus master *reads* host memory into its P2A FIFO, and the card pops one word per
// pacer tick.
namespace amcc {
inline constexpr std::uint32_t kFifo = 0x20;    // P2A FIFO port: programmed-I/O writes
inline constexpr std::uint32_t kMrar = 0x2c;    // master read address (bus address)
inline constexpr std::uint32_t kMrtc = 0x30;    // master read transfer count, in bytes
inline constexpr std::uint32_t kIntcsr = 0x38;  // interrupt control/status
inline constexpr std::uint32_t kMcsr = 0x3c;    // bus master control/status

inline constexpr std::uint32_t kMcsrP2aFifoFull = 1u << 0;
inline constexpr std::uint32_t kMcsrP2aFifoEmpty = 1u << 2;
inline constexpr std::uint32_t kMcsrP2aCountZero = 1u << 6;
inline constexpr std::uint32_t kMcsrReadPriority = 1u << 12;
inline constexpr std::uint32_t kMcsrReadEnable = 1u << 14;
inline constexpr std::uint32_t kMcsrP2aFifoReset = 1u << 25;

inline constexpr std::uint32_t kIntcsrReadCompleteEnable = 1u << 15;
inline constexpr std::uint32_t kIntcsrReadComplete = 1u << 19;  // write 1 to clear
inline constexpr std::uint32_t kIntcsrMasterAbort = 1u << 20;   // write 1 to clear
inline constexpr std::uint32_t kIntcsrTargetAbort = 1u << 21;   // write 1 to clear
inline constexpr std::uint32_t kIntcsrStatusBits =
    kIntcsrReadComplete | kIntcsrMasterAbort | kIntcsrTargetAbort;

// The only output buffer on the card: the bridge's P2A FIFO. If the card has a deeper add-on
// FIFO (UNVERIFIED either way) it only relaxes the reload deadline this implies.
inline constexpr std::uint32_t kFifoWords = 8;
inline constexpr std::uint32_t kMaxTransferBytes = 1u << 26;
}  // namespace amcc

// The card's registers (BAR1), all accessed as 32-bit words.
namespace card {
inline constexpr std::uint32_t kCounter0 = 0x00;  // 8254 counter 0: input pacer
inline constexpr std::uint32_t kCounter1 = 0x04;  // 8254 counter 1: output pacer
inline constexpr std::uint32_t kCounter2 = 0x08;  // 8254 counter 2: cascade stage
inline constexpr std::uint32_t kCounterControl = 0x0c;
inline constexpr std::uint32_t kDiPort = 0x10;  // 32 inputs, read
inline constexpr std::uint32_t kDoPort = 0x14;  // 32 outputs: write sets them when not paced
inline constexpr std::uint32_t kDioCsr = 0x18;  // digital I/O control/status
inline constexpr std::uint32_t kIntCsr = 0x1c;  // interrupt control/status, cascade bits

// Output half of the DIO control/status register. The bit positions come from a public
// driver that writes them; what each reads back as is UNVERIFIED.
inline constexpr std::uint32_t kDioDoTimerPaced = 0x200;  // output clocked by counter 1
inline constexpr std::uint32_t kDioDoClearFifo = 0x400;
inline constexpr std::uint32_t kDioDoUnderrun = 0x10000;  // write 1 clears; read: flag (UNVERIFIED)

inline constexpr std::uint32_t kIntT1T2Cascade = 0x800;  // pacer = clock / (C1 * C2) when set
}  // namespace card

namespace i8254 {
inline constexpr double kClockHz = 4'000'000;
inline constexpr int kMinDivisor = 2;  // 2 MHz, the card's fastest pacer
inline constexpr int kMaxDivisor = 65535;
inline constexpr int kPacerCounter = 1;
inline constexpr int kPacerMode = 3;  // square wave, as the public driver programs it

// Select `counter`, load LSB then MSB, `mode`, binary. Writing it alone halts the counter
// until a new count is written.
constexpr std::uint32_t control_word(int counter, int mode) {
  return static_cast<std::uint32_t>(counter << 6 | 0x30 | mode << 1);
}
inline constexpr std::uint32_t counter_offset(int counter) {
  return static_cast<std::uint32_t>(counter) * 4;
}
}  // namespace i8254

}  // namespace gantry::pci7200
