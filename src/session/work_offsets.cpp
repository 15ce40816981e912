// The work offsets per axis.
#include "gantry/session/work_offsets.hpp"

#include <fmt/format.h>

namespace gantry::session {

std::vector<OffsetRow> offset_rows(const Vec6& work, const ModalState& m, int axes,
                                   const CommandTable& table) {
  static const char kAxes[] = "XYZABC";
  std::vector<OffsetRow> rows;
  for (int i = 0; i < axes && i < kAxisCount; ++i) {
    const double offset = m.zero[i] + m.applied_offset[i];
    const std::string code = fmt::format("Z{}", kAxes[i]);
    rows.push_back(
        {kAxes[i], work[i] + offset, offset, work[i], table.find(code) ? code : std::string()});
  }
  return rows;
}

}  // namespace gantry::session
