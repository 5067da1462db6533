// Simulator logs as files: the CARMEN log read back gives the same odometry, scans and
// ground truth (FLASER for SICK-layout scans, ROBOTLASER1 for the 270 deg UTM-30LX), and
// the TUM ground truth reads back to the simulator's true poses.

#include "pgmcl/io/sim_log_io.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "io_test_util.hpp"
#include "pgmcl/io/carmen_writer.hpp"
#include "pgmcl/io/tum.hpp"

namespace pgmcl::io {
namespace {

using test::TempDir;

/// A 6 x 4 m walled room at 5 cm, a robot driving a short waypoint path.
maps::OccupancyGrid room() {
  return test::walled_room(120, 80, 0.05, Pose2{-1.0, -1.0, 0.0});
}

sims::SimulationLog simulate(const sims::SensorProfile& sensor, const Pose2& mount) {
  sims::Scenario sc;
  sc.sensor = sensor;
  sc.sensor_mount = mount;
  sc.scan_rate = 5.0;
  sc.duration = 3.0;
  sc.start = {0.0, 0.5, 0.0};
  sc.waypoints.waypoints = {{2.0, 0.5}, {2.5, 1.5}};
  sc.odometry.wheel_radius_bias = 0.02;  // odometry != truth
  return sims::simulate(sc, room());
}

void expect_round_trip(const sims::SimulationLog& log, LaserMessage expected) {
  TempDir dir;
  const std::string path = dir.file("sim.log.gz");
  write_sim_carmen(path, log);
  CarmenReadOptions opt;
  opt.strict = true;
  const CarmenLog back = read_carmen(path, opt);
  ASSERT_EQ(back.scans.size(), log.records.size());
  ASSERT_EQ(back.odometry.size(), log.records.size());
  ASSERT_EQ(back.truepos.size(), log.records.size());
  for (std::size_t k = 0; k < log.records.size(); ++k) {
    SCOPED_TRACE(k);
    const sims::SimulationRecord& r = log.records[k];
    const CarmenScan& s = back.scans[k];
    EXPECT_EQ(s.message, expected);
    EXPECT_EQ(s.stamp, r.stamp);
    ASSERT_EQ(s.scan.ranges, r.scan.ranges);  // shortest exact float text: bit-identical
    EXPECT_NEAR(s.scan.angle_min, r.scan.angle_min, 1e-12);
    EXPECT_NEAR(s.scan.angle_increment, r.scan.angle_increment, 1e-12);
    EXPECT_EQ(s.scan.range_max, r.scan.range_max);
    EXPECT_NEAR(s.scan.sensor_pose.x, r.scan.sensor_pose.x, 1e-12);
    EXPECT_NEAR(s.scan.sensor_pose.y, r.scan.sensor_pose.y, 1e-12);
    EXPECT_NEAR(s.scan.sensor_pose.theta, r.scan.sensor_pose.theta, 1e-12);
    EXPECT_TRUE(test::same_pose(s.odom_pose, r.odometry));
    EXPECT_TRUE(test::same_pose(back.odometry[k].pose, r.odometry));
    EXPECT_EQ(back.odometry[k].stamp, r.stamp);
    EXPECT_TRUE(test::same_pose(back.truepos[k].true_pose, r.truth));
    EXPECT_TRUE(test::same_pose(back.truepos[k].odom_pose, r.odometry));
  }
  // tv, rv: the odometry increment since the previous scan, per second, robot frame.
  for (std::size_t k = 1; k < log.records.size(); ++k) {
    const auto& a = log.records[k - 1];
    const auto& b = log.records[k];
    const Pose2 inc = a.odometry.between(b.odometry);
    EXPECT_NEAR(back.odometry[k].tv, inc.x / (b.stamp - a.stamp), 1e-9);
    EXPECT_NEAR(back.odometry[k].rv, inc.theta / (b.stamp - a.stamp), 1e-9);
  }
}

TEST(SimLogIo, SickScansAreWrittenAsFlaser) {
  const auto log = simulate(sims::carmen_sick(181), Pose2{0.2, 0.0, 0.0});
  expect_round_trip(log, LaserMessage::kFlaser);
}

TEST(SimLogIo, Utm30lxScansAreWrittenAsRobotLaser1) {
  const auto log = simulate(sims::utm30lx(), Pose2{0.15, 0.05, 0.1});
  expect_round_trip(log, LaserMessage::kRobotLaser1);
}

TEST(SimLogIo, MountedSickOffTheAxisNeedsRobotLaser1) {
  // FLASER logs only the forward offset, so a sideways mounting must go to ROBOTLASER1.
  const auto log = simulate(sims::carmen_sick(180), Pose2{0.2, 0.1, 0.0});
  expect_round_trip(log, LaserMessage::kRobotLaser1);
}

TEST(SimLogIo, TruthTumReadsBackToTheTruePoses) {
  TempDir dir;
  const auto log = simulate(sims::utm30lx(), Pose2{});
  write_sim_truth_tum(dir.file("truth.tum"), log);
  const Trajectory t = read_tum(dir.file("truth.tum"));
  ASSERT_EQ(t.size(), log.records.size());
  for (std::size_t k = 0; k < t.size(); ++k) {
    EXPECT_EQ(t[k].stamp, log.records[k].stamp);
    EXPECT_EQ(t[k].pose.x, log.records[k].truth.x);
    EXPECT_EQ(t[k].pose.y, log.records[k].truth.y);
    EXPECT_NEAR(t[k].pose.theta, log.records[k].truth.theta, 1e-12);
  }
  const Trajectory odom = sim_odometry_trajectory(log);
  ASSERT_EQ(odom.size(), log.records.size());
  EXPECT_GT(std::hypot(odom.back().pose.x - t.back().pose.x, odom.back().pose.y - t.back().pose.y),
            0.01);  // the biased odometry drifted away from the truth
}

}  // namespace
}  // namespace pgmcl::io
