#pragma once
/// Frames as a localisation node sees them, without any middleware: the planar pose of a
/// 3D transform, where the laser sits on the robot (any mounting, upside down included),
/// a laser scan message turned into the engine's LaserScan, the map->odom correction, and
/// covariances in ROS's 6x6 layout.
///
/// Conventions (REP 103/105): map -> odom -> base; a transform `a_T_b` maps points of
/// frame b into frame a, i.e. it is b's pose in a. Angles in radians, lengths in metres.

#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <span>

#include "pgmcl/common/laser_scan.hpp"
#include "pgmcl/common/se2.hpp"

namespace pgmcl::nav {

/// x, y and heading of a 3D pose: the heading is that of its x axis projected on the
/// plane (for a rotation about z alone, its yaw).
[[nodiscard]] Pose2 planar(const Eigen::Isometry3d& t) noexcept;
/// The 3D transform of a planar pose: z = 0, a rotation about z by theta.
[[nodiscard]] Eigen::Isometry3d to_isometry(const Pose2& p) noexcept;

/// A laser's mounting on the robot, reduced to the plane.
struct SensorMount {
  Pose2 pose{};              ///< the laser frame in the base frame (its x axis's heading)
  bool upside_down = false;  ///< the laser's z axis points down: its angles run clockwise
};

/// Default for sensor_mount(): a scan plane tilted more than this (rad) is refused.
inline constexpr double kMaxMountTilt = 0.1;

/// The mounting of a laser whose frame is `base_T_laser` in the base frame. Throws
/// std::invalid_argument when the scan plane is tilted from the base's plane by more than
/// `max_tilt` radians (the laser's z axis, up or down, against the base's), or the
/// transform is not finite.
[[nodiscard]] SensorMount sensor_mount(const Eigen::Isometry3d& base_T_laser,
                                       double max_tilt = kMaxMountTilt);

/// A laser scan message's fields (sensor_msgs/LaserScan): beam i at angle_min +
/// i * angle_increment in the laser frame (a negative increment is a scan in reversed
/// order), ranges in metres, NaN / +-Inf allowed (the filter skips and counts them).
struct ScanView {
  double angle_min = 0.0;
  double angle_increment = 0.0;
  double range_min = 0.0;
  double range_max = 0.0;
  std::span<const float> ranges;
};

/// amcl's laser_min_range / laser_max_range: a value <= 0 keeps the scan's own limit.
struct RangeLimits {
  double min = -1.0;
  double max = -1.0;
};

/// Fills `out` (its buffer is reused) with `in` as the engine reads it: angles in the
/// base's sense of rotation (negated for an upside-down laser, whose beams sweep
/// clockwise seen from above), the sensor pose from `mount`, the limits from `limits`
/// where set. Throws std::invalid_argument for non-finite angles.
void to_laser_scan(const ScanView& in, const SensorMount& mount, const RangeLimits& limits,
                   LaserScan& out);

/// The correction a localisation node publishes, map_T_odom = map_T_base ∘ odom_T_base^-1:
/// with it, map -> odom -> base puts the robot at the estimate.
[[nodiscard]] Pose2 map_to_odom(const Pose2& map_T_base, const Pose2& odom_T_base) noexcept;

/// Row-major 6x6 covariance of (x, y, z, rotation about x, y, z), as in
/// geometry_msgs/PoseWithCovariance.
using RosCovariance = std::array<double, 36>;
/// The planar (x, y, theta) covariance in ROS's layout; z, roll and pitch rows are zero.
[[nodiscard]] RosCovariance to_ros_covariance(const Eigen::Matrix3d& xy_theta) noexcept;
/// The (x, y, yaw) block of a ROS covariance, symmetrised.
[[nodiscard]] Eigen::Matrix3d from_ros_covariance(const RosCovariance& c) noexcept;

}  // namespace pgmcl::nav
