#pragma once
/// The per-beam log-likelihood the filter runs: the planar Gaussian of Dekan et al. (Eq. (6))
/// on a grid map, mixed with a uniform "random reading" floor, and the 8-bit quantisation the
/// likelihood tables store. maps::LikelihoodField rasterises exactly this function.
///
/// With (along, across) the offset from a beam's endpoint to the nearest mapped obstacle in
/// the beam's frame and the effective sigmas of effective_sigma() (sensor, cell, mismatch),
///   m2 = along^2 / sigma_along_eff^2 + across^2 / sigma_across_eff^2,
///   p  = w_hit * exp(-m2 / 2) / (sqrt(2 pi) sigma_along_eff) + w_rand / max_range.
/// Eq. (6) is a density per m^2 but a range reading is a density per metre along the beam,
/// so the hit term keeps Eq. (4)'s along-beam normaliser and uses the across-beam factor
/// unnormalised (peak 1), as a penalty for lateral misfit; both terms are then per metre and
/// the mixture is well defined. From m2 = reach_sigmas^2 on, p is the floor alone,
/// log(w_rand / max_range) (with w_rand = 0: the hit term's value at the reach).
///
/// Quantisation: q = round((ll_max - ll) / nats_per_step) in 0..255 with ll_max = ll(m2 = 0)
/// and nats_per_step = (ll_max - ll_background) / 255, so q = 0 is a perfect hit, 255 the
/// floor, and a scan's log-likelihood is ll_max * beams - nats_per_step * (integer sum of q).
/// Paper sigmas: 0.0414 nats per step on a 5 mm grid, 0.0376 on a 5 cm grid. With w_hit = 0
/// the model is flat and every q is 0.

#include <cstdint>

#include "pgmcl/sensor_model/paper_constants.hpp"

namespace pgmcl::sensor_model {

/// The model's parameters. The sigmas are the sensor's own (Dekan et al., Section 5); the
/// effective variance is sigma^2 + (add_discretisation ? res^2 / 12 : 0) + model_mismatch^2.
struct BeamLikelihoodParams {
  double sigma_along = paper::kSigmaAlong;    ///< metres, Dekan et al. Section 5
  double sigma_across = paper::kSigmaAcross;  ///< metres, Dekan et al. Section 5
  double model_mismatch = 0.0;                ///< metres, added in quadrature to both sigmas
  bool add_discretisation = true;             ///< add res^2/12 (uniform position within a cell)
  double w_hit = 0.95;      ///< mixture weight of the Gaussian hit term, in [0, 1]
  double w_rand = 0.05;     ///< mixture weight of the uniform term, in [0, 1]
  double max_range = 30.0;  ///< metres; support of the uniform term

  /// Throws std::invalid_argument naming the field: sigmas not positive and finite,
  /// model_mismatch < 0, weights outside [0, 1] or not summing to 1 within 1e-9,
  /// max_range not positive and finite.
  void validate() const;
};

class BeamLikelihood {
 public:
  /// The model on a map of `resolution` metres per cell (0: continuous, no cell term), with
  /// the floor from m2 = reach_sigmas^2 on. Throws std::invalid_argument for invalid params,
  /// a resolution that is negative or not finite, or reach_sigmas not positive and finite.
  BeamLikelihood(const BeamLikelihoodParams& params, double resolution, double reach_sigmas);

  [[nodiscard]] const BeamLikelihoodParams& params() const noexcept { return params_; }
  [[nodiscard]] double sigma_along_eff() const noexcept { return sigma_along_eff_; }    ///< m
  [[nodiscard]] double sigma_across_eff() const noexcept { return sigma_across_eff_; }  ///< m
  [[nodiscard]] double reach_sigmas() const noexcept { return reach_sigmas_; }
  [[nodiscard]] double reach_m2() const noexcept { return reach_sigmas_ * reach_sigmas_; }

  /// Squared Mahalanobis distance of an offset in the beam frame (metres).
  [[nodiscard]] double mahalanobis_sq(double along, double across) const noexcept {
    return along * along * inv_var_along_ + across * across * inv_var_across_;
  }
  /// Per-beam log-likelihood (nats) as a function of m2; the floor for m2 >= reach_m2().
  [[nodiscard]] double log_likelihood_of_m2(double m2) const noexcept;
  /// Per-beam log-likelihood of an endpoint whose nearest obstacle lies (along, across)
  /// metres away in the beam frame.
  [[nodiscard]] double log_likelihood(double along, double across) const noexcept {
    return log_likelihood_of_m2(mahalanobis_sq(along, across));
  }

  [[nodiscard]] double ll_max() const noexcept { return ll_max_; }  ///< at m2 = 0 (q = 0)
  [[nodiscard]] double ll_background() const noexcept { return ll_background_; }  ///< floor
  [[nodiscard]] double nats_per_step() const noexcept { return nats_per_step_; }
  /// The quantised value of log_likelihood_of_m2(m2): what the tables store.
  [[nodiscard]] std::uint8_t quantise_m2(double m2) const noexcept;
  /// q of the floor (255 unless the model is flat).
  [[nodiscard]] std::uint8_t background() const noexcept { return background_; }
  /// Quantised value -> per-beam log-likelihood (nats).
  [[nodiscard]] double log_likelihood_of_q(std::uint8_t q) const noexcept {
    return ll_max_ - static_cast<double>(q) * nats_per_step_;
  }

 private:
  BeamLikelihoodParams params_;
  double reach_sigmas_ = 0.0;
  double sigma_along_eff_ = 0.0, sigma_across_eff_ = 0.0;
  double inv_var_along_ = 0.0, inv_var_across_ = 0.0;
  double log_hit_norm_ = 0.0;  // log(w_hit / (sqrt(2 pi) sigma_along_eff)), -inf if w_hit = 0
  double log_floor_ = 0.0;     // log(w_rand / max_range), -inf if w_rand = 0
  double ll_max_ = 0.0, ll_background_ = 0.0, nats_per_step_ = 1.0;
  std::uint8_t background_ = 255;
};

}  // namespace pgmcl::sensor_model
