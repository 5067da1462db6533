#pragma once
/// Configuration of pgmcl::Localizer: plain structs, documented defaults and units.
/// LocalizerConfig::validate() is the always-on check at the API boundary; it throws
/// std::invalid_argument naming the offending field ("filter.kld.epsilon must be ...").

#include <cstddef>
#include <cstdint>
#include <numbers>

#include "pgmcl/common/motion_model.hpp"
#include "pgmcl/maps/likelihood_field.hpp"
#include "pgmcl/mcl/beam_selection.hpp"
#include "pgmcl/mcl/pose_search.hpp"

namespace pgmcl {

struct MotionConfig {
  MotionModelKind kind = MotionModelKind::kDifferentialDrive;
  MotionNoise noise{};  ///< Probabilistic Robotics Table 5.6, variance form (motion_model.hpp)
};

/// How the per-beam log-likelihoods of one scan are combined.
///
/// Beams of one scan are not independent: neighbouring beams see the same map error
/// (discretisation, unmapped clutter, a wall that moved), so the plain sum of M per-beam
/// log-likelihoods is overconfident by roughly M / (number of independent errors), and
/// the posterior collapses onto a few particles (and changes with the beam selection).
/// pgmcl tempers the sum (a power posterior) instead of AMCL's ad-hoc p += pz^3:
///   log w += tau * sum_j ll_j,   tau = min(1, K / beams_used),  K = effective_beams,
/// i.e. a scan counts as `effective_beams` independent readings whatever its beam count.
/// The default 20 is a judgement, not a fit. On the synthetic test room (i.i.d. range
/// noise, exact map, 120 beams) larger K is slightly more accurate, because there the
/// errors really are independent: RMSE 2.5 / 2.4 / 2.1 / 1.9 / 1.7 cm for K = 5 / 10 / 20
/// / 50 / 120, and global localisation converged from all 8 starts for K = 10..120. Real
/// scans see unmapped clutter and map error shared by neighbouring beams; K = 20 keeps
/// N_eff / N near 0.55 after a scan while tracking, so selective resampling skips about
/// half of the resamplings. K = M (no correction) with 1081 beams and the paper's sigmas
/// puts all the weight on one particle (N_eff = 1.0 in the stress test).
/// With effective_beams <= 0 the fixed exponent `tempering` is used instead.
struct LikelihoodConfig {
  /// The sensor's own sigmas are Dekan et al.'s (5.69 mm / 3 mm). model_mismatch widens
  /// the kernel for map error (a 5 cm map's kernel is otherwise ~15 mm wide, and a pose
  /// 5 cm off scores like a random one). On the synthetic room: mismatch 0 / 0.02 / 0.05 /
  /// 0.1 m tracked with RMSE 1.7 / 1.7 / 2.1 / 2.6 cm and localised globally from 6 / 7 /
  /// 8 / 8 of 8 starts. 5 cm trades a few millimetres of tracking for a global basin.
  maps::BeamLikelihoodParams beam{.model_mismatch = 0.05};
  maps::LikelihoodFieldOptions table{};
  double effective_beams = 20.0;  ///< independent readings a scan is worth; <= 0: `tempering`
  double tempering = 1.0;         ///< fixed exponent in (0, 1], used when effective_beams <= 0
  /// Adaptive safety net while the filter is not converged (as in adaptive-tempering SMC
  /// samplers, Jasra et al. 2011): if one scan would cut the effective sample size below
  /// min_ess_ratio times its value before the scan, tau is lowered (never raised) until it
  /// does not. During global localisation and recovery the likelihood is far narrower than
  /// the particle spacing; without the limit the set collapses onto one lucky particle,
  /// possibly on the wrong mode of a near-symmetric room, within a scan or two. 0.5 (a scan
  /// may at most halve N_eff) converged from all 8 starts of the synthetic test room in
  /// 8-12 scans; 0.1 locked onto the 180-degree mirror pose from one start. Off once
  /// converged (EstimateConfig), where it would only slow the pull of a compact cluster
  /// that sits a little off. 0 disables it.
  double min_ess_ratio = 0.5;
  BeamSelection selection{};
  /// 0 accepts any beam count; otherwise update() rejects (std::invalid_argument) a scan
  /// with a different number of readings, before touching any state.
  std::size_t expected_beams = 0;
};

/// KLD-sampling (Fox 2003, "Adapting the sample size in particle filters through
/// KLD-sampling"): after resampling keep just enough particles that, with probability
/// 1 - delta, the KL divergence between the sample-based and the true posterior stays
/// below epsilon, given the number k of histogram bins the particles occupy.
struct KldConfig {
  bool enabled = true;
  std::size_t min_particles = 300;    ///< lower bound on the particle count
  std::size_t max_particles = 20000;  ///< upper bound on the particle count
  double epsilon = 0.05;              ///< KL bound (Fox: 0.05)
  double delta = 0.01;                ///< z = normal_quantile(1 - delta) (Fox: 0.01)
  double bin_xy = 0.2;                ///< metres, bin side along x and y
  double bin_theta = 10.0 * std::numbers::pi / 180.0;  ///< radians, heading bin width
};

/// Augmented MCL (Probabilistic Robotics, Table 8.3): short- and long-term averages of the
/// measurement likelihood; when the short-term one falls below the long-term one, each
/// resampled particle is, with probability max(0, 1 - w_fast / w_slow), a uniform draw
/// over free space. 0 < alpha_slow << alpha_fast < 1. pgmcl's deviations, each because a
/// synthetic kidnapping did not recover without it:
///  - the likelihood averaged is the per-beam geometric mean p(z | x)^(1/M), so the rate
///    does not depend on the beam count;
///  - the averages start at the first converged update (set_pose() with a small
///    covariance counts), not during a global search;
///  - injected poses take part in KLD-sampling's bin count, so a lost filter gets more
///    particles (as in AMCL) instead of KLD's minimum;
///  - after an update that injected, w_fast is reset to w_slow: injection then comes in
///    bursts of at most ~alpha_fast of the set, and between bursts the set can
///    concentrate (continuous injection at the raw rate replaced ~70 % of the set every
///    scan and never converged);
///  - probation (added after long real-log tracking diverged with the textbook scheme):
///    the particles injected by a resampling, and their descendants, are "on probation"
///    for `probation` measurement updates, during which all of them together may hold at
///    most `probation_weight` of the weight (their relative weights are kept, so the
///    best-fitting lineages still multiply). Only a lineage that keeps fitting after that
///    competes freely. Why: on the SICK logs the per-beam fit at the true pose varies by
///    a factor of 25-100 over a run (fr079: w_fast / w_slow between 0.04 and 11 while
///    tracking within 16 cm; intel: 0.28 for a minute), so injection fires in ordinary
///    tracking, and a few scans fit the map badly even at the true pose (intel ~790 s:
///    best tracked particle -290 nats, usually +150), where one random pose out of ~2000
///    fits far better and took over: ATE 1.6 m intel, 9.1 m fr079 (1000 particles, 90
///    beams, realistic odometry; configs/experiments/README.md). A single scan cannot
///    tell the two apart (a fixed log-weight handicap for injected poses: intel still
///    diverged at 40 nats, fr079 needed 150, the depot kidnapping no longer recovered at
///    80); the wrong pose's fit falls behind within a few updates as the view changes.
///    probation 3 / 6 / 10 / 15 (weight 0.1): intel 0.033 m from 3 on; fr079 8.3 / 6.9 / 0.043 /
///    0.043 m; fr079 biased odometry 5.7 m at 10, 0.044 m at 15. Cost: the depot
///    kidnapping (closed-loop test) re-localised at 20.5 s (10) / 21.1 s (15) instead of
///    18.6 s. Rejected: injecting only below threshold * w_slow (threshold 0.5 and 0.3
///    still diverged on fr079 and the depot kidnapping never recovered, because the
///    bursts shrink to a few particles); a faster alpha_slow (0.01, 0.03: still
///    diverged). `threshold` is kept as an option; 1 is Table 8.3.
///    probation 15 was the default until fixed particle counts (KLD off) were swept: fr079
///    with 1000 particles and 90 beams still diverged (11.0 m ATE; 1.25 m on its first 1200
///    scans); 30 tracks there (0.043 m) and on intel / aces / csail-raw with KLD on and off
///    (0.030-0.101 m, none worse than at 15).
///    probation_weight 0.1 / 0.05 / 0.02 in the clutter test (tests/mcl): max error 0.78-1.0
///    / 0.38-0.85 / 0.15-0.51 m (seeds 1-4; recovery off 0.09-0.12 m), because with more
///    than 1 - EstimateConfig::converged_weight on probation the filter counts as not
///    converged and limits the tempering; real logs and kidnappings: no change (within
///    1 mm ATE, same recovery times).
struct RecoveryConfig {
  bool enabled = true;
  double alpha_slow = 0.001;  ///< long-term average rate (per measurement update)
  double alpha_fast = 0.1;    ///< short-term average rate (per measurement update)
  /// Inject with probability max(0, 1 - w_fast / (threshold * w_slow)); in (0, 1].
  double threshold = 1.0;
  std::size_t probation = 30;      ///< measurement updates an injected lineage waits, <= 255
  double probation_weight = 0.02;  ///< largest total weight of the lineages on probation
};

struct FilterConfig {
  std::size_t particles = 2000;          ///< after set_pose(); the fixed count without KLD
  std::size_t global_particles = 20000;  ///< after global_localize() and at construction
  /// Selective resampling: resample only when N_eff < resample_threshold * N
  /// (1 = every update). Skipping resampling while weights are healthy keeps diversity.
  double resample_threshold = 0.5;
  KldConfig kld{};
  RecoveryConfig recovery{};
};

/// No measurement update until odometry moved this much since the last one
/// (Localizer::force_update() overrides once). Between updates the estimate is
/// dead-reckoned with odometry.
struct GatingConfig {
  bool enabled = true;
  double d_min = 0.1;      ///< metres of translation
  double theta_min = 0.1;  ///< radians of rotation
};

/// Best hypothesis = heaviest cluster of particles; "converged" when that cluster holds
/// more than `converged_weight` of the weight and its spread is below both stds.
struct EstimateConfig {
  /// Clustering grid (clustering.hpp): particles in touching cells of this size share a
  /// cluster (single linkage at the cell scale).
  double cluster_xy = 0.5;                               ///< metres, cell side in x and y
  double cluster_theta = 30.0 * std::numbers::pi / 180;  ///< radians, heading cell width
  double converged_weight = 0.9;                         ///< fraction of the total weight
  double converged_xy_std = 0.25;                        ///< metres (sqrt of largest eigenvalue)
  double converged_theta_std = 10.0 * std::numbers::pi / 180.0;  ///< radians
};

/// Competing hypotheses from scan-to-map search (pose_search.hpp): poses that odometry and
/// the particle set cannot explain but the map does. A global search seeds the particles
/// until the first convergence after global_localize(); while tracking, a search around
/// the prediction when the scan stops fitting it (odometry glitches, wheel slip) and a
/// sweep of the map (another place that fits as well) propose competitors. Each is moved by
/// odometry and scored against the prediction; its evidence (the tempered log-likelihood
/// ratio, fading over 10 m of new view) decides: while it is positive the filter does not
/// report `converged`; when it wins (rules in mcl/README.md), part of the set is redrawn
/// there. Measured in bench/robustness (README).
struct HypothesesConfig {
  bool enabled = true;
  PoseSearchConfig search{};
  std::size_t global_candidates = 64;  ///< distinct places seeded per global search
  double global_seed_fraction = 0.5;   ///< of the particles redrawn around them per update
  double candidate_margin = 15.0;      ///< tempered nats: global candidates within this of the best
  std::uint64_t global_budget = 20'000'000;  ///< beam lookups per global search
  std::size_t max_competitors = 4;           ///< hypotheses tracked beside the estimate
  double switch_evidence = 8.0;              ///< tempered nats a competitor needs to take over
  double drop_evidence = -15.0;              ///< tempered nats below which a competitor is dropped
  double switch_seed_fraction = 0.5;         ///< of the particles redrawn around a winner
  /// New view (metres travelled + metres per radian turned) over which a place the global
  /// search proposed must stay ahead before the filter moves there.
  double rival_view = 2.0;
  /// Search around the prediction when its fit (beams that fit the map) falls below this
  /// fraction of its running mean.
  double rescue_fit_ratio = 0.6;
  double rescue_xy = 2.5;                   ///< metres, half-width of that search
  double rescue_theta = 0.7;                ///< radians (40 deg), half-width of that search
  std::uint64_t rescue_budget = 2'000'000;  ///< beam lookups per rescue search
  /// Map sweep while tracking, a root block at a time: lookups per update, as a share of
  /// the particles' own (particles x beams). 0 turns the sweep off.
  double sweep_share = 0.25;
  double separation_xy = 1.0;      ///< metres: closer hypotheses are the same place
  double separation_theta = 0.44;  ///< radians (25 deg)
};

/// What update() does when `stamp` is earlier than the previous update's stamp.
enum class TimeBackwardsPolicy : std::uint8_t {
  kThrow,  ///< throw std::invalid_argument; the filter state is untouched (default)
  kReset,  ///< drop the odometry reference, keep the particles, return skipped; the next
           ///< update starts a fresh odometry chain (e.g. a replayed log looping around)
};

struct LocalizerConfig {
  MotionConfig motion{};
  LikelihoodConfig likelihood{};
  FilterConfig filter{};
  GatingConfig gating{};
  EstimateConfig estimate{};
  HypothesesConfig hypotheses{};
  TimeBackwardsPolicy time_backwards = TimeBackwardsPolicy::kThrow;
  int threads = 1;          ///< OpenMP threads for motion + measurement; 0 = OpenMP default
  std::uint64_t seed = 42;  ///< every random stream derives from this (random.hpp)

  /// Throws std::invalid_argument naming the first invalid field.
  void validate() const;
};

}  // namespace pgmcl
