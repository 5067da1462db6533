#pragma once
// Internal: weighted first and second moments of (x, y, theta) particles, shared by the
// pose estimate and the clustering. Everything is accumulated relative to a reference
// particle: a collapsed cloud then has exactly zero deviations, and map coordinates far
// from the origin do not cancel in the second moments.

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>

#include "pgmcl/common/se2.hpp"

namespace pgmcl::detail {

/// sum w, sum w dx, sum w dy, sum w cos(dtheta), sum w sin(dtheta).
using FirstMoments = std::array<double, 5>;
/// sum w e e^T: xx, xy, xt, yy, yt, tt.
using SecondMoments = std::array<double, 6>;

struct Reference {
  double x = 0.0, y = 0.0, theta = 0.0;
};

/// The mean relative to the reference: dx, dy, and the circular mean heading offset.
struct RelativeMean {
  double dx = 0.0, dy = 0.0, dtheta = 0.0;
  double concentration = 0.0;  // mean resultant length R
};

inline void add_first(FirstMoments& m, const Reference& r, double x, double y, double theta,
                      double w) noexcept {
  const double dt = theta - r.theta;
  m[0] += w;
  m[1] += w * (x - r.x);
  m[2] += w * (y - r.y);
  m[3] += w * std::cos(dt);
  m[4] += w * std::sin(dt);
}

[[nodiscard]] inline RelativeMean relative_mean(const FirstMoments& m) noexcept {
  // R <= 1 mathematically; min() removes the rounding excess.
  return {m[1] / m[0], m[2] / m[0], std::atan2(m[4], m[3]),
          std::min(1.0, std::hypot(m[3], m[4]) / m[0])};
}

[[nodiscard]] inline Pose2 absolute_mean(const Reference& r, const RelativeMean& rm) noexcept {
  return {r.x + rm.dx, r.y + rm.dy, wrap_angle(r.theta + rm.dtheta)};
}

inline void add_second(SecondMoments& m, const Reference& r, const RelativeMean& rm, double x,
                       double y, double theta, double w) noexcept {
  const double ex = (x - r.x) - rm.dx;
  const double ey = (y - r.y) - rm.dy;
  const double et = wrap_angle((theta - r.theta) - rm.dtheta);  // around the circular mean
  m[0] += w * ex * ex;
  m[1] += w * ex * ey;
  m[2] += w * ex * et;
  m[3] += w * ey * ey;
  m[4] += w * ey * et;
  m[5] += w * et * et;
}

/// Covariance sum w e e^T / sum w, symmetric by construction. A sum of rank-one PSD terms
/// can still round to a tiny negative eigenvalue (collinear clouds); then the eigenvalues
/// are floored at 1e-12 of the largest and the matrix rebuilt, so Cholesky succeeds.
[[nodiscard]] inline Eigen::Matrix3d covariance_of(const SecondMoments& m, double w_sum) {
  Eigen::Matrix3d c;
  c << m[0], m[1], m[2], m[1], m[3], m[4], m[2], m[4], m[5];
  c /= w_sum;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(c);
  if (es.info() == Eigen::Success && es.eigenvalues()(0) < 0.0) {
    const double floor = 1e-12 * std::max(es.eigenvalues()(2), 0.0);
    const Eigen::Vector3d lambda = es.eigenvalues().cwiseMax(floor);
    c = es.eigenvectors() * lambda.asDiagonal() * es.eigenvectors().transpose();
    c = 0.5 * (c + c.transpose()).eval();
  }
  return c;
}

}  // namespace pgmcl::detail
