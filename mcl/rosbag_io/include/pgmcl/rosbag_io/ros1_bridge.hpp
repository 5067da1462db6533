#pragma once
/// Plain types between pgmcl (C++20) and the code that includes ROS 1 headers, which is
/// built as C++17: Debian's ROS 1 generated messages use std::allocator<void>::rebind,
/// which C++20 removed. This header must stay C++17 and free of ROS and pgmcl types.

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace pgmcl::ros1 {

/// A 3D rigid transform: translation (metres) and unit quaternion (geometry_msgs/Transform).
struct Rigid {
  double x = 0.0, y = 0.0, z = 0.0;
  double qx = 0.0, qy = 0.0, qz = 0.0, qw = 1.0;
};

/// sensor_msgs/LaserScan without intensities and timing fields.
struct Scan {
  double stamp = 0.0;  ///< seconds
  std::string frame_id;
  double angle_min = 0.0, angle_increment = 0.0;  ///< radians
  double range_min = 0.0, range_max = 0.0;        ///< metres
  std::vector<float> ranges;
};

/// One transform of /tf or /tf_static: `child`'s pose in `parent`.
struct StampedTransform {
  double stamp = 0.0;
  std::string parent, child;
  Rigid transform;
};

/// nav_msgs/Odometry's pose: `child_frame_id`'s pose in `frame_id`.
struct OdometryPose {
  double stamp = 0.0;
  std::string frame_id, child_frame_id;
  Rigid pose;
};

/// What localisation reads from a bag, each kind in the bag's order.
struct BagMessages {
  std::vector<Scan> scans;
  std::vector<StampedTransform> transforms;         ///< /tf
  std::vector<StampedTransform> static_transforms;  ///< /tf_static
  std::vector<OdometryPose> odometry;
  std::vector<std::pair<std::string, std::size_t>> other_topics;  ///< not read: topic, count
};

/// Reads `scan_topic` (sensor_msgs/LaserScan), /tf and /tf_static (tf2_msgs/TFMessage) and,
/// unless empty, `odom_topic` (nav_msgs/Odometry) with librosbag-storage (no master).
/// Throws std::runtime_error naming the file for an unreadable bag, or a topic whose type is
/// not the one expected.
[[nodiscard]] BagMessages read_bag_messages(const std::string& path, const std::string& scan_topic,
                                            const std::string& odom_topic);

/// Writes the scans to `scan_topic`, transforms to /tf, static ones to /tf_static (latched,
/// so that `rosbag play` republishes them latched) and odometry to `odom_topic` (if not
/// empty), each at its stamp. Throws std::runtime_error naming the file on failure.
void write_bag_messages(const std::string& path, const BagMessages& m,
                        const std::string& scan_topic, const std::string& odom_topic);

}  // namespace pgmcl::ros1
