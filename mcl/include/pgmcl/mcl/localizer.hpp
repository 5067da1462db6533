#pragma once
/// pgmcl::Localizer: Monte Carlo localisation (Probabilistic Robotics, Table 8.2 with the
/// augmented-MCL recovery of Table 8.3 and Fox's KLD-sampling) with the planar Gaussian
/// beam model of Dekan et al. read from precomputed likelihood tables.
///
/// mcl/README.md, "One update()", walks through the steps of update() once.
/// The hot loops neither allocate nor throw nor do I/O.
///
/// Frames: everything public is in the *global* frame (the map's frame, possibly at UTM
/// scale); particles live in the grid's map-local frame as float (particles.hpp).
/// Threading: a Localizer is not thread-safe; use one per thread (it parallelises inside).

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "pgmcl/common/laser_scan.hpp"
#include "pgmcl/common/random.hpp"
#include "pgmcl/maps/likelihood_field.hpp"
#include "pgmcl/maps/occupancy_grid.hpp"
#include "pgmcl/mcl/clustering.hpp"
#include "pgmcl/mcl/kld_sampling.hpp"
#include "pgmcl/mcl/localizer_config.hpp"
#include "pgmcl/mcl/measurement_model.hpp"
#include "pgmcl/mcl/particles.hpp"
#include "pgmcl/mcl/thread_policy.hpp"
#include "pgmcl/mcl/update_result.hpp"

namespace pgmcl {
namespace detail {
class HypothesisTracker;
class MotionNoiseAdaptation;
struct SeedRequest;
}  // namespace detail

/// Linear indices (row * width + col) of the grid's free cells (OccupancyGrid::free):
/// where global localisation and random injection may put particles.
[[nodiscard]] std::vector<std::uint32_t> free_cell_indices(const maps::OccupancyGrid& grid);

class Localizer {
 public:
  /// Builds the likelihood field from `grid` with cfg.likelihood and starts with
  /// global_localize(). Throws std::invalid_argument for an invalid config or a grid
  /// without free cells (and whatever maps::LikelihoodField throws).
  Localizer(const maps::OccupancyGrid& grid, const LocalizerConfig& cfg);
  /// Shares an existing field (several localizers, one table). `free_cells` are linear
  /// indices into the field's grid (free_cell_indices()); they must be non-empty and in
  /// range. The field's own parameters win over cfg.likelihood.beam / .table.
  Localizer(std::shared_ptr<const maps::LikelihoodField> field,
            std::vector<std::uint32_t> free_cells, const LocalizerConfig& cfg);
  ~Localizer();
  Localizer(Localizer&&) noexcept;
  Localizer& operator=(Localizer&&) noexcept;

  /// One filter step for the scan taken at `odometry_pose` (odometry frame) and `stamp`
  /// (seconds). Throws std::invalid_argument, before any state change, when the scan is
  /// malformed (beam count != likelihood.expected_beams, non-finite angles or limits, bad
  /// sensor pose), the odometry pose or stamp is not finite, or (policy kThrow) the stamp
  /// is earlier than the previous one. Everything after validation is noexcept in spirit:
  /// no exception leaves the hot path.
  UpdateResult update(const Pose2& odometry_pose, const LaserScan& scan, double stamp);

  /// The next update() runs the measurement even if the robot has not moved.
  void force_update() noexcept { force_ = true; }

  /// Re-initialises around `mean` (global frame) with covariance `cov` (x, y, theta;
  /// global frame; symmetric PSD, else std::invalid_argument): filter.particles samples
  /// from the Gaussian, headings wrapped. Forces the next measurement update. The pose is
  /// the robot's at the filter's current time (the last update's odometry pose): the next
  /// update() applies the odometry since then. Also resets the augmented-MCL averages.
  void set_pose(const Pose2& mean, const Eigen::Matrix3d& cov);
  /// Re-initialises uniformly over the free cells (uniform heading) with
  /// filter.global_particles particles. Forces the next measurement update.
  void global_localize();
  /// Swaps in a new map (its likelihood field and free cells, as for the second constructor)
  /// and keeps the particles: each keeps its global pose, weight and probation, re-expressed
  /// in the new grid's map-local frame. For a map of the same global frame (an edited or
  /// re-published map), not for one whose frame moved. Competing hypotheses found on the
  /// old map are dropped; the next update() measures against the new one. Throws
  /// std::invalid_argument (state unchanged) for empty or out-of-range free cells or a null
  /// field.
  void replace_map(std::shared_ptr<const maps::LikelihoodField> field,
                   std::vector<std::uint32_t> free_cells);

  [[nodiscard]] ParticlesView particles() const noexcept;
  [[nodiscard]] const LocalizerConfig& config() const noexcept { return cfg_; }
  [[nodiscard]] const maps::LikelihoodField& field() const noexcept { return *field_; }
  /// Pose of the map-local grid frame in the global frame.
  [[nodiscard]] const Pose2& origin() const noexcept { return origin_; }
  /// The result of the last update() (or of the initial state).
  [[nodiscard]] const UpdateResult& last_result() const noexcept { return last_; }

