// One degree in radians, for the tests that state angles in degrees.
#pragma once

#include <numbers>

namespace gf::test {

inline constexpr double kDeg = std::numbers::pi / 180;  ///< rad per degree

}  // namespace gf::test
