#pragma once
/// What one Localizer::update() did: the estimate plus diagnostics.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>

#include "pgmcl/common/se2.hpp"

namespace pgmcl {

/// Why the measurement update (or the whole update) was skipped.
enum class SkipReason : std::uint8_t {
  kNone,               ///< full update: motion, measurement, (maybe) resampling
  kNotMoved,           ///< odometry moved less than gating.d_min / theta_min: nothing ran
  kNoValidBeams,       ///< motion ran, but no reading was valid: weights untouched
  kTimeWentBackwards,  ///< TimeBackwardsPolicy::kReset: odometry reference dropped
};

[[nodiscard]] const char* to_string(SkipReason reason) noexcept;

/// Wall-clock durations (std::chrono::steady_clock), milliseconds.
struct UpdateTimings {
  double motion_ms = 0.0;
  double measurement_ms = 0.0;  ///< beam preparation + scoring + normalisation
  /// Of measurement_ms: competing hypotheses (HypothesesConfig). While tracking with more
  /// than one thread, the particles are scored alongside, so the two overlap.
  double hypotheses_ms = 0.0;
  double free_space_ms = 0.0;  ///< of measurement_ms: HypothesesConfig::free_space_weights
  double resample_ms = 0.0;    ///< KLD sizing + resampling + random injection
  double estimate_ms = 0.0;    ///< mean, covariance, clustering
  double total_ms = 0.0;
};

struct UpdateResult {
  /// Best hypothesis in the global frame: the weighted mean of the heaviest cluster. While
  /// the set still holds several places (the tempering limit, LikelihoodConfig::min_ess_ratio,
  /// keeps them), the particles near that cluster's mean are weighed by the whole scan.
  /// On skipped updates, the last estimate moved by the odometry since (dead reckoning).
  Pose2 estimate{};
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  ///< of `estimate`; x, y, theta; global
  Pose2 mean{};                                          ///< weighted mean of all particles
  Eigen::Matrix3d mean_covariance = Eigen::Matrix3d::Zero();  ///< of `mean`, global frame
  double cluster_weight = 0.0;  ///< weight of the heaviest cluster, in [0, 1]
  std::size_t clusters = 0;     ///< number of clusters found
  /// One dominant compact cluster (EstimateConfig), no competing hypothesis that fits
  /// better so far (HypothesesConfig), and a scan that fits the estimate about as well as
  /// usual (EstimateConfig::converged_fit_ratio).
  bool converged = false;

  SkipReason skipped = SkipReason::kNone;
  bool motion_applied = false;
  bool resampled = false;
  double n_eff = 0.0;         ///< 1 / sum w^2 after the measurement update, before resampling
  double tempering = 0.0;     ///< exponent tau used for this scan (0 when not measured)
  std::size_t particles = 0;  ///< particle count after this update (KLD may change it)
  std::size_t injected = 0;   ///< particles redrawn over free space (augmented MCL)
  double w_slow = 0.0;        ///< augmented MCL long-term average (per-beam likelihood)
  double w_fast = 0.0;        ///< augmented MCL short-term average

  std::size_t beams_total = 0;    ///< readings in the scan
  std::size_t beams_invalid = 0;  ///< NaN/Inf/out-of-range readings (beam_selection.hpp)
  std::size_t beams_used = 0;     ///< readings scored per particle after selection
  /// Of the used beams, those whose endpoint seen from `estimate` reads the table's
  /// background (beyond the kernel's reach or off the map): no table work was done there.
  std::size_t beams_background = 0;
  /// Of the used beams, the fraction whose endpoint seen from `estimate` lies within 3
  /// effective sigmas of a mapped obstacle (kFitSigmas): how much of the scan the map
  /// explains there. Near 1 on a well-mapped scene; low in clutter, open space, or when lost.
  double fit = 0.0;

  /// Competing hypotheses (HypothesesConfig) tracked after this update, and the largest
  /// evidence among them (tempered nats; > 0: another place fits better so far, and
  /// `converged` is false). 0 when there are none.
  std::size_t competitors = 0;
  double alternative_evidence = 0.0;
  std::size_t seeded = 0;  ///< particles redrawn around searched hypotheses this update
  bool switched = false;   ///< the filter moved to a competitor that outweighed it
  bool searched = false;   ///< a scan-to-map search ran this update (global or rescue)
  /// Factors on the motion noise's rotation and translation variances that the odometry's
  /// residuals called for so far (MotionAdaptationConfig); 1 = the configured noise.
  double rotation_noise_factor = 1.0;
  double translation_noise_factor = 1.0;

  UpdateTimings timings{};
  /// Threads this update's parallel loops ran with: LocalizerConfig::threads, or 1 while
  /// recent updates found the team slower (ThreadPolicy). Results do not depend on it.
  int threads = 1;

  /// The weights were updated from this scan: nothing skipped it and it had beams to score
  /// (false for the state after construction, set_pose() or global_localize()).
  [[nodiscard]] bool measured() const noexcept {
    return skipped == SkipReason::kNone && beams_used > 0;
  }
};

}  // namespace pgmcl
