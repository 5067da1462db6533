#include "pgmcl/sensor_model/beam_likelihood.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "pgmcl/sensor_model/sigma_models.hpp"

namespace pgmcl::sensor_model {
namespace {

constexpr double kNegInf = -std::numeric_limits<double>::infinity();

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("BeamLikelihood: " + what);
}
bool positive(double v) {
  return std::isfinite(v) && v > 0.0;
}
bool unit(double v) {
  return std::isfinite(v) && v >= 0.0 && v <= 1.0;
}

}  // namespace

void BeamLikelihoodParams::validate() const {
  require(positive(sigma_along),
          "sigma_along must be positive and finite (got " + std::to_string(sigma_along) + " m)");
  require(positive(sigma_across),
          "sigma_across must be positive and finite (got " + std::to_string(sigma_across) + " m)");
  require(std::isfinite(model_mismatch) && model_mismatch >= 0.0,
          "model_mismatch must be finite and >= 0 (got " + std::to_string(model_mismatch) + " m)");
  require(unit(w_hit), "w_hit must be in [0, 1] (got " + std::to_string(w_hit) + ")");
  require(unit(w_rand), "w_rand must be in [0, 1] (got " + std::to_string(w_rand) + ")");
  require(std::abs(w_hit + w_rand - 1.0) <= 1e-9,
          "w_hit + w_rand must be 1 within 1e-9 (got " + std::to_string(w_hit + w_rand) + ")");
  require(positive(max_range),
          "max_range must be positive and finite (got " + std::to_string(max_range) + " m)");
}

BeamLikelihood::BeamLikelihood(const BeamLikelihoodParams& params, double resolution,
                               double reach_sigmas)
    : params_(params), reach_sigmas_(reach_sigmas) {
  params.validate();
  require(std::isfinite(resolution) && resolution >= 0.0,
          "resolution must be finite and >= 0 (got " + std::to_string(resolution) + " m)");
  require(positive(reach_sigmas),
          "reach_sigmas must be positive and finite (got " + std::to_string(reach_sigmas) + ")");
  const double cell = params.add_discretisation ? resolution : 0.0;
  sigma_along_eff_ = effective_sigma(params.sigma_along, cell, params.model_mismatch);
  sigma_across_eff_ = effective_sigma(params.sigma_across, cell, params.model_mismatch);
  inv_var_along_ = 1.0 / (sigma_along_eff_ * sigma_along_eff_);
  inv_var_across_ = 1.0 / (sigma_across_eff_ * sigma_across_eff_);

  log_hit_norm_ =
      params.w_hit > 0.0
          ? std::log(params.w_hit / (std::sqrt(2.0 * std::numbers::pi) * sigma_along_eff_))
          : kNegInf;
  log_floor_ = params.w_rand > 0.0 ? std::log(params.w_rand / params.max_range) : kNegInf;
  ll_background_ = params.w_rand > 0.0 ? log_floor_ : log_hit_norm_ - 0.5 * reach_m2();
  ll_max_ = log_likelihood_of_m2(0.0);  // reads neither ll_max_ nor nats_per_step_
  const double range = ll_max_ - ll_background_;
  nats_per_step_ = range > 1e-12 ? range / 255.0 : 1.0;
  background_ = quantise_m2(std::numeric_limits<double>::infinity());
}

double BeamLikelihood::log_likelihood_of_m2(double m2) const noexcept {
  if (!(m2 < reach_m2())) return ll_background_;
  const double a = log_hit_norm_ - 0.5 * m2, b = log_floor_;
  const double hi = std::max(a, b), lo = std::min(a, b);
  return lo == kNegInf ? hi : hi + std::log1p(std::exp(lo - hi));
}

std::uint8_t BeamLikelihood::quantise_m2(double m2) const noexcept {
  const double steps = (ll_max_ - log_likelihood_of_m2(m2)) / nats_per_step_;
  return static_cast<std::uint8_t>(std::clamp(std::lround(steps), 0L, 255L));
}

}  // namespace pgmcl::sensor_model
