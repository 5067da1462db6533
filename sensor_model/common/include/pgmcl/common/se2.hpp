#pragma once
/// SE(2) maths used across pgmcl: poses, composition, angle wrapping, circular means.
/// Everything here is double: global poses and accumulations never drop to float.

#include <cmath>
#include <numbers>

namespace pgmcl {

/// Wraps an angle to (-pi, pi].
[[nodiscard]] inline double wrap_angle(double a) noexcept {
  constexpr double kPi = std::numbers::pi;
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  if (a > -kPi && a <= kPi) return a;
  a = std::fmod(a + kPi, kTwoPi);
  if (a <= 0.0) a += kTwoPi;
  return a - kPi;
}

/// Float version for the map-local hot path. The range is (-pi, pi] as float sees it,
/// i.e. (-float(pi), float(pi)], with float(pi) slightly above pi: in-range inputs are
/// returned unchanged (so wrapping is idempotent), and a double result that rounds to
/// -float(pi) is mapped to +float(pi).
[[nodiscard]] inline float wrap_angle(float a) noexcept {
  constexpr float kPiF = std::numbers::pi_v<float>;
  if (a > -kPiF && a <= kPiF) return a;
  const auto r = static_cast<float>(wrap_angle(static_cast<double>(a)));
  return r <= -kPiF ? kPiF : r;
}

/// A planar rigid transform / pose: x, y in metres, theta in radians (kept wrapped).
struct Pose2 {
  double x = 0.0;      ///< metres
  double y = 0.0;      ///< metres
  double theta = 0.0;  ///< radians, in (-pi, pi]

  /// this ∘ other: `other` expressed in this pose's frame, mapped to the parent frame.
  [[nodiscard]] Pose2 compose(const Pose2& other) const noexcept {
    const double c = std::cos(theta), s = std::sin(theta);
    return {x + c * other.x - s * other.y, y + s * other.x + c * other.y,
            wrap_angle(theta + other.theta)};
  }
  [[nodiscard]] Pose2 inverse() const noexcept {
    const double c = std::cos(theta), s = std::sin(theta);
    return {-c * x - s * y, s * x - c * y, wrap_angle(-theta)};
  }
  /// The pose of `to` in this pose's frame: inverse() ∘ to.
  [[nodiscard]] Pose2 between(const Pose2& to) const noexcept { return inverse().compose(to); }
  /// Maps a point from this pose's frame to the parent frame.
  void transform_point(double px, double py, double& out_x, double& out_y) const noexcept {
    const double c = std::cos(theta), s = std::sin(theta);
    out_x = x + c * px - s * py;
    out_y = y + s * px + c * py;
  }
};

/// Running circular mean of headings: accumulate weighted unit vectors, read atan2.
struct CircularMean {
  double sum_cos = 0.0;
  double sum_sin = 0.0;
  void add(double angle, double weight = 1.0) noexcept {
    sum_cos += weight * std::cos(angle);
    sum_sin += weight * std::sin(angle);
  }
  [[nodiscard]] double mean() const noexcept { return std::atan2(sum_sin, sum_cos); }
  /// Mean resultant length R in [0, 1] given the total weight (1 = all headings equal).
  [[nodiscard]] double resultant_length(double total_weight) const noexcept {
    return total_weight > 0.0 ? std::hypot(sum_cos, sum_sin) / total_weight : 0.0;
  }
};

}  // namespace pgmcl
