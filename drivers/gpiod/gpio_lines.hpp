// The seam between the card and the GPIO hardware: the requested output lines set together,
// the requested input lines read together. Lines are named by their index in the map's
// `outputs` / `inputs` lists, as bits of a 64-bit mask.
#pragma once

#include <cstdint>

namespace gantry {

class GpioLines {
 public:
  virtual ~GpioLines() = default;
  // Drives every output line whose bit is set in `changed` to its bit in `levels`; the other
  // lines keep their level. Called from the real-time thread: must not allocate. False on a
  // device error (errno says which).
  virtual bool set_outputs(std::uint64_t changed, std::uint64_t levels) = 0;
  // Reads every input line at once into `levels`. False on a device error (errno says which).
  virtual bool read_inputs(std::uint64_t& levels) = 0;
};

}  // namespace gantry
