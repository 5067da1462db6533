#include "pgmcl/nav/frames.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace pgmcl::nav {

Pose2 planar(const Eigen::Isometry3d& t) noexcept {
  const Eigen::Matrix3d r = t.linear();
  return {t.translation().x(), t.translation().y(), std::atan2(r(1, 0), r(0, 0))};
}

Eigen::Isometry3d to_isometry(const Pose2& p) noexcept {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Eigen::Vector3d(p.x, p.y, 0.0);
  t.linear() = Eigen::AngleAxisd(p.theta, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return t;
}

SensorMount sensor_mount(const Eigen::Isometry3d& base_T_laser, double max_tilt) {
  if (!base_T_laser.matrix().allFinite())
    throw std::invalid_argument("sensor mount: the base -> laser transform is not finite");
  const Eigen::Matrix3d r = base_T_laser.linear();
  // The laser's z axis in the base frame: up (normal) or down (upside down); anything
  // else tilts the scan plane, and its beams would not lie in the map's plane.
  const double z = std::clamp(r(2, 2), -1.0, 1.0);
  const double tilt = std::acos(std::abs(z));
  if (tilt > max_tilt)
    throw std::invalid_argument("sensor mount: the scan plane is tilted " + std::to_string(tilt) +
                                " rad from the base's plane (at most " + std::to_string(max_tilt) +
                                " rad): a planar localiser cannot use it");
  SensorMount m;
  m.pose = planar(base_T_laser);
  m.upside_down = z < 0.0;
  return m;
}

void to_laser_scan(const ScanView& in, const SensorMount& mount, const RangeLimits& limits,
                   LaserScan& out) {
  if (!std::isfinite(in.angle_min) || !std::isfinite(in.angle_increment))
    throw std::invalid_argument("laser scan: angle_min and angle_increment must be finite");
  // Upside down, a beam at angle a in the laser frame points at heading(mount) - a in the
  // base frame (R = Rz(yaw) Rx(pi) maps (cos a, sin a, 0) to angle yaw - a).
  const double sense = mount.upside_down ? -1.0 : 1.0;
  out.angle_min = sense * in.angle_min;
  out.angle_increment = sense * in.angle_increment;
  out.range_min = limits.min > 0.0 ? limits.min : in.range_min;
  out.range_max = limits.max > 0.0 ? limits.max : in.range_max;
  out.sensor_pose = mount.pose;
  out.ranges.assign(in.ranges.begin(), in.ranges.end());
}

Pose2 map_to_odom(const Pose2& map_T_base, const Pose2& odom_T_base) noexcept {
  return map_T_base.compose(odom_T_base.inverse());
}

RosCovariance to_ros_covariance(const Eigen::Matrix3d& c) noexcept {
  constexpr std::size_t kIndex[3] = {0, 1, 5};  // x, y, rotation about z
  RosCovariance out{};
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j)
      out[6 * kIndex[i] + kIndex[j]] =
          c(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
  return out;
}

Eigen::Matrix3d from_ros_covariance(const RosCovariance& c) noexcept {
  constexpr std::size_t kIndex[3] = {0, 1, 5};
  Eigen::Matrix3d m;
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j)
      m(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = c[6 * kIndex[i] + kIndex[j]];
  return 0.5 * (m + m.transpose());
}

}  // namespace pgmcl::nav
