#pragma once
/// A 1D range-reading model: the Gaussian hit term of Dekan et al. (Eq. (4), sigma along the
/// beam) mixed with a uniform random-reading term and a max-range term, in the style of
/// Probabilistic Robotics, Sec. 6.3 (beam model, Table 6.1) without the "short" term.

#include "pgmcl/sensor_model/paper_constants.hpp"

namespace pgmcl::sensor_model {

/// Mixture parameters. The weights are tuning defaults, not from Dekan et al.
struct BeamMixtureParams {
  double w_hit = 0.90;   ///< weight of the Gaussian hit term, [0, 1]
  double w_rand = 0.05;  ///< weight of the uniform term over [0, max_range], [0, 1]
  double w_max = 0.05;   ///< weight of the max-range term, [0, 1]
  double sigma_hit = paper::kSigmaAlong;                    ///< m (Dekan et al., Sec. 5)
  double max_range = paper::kUtm30lx.guaranteed_range_max;  ///< m (Table 1: 30 m)
  /// The max-range term is a narrow box of this width, [max_range - w, max_range], with density
  /// 1/w, not a point mass: a point mass has no density, so pdf() would be undefined at
  /// max_range and the mixture would not integrate to 1. Metres, (0, max_range].
  double max_spike_width = 0.01;

  /// Throws std::invalid_argument naming the offending field: each weight must be in [0, 1]
  /// and w_hit + w_rand + w_max must equal 1 within 1e-9; sigma_hit, max_range and
  /// max_spike_width must be finite and > 0, with max_spike_width <= max_range.
  void validate() const;
};

class BeamMixture {
 public:
  /// Validates `params` (see BeamMixtureParams::validate).
  explicit BeamMixture(const BeamMixtureParams& params = {});

  [[nodiscard]] const BeamMixtureParams& params() const noexcept { return p_; }

  /// Density (per metre) of reading `range` given the ray-cast `expected_range`:
  ///   w_hit * N(range; expected, sigma_hit) / eta + w_rand / max_range + w_max * box / w,
  /// where eta is the Gaussian's mass in [0, max_range] (Probabilistic Robotics, Eq. 6.4-6.6),
  /// so the mixture integrates to 1 over [0, max_range].
  /// Conventions: expected_range is clamped to [0, max_range] (a ray that hits nothing within
  /// range expects max_range); a reading >= max_range, +inf or NaN is a no-return and counts
  /// as max_range; a negative reading has density 0.
  [[nodiscard]] double pdf(double range, double expected_range) const noexcept;

  /// log of pdf(), evaluated by log-sum-exp over the three terms, so a miss far in the
  /// Gaussian's tail stays finite even with w_rand = w_max = 0. -inf where pdf() is 0.
  [[nodiscard]] double log_pdf(double range, double expected_range) const noexcept;

 private:
  BeamMixtureParams p_;
  double log_w_hit_;
  double log_rand_;   // log(w_rand / max_range)
  double log_spike_;  // log(w_max / max_spike_width)
};

}  // namespace pgmcl::sensor_model
