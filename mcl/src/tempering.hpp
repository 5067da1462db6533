#pragma once
// Internal: adaptive limit on the tempering exponent (see LikelihoodConfig::min_ess_ratio).

#include <span>

namespace pgmcl::detail {

/// Effective sample size of the weights w_i ∝ exp(log_w[i] + t * ll[i]).
[[nodiscard]] double tempered_ess(std::span<const double> log_w, std::span<const double> ll,
                                  double t) noexcept;

/// The tempering exponent to use: tau_max if the scan keeps
///   ESS(tau_max) >= min_ess_ratio * ESS(0),
/// otherwise (bisection in log t over [tau_max * 1e-6, tau_max]) the largest t found that
/// keeps it, so one scan never collapses the particle set onto a handful of particles.
/// min_ess_ratio <= 0 disables the limit.
[[nodiscard]] double limit_tempering(std::span<const double> log_w, std::span<const double> ll,
                                     double tau_max, double min_ess_ratio) noexcept;

}  // namespace pgmcl::detail
