#pragma once
/// pgmcl::nav::NavLocalizer: what a localisation node does around the filter, with no
/// middleware. A node (ROS 1, ROS 2, anything) looks up transforms, converts messages into
/// the plain structs below, calls these methods and publishes what they return.
///
/// Per scan: the node passes the scan, the base -> laser transform and the odometry pose
/// odom_T_base at the scan's stamp.
/// The adapter
///  - decides whether the filter sees the scan (every Nth scan; a requested no-motion
///    update or a new initial pose always goes through) and the filter gates on d/theta;
///  - keeps map_T_odom = estimate ∘ odom_T_base^-1, refreshed by every update that moved
///    the filter, and stamps it scan + transform_tolerance (amcl's convention);
///  - says whether a new pose is ready (a measured update), with its covariance in ROS's
///    6x6 layout, the confidence (fit, converged, alternative_evidence) and diagnostics;
///  - counts every scan it refuses (bad angles, tilted mount, filter errors) instead of
///    throwing: a stream never stops on one bad message.
/// Not thread-safe: one caller at a time (a node serialises its callbacks or locks).

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "pgmcl/maps/occupancy_grid.hpp"
#include "pgmcl/mcl/localizer.hpp"
#include "pgmcl/nav/frames.hpp"
#include "pgmcl/nav/stored_pose.hpp"

namespace pgmcl::nav {

/// The adapter's own settings; the filter's are `filter` (LocalizerConfig, whose gating
/// section is the d/theta trigger: amcl's update_min_d / update_min_a).
struct NavConfig {
  LocalizerConfig filter{};
  /// Seconds added to the scan's stamp on the map -> odom transform, so that consumers can
  /// use it until the next one arrives (amcl's transform_tolerance).
  double transform_tolerance = 0.1;
  /// The filter sees every scan_stride-th scan (1 = all); the others only refresh the
  /// transform's stamp.
  std::size_t scan_stride = 1;
  RangeLimits ranges{};                   ///< amcl's laser_min_range / laser_max_range
  double max_mount_tilt = kMaxMountTilt;  ///< radians, see sensor_mount()
  /// Seconds between stored poses (amcl's 1 / save_pose_rate); <= 0 never.
  double save_pose_period = 2.0;

  /// Throws std::invalid_argument naming the first bad field (then filter.validate()).
  void validate() const;
};

/// One scan as the node received it.
struct ScanInput {
  ScanView scan;
  /// The laser frame in the base frame (the scan message's frame); sensor_mount() reduces
  /// it to the plane.
  Eigen::Isometry3d base_T_laser = Eigen::Isometry3d::Identity();
  Pose2 odom{};        ///< odom_T_base at the scan's stamp
  double stamp = 0.0;  ///< seconds
};

/// What process_scan() did with a scan.
struct ScanOutcome {
  bool filtered = false;  ///< the filter saw it (false: stride skip or rejected)
  bool rejected = false;  ///< refused; `error` says why (counted in Diagnostics)
  std::string error;
  bool pose_ready = false;       ///< a measured update: publish pose() (and the cloud)
  bool transform_ready = false;  ///< map_to_odom() is valid (after the first accepted scan)
  UpdateResult result{};         ///< the filter's answer (the previous one when not filtered)
};

/// The estimate for publishing (amcl_pose).
struct PoseOutput {
  Pose2 pose{};                                          ///< map frame
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  ///< x, y, theta
  RosCovariance ros_covariance{};                        ///< the same in ROS's 6x6 layout
  double stamp = 0.0;                                    ///< the scan's stamp
  // The confidence (UpdateResult): how much of the scan the map explains there, whether
  // one compact hypothesis dominates, and whether another place fits better so far.
  double fit = 0.0;
  bool converged = false;
  double alternative_evidence = 0.0;
};

/// The correction to publish as map -> odom.
struct TransformOutput {
  Pose2 map_T_odom{};
  double stamp = 0.0;  ///< the last scan's stamp + transform_tolerance
};

struct WeightedPose {
  Pose2 pose{};  ///< map frame
  double weight = 0.0;
};

/// Counters since construction and the last update's figures.
struct Diagnostics {
  std::size_t scans = 0;           ///< process_scan() calls
  std::size_t filtered = 0;        ///< handed to the filter
  std::size_t measured = 0;        ///< ... that updated the weights
  std::size_t not_moved = 0;       ///< ... gated (d/theta)
  std::size_t no_valid_beams = 0;  ///< ... without a usable reading
  std::size_t time_resets = 0;     ///< ... stamped before the previous (policy kReset)
  std::size_t stride_skipped = 0;  ///< left out by scan_stride
  std::size_t rejected = 0;        ///< refused (ScanOutcome::error)
  std::string last_error;          ///< the last refusal's reason
  SkipReason last_skip = SkipReason::kNone;
  double update_ms = 0.0;  ///< the last filter update's wall time
  std::size_t particles = 0;
  std::size_t beams_total = 0, beams_invalid = 0, beams_used = 0;
  double n_eff = 0.0;
};

/// What replace_map() did.
struct MapChange {
  bool kept_particles = false;  ///< same frame: the particles moved to the new map
};

class NavLocalizer {
 public:
  /// Builds the likelihood tables from `grid` (map frame = the global frame) and starts
  /// with global localisation. Throws std::invalid_argument for a bad config or map.
  NavLocalizer(const maps::OccupancyGrid& grid, NavConfig cfg);

