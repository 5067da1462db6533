// ROS 1 bags as io::CarmenLog: round trips through a bag, mounts from the transform tree
// (upside down, chains of static frames), odometry from /tf or a topic, and errors that
// name the bag and the topic or frame.
#include "pgmcl/rosbag_io/rosbag_io.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "pgmcl/io/errors.hpp"
#include "pgmcl/io/odometry_pairing.hpp"
#include "temp_files.hpp"

namespace pgmcl::rosbag_io {
namespace {

constexpr double kPi = std::numbers::pi;

ros1::Rigid rigid(double x, double y, double z, const Eigen::Quaterniond& q) {
  return {x, y, z, q.x(), q.y(), q.z(), q.w()};
}
Eigen::Quaterniond yaw_q(double a) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()));
}

/// A log of `n` ROBOTLASER1-like scans with odometry, as the reader or a simulator has it.
io::CarmenLog small_log(std::size_t n, const Pose2& mount = {0.2, -0.05, 0.1}) {
  io::CarmenLog log;
  for (std::size_t k = 0; k < n; ++k) {
    io::CarmenScan s;
    s.message = io::LaserMessage::kRobotLaser1;
    s.stamp = 5.0 + 0.25 * static_cast<double>(k);
    s.scan.angle_min = -2.0;
    s.scan.angle_increment = 0.01;
    s.scan.range_min = 0.05;
    s.scan.range_max = 25.0;
    s.scan.sensor_pose = mount;
    for (int i = 0; i < 401; ++i)
      s.scan.ranges.push_back(1.0f + 0.001f * static_cast<float>(i + k));
    s.scan.ranges[7] = std::numeric_limits<float>::quiet_NaN();
    s.odom_pose = {0.1 * static_cast<double>(k), 0.02 * static_cast<double>(k),
                   0.05 * static_cast<double>(k)};
    s.laser_pose = s.odom_pose.compose(mount);
    s.line = k + 1;
    log.scans.push_back(s);
  }
  return log;
}

TEST(RosbagIo, LogRoundTripsThroughABag) {
  const testkit::TempDir dir("rosbag_io");
  const std::string bag = dir.file("log.bag");
  const io::CarmenLog log = small_log(30);
  const BagWriteReport w = write_bag(log, bag);
  EXPECT_EQ(w.scans, 30u);
  for (const std::string& odom_topic : {std::string(), std::string("/odom")}) {
    BagReadOptions opt;
    opt.odom_topic = odom_topic;  // odometry from /tf, then from the Odometry topic
    BagReadReport report;
    const io::CarmenLog back = read_bag(bag, opt, &report);
    ASSERT_EQ(back.scans.size(), 30u);
    EXPECT_EQ(report.odometry, 30u);
    EXPECT_EQ(report.outside_odometry, 0u);
    const io::PairedScans paired = io::pair_odometry(back);
    for (std::size_t k = 0; k < 30; ++k) {
      const io::CarmenScan& a = log.scans[k];
      const io::CarmenScan& b = back.scans[k];
      EXPECT_EQ(b.message, io::LaserMessage::kRobotLaser1);
      EXPECT_EQ(b.stamp, a.stamp);
      EXPECT_EQ(b.line, k + 1);
      ASSERT_EQ(b.scan.ranges.size(), a.scan.ranges.size());
      for (std::size_t i = 0; i < a.scan.ranges.size(); ++i) {
        if (i == 7) {
          EXPECT_TRUE(std::isnan(b.scan.ranges[i]));
        } else {
          ASSERT_EQ(b.scan.ranges[i], a.scan.ranges[i]);
        }
      }
      // LaserScan's angles and limits are float32 in the message.
      EXPECT_EQ(b.scan.angle_min, static_cast<double>(static_cast<float>(a.scan.angle_min)));
      EXPECT_EQ(b.scan.angle_increment, static_cast<double>(static_cast<float>(0.01)));
      EXPECT_EQ(b.scan.range_max, 25.0);
      EXPECT_NEAR(b.scan.sensor_pose.x, 0.2, 1e-12);
      EXPECT_NEAR(b.scan.sensor_pose.y, -0.05, 1e-12);
      EXPECT_NEAR(b.scan.sensor_pose.theta, 0.1, 1e-12);
      ASSERT_EQ(paired.scans[k].source, io::OdomSource::kInterpolated);
      EXPECT_NEAR(paired.scans[k].odom.x, a.odom_pose.x, 1e-12);
      EXPECT_NEAR(paired.scans[k].odom.y, a.odom_pose.y, 1e-12);
      EXPECT_NEAR(paired.scans[k].odom.theta, a.odom_pose.theta, 1e-12);
    }
  }
}