 private:
  void init_geometry();
  void validate_scan(const LaserScan& scan) const;
  [[nodiscard]] Pose2 random_free_pose(Rng& rng) const noexcept;
  void motion_update(const Pose2& odom_prev, const Pose2& odom_now);
  /// Returns false (and leaves weights alone) when no beam is valid. `delta`: odometry
  /// increment since the last filter update (robot frame).
  bool measurement_update(const LaserScan& scan, const Pose2& delta, UpdateResult& r);
  /// Redraws the `count` lightest particles around `seed.poses`. Returns how many it
  /// redrew: the first ones of ws_.seed_victims.
  std::size_t seed_particles(const detail::SeedRequest& seed);
  void update_recovery_averages(double w_avg, UpdateResult& r) noexcept;
  /// Withdraws r.converged while the scan fits the estimate far worse than usual.
  void confirm_by_fit(UpdateResult& r) noexcept;
  void limit_probation_weight(const Pose2& prediction);  // map-local
  /// Puts the particles farther than the tracker's hold radius from `estimate` (map-local) on
  /// probation: on leaving global mode, the places the global search seeded are competitors.
  void hold_other_places(const Pose2& estimate);
  /// Lowers the weight of the particles that lead this update by the readings that crossed
  /// walls to reach them (`tau`: this update's scan exponent).
  void discount_blocked_readings(double tau);
  void resample(UpdateResult& r);
  [[nodiscard]] std::size_t kld_sample_count(Rng& rng, double p_inject, Rng& inject_rng);
  /// `withheld_tau`: the part of this update's scan exponent the tempering limit held back
  /// (0 outside an update).
  void compute_estimate(UpdateResult& r, double withheld_tau = 0.0);
  [[nodiscard]] Pose2 within_best_cluster(const Pose2& tempered_mean, double withheld_tau);
  void count_background(UpdateResult& r) const noexcept;
  void reset_after_init();
  [[nodiscard]] std::uint64_t next_step() noexcept { return step_++; }

  LocalizerConfig cfg_;
  std::shared_ptr<const maps::LikelihoodField> field_;
  MeasurementModel model_;
  std::vector<std::uint32_t> free_cells_;
  Pose2 origin_{};
  double resolution_ = 0.0;
  int width_ = 0;

  /// Buffers reused across updates; they only grow, so a steady-state update allocates
  /// nothing.
  struct Workspace {
    std::vector<std::uint32_t> valid_beams, selected_beams;  // beam indices into the scan
    std::vector<std::uint32_t> beam_sums;           // per particle: integer sum of quantised beams
    std::vector<double> scan_ll;                    // per particle: scan log-likelihood
    std::vector<double> cumulative_w;               // KLD's inverse-CDF draws
    std::vector<std::uint32_t> ancestors;           // systematic resampling's picks
    std::vector<float> next_x, next_y, next_theta;  // the resampled set, swapped in
    std::vector<float> injected_x, injected_y, injected_theta;  // poses injected this time
    std::vector<std::uint8_t> next_probation;
    std::vector<double> log_w_probation, log_w_tracked;  // limit_probation_weight()
    std::vector<std::uint32_t> seed_victims;             // seed_particles()
    std::vector<double> estimate_w;                      // compute_estimate(): untempered
    std::vector<std::uint32_t> by_weight;                // discount_blocked_readings()
    std::vector<double> discounts;                       // ... per checked particle, nats
    struct BlockedReadings {  // ... one particle's blocked beams, per parallel slice
      std::vector<std::uint32_t> indices;
      PreparedBeams beams;
    };
    std::vector<BlockedReadings> blocked;
  };

  ParticleSet p_;
  // Per particle: measurement updates its injected lineage stays on probation
  // (RecoveryConfig::probation); 0 for particles that descend from the tracked set.
  std::vector<std::uint8_t> probation_;
  Workspace ws_;
  KldBinner binner_;
  double kld_z_ = 0.0;  // normal_quantile(1 - kld.delta)
  ParticleClusterer clusterer_;
  std::unique_ptr<detail::HypothesisTracker> hypotheses_;  // null when disabled
  std::unique_ptr<detail::MotionNoiseAdaptation> motion_noise_;
  bool adaptable_ = false;  // the last estimate can anchor a motion residual (see update())
  bool clustered_ = false;  // the last estimate met EstimateConfig's cluster criterion
  bool one_mode_ = false;  // the last estimate: one cluster with nearly all the weight, <= 1 m wide
  int unimodal_ = 0;       // consecutive updates with one_mode_
  // UpdateResult::fit over converged updates (EstimateConfig::converged_fit_ratio).
  bool have_usual_fit_ = false;
  double usual_fit_ = 0.0;

  // Filter state.
  bool have_odom_ = false;
  Pose2 odom_ref_{};   ///< odometry at the last filter update
  Pose2 odom_last_{};  ///< odometry at the last update() call, skipped or not
  /// Rotation moments of the odometry readings' increments since odom_ref_
  /// (MotionConfig::per_reading_noise).
  double rotation_moment_ = 0.0;
  Pose2 anchor_{};  ///< global estimate at odom_ref_ (for dead reckoning)
  bool have_stamp_ = false;
  double last_stamp_ = 0.0;
  bool force_ = true;
  std::uint64_t step_ = 0;      ///< counter keying every random stream
  ThreadPolicy thread_policy_;  ///< team or one thread, by the last updates' cost
  int threads_ = 1;             ///< what this update's parallel loops use
  bool have_averages_ = false;
  double w_slow_ = 0.0, w_fast_ = 0.0;
  UpdateResult last_{};
};

}  // namespace pgmcl
