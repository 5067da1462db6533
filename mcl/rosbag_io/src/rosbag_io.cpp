// Bags <-> io::CarmenLog (C++20; the ROS 1 side is bag_messages.cpp).
#include "pgmcl/rosbag_io/rosbag_io.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>

#include "pgmcl/io/errors.hpp"
#include "pgmcl/io/odometry_pairing.hpp"
#include "pgmcl/rosbag_io/ros1_bridge.hpp"

namespace pgmcl::rosbag_io {
namespace {

/// base_T_frame for every frame below `base` in the static tree (/tf_static, then the
/// first value of any other /tf edge, as bags recorded before /tf_static existed have it).
class MountTree {
 public:
  MountTree(const ros1::BagMessages& m, const std::string& base, const std::string& odom) {
    for (const auto& t : m.static_transforms) parent_.try_emplace(t.child, t);
    for (const auto& t : m.transforms)
      if (!(t.parent == odom && t.child == base)) parent_.try_emplace(t.child, t);
  }
  [[nodiscard]] std::optional<Eigen::Isometry3d> base_T(const std::string& frame,
                                                        const std::string& base) const {
    Eigen::Isometry3d acc = Eigen::Isometry3d::Identity();
    std::string f = frame;
    for (std::size_t hops = 0; hops <= parent_.size(); ++hops) {
      if (f == base) return acc;
      const auto it = parent_.find(f);
      if (it == parent_.end()) return std::nullopt;
      acc = to_isometry(it->second.transform) * acc;
      f = it->second.parent;
    }
    return std::nullopt;  // a cycle
  }

 private:
  std::map<std::string, ros1::StampedTransform> parent_;  // child -> edge
};

std::string edge_list(const std::vector<ros1::StampedTransform>& tf) {
  std::map<std::string, std::size_t> edges;
  for (const auto& t : tf) ++edges[t.parent + " -> " + t.child];
  std::string out;
  for (const auto& [e, n] : edges) out += (out.empty() ? "" : ", ") + e;
  return out.empty() ? "none" : out;
}

io::Trajectory odometry_track(const ros1::BagMessages& m, const std::string& path,
                              const BagReadOptions& opt) {
  io::Trajectory odom;
  if (!opt.odom_topic.empty()) {
    for (const auto& o : m.odometry) {
      if (!o.child_frame_id.empty() && o.child_frame_id != opt.base_frame)
        throw io::FormatError(path, 0, opt.odom_topic,
                              "odometry of frame '" + o.child_frame_id + "', expected '" +
                                  opt.base_frame + "' (--base-frame)");
      odom.push_back({o.stamp, nav::planar(to_isometry(o.pose))});
    }
    if (odom.empty()) throw io::FormatError(path, 0, opt.odom_topic, "no odometry message");
  } else {
    for (const auto& t : m.transforms)
      if (t.parent == opt.odom_frame && t.child == opt.base_frame)
        odom.push_back({t.stamp, nav::planar(to_isometry(t.transform))});
    if (odom.empty())
      throw io::FormatError(
          path, 0, "/tf",
          "no transform " + opt.odom_frame + " -> " + opt.base_frame +
              " (--odom-frame, --base-frame; edges in the bag: " + edge_list(m.transforms) + ")");
  }
  io::sort_by_stamp(odom);
  return odom;
}

}  // namespace

Eigen::Isometry3d to_isometry(const ros1::Rigid& r) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Eigen::Vector3d(r.x, r.y, r.z);
  t.linear() = Eigen::Quaterniond(r.qw, r.qx, r.qy, r.qz).normalized().toRotationMatrix();
  return t;
}

ros1::Rigid to_rigid(const Pose2& p) {
  return {p.x, p.y, 0.0, 0.0, 0.0, std::sin(p.theta / 2), std::cos(p.theta / 2)};
}

