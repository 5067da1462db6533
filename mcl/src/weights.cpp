#include "pgmcl/mcl/weights.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace pgmcl {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Largest entry, skipping NaN (every comparison with NaN is false).
[[nodiscard]] double max_of(std::span<const double> v) noexcept {
  double m = -kInf;
  for (const double x : v) {
    if (x > m) m = x;
  }
  return m;
}

}  // namespace

double log_sum_exp(std::span<const double> v) noexcept {
  const double m = max_of(v);
  if (!std::isfinite(m)) return m;  // empty / all -inf / NaN -> -inf; any +inf -> +inf
  double sum = 0.0;
  for (const double x : v) {
    if (x > -kInf) sum += std::exp(x - m);  // NaN fails the test and adds nothing
  }
  return m + std::log(sum);  // sum >= 1: the maximum contributes exp(0)
}

double normalise_log_weights(std::span<double> log_w, std::span<double> w_out) {
  if (log_w.size() != w_out.size()) {
    throw std::invalid_argument("normalise_log_weights: " + std::to_string(log_w.size()) +
                                " log weights but " + std::to_string(w_out.size()) +
                                " output weights");
  }
  const std::size_t n = log_w.size();
  if (n == 0) return -kInf;
  const double m = max_of(log_w);

  if (m == -kInf) {  // nothing has positive likelihood: fall back to uniform
    const double u = 1.0 / static_cast<double>(n);
    const double log_u = -std::log(static_cast<double>(n));
    for (std::size_t i = 0; i < n; ++i) {
      w_out[i] = u;
      log_w[i] = log_u;
    }
    return -kInf;
  }

  if (m == kInf) {  // infinite likelihoods dominate and share the mass
    std::size_t count = 0;
    for (const double x : log_w) count += (x == kInf) ? 1u : 0u;
    const double u = 1.0 / static_cast<double>(count);
    const double log_u = -std::log(static_cast<double>(count));
    for (std::size_t i = 0; i < n; ++i) {
      const bool hit = log_w[i] == kInf;
      w_out[i] = hit ? u : 0.0;
      log_w[i] = hit ? log_u : -kInf;
    }
    return kInf;
  }

  // Max-shifted log-sum-exp: exp(x - m) is in (0, 1], and the maximum contributes 1,
  // so the sum is >= 1 and its log is exact enough for any spread of log weights.
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = log_w[i];
    const double e = (x > -kInf) ? std::exp(x - m) : 0.0;
    w_out[i] = e;
    sum += e;
  }
  const double log_sum = std::log(sum);
  const double inv_sum = 1.0 / sum;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = log_w[i];
    w_out[i] *= inv_sum;
    log_w[i] = (x > -kInf) ? (x - m) - log_sum : -kInf;
  }
  return m + log_sum;
}

double effective_sample_size(std::span<const double> w) noexcept {
  double sum = 0.0, sum_sq = 0.0;
  for (const double x : w) {
    sum += x;
    sum_sq += x * x;
  }
  return sum_sq > 0.0 ? (sum * sum) / sum_sq : 0.0;
}

}  // namespace pgmcl
