#include "tempering.hpp"

#include <cmath>
#include <limits>

namespace pgmcl::detail {

double tempered_ess(std::span<const double> log_w, std::span<const double> ll, double t) noexcept {
  double m = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < log_w.size(); ++i) {
    const double a = log_w[i] + t * ll[i];
    if (a > m) m = a;
  }
  if (!std::isfinite(m)) return 0.0;
  double s1 = 0.0, s2 = 0.0;
  for (std::size_t i = 0; i < log_w.size(); ++i) {
    const double e = std::exp(log_w[i] + t * ll[i] - m);  // exp(-inf) = 0
    s1 += e;
    s2 += e * e;
  }
  return s2 > 0.0 ? s1 * s1 / s2 : 0.0;
}

double limit_tempering(std::span<const double> log_w, std::span<const double> ll, double tau_max,
                       double min_ess_ratio) noexcept {
  if (!(min_ess_ratio > 0.0) || log_w.empty()) return tau_max;
  const double target = min_ess_ratio * tempered_ess(log_w, ll, 0.0);
  if (tempered_ess(log_w, ll, tau_max) >= target) return tau_max;
  // ESS falls as t grows (the weights sharpen); bisect on log t for the crossing. 16 steps
  // over a factor 1e6 (13.8 in log t) pin t to within 0.03 %.
  double lo = std::log(tau_max) - 13.8, hi = std::log(tau_max);
  if (tempered_ess(log_w, ll, std::exp(lo)) < target) return std::exp(lo);
  for (int it = 0; it < 16; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (tempered_ess(log_w, ll, std::exp(mid)) >= target)
      lo = mid;
    else
      hi = mid;
  }
  return std::exp(lo);
}

}  // namespace pgmcl::detail