  /// One scan; never throws for bad scan content (see ScanOutcome::rejected).
  ScanOutcome process_scan(const ScanInput& in);

  /// Starts around `pose` (map frame) with `covariance` (x, y, theta). `odom_at_pose`, the
  /// odometry pose at the stamp the pose refers to, moves it to the filter's time with the
  /// odometry since (as amcl does with the initial pose's stamp); without it the pose is
  /// taken as the robot's now. The next scan updates even if the robot has not moved.
  /// Throws std::invalid_argument for a non-finite pose or a covariance that is not
  /// symmetric positive semidefinite.
  void set_initial_pose(const Pose2& pose, const Eigen::Matrix3d& covariance,
                        const std::optional<Pose2>& odom_at_pose = std::nullopt);
  /// Spreads the particles over the free space (amcl's global_localization service).
  void global_localize();
  /// The next scan updates the filter even if the robot has not moved (amcl's
  /// request_nomotion_update service); it also bypasses scan_stride.
  void request_nomotion_update() noexcept;

  /// A new map. `same_frame`: it is in the frame of the current one (an edited or
  /// re-published map): the particles are kept. Otherwise the filter restarts with global
  /// localisation. Throws std::invalid_argument for a map without free cells (state kept).
  MapChange replace_map(const maps::OccupancyGrid& grid, bool same_frame);

  [[nodiscard]] PoseOutput pose() const;
  /// Valid once a scan was accepted (ScanOutcome::transform_ready).
  [[nodiscard]] std::optional<TransformOutput> map_to_odom() const;
  /// The particle cloud in the map frame with normalised weights; `out` is reused.
  void particles(std::vector<WeightedPose>& out) const;
  [[nodiscard]] const Diagnostics& diagnostics() const noexcept { return diag_; }

  /// The pose to store now: the last measured estimate, at most once per
  /// save_pose_period (by `now`, seconds, the node's clock), nullopt otherwise.
  [[nodiscard]] std::optional<StoredPose> pose_to_store(double now);

  [[nodiscard]] const Localizer& localizer() const noexcept { return *loc_; }
  [[nodiscard]] const NavConfig& config() const noexcept { return cfg_; }

 private:
  void apply_pending_pose(const Pose2& odom_now);
  ScanOutcome reject(ScanOutcome out, const std::string& why);

  NavConfig cfg_;
  std::unique_ptr<Localizer> loc_;
  LaserScan scan_;  // conversion buffer, reused
  Diagnostics diag_;
  std::size_t stride_counter_ = 0;
  bool forced_ = true;  // the next scan bypasses the stride (start, initial pose, request)

  // The odometry pose of the filter's last update (what set_pose() refers to).
  std::optional<Pose2> odom_ref_;
  std::optional<Pose2> last_odom_;  // the odometry of the last scan seen
  // An initial pose given before the filter had an odometry reference: map_T_odom it
  // implies, applied at the next scan's odometry.
  std::optional<Pose2> pending_correction_;
  Eigen::Matrix3d pending_covariance_ = Eigen::Matrix3d::Zero();

  std::optional<Pose2> correction_;  // map_T_odom
  double last_stamp_ = 0.0;
  double pose_stamp_ = 0.0;
  bool have_measured_ = false;
  std::optional<double> last_saved_;
};

}  // namespace pgmcl::nav
