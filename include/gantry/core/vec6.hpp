// The 6-axis vector of real-valued units (Eigen), kept out of axes.hpp so that only the
// translation units that do vector arithmetic parse Eigen.
#pragma once

#include <Eigen/Core>  // Matrix for 6-axis vectors
#include <array>

#include "gantry/core/axes.hpp"  // kAxisCount

namespace gantry {

// A position or displacement in machine units (in or mm; degrees for rotary axes).
using Vec6 = Eigen::Matrix<double, kAxisCount, 1>;

// A per-axis array (settings' Eigen-free form) as a Vec6.
inline Vec6 to_vec6(const std::array<double, kAxisCount>& a) {
  return Eigen::Map<const Vec6>(a.data());
}

}  // namespace gantry
