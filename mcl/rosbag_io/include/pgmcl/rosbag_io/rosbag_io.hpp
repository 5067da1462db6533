#pragma once
/// ROS 1 bags as localisation input and output, without a master (librosbag-storage).
///
/// A bag is read into the same in-memory log as a CARMEN file (io::CarmenLog), so every
/// command that replays a log replays a bag: each sensor_msgs/LaserScan becomes a scan
/// (ROBOTLASER1, so its angles are kept) with the laser's mounting from the transform tree
/// (nav::sensor_mount: upside down handled, a tilted plane refused), and the odometry
/// (odom -> base from /tf, or a nav_msgs/Odometry topic) becomes ODOM records, which
/// io::pair_odometry interpolates at each scan's stamp. A CARMEN log is written as a bag
/// with /scan, /tf (odom -> base at each scan), /tf_static (base -> laser) and /odom, so
/// that every logged run can drive the ROS node.

#include <cstddef>
#include <string>
#include <vector>

#include "pgmcl/io/carmen.hpp"
#include "pgmcl/nav/frames.hpp"
#include "pgmcl/rosbag_io/ros1_bridge.hpp"

namespace pgmcl::rosbag_io {

struct BagReadOptions {
  std::string scan_topic = "/scan";
  std::string odom_topic;  ///< nav_msgs/Odometry; empty: odometry from /tf
  std::string odom_frame = "odom";
  std::string base_frame = "base_link";
  double max_mount_tilt = nav::kMaxMountTilt;  ///< radians
};

/// What read_bag() saw besides the log.
struct BagReadReport {
  std::size_t scans = 0;
  std::size_t odometry = 0;          ///< odometry poses (from /tf or the odometry topic)
  std::size_t outside_odometry = 0;  ///< scans before the first / after the last odometry
  std::vector<std::string> notes;    ///< other topics left unread, per topic with its count
};

/// Reads `path`. Throws io::FormatError naming the bag and the topic or frame for: no scan
/// on the scan topic, a topic of the wrong type, no odometry, no transform from the base
/// to a scan's frame, a tilted laser; io::IoError for an unreadable bag. Scans outside the
/// odometry's time span carry no odometry (io::pair_odometry leaves them unpaired). A
/// scan's CarmenScan::line is its 1-based index on the scan topic.
[[nodiscard]] io::CarmenLog read_bag(const std::string& path, const BagReadOptions& opt = {},
                                     BagReadReport* report = nullptr);

struct BagWriteOptions {
  std::string scan_topic = "/scan";
  std::string odom_topic = "/odom";  ///< empty: no odometry topic, /tf only
  std::string odom_frame = "odom";
  std::string base_frame = "base_link";
  std::string laser_frame = "laser";
  double time_offset = 0.0;  ///< seconds added to every stamp (ROS time must be > 0)
};

struct BagWriteReport {
  std::size_t scans = 0;             ///< written
  std::size_t without_odometry = 0;  ///< left out: no odometry at their stamp
  std::size_t out_of_order = 0;      ///< left out: stamped before the previous scan
};

/// Writes the scans of `log` that have odometry (io::pair_odometry) and are not stamped
/// before the previous one (a bag plays in time order; `pgmcl localize` skips such scans
/// too), each with odom -> base
/// at its stamp on /tf and /odom; base -> laser once on /tf_static. Throws
/// std::invalid_argument when the laser's mounting changes between scans or a stamp plus
/// the offset is not > 0 (naming the scan's line), io::IoError when the bag cannot be
/// written.
BagWriteReport write_bag(const io::CarmenLog& log, const std::string& path,
                         const BagWriteOptions& opt = {});

/// A bridge transform as Eigen (the quaternion normalised) and a planar pose as one.
[[nodiscard]] Eigen::Isometry3d to_isometry(const ros1::Rigid& r);
[[nodiscard]] ros1::Rigid to_rigid(const Pose2& p);

}  // namespace pgmcl::rosbag_io