TEST(RosbagIo, WriteLeavesOutScansWithoutOdometryOrOutOfOrder) {
  const testkit::TempDir dir("rosbag_io");
  io::CarmenLog log = small_log(10);
  log.scans[3].has_poses = false;                 // no odometry at all
  log.scans[6].stamp = log.scans[5].stamp - 0.1;  // stamped before its predecessor
  const BagWriteReport w = write_bag(log, dir.file("x.bag"));
  EXPECT_EQ(w.scans, 8u);
  EXPECT_EQ(w.without_odometry, 1u);
  EXPECT_EQ(w.out_of_order, 1u);
  EXPECT_EQ(read_bag(dir.file("x.bag")).scans.size(), 8u);
}

TEST(RosbagIo, WriteRefusesWhatABagCannotHold) {
  const testkit::TempDir dir("rosbag_io");
  io::CarmenLog log = small_log(5);
  log.scans[2].scan.sensor_pose.x = 0.3;
  try {
    write_bag(log, dir.file("x.bag"));
    FAIL() << "a changing mount was written";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).substr(0, 34), "line 3: the laser's mounting chang");
  }
  log = small_log(5);
  log.scans[0].stamp = -1.0;
  EXPECT_THROW(write_bag(log, dir.file("y.bag")), std::invalid_argument);
  BagWriteOptions opt;
  opt.time_offset = 2.0;
  EXPECT_EQ(write_bag(log, dir.file("y.bag"), opt).scans, 5u);
  EXPECT_THROW(write_bag(small_log(2), dir.file("no/such/dir/z.bag")), io::IoError);
}

/// A bag written from plain messages: a laser mounted upside down behind a chain of static
/// frames, reporting its beams in reversed order.
TEST(RosbagIo, UpsideDownLaserBehindAChainOfFrames) {
  const testkit::TempDir dir("rosbag_io");
  ros1::BagMessages m;
  const Eigen::Quaterniond flipped =
      yaw_q(0.5) * Eigen::Quaterniond(Eigen::AngleAxisd(kPi, Eigen::Vector3d::UnitX()));
  m.static_transforms.push_back({1.0, "base_link", "mast", rigid(0.1, 0.0, 0.5, yaw_q(0.0))});
  m.static_transforms.push_back({1.0, "mast", "laser_flipped", rigid(0.2, 0.3, 0.1, flipped)});
  for (int k = 0; k < 3; ++k) {
    const double t = 2.0 + k;
    m.transforms.push_back({t, "odom", "base_link", rigid(k, 0, 0, yaw_q(0.1 * k))});
    m.scans.push_back({t, "laser_flipped", 1.0, -0.02, 0.1, 20.0, std::vector<float>(101, 2.0f)});
  }
  ros1::write_bag_messages(dir.file("m.bag"), m, "/scan", "");
  const io::CarmenLog log = read_bag(dir.file("m.bag"));
  ASSERT_EQ(log.scans.size(), 3u);
  const LaserScan& s = log.scans[0].scan;
  EXPECT_NEAR(s.sensor_pose.x, 0.3, 1e-9);
  EXPECT_NEAR(s.sensor_pose.y, 0.3, 1e-9);
  EXPECT_NEAR(s.sensor_pose.theta, 0.5, 1e-9);
  EXPECT_NEAR(s.angle_min, -1.0, 1e-6);  // negated: the beams sweep clockwise seen from above
  EXPECT_NEAR(s.angle_increment, 0.02, 1e-7);
  EXPECT_EQ(log.odometry.size(), 3u);
  EXPECT_NEAR(log.scans[2].odom_pose.theta, 0.2, 1e-12);
}

TEST(RosbagIo, ErrorsNameTheBagAndTheTopicOrFrame) {
  const testkit::TempDir dir("rosbag_io");
  const std::string bag = dir.file("log.bag");
  (void)write_bag(small_log(4), bag);
  const auto error_of = [&](const BagReadOptions& opt) -> std::string {
    try {
      (void)read_bag(bag, opt);
    } catch (const std::exception& e) {
      return e.what();
    }
    return "";
  };
  BagReadOptions opt;
  opt.scan_topic = "/base_scan";
  EXPECT_EQ(error_of(opt), bag + ": /base_scan: no sensor_msgs/LaserScan on this topic");
  opt = {};
  opt.odom_frame = "odom_combined";
  EXPECT_EQ(error_of(opt), bag +
                               ": /tf: no transform odom_combined -> base_link (--odom-frame, "
                               "--base-frame; edges in the bag: odom -> base_link)");
  opt = {};
  opt.scan_topic = "/odom";
  EXPECT_EQ(error_of(opt), bag +
                               ": topic /odom holds nav_msgs/Odometry, expected "
                               "sensor_msgs/LaserScan");
  opt = {};
  opt.base_frame = "base_footprint";
  opt.odom_topic = "/odom";
  EXPECT_EQ(error_of(opt), bag +
                               ": /odom: odometry of frame 'base_link', expected "
                               "'base_footprint' (--base-frame)");
  EXPECT_THROW((void)read_bag(dir.file("missing.bag")), io::IoError);
}

}  // namespace
}  // namespace pgmcl::rosbag_io
