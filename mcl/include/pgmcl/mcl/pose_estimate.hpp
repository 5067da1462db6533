#pragma once
/// Weighted mean and covariance of a particle set (structure of arrays, map-local floats).

#include <Eigen/Core>
#include <span>

#include "pgmcl/common/se2.hpp"

namespace pgmcl {

struct PoseEstimate {
  /// Weighted mean: x, y arithmetic; heading the circular mean atan2(sum w sin, sum w cos).
  Pose2 mean{};
  /// Weighted covariance of (x, y, theta) about the mean, heading deviations wrapped to
  /// (-pi, pi] around the circular mean: sum w e e^T / sum w (the population form).
  /// Units m^2, m rad, rad^2. Symmetric and positive semi-definite.
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  /// Mean resultant length R of the headings in [0, 1]: 1 = all equal, ~0 = spread round
  /// the circle (the circular mean is then arbitrary and the heading variance meaningless).
  double heading_concentration = 0.0;
};

/// Weighted mean and covariance of the particles (x[i], y[i], theta[i]) with weights w[i]
/// (non-negative; need not be normalised). Sums run in double, relative to the first
/// particle, over fixed blocks combined in order: `threads` (1 = serial reference,
/// 0 = OpenMP default, n = n threads) changes the speed, never the bits of the result.
/// A collapsed cloud gives exactly zero covariance. Covariance round-off that would make
/// an eigenvalue negative is repaired (eigenvalues floored at 1e-12 of the largest).
/// Throws std::invalid_argument if the spans differ in size, are empty, or the weights
/// do not have a positive finite sum.
[[nodiscard]] PoseEstimate estimate_pose(std::span<const float> x, std::span<const float> y,
                                         std::span<const float> theta, std::span<const double> w,
                                         int threads = 0);

}  // namespace pgmcl
