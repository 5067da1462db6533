#include "pgmcl/mcl/kld_sampling.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "grid_key.hpp"
#include "pgmcl/common/random.hpp"

namespace pgmcl {
namespace {

/// Standard normal quantile for p in (0, 0.5]: P. J. Acklam's algorithm (2003), lower
/// and central regions, then one Halley step x -= u / (1 + x u / 2) with
/// u = (Phi(x) - p) / phi(x). Phi is evaluated with erfc(-x / sqrt 2), exact in relative
/// terms for x <= 0, which is why the upper half is handled by symmetry.
double lower_normal_quantile(double p) {
  constexpr double a[] = {-3.969683028665376e+01, 2.209460984245205e+02,  -2.759285104469687e+02,
                          1.383577518672690e+02,  -3.066479806614716e+01, 2.506628277459239e+00};
  constexpr double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                          6.680131188771972e+01, -1.328068155288572e+01};
  constexpr double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                          -2.549732539343734e+00, 4.374664141464968e+00,  2.938163982698783e+00};
  constexpr double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                          3.754408661907416e+00};
  constexpr double kLowRegion = 0.02425;

  double x = 0.0;
  if (p < kLowRegion) {
    const double q = std::sqrt(-2.0 * std::log(p));
    x = (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
        ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1.0);
  } else {
    const double q = p - 0.5;
    const double r = q * q;
    x = (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
        (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1.0);
  }
  const double e = 0.5 * std::erfc(-x / std::numbers::sqrt2) - p;
  const double u = e * std::sqrt(2.0 * std::numbers::pi) * std::exp(0.5 * x * x);
  // For subnormal p, exp(x^2 / 2) overflows; Acklam's value is then kept unrefined.
  return std::isfinite(u) ? x - u / (1.0 + 0.5 * x * u) : x;
}

}  // namespace

double normal_quantile(double p) {
  if (!(p >= 0.0 && p <= 1.0)) {
    throw std::invalid_argument("normal_quantile: p = " + std::to_string(p) + " is outside [0, 1]");
  }
  if (p == 0.0) return -std::numeric_limits<double>::infinity();
  if (p == 1.0) return std::numeric_limits<double>::infinity();
  if (p == 0.5) return 0.0;
  // 1 - p is exact for p in [0.5, 1] (Sterbenz), so the symmetry costs no accuracy.
  return p < 0.5 ? lower_normal_quantile(p) : -lower_normal_quantile(1.0 - p);
}

std::size_t kld_required_particles(std::size_t k_bins, double epsilon, double z_quantile) {
  if (!(epsilon > 0.0) || !std::isfinite(epsilon) || !std::isfinite(z_quantile)) {
    throw std::invalid_argument("kld_required_particles: epsilon = " + std::to_string(epsilon) +
                                ", z = " + std::to_string(z_quantile) +
                                "; need finite epsilon > 0 and finite z");
  }
  if (k_bins <= 1) return 0;
  const double km1 = static_cast<double>(k_bins - 1);
  const double a = 2.0 / (9.0 * km1);
  const double bracket = 1.0 - a + std::sqrt(a) * z_quantile;  // Fox 2003, Eq. (13)
  if (bracket <= 0.0) return 0;
  const double n = std::ceil(km1 / (2.0 * epsilon) * bracket * bracket * bracket);
  constexpr auto kMax = static_cast<double>(std::numeric_limits<std::size_t>::max());
  return n >= kMax ? std::numeric_limits<std::size_t>::max() : static_cast<std::size_t>(n);
}

KldBinner::KldBinner(double bin_x, double bin_y, double bin_theta)
    : bin_x_(bin_x), bin_y_(bin_y), bin_theta_(bin_theta) {
  const auto ok = [](double v) { return v > 0.0 && std::isfinite(v); };
  if (!ok(bin_x) || !ok(bin_y) || !ok(bin_theta)) {
    throw std::invalid_argument(
        "KldBinner: bin sizes must be finite and > 0 (got x = " + std::to_string(bin_x) +
        " m, y = " + std::to_string(bin_y) + " m, theta = " + std::to_string(bin_theta) + " rad)");
  }
  const double sectors = detail::sector_count(bin_theta);
  if (sectors > static_cast<double>(detail::kMaxSectors)) {
    throw std::invalid_argument("KldBinner: bin_theta = " + std::to_string(bin_theta) +
                                " rad gives more than 65535 heading bins");
  }
  theta_bins_ = static_cast<std::size_t>(sectors);
  inv_x_ = 1.0 / bin_x;
  inv_y_ = 1.0 / bin_y;
  inv_theta_ = sectors / (2.0 * std::numbers::pi);
  reserve(4096);
}

void KldBinner::reserve(std::size_t max_bins) {
  // Load factor <= 1/2 keeps linear probing short.
  const std::size_t slots = std::bit_ceil(std::max<std::size_t>(16, 2 * max_bins));
  if (slots > keys_.size()) rehash(slots);
}

void KldBinner::clear() noexcept {
  occupied_ = 0;
  if (++generation_ == 0) {  // stamps wrapped after 2^32 clears: reset them once
    std::fill(stamps_.begin(), stamps_.end(), 0u);
    generation_ = 1;
  }
}

std::uint64_t KldBinner::key_of(double x, double y, double theta) const noexcept {
  return detail::pack_cell(detail::cell_field(x * inv_x_), detail::cell_field(y * inv_y_),
                           detail::sector_of(theta, inv_theta_, theta_bins_));
}

bool KldBinner::insert_key(std::uint64_t key) noexcept {
  const std::size_t mask = keys_.size() - 1;
  for (std::size_t i = splitmix64(key) & mask;; i = (i + 1) & mask) {
    if (stamps_[i] != generation_) {
      stamps_[i] = generation_;
      keys_[i] = key;
      ++occupied_;
      return true;
    }
    if (keys_[i] == key) return false;
  }
}

void KldBinner::rehash(std::size_t slots) {
  std::vector<std::uint64_t> old_keys(slots);
  std::vector<std::uint32_t> old_stamps(slots, 0u);
  old_keys.swap(keys_);
  old_stamps.swap(stamps_);
  const std::uint32_t old_generation = generation_;
  generation_ = 1;
  occupied_ = 0;
  for (std::size_t i = 0; i < old_keys.size(); ++i) {
    if (old_stamps[i] == old_generation) insert_key(old_keys[i]);
  }
}

bool KldBinner::insert(double x, double y, double theta) {
  if (2 * (occupied_ + 1) > keys_.size()) rehash(2 * keys_.size());
  return insert_key(key_of(x, y, theta));
}

}  // namespace pgmcl
