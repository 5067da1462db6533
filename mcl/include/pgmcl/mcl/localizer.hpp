#pragma once
/// pgmcl::Localizer: Monte Carlo localisation (Probabilistic Robotics, Table 8.2 with the
/// augmented-MCL recovery of Table 8.3 and Fox's KLD-sampling) with the planar Gaussian
/// beam model of Dekan et al. read from precomputed likelihood tables.
///
/// One update():
///  1. validate the scan at the boundary (throws std::invalid_argument, state untouched);
///  2. gating: skip everything while odometry moved less than d_min / theta_min;
///  3. motion: every particle samples the odometry model (Table 5.6), one RNG stream per
///     block of 256 particles, so the result is identical for any thread count;
///  4. measurement: log w += tau * sum_j ll_j (tempered, see LikelihoodConfig), then
///     log-sum-exp normalisation and N_eff;
///  5. estimate: weighted mean (circular heading), covariance, heaviest cluster;
///  6. selective resampling (systematic) with KLD-sized output and random injection.
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
#include "pgmcl/mcl/update_result.hpp"

namespace pgmcl {
namespace detail {
class HypothesisTracker;
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

  [[nodiscard]] ParticlesView particles() const noexcept;
  [[nodiscard]] const LocalizerConfig& config() const noexcept { return cfg_; }
  [[nodiscard]] const maps::LikelihoodField& field() const noexcept { return *field_; }
  [[nodiscard]] std::shared_ptr<const maps::LikelihoodField> field_ptr() const noexcept {
    return field_;
  }
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
  /// Redraws the `count` lightest particles around `seed.poses` before the scan scores them.
  void seed_particles(const detail::SeedRequest& seed);
  void update_recovery_averages(double w_avg, UpdateResult& r) noexcept;
  void limit_probation_weight();
  void resample(UpdateResult& r);
  [[nodiscard]] std::size_t kld_sample_count(Rng& rng, double p_inject, Rng& inject_rng);
  void compute_estimate(UpdateResult& r);
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

  ParticleSet p_;
  // Scratch buffers, reused across updates (grow only).
  std::vector<std::uint32_t> sum_q_;
  std::vector<double> ll_;  // per-particle scan log-likelihood
  std::vector<std::uint32_t> idx_;
  std::vector<std::uint32_t> valid_;
  std::vector<std::uint32_t> selected_;
  std::vector<float> tmp_x_, tmp_y_, tmp_theta_;
  std::vector<float> inj_x_, inj_y_, inj_theta_;  // poses injected by this resampling
  // Per particle: measurement updates its injected lineage stays on probation
  // (RecoveryConfig::probation); 0 for particles that descend from the tracked set.
  std::vector<std::uint8_t> probation_, tmp_probation_;
  std::vector<double> lw_probation_, lw_tracked_;  // limit_probation_weight() scratch
  std::vector<double> cum_;                        // cumulative weights for KLD's draws
  KldBinner binner_;
  double kld_z_ = 0.0;  // normal_quantile(1 - kld.delta)
  ParticleClusterer clusterer_;
  std::unique_ptr<detail::HypothesisTracker> hypotheses_;  // null when disabled
  std::vector<std::uint32_t> victims_;                     // seed_particles() scratch
  bool clustered_ = false;  // the last estimate met EstimateConfig's cluster criterion

  // Filter state.
  bool have_odom_ = false;
  Pose2 odom_ref_{};  ///< odometry at the last filter update
  Pose2 anchor_{};    ///< global estimate at odom_ref_ (for dead reckoning)
  bool have_stamp_ = false;
  double last_stamp_ = 0.0;
  bool force_ = true;
  std::uint64_t step_ = 0;  ///< counter keying every random stream
  bool have_averages_ = false;
  double w_slow_ = 0.0, w_fast_ = 0.0;
  UpdateResult last_{};
};

}  // namespace pgmcl