io::CarmenLog read_bag(const std::string& path, const BagReadOptions& opt, BagReadReport* report) {
  ros1::BagMessages m;
  try {
    m = ros1::read_bag_messages(path, opt.scan_topic, opt.odom_topic);
  } catch (const std::runtime_error& e) {
    throw io::IoError(e.what());
  }
  if (m.scans.empty())
    throw io::FormatError(path, 0, opt.scan_topic, "no sensor_msgs/LaserScan on this topic");
  const io::Trajectory odom = odometry_track(m, path, opt);
  const MountTree tree(m, opt.base_frame, opt.odom_frame);
  std::map<std::string, nav::SensorMount> mounts;

  io::CarmenLog log;
  BagReadReport rep;
  rep.scans = m.scans.size();
  rep.odometry = odom.size();
  for (const io::StampedPose& p : odom)
    log.odometry.push_back({p.pose, 0, 0, 0, p.stamp, "bag", p.stamp, 0});
  for (std::size_t i = 0; i < m.scans.size(); ++i) {
    const ros1::Scan& s = m.scans[i];
    auto mount = mounts.find(s.frame_id);
    if (mount == mounts.end()) {
      const auto t = tree.base_T(s.frame_id, opt.base_frame);
      if (!t)
        throw io::FormatError(path, i + 1, opt.scan_topic,
                              "no transform from " + opt.base_frame + " to the scan's frame '" +
                                  s.frame_id + "' in /tf_static or /tf");
      try {
        mount = mounts.emplace(s.frame_id, nav::sensor_mount(*t, opt.max_mount_tilt)).first;
      } catch (const std::invalid_argument& e) {
        throw io::FormatError(path, i + 1, opt.scan_topic, e.what());
      }
    }
    io::CarmenScan c;
    c.message = io::LaserMessage::kRobotLaser1;
    try {
      nav::to_laser_scan({s.angle_min, s.angle_increment, s.range_min, s.range_max, s.ranges},
                         mount->second, {}, c.scan);
    } catch (const std::invalid_argument& e) {
      throw io::FormatError(path, i + 1, opt.scan_topic, e.what());
    }
    c.stamp = c.logger_stamp = s.stamp;
    c.config.field_of_view = std::abs(s.angle_increment) *
                             static_cast<double>(s.ranges.empty() ? 0 : s.ranges.size() - 1);
    c.host = "bag";
    c.line = i + 1;
    const auto at = io::interpolate_at(odom, s.stamp);
    c.has_poses = at.has_value();
    if (at) {
      c.odom_pose = *at;
      c.laser_pose = at->compose(c.scan.sensor_pose);
    } else {
      ++rep.outside_odometry;
    }
    log.scans.push_back(std::move(c));
  }
  for (const auto& [topic, n] : m.other_topics)
    rep.notes.push_back("left unread: " + topic + " (" + std::to_string(n) + " messages)");
  log.report.source = path;
  log.report.records["ROBOTLASER1"] = log.scans.size();
  log.report.records["ODOM"] = log.odometry.size();
  if (report != nullptr) *report = std::move(rep);
  return log;
}

BagWriteReport write_bag(const io::CarmenLog& log, const std::string& path,
                         const BagWriteOptions& opt) {
  const io::PairedScans paired = io::pair_odometry(log);
  ros1::BagMessages m;
  BagWriteReport rep;
  std::optional<Pose2> mount;
  for (const io::PairedScan& p : paired.scans) {
    const io::CarmenScan& c = log.scans[p.scan_index];
    if (p.source == io::OdomSource::kNone) {
      ++rep.without_odometry;
      continue;
    }
    const std::string where = "line " + std::to_string(c.line);
    const double stamp = c.stamp + opt.time_offset;
    if (!m.scans.empty() && stamp < m.scans.back().stamp) {
      ++rep.out_of_order;  // a bag is played in time order: it would come out elsewhere
      continue;
    }
    if (!(std::isfinite(stamp) && stamp > 0.0))
      throw std::invalid_argument(where + ": stamp " + std::to_string(c.stamp) +
                                  " s + offset is not > 0: ROS time starts at 0 (--time-offset)");
    const Pose2& sp = c.scan.sensor_pose;
    if (!mount) {
      mount = sp;
      m.static_transforms.push_back({stamp, opt.base_frame, opt.laser_frame, to_rigid(sp)});
    } else if (std::abs(sp.x - mount->x) > 1e-9 || std::abs(sp.y - mount->y) > 1e-9 ||
               std::abs(wrap_angle(sp.theta - mount->theta)) > 1e-9) {
      throw std::invalid_argument(where +
                                  ": the laser's mounting changes between scans; a bag "
                                  "holds one static base -> laser transform");
    }
    m.transforms.push_back({stamp, opt.odom_frame, opt.base_frame, to_rigid(p.odom)});
    m.odometry.push_back({stamp, opt.odom_frame, opt.base_frame, to_rigid(p.odom)});
    m.scans.push_back({stamp, opt.laser_frame, c.scan.angle_min, c.scan.angle_increment,
                       c.scan.range_min, c.scan.range_max, c.scan.ranges});
    ++rep.scans;
  }
  if (m.scans.empty()) throw std::invalid_argument("no scan with odometry to write");
  try {
    ros1::write_bag_messages(path, m, opt.scan_topic, opt.odom_topic);
  } catch (const std::runtime_error& e) {
    throw io::IoError(e.what());
  }
  return rep;
}

}  // namespace pgmcl::rosbag_io
