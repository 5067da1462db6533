#include "pgmcl/mcl/pose_estimate.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "block_sum.hpp"
#include "weighted_moments.hpp"

namespace pgmcl {

PoseEstimate estimate_pose(std::span<const float> x, std::span<const float> y,
                           std::span<const float> theta, std::span<const double> w, int threads) {
  const std::size_t n = w.size();
  if (x.size() != n || y.size() != n || theta.size() != n) {
    throw std::invalid_argument("estimate_pose: x, y, theta, w have sizes " +
                                std::to_string(x.size()) + ", " + std::to_string(y.size()) + ", " +
                                std::to_string(theta.size()) + ", " + std::to_string(n));
  }
  if (n == 0) throw std::invalid_argument("estimate_pose: no particles");

  const detail::Reference ref{x[0], y[0], theta[0]};
  const detail::FirstMoments first = detail::block_sum<5>(
      n, threads, [&](std::size_t begin, std::size_t end, detail::FirstMoments& acc) {
        for (std::size_t i = begin; i < end; ++i) {
          detail::add_first(acc, ref, x[i], y[i], theta[i], w[i]);
        }
      });
  if (!(first[0] > 0.0) || !std::isfinite(first[0])) {
    throw std::invalid_argument("estimate_pose: weights sum to " + std::to_string(first[0]) +
                                ", expected a positive finite sum");
  }
  const detail::RelativeMean rm = detail::relative_mean(first);

  const detail::SecondMoments second = detail::block_sum<6>(
      n, threads, [&](std::size_t begin, std::size_t end, detail::SecondMoments& acc) {
        for (std::size_t i = begin; i < end; ++i) {
          detail::add_second(acc, ref, rm, x[i], y[i], theta[i], w[i]);
        }
      });

  PoseEstimate e;
  e.mean = detail::absolute_mean(ref, rm);
  e.covariance = detail::covariance_of(second, first[0]);
  e.heading_concentration = rm.concentration;
  return e;
}

}  // namespace pgmcl
