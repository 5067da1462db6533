#pragma once
// Private helper: standard normal probability mass of an interval, accurate in both tails.

#include <cmath>
#include <numbers>

namespace pgmcl::sensor_model::detail {

/// P(a <= Z <= b) for Z ~ N(0, 1), a <= b. Uses erfc on the side of the tail the interval
/// lies in, so masses far from 0 keep their relative precision instead of cancelling to 0.
[[nodiscard]] inline double normal_mass(double a, double b) noexcept {
  constexpr double r = 1.0 / std::numbers::sqrt2;
  if (a >= 0.0) return 0.5 * (std::erfc(a * r) - std::erfc(b * r));
  if (b <= 0.0) return 0.5 * (std::erfc(-b * r) - std::erfc(-a * r));
  return 1.0 - 0.5 * (std::erfc(-a * r) + std::erfc(b * r));
}

}  // namespace pgmcl::sensor_model::detail
