#pragma once
/// Configuration of pgmcl::Localizer: plain structs, documented defaults and units.
/// LocalizerConfig::validate() is the always-on check at the API boundary; it throws
/// InvalidConfigField naming the offending field ("filter.kld.epsilon must be ..."). Every
/// field's unit and allowed values are described once, in config_schema.hpp.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <stdexcept>
#include <string>

#include "pgmcl/common/motion_model.hpp"
#include "pgmcl/maps/likelihood_field.hpp"
#include "pgmcl/mcl/beam_selection.hpp"
#include "pgmcl/mcl/pose_search.hpp"

namespace pgmcl {

/// Odometry is often noisier than any fixed model says (real wheels, or a log from another
/// robot), and a proposal narrower than the odometry's error loses track. So the filter
/// compares each odometry increment with the motion between its own converged estimates:
/// the squared residual over the variance that the model and the two estimates'
/// covariances predict, for the heading and along the direction of travel. The median of
/// that ratio over the last `window` updates, over its median when the model is right
/// (chi-square, one degree of freedom), times `margin`, scales the rotation terms (a1, a2)
/// and the translation terms (a3, a4, a5) of the next motion updates; never below the
/// configured noise. A median, so the glitches the competing hypotheses absorb do not count.
/// The margin: the residuals understate the odometry's error, because the estimates they
/// are measured against sit between the truth and the prediction that pulled them there
/// (bench/robustness/README.md, "Odometry noisier than the model").
struct MotionAdaptationConfig {
  bool enabled = true;
  std::size_t window = 30;      ///< updates pooled; adapts once a third of them are in
  double margin = 2.0;          ///< on the measured factor
  double max_inflation = 25.0;  ///< largest variance factor (5x the standard deviations)
};

struct MotionConfig {
  MotionModelKind kind = MotionModelKind::kDifferentialDrive;
  MotionNoise noise{};  ///< Probabilistic Robotics Table 5.6, variance form (motion_model.hpp)
  /// The heading noise of an update is that of every odometry reading since the last one,
  /// not of their composite: readings the gating skipped (in-place turns, short reversals)
  /// each carry their own rot1 and rot2 noise, which a composite nearly straight step hides.
  bool per_reading_noise = true;
  MotionAdaptationConfig adaptation{};
};

/// How the per-beam log-likelihoods of one scan are combined: a power posterior,
///   log w += tau * sum_j ll_j,   tau = min(1, effective_beams / beams_used),
/// because neighbouring beams share map error and the plain sum collapses the set onto a
/// few particles (instead of AMCL's p += pz^3). The measurements behind each default:
/// configs/experiments/README.md, "Why the defaults".
struct LikelihoodConfig {
  /// Dekan et al.'s sensor sigmas; model_mismatch (metres) widens the kernel for map error,
  /// which on a 5 cm map is larger than the sensor's.
  sensor_model::BeamLikelihoodParams beam{.model_mismatch = 0.05};
  maps::LikelihoodFieldOptions table{};
  double effective_beams = 20.0;  ///< independent readings a scan is worth; <= 0: `tempering`
  double tempering = 1.0;         ///< fixed exponent in (0, 1], used when effective_beams <= 0
  /// tau for a scan scored on `beams` readings, before the adaptive limit below.
  [[nodiscard]] double tempering_for(double beams) const noexcept {
    return effective_beams > 0.0 ? std::min(1.0, effective_beams / beams) : tempering;
  }
  /// While not converged, tau is lowered (never raised) so that one scan keeps at least
  /// this fraction of the effective sample size (adaptive tempering, Jasra et al. 2011):
  /// a global search must not collapse onto one lucky particle. 0 disables it.
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
  /// Lower bound on the particle count. It samples the next prediction whenever a scan
  /// collapses the set onto a few particles, as noisy odometry does on most updates, and
  /// KLD, binning that collapsed set, asks for no more (bench/robustness/README.md).
  std::size_t min_particles = 1000;
  std::size_t max_particles = 20000;  ///< upper bound on the particle count
  double epsilon = 0.05;              ///< KL bound (Fox: 0.05)
  double delta = 0.01;                ///< z = normal_quantile(1 - delta) (Fox: 0.01)
  double bin_xy = 0.2;                ///< metres, bin side along x and y
  double bin_theta = 10.0 * std::numbers::pi / 180.0;  ///< radians, heading bin width
};

/// Augmented MCL (Probabilistic Robotics, Table 8.3): when the short-term average of the
/// per-beam likelihood falls below the long-term one, resampled particles are redrawn
/// uniformly over free space with probability max(0, 1 - w_fast / w_slow). pgmcl's
/// deviations (averages of the per-beam geometric mean, started at convergence, injection
/// in bursts, injected poses in KLD's bins) and the probation that keeps a random pose from
/// taking over a good track: mcl/README.md; the runs that chose the numbers:
/// configs/experiments/README.md.
struct RecoveryConfig {
  bool enabled = true;
  double alpha_slow = 0.001;  ///< long-term average rate (per measurement update)
  double alpha_fast = 0.1;    ///< short-term average rate (per measurement update)
  /// Measurement updates a redrawn lineage waits before it competes freely, <= 255: one
  /// scan that fits badly at the true pose must not hand the set to a random pose. With
  /// competing hypotheses, far from the prediction it waits longer (mcl/README.md).
  std::size_t probation = 30;
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
  /// Reported `converged` also needs the scan to fit the estimate at least this fraction
  /// of its usual fit (UpdateResult::fit, running mean over ~100 converged updates): a
  /// filter settled in the wrong place, or one a crowd hides the walls from, cannot
  /// confirm its pose. Stricter than the tracker's lost line (0.6, rescue_fit_ratio): a
  /// pose it does not count as lost need not be confirmed either (bench/robustness/README
  /// measures the trade). Only the report: the filter's own dynamics use the cluster
  /// alone. 0 turns it off.
  double converged_fit_ratio = 0.75;
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
  /// search proposed must stay ahead before the filter moves there, on a scan that place
  /// explains as the map usually does.
  double rival_view = 2.0;
  /// Search around the prediction when its fit (beams that fit the map) falls below this
  /// fraction of its running mean.
  double rescue_fit_ratio = 0.6;
  double rescue_xy = 2.5;                   ///< metres, half-width of that search
  double rescue_theta = 0.7;                ///< radians (40 deg), half-width of that search
  std::uint64_t rescue_budget = 2'000'000;  ///< beam lookups per rescue search
  /// The rescue search also searches, on its finest leaves, the positions a heading glitch
  /// can reach (the step turned through the heading window): amid people, its coarse bound
  /// ranks far poses their readings happen to fit above the turned one.
  bool glitch_search = true;
  /// Map sweep while tracking, a root block at a time: lookups per update, as a share of
  /// the particles' own (particles x beams). 0 turns the sweep off.
  double sweep_share = 0.15;
  double separation_xy = 1.0;      ///< metres: closer hypotheses are the same place
  double separation_theta = 0.44;  ///< radians (25 deg)
  /// Judge hypotheses also by the free space their readings cross (a ray through a wall
  /// contradicts a pose): it vetoes and confirms switches, starts a search when the tracked
  /// pose's rays start crossing walls, and rules out contradicted places in global search.
  bool free_space = true;
  /// With free_space, while the scan does not fit the prediction of a converged set (a
  /// rescue search runs, no competitor wins), the particles that carry the weight lose the
  /// credit of readings that crossed walls to reach their endpoints: people hiding the
  /// walls otherwise let a turned particle win.
  bool free_space_weights = true;
  /// A candidate of the rescue search (or a sweep place within its window), turned less
  /// than 10 deg from the prediction (a slip), that for three scans in a row fitted as the
  /// map usually does and by three tenths of the probe beams more than the prediction wins
  /// even where its rays cross more mapped walls than the prediction's: a map that shows
  /// what is not there now (a door shut when it was mapped) must not hold a slip's true pose
  /// back.
  bool sustained_lead = true;
};

/// What update() does when `stamp` is earlier than the previous update's stamp.
enum class TimeBackwardsPolicy : std::uint8_t {
  kThrow,  ///< throw std::invalid_argument; the filter state is untouched (default)
  kReset,  ///< drop the odometry reference, keep the particles, return skipped; the next
           ///< update starts a fresh odometry chain (e.g. a replayed log looping around)
};

/// What LocalizerConfig::validate() throws: the dotted path of the first invalid field
/// ("filter.kld.epsilon") and what is wrong with it; what() says "LocalizerConfig: " + both.
class InvalidConfigField : public std::invalid_argument {
 public:
  InvalidConfigField(std::string field, std::string problem);
  [[nodiscard]] const std::string& field() const noexcept { return field_; }
  [[nodiscard]] const std::string& problem() const noexcept { return problem_; }

 private:
  std::string field_;
  std::string problem_;
};

struct LocalizerConfig {
  MotionConfig motion{};
  LikelihoodConfig likelihood{};
  FilterConfig filter{};
  GatingConfig gating{};
  EstimateConfig estimate{};
  HypothesesConfig hypotheses{};
  TimeBackwardsPolicy time_backwards = TimeBackwardsPolicy::kThrow;
  int threads = 1;  ///< OpenMP threads for motion + measurement; 0 = OpenMP default
  /// With a team (threads != 1): run an update on one thread while the last updates found
  /// the team slower, e.g. when another process keeps a core busy (ThreadPolicy). The
  /// results are the same bits either way.
  bool adaptive_threads = true;
  std::uint64_t seed = 42;  ///< every random stream derives from this (random.hpp)

  /// Throws InvalidConfigField (a std::invalid_argument) for the first invalid field.
  void validate() const;
};

}  // namespace pgmcl
