#include "pgmcl/sensor_model/beam_mixture.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>

#include "detail/normal_mass.hpp"

namespace pgmcl::sensor_model {
namespace {

constexpr double kNegInf = -std::numeric_limits<double>::infinity();

void require_weight(double w, const char* name) {
  if (!(w >= 0.0 && w <= 1.0)) {  // also rejects NaN
    std::ostringstream os;
    os << "BeamMixtureParams: " << name << " = " << w << " is outside [0, 1]";
    throw std::invalid_argument(os.str());
  }
}

void require_positive(double v, const char* name) {
  if (!(std::isfinite(v) && v > 0.0)) {
    std::ostringstream os;
    os << "BeamMixtureParams: " << name << " = " << v << " must be finite and > 0 (metres)";
    throw std::invalid_argument(os.str());
  }
}

double log_or_neg_inf(double v) {
  return v > 0.0 ? std::log(v) : kNegInf;
}

}  // namespace

void BeamMixtureParams::validate() const {
  require_weight(w_hit, "w_hit");
  require_weight(w_rand, "w_rand");
  require_weight(w_max, "w_max");
  const double sum = w_hit + w_rand + w_max;
  if (std::abs(sum - 1.0) > 1e-9) {
    std::ostringstream os;
    os.precision(17);
    os << "BeamMixtureParams: w_hit + w_rand + w_max = " << w_hit << " + " << w_rand << " + "
       << w_max << " = " << sum << " must equal 1 within 1e-9";
    throw std::invalid_argument(os.str());
  }
  require_positive(sigma_hit, "sigma_hit");
  require_positive(max_range, "max_range");
  require_positive(max_spike_width, "max_spike_width");
  if (max_spike_width > max_range) {
    std::ostringstream os;
    os << "BeamMixtureParams: max_spike_width = " << max_spike_width
       << " exceeds max_range = " << max_range;
    throw std::invalid_argument(os.str());
  }
}

BeamMixture::BeamMixture(const BeamMixtureParams& params) : p_(params) {
  p_.validate();
  log_w_hit_ = log_or_neg_inf(p_.w_hit);
  log_rand_ = log_or_neg_inf(p_.w_rand / p_.max_range);
  log_spike_ = log_or_neg_inf(p_.w_max / p_.max_spike_width);
}

double BeamMixture::pdf(double range, double expected_range) const noexcept {
  return std::exp(log_pdf(range, expected_range));
}

double BeamMixture::log_pdf(double range, double expected_range) const noexcept {
  if (range < 0.0) return kNegInf;
  if (!(range < p_.max_range)) range = p_.max_range;  // no-return: >= max, +inf, NaN
  const double mu = std::clamp(expected_range, 0.0, p_.max_range);
  const double s = p_.sigma_hit;

  double hit = kNegInf;
  if (p_.w_hit > 0.0) {
    const double z = (range - mu) / s;
    hit = log_w_hit_ - 0.5 * z * z - std::log(s) - 0.5 * std::log(2.0 * std::numbers::pi);
    // Truncation to [0, max_range]: eta differs from 1 by < 1e-15 beyond 8 sigma from both
    // ends, so the two erfc calls are only paid near them.
    if (mu < 8.0 * s || mu > p_.max_range - 8.0 * s)
      hit -= std::log(detail::normal_mass(-mu / s, (p_.max_range - mu) / s));
  }
  const double spike = range >= p_.max_range - p_.max_spike_width ? log_spike_ : kNegInf;
  const double top = std::max({hit, log_rand_, spike});
  if (top == kNegInf) return kNegInf;
  return top + std::log(std::exp(hit - top) + std::exp(log_rand_ - top) + std::exp(spike - top));
}

}  // namespace pgmcl::sensor_model
