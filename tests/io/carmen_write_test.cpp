// Writing CARMEN logs: every record type round-trips exactly, plain and gzip.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "io_test_util.hpp"
#include "pgmcl/io/carmen.hpp"
#include "pgmcl/io/carmen_writer.hpp"

namespace pgmcl::io {
namespace {

using test::same;
using test::same_pose;

CarmenScan laser(LaserMessage m, std::size_t n, double stamp) {
  CarmenScan s;
  s.message = m;
  const BeamLayout l = sick_beam_layout(n);
  s.scan.angle_min = l.angle_min;
  s.scan.angle_increment = l.angle_increment;
  for (std::size_t i = 0; i < n; ++i) s.scan.ranges.push_back(1.0f / 3.0f + static_cast<float>(i));
  s.stamp = stamp;
  s.laser_pose = {1.0 / 3.0, -2e-7, std::numbers::pi};
  s.odom_pose = {1e6 + 0.1, -5.5, -3.0};
  s.host = "robot";
  s.logger_stamp = stamp + 0.001;
  return s;
}

CarmenLog every_record_type() {
  CarmenLog log;
  log.params["robot_front_laser_max"] = "20";
  log.params["robot_rearlaser_offset"] = "0.125";
  log.params["robot_frontlaser_offset"] = "0.25";
  log.odometry.push_back({{0.1, 0.2, 0.3}, 0.5, -0.25, 1e-9, 976052905.167303, "h", 976052905.2});
  log.odometry.push_back({{-1.0 / 7.0, 2.0, -std::numbers::pi / 3}, 0, 0, 0, 976052906.5, "h", 1});
  log.truepos.push_back({{3, 4, 2.5}, {5, 6, -2.5}, 976052906.0, "sim", 976052906.0});
  log.scans.push_back(laser(LaserMessage::kFlaser, 181, 976052905.5));
  log.scans.back().scan.ranges[7] = std::numeric_limits<float>::quiet_NaN();
  log.scans.back().scan.ranges[8] = -1.0f;
  log.scans.push_back(laser(LaserMessage::kRlaser, 360, 976052905.6));
  CarmenScan rl = laser(LaserMessage::kRobotLaser1, 1081, 976052905.7);
  rl.scan.angle_min = -2.35619449;
  rl.scan.angle_increment = 0.004363323;
  rl.scan.range_max = 30.0;
  rl.config = {3, 4.71238898, 0.03, 1};
  rl.remissions = {0.5f, 1e-3f};
  rl.extras = {0.3, -0.1, 0.4, 0.2, 0.05};
  log.scans.push_back(rl);
  for (LaserMessage m : {LaserMessage::kRawLaser1, LaserMessage::kRawLaser2,
                         LaserMessage::kRawLaser3, LaserMessage::kRawLaser4}) {
    CarmenScan raw = laser(m, 5, 976052905.8);
    raw.has_poses = false;
    raw.laser_pose = raw.odom_pose = {};
    raw.scan.range_max = 8.0;
    raw.config = {1, 4.0 * raw.scan.angle_increment, 0.01, 0};  // fov spans the 5 readings
    log.scans.push_back(raw);
  }
  return log;
}

void expect_same_scan(const CarmenScan& a, const CarmenScan& b) {
  EXPECT_EQ(a.message, b.message);
  ASSERT_EQ(a.scan.size(), b.scan.size());
  for (std::size_t i = 0; i < a.scan.size(); ++i) {
    ASSERT_TRUE(same(a.scan.ranges[i], b.scan.ranges[i])) << i;
  }
  EXPECT_EQ(a.stamp, b.stamp);
  EXPECT_EQ(a.scan.angle_min, b.scan.angle_min);
  EXPECT_EQ(a.scan.angle_increment, b.scan.angle_increment);
  EXPECT_EQ(a.remissions, b.remissions);
  EXPECT_EQ(a.has_poses, b.has_poses);
  EXPECT_TRUE(same_pose(a.laser_pose, b.laser_pose));
  EXPECT_TRUE(same_pose(a.odom_pose, b.odom_pose));
  EXPECT_EQ(a.host, b.host);
  EXPECT_EQ(a.logger_stamp, b.logger_stamp);
  if (a.message != LaserMessage::kFlaser && a.message != LaserMessage::kRlaser) {
    EXPECT_EQ(a.scan.range_max, b.scan.range_max);
    EXPECT_EQ(a.config.laser_type, b.config.laser_type);
    EXPECT_EQ(a.config.field_of_view, b.config.field_of_view);
    EXPECT_EQ(a.config.accuracy, b.config.accuracy);
    EXPECT_EQ(a.config.remission_mode, b.config.remission_mode);
  }
  if (a.message == LaserMessage::kRobotLaser1) {
    EXPECT_EQ(a.extras.tv, b.extras.tv);
    EXPECT_EQ(a.extras.rv, b.extras.rv);
    EXPECT_EQ(a.extras.forward_safety_dist, b.extras.forward_safety_dist);
    EXPECT_EQ(a.extras.side_safety_dist, b.extras.side_safety_dist);
    EXPECT_EQ(a.extras.turn_axis, b.extras.turn_axis);
  }
}

void expect_same_log(const CarmenLog& a, const CarmenLog& b) {
  EXPECT_EQ(a.params, b.params);
  ASSERT_EQ(a.odometry.size(), b.odometry.size());
  for (std::size_t i = 0; i < a.odometry.size(); ++i) {
    const OdomRecord &x = a.odometry[i], &y = b.odometry[i];
    EXPECT_TRUE(same_pose(x.pose, y.pose));
    EXPECT_EQ(x.tv, y.tv);
    EXPECT_EQ(x.rv, y.rv);
    EXPECT_EQ(x.accel, y.accel);
    EXPECT_EQ(x.stamp, y.stamp);
    EXPECT_EQ(x.host, y.host);
    EXPECT_EQ(x.logger_stamp, y.logger_stamp);
  }
  ASSERT_EQ(a.truepos.size(), b.truepos.size());
  for (std::size_t i = 0; i < a.truepos.size(); ++i) {
    EXPECT_TRUE(same_pose(a.truepos[i].true_pose, b.truepos[i].true_pose));
    EXPECT_TRUE(same_pose(a.truepos[i].odom_pose, b.truepos[i].odom_pose));
    EXPECT_EQ(a.truepos[i].stamp, b.truepos[i].stamp);
    EXPECT_EQ(a.truepos[i].logger_stamp, b.truepos[i].logger_stamp);
  }
  ASSERT_EQ(a.scans.size(), b.scans.size());
  for (std::size_t i = 0; i < a.scans.size(); ++i) {
    SCOPED_TRACE(i);
    expect_same_scan(a.scans[i], b.scans[i]);
  }
}

TEST(CarmenWrite, EveryRecordTypeRoundTripsPlainAndGzip) {
  const CarmenLog log = every_record_type();
  test::TempDir dir;
  for (const char* name : {"all.log", "all.log.gz"}) {
    SCOPED_TRACE(name);
    write_carmen(dir.file(name), log);
    const CarmenLog back = read_carmen(dir.file(name));
    EXPECT_EQ(back.report.malformed, 0u) << back.report.summary();
    EXPECT_EQ(back.report.backwards, 0u) << back.report.summary();
    expect_same_log(log, back);
    // What the format does not carry comes back from the PARAMs.
    EXPECT_EQ(back.scans[0].scan.range_max, 20.0);
    EXPECT_TRUE(same_pose(back.scans[0].scan.sensor_pose, {0.25, 0, 0}));
    EXPECT_TRUE(same_pose(back.scans[1].scan.sensor_pose, {-0.125, 0, std::numbers::pi}));
  }
}

TEST(CarmenWrite, IntelRewritesIdentically) {
  const CarmenLog log = read_carmen(test::data_path("logs/intel-corrected.log.gz"));
  test::TempDir dir;
  write_carmen(dir.file("intel.log.gz"), log);
  const CarmenLog back = read_carmen(dir.file("intel.log.gz"));
  expect_same_log(log, back);
  // File order is kept, so the backwards timestamps are the same ones.
  EXPECT_EQ(back.report.backwards_by_type, log.report.backwards_by_type);
}

TEST(CarmenWrite, ScanRecordsForSimulatedScans) {
  LaserScan sick;
  const BeamLayout l = sick_beam_layout(181);
  sick.angle_min = l.angle_min;
  sick.angle_increment = l.angle_increment;
  sick.ranges.assign(181, 2.5f);
  sick.range_max = 25.0;
  sick.sensor_pose = {0.2, 0.0, 0.0};
  LaserScan utm = sick;  // a 270 deg, 1081-beam UTM-30LX mounted sideways
  utm.angle_min = -0.75 * std::numbers::pi;
  utm.angle_increment = 1.5 * std::numbers::pi / 1080.0;
  utm.ranges.assign(1081, 3.0f);
  utm.sensor_pose = {0.1, -0.05, 0.5};

  const Pose2 odom{1.0, 2.0, 0.3};
  CarmenLog log;
  log.scans.push_back(make_scan_record(sick, 12.5, odom));
  log.scans.push_back(make_scan_record(utm, 12.5, odom));
  EXPECT_EQ(log.scans[0].message, LaserMessage::kFlaser);
  EXPECT_EQ(log.scans[1].message, LaserMessage::kRobotLaser1);
  set_front_laser_params(log.params, sick);

  test::TempDir dir;
  write_carmen(dir.file("sim.log"), log);
  const CarmenLog back = read_carmen(dir.file("sim.log"));
  ASSERT_EQ(back.scans.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    const LaserScan& want = i == 0 ? sick : utm;
    const LaserScan& got = back.scans[i].scan;
    EXPECT_EQ(got.ranges, want.ranges);
    EXPECT_EQ(back.scans[i].stamp, 12.5);
    EXPECT_NEAR(got.angle_min, want.angle_min, 1e-12);
    EXPECT_NEAR(got.angle_increment, want.angle_increment, 1e-12);
    EXPECT_EQ(got.range_max, want.range_max);
    EXPECT_NEAR(got.sensor_pose.x, want.sensor_pose.x, 1e-12);
    EXPECT_NEAR(got.sensor_pose.y, want.sensor_pose.y, 1e-12);
    EXPECT_NEAR(got.sensor_pose.theta, want.sensor_pose.theta, 1e-12);
    EXPECT_TRUE(same_pose(back.scans[i].odom_pose, odom));
  }
}

TEST(CarmenWrite, RejectsWhatTheFormatCannotHold) {
  CarmenScan s = laser(LaserMessage::kFlaser, 10, 1.0);
  s.scan.angle_increment *= 1.01;  // not the SICK layout: FLASER would change the angles
  EXPECT_THROW((void)format_scan(s), std::invalid_argument);
  s.message = LaserMessage::kRobotLaser1;
  EXPECT_NO_THROW((void)format_scan(s));
  s.host = "two words";
  EXPECT_THROW((void)format_scan(s), std::invalid_argument);
  EXPECT_THROW((void)format_param("name", ""), std::invalid_argument);
  EXPECT_EQ(format_param("a", "b"), "PARAM a b nohost 0");
  OdomRecord o{{1, 2, 0.5}, 0, 0, 0, 2.25, "h", 2.5};
  EXPECT_EQ(format_odom(o), "ODOM 1 2 0.5 0 0 0 2.25 h 2.5");
}

}  // namespace
}  // namespace pgmcl::io
