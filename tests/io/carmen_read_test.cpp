// Reading CARMEN logs: the bundled Intel log, beam-angle conventions, every message type.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "io_test_util.hpp"
#include "pgmcl/io/carmen.hpp"
#include "pgmcl/io/errors.hpp"
#include "pgmcl/io/line_io.hpp"

namespace pgmcl::io {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

std::string intel_path() {
  return test::data_path("logs/intel-corrected.log.gz");
}

// Expected figures counted independently from the file (python over the text).
TEST(CarmenIntel, CountsStampsAndPoses) {
  const CarmenLog log = read_carmen(intel_path());
  const ParseReport& r = log.report;
  EXPECT_EQ(r.lines, 16365u);
  EXPECT_EQ(r.records.at("FLASER"), 910u);
  EXPECT_EQ(r.records.at("ODOM"), 14541u);
  EXPECT_EQ(r.records.at("PARAM"), 2u);
  EXPECT_EQ(r.skipped.at("NEFF"), 910u);
  EXPECT_EQ(r.malformed, 0u);
  EXPECT_EQ(r.invalid_beams, 0u);
  // The corrected log re-anchors ODOM after every scan with lines stamped 0.
  EXPECT_EQ(r.backwards_by_type.at("ODOM"), 1498u);
  EXPECT_EQ(r.backwards_by_type.at("FLASER"), 4u);
  EXPECT_EQ(r.backwards, 1502u);

  ASSERT_EQ(log.scans.size(), 910u);
  for (const CarmenScan& s : log.scans) {
    ASSERT_EQ(s.message, LaserMessage::kFlaser);
    ASSERT_EQ(s.scan.size(), 180u);
  }
  const CarmenScan& first = log.scans.front();
  const CarmenScan& last = log.scans.back();
  EXPECT_EQ(first.line, 175u);
  EXPECT_EQ(first.stamp, 32.9068);
  EXPECT_EQ(first.scan.ranges[0], 1.09f);
  EXPECT_EQ(last.line, 16316u);
  EXPECT_EQ(last.stamp, 2683.77);
  EXPECT_TRUE(test::same_pose(last.laser_pose, {-0.596494, -0.101202, 0.0119294}));
  EXPECT_EQ(first.host, "pippo");
  EXPECT_EQ(log.params.at("robot_frontlaser_offset"), "0.0");
  // No PARAM for the maximum: the largest reading (81.83 m, 4172 beams) means "no return".
  EXPECT_DOUBLE_EQ(first.scan.range_max, static_cast<double>(81.83f));
  EXPECT_TRUE(test::same_pose(first.scan.sensor_pose, {0.0, 0.0, 0.0}));

  // SICK convention for 180 beams: -90 deg .. +89 deg in 1 deg steps.
  EXPECT_NEAR(first.scan.beam_angle(0), -90.0 * kDeg, 1e-12);
  EXPECT_NEAR(first.scan.beam_angle(90), 0.0, 1e-12);
  EXPECT_NEAR(first.scan.beam_angle(179), 89.0 * kDeg, 1e-12);

  const Trajectory truth = scan_truth(log);
  ASSERT_EQ(truth.size(), 910u);
  EXPECT_TRUE(test::same_pose(truth.back().pose, last.laser_pose));
}

TEST(CarmenIntel, GzipAndPlainReadIdentically) {
  test::TempDir dir;
  const std::string plain = dir.file("intel.log");
  {
    LineReader in(intel_path());
    LineWriter out(plain);
    std::string_view line;
    while (in.next(line)) out.write_line(line);
    out.close();
  }
  const CarmenLog a = read_carmen(intel_path());
  const CarmenLog b = read_carmen(plain);
  EXPECT_EQ(a.report.lines, b.report.lines);
  EXPECT_EQ(a.report.records, b.report.records);
  EXPECT_EQ(a.report.backwards, b.report.backwards);
  ASSERT_EQ(a.scans.size(), b.scans.size());
  for (std::size_t i = 0; i < a.scans.size(); ++i) {
    ASSERT_EQ(a.scans[i].scan.ranges, b.scans[i].scan.ranges) << i;
    ASSERT_EQ(a.scans[i].stamp, b.scans[i].stamp) << i;
    ASSERT_TRUE(test::same_pose(a.scans[i].laser_pose, b.scans[i].laser_pose)) << i;
    ASSERT_TRUE(test::same_pose(a.scans[i].odom_pose, b.scans[i].odom_pose)) << i;
  }
  ASSERT_EQ(a.odometry.size(), b.odometry.size());
  for (std::size_t i = 0; i < a.odometry.size(); ++i) {
    ASSERT_TRUE(test::same_pose(a.odometry[i].pose, b.odometry[i].pose)) << i;
    ASSERT_EQ(a.odometry[i].stamp, b.odometry[i].stamp) << i;
  }
}

// A FLASER line with n beams 0.5, 1.0, ... and poses (1, 2, 0.5) / (3, 4, -0.5).
std::string flaser_line(std::size_t n, const char* type = "FLASER") {
  // Appending piecewise (not a + b + c) also dodges GCC 12's false -Wrestrict on operator+.
  std::string s = type;
  s += ' ';
  s += std::to_string(n);
  for (std::size_t i = 0; i < n; ++i) {
    s += ' ';
    s += std::to_string(0.5 * static_cast<double>(i + 1));
  }
  s += " 1 2 0.5 3 4 -0.5 10.25 host 10.5\n";
  return s;
}

TEST(CarmenBeams, SickConventionForOddAndEvenCounts) {
  struct Case {
    std::size_t n;
    double first_deg, step_deg, last_deg;
  };
  for (const Case& c : {Case{181, -90, 1.0, 90}, Case{361, -90, 0.5, 90}, Case{360, -90, 0.5, 89.5},
                        Case{180, -90, 1.0, 89}, Case{2, -90, 90, 0}}) {
    const CarmenLog log = parse_carmen(flaser_line(c.n), "synthetic");
    ASSERT_EQ(log.scans.size(), 1u) << c.n;
    const LaserScan& s = log.scans[0].scan;
    ASSERT_EQ(s.size(), c.n);
    EXPECT_NEAR(s.beam_angle(0), c.first_deg * kDeg, 1e-12) << c.n;
    EXPECT_NEAR(s.angle_increment, c.step_deg * kDeg, 1e-12) << c.n;
    EXPECT_NEAR(s.beam_angle(c.n - 1), c.last_deg * kDeg, 1e-12) << c.n;
    EXPECT_TRUE(matches_sick_layout(s));
  }
}

TEST(CarmenMessages, FlaserFieldsAndParams) {
  const std::string text =
      "PARAM robot_front_laser_max 40 nohost 0\n"
      "PARAM robot_frontlaser_offset 0.25 1071078718.46 merci 1071078718.46\n"
      "PARAM robot_rearlaser_offset 0.1 nohost 0\n" +
      flaser_line(3) + flaser_line(4, "RLASER");
  CarmenReadOptions opt;
  opt.range_min = 0.02;
  const CarmenLog log = parse_carmen(text, "synthetic", opt);
  ASSERT_EQ(log.scans.size(), 2u);
  const CarmenScan& f = log.scans[0];
  EXPECT_EQ(f.scan.ranges, (std::vector<float>{0.5f, 1.0f, 1.5f}));
  EXPECT_TRUE(test::same_pose(f.laser_pose, {1, 2, 0.5}));
  EXPECT_TRUE(test::same_pose(f.odom_pose, {3, 4, -0.5}));
  EXPECT_EQ(f.stamp, 10.25);
  EXPECT_EQ(f.logger_stamp, 10.5);
  EXPECT_EQ(f.host, "host");
  EXPECT_EQ(f.scan.range_max, 40.0);
  EXPECT_EQ(f.scan.range_min, 0.02);
  EXPECT_TRUE(test::same_pose(f.scan.sensor_pose, {0.25, 0.0, 0.0}));
  const CarmenScan& r = log.scans[1];
  EXPECT_EQ(r.message, LaserMessage::kRlaser);
  EXPECT_EQ(r.scan.range_max, 2.0);  // no rear PARAM: the largest rear reading
  EXPECT_TRUE(test::same_pose(r.scan.sensor_pose, {-0.1, 0.0, std::numbers::pi}));
  // Robot pose from the laser pose undoes the mounting.
  const Trajectory truth = scan_truth(log);
  ASSERT_EQ(truth.size(), 1u);
  EXPECT_NEAR(truth[0].pose.x, 1 - 0.25 * std::cos(0.5), 1e-12);
  EXPECT_NEAR(truth[0].pose.y, 2 - 0.25 * std::sin(0.5), 1e-12);
}

// Without PARAM robot_frontlaser_offset, a laser logged 25 cm ahead of the odometry pose on
// every scan is read as mounted there; the corrected benchmark logs, whose odometry fields
// are re-anchored, keep a zero mounting.
TEST(CarmenMessages, FlaserMountingFromTheLoggedPosesWithoutParam) {
  auto line = [](const Pose2& odom, const Pose2& laser, double t) {
    char buf[256];
    std::snprintf(buf, sizeof buf, "FLASER 3 1 1 1 %.9f %.9f %.9f %.9f %.9f %.9f %.3f host %.3f\n",
                  laser.x, laser.y, laser.theta, odom.x, odom.y, odom.theta, t, t);
    return std::string(buf);
  };
  const Pose2 mount{0.25, 0.0, 0.0};
  std::string text;
  for (int i = 0; i < 5; ++i) {
    const Pose2 odom{1.0 + 0.3 * i, -2.0 + 0.1 * i * i, 0.4 * i - 1.0};
    text += line(odom, odom.compose(mount), i);
  }
  const CarmenLog log = parse_carmen(text, "synthetic");
  ASSERT_TRUE(log.report.derived_front_mount);
  for (const CarmenScan& s : log.scans) {
    EXPECT_NEAR(s.scan.sensor_pose.x, 0.25, 1e-6);
    EXPECT_NEAR(s.scan.sensor_pose.y, 0.0, 1e-6);
    EXPECT_NEAR(s.scan.sensor_pose.theta, 0.0, 1e-6);
  }
  // Not constant (the mounting changes on the third scan): no mounting derived.
  text += line({5, 5, 0}, Pose2{5, 5, 0}.compose({0.1, 0.0, 0.0}), 6);
  const CarmenLog mixed = parse_carmen(text, "synthetic");
  EXPECT_FALSE(mixed.report.derived_front_mount);
  EXPECT_TRUE(test::same_pose(mixed.scans[0].scan.sensor_pose, {}));
  EXPECT_FALSE(read_carmen(intel_path()).report.derived_front_mount);
}

TEST(CarmenMessages, RobotLaserRawLaserTruePos) {
  const std::string text =
      "ROBOTLASER1 0 -2.35619 4.71239 0.785398 30 0.01 0 7 1 2 3 4 5 6 7 2 0.5 0.25"
      " 1.1 2 0 1 2 0 0.3 0.1 0.4 0.2 0.6 5.5 robo 5.6\n"
      "RAWLASER2 5 -1.5 3 1.5 8 0.02 1 3 7 nan -1 0 6.5 raw 6.6\n"
      "TRUEPOS 1 2 3.5 4 5 -0.25 7.5 sim 7.75\n"
      "ODOM 1 2 0.1 0.3 0.2 0 8 h 8.1\n";
  const CarmenLog log = parse_carmen(text, "synthetic");
  ASSERT_EQ(log.scans.size(), 2u);
  EXPECT_EQ(log.report.malformed, 0u);
  const CarmenScan& rl = log.scans[0];
  EXPECT_EQ(rl.message, LaserMessage::kRobotLaser1);
  EXPECT_EQ(rl.scan.angle_min, -2.35619);
  EXPECT_EQ(rl.scan.angle_increment, 0.785398);
  EXPECT_EQ(rl.config.field_of_view, 4.71239);
  EXPECT_EQ(rl.scan.range_max, 30.0);
  EXPECT_EQ(rl.config.accuracy, 0.01);
  EXPECT_EQ(rl.scan.size(), 7u);
  EXPECT_EQ(rl.remissions, (std::vector<float>{0.5f, 0.25f}));
  EXPECT_TRUE(test::same_pose(rl.laser_pose, {1.1, 2, 0}));
  EXPECT_TRUE(test::same_pose(rl.odom_pose, {1, 2, 0}));
  EXPECT_EQ(rl.extras.tv, 0.3);
  EXPECT_EQ(rl.extras.turn_axis, 0.6);
  EXPECT_EQ(rl.stamp, 5.5);
  // Mounting = robot_pose^-1 * laser_pose: 0.1 m forward.
  EXPECT_NEAR(rl.scan.sensor_pose.x, 0.1, 1e-12);
  EXPECT_NEAR(rl.scan.sensor_pose.y, 0.0, 1e-12);
  EXPECT_NEAR(rl.scan.sensor_pose.theta, 0.0, 1e-12);

  const CarmenScan& raw = log.scans[1];
  EXPECT_EQ(raw.message, LaserMessage::kRawLaser2);
  EXPECT_FALSE(raw.has_poses);
  EXPECT_EQ(raw.config.laser_type, 5);
  EXPECT_EQ(raw.config.remission_mode, 1);
  EXPECT_EQ(raw.scan.range_max, 8.0);
  EXPECT_TRUE(raw.remissions.empty());
  ASSERT_EQ(raw.scan.size(), 3u);
  EXPECT_TRUE(std::isnan(raw.scan.ranges[1]));
  EXPECT_EQ(log.report.invalid_beams, 2u);  // nan and -1 are invalid beams, not bad lines

  ASSERT_EQ(log.truepos.size(), 1u);
  EXPECT_NEAR(log.truepos[0].true_pose.theta, 3.5 - 2 * std::numbers::pi, 1e-15);  // wrapped
  EXPECT_TRUE(test::same_pose(log.truepos[0].odom_pose, {4, 5, -0.25}));
  EXPECT_EQ(log.truepos[0].logger_stamp, 7.75);
  ASSERT_EQ(log.odometry.size(), 1u);
  EXPECT_EQ(log.odometry[0].tv, 0.3);
  EXPECT_EQ(log.odometry[0].stamp, 8.0);
}

TEST(CarmenMessages, MissingFileIsIoError) {
  EXPECT_THROW((void)read_carmen(test::data_path("logs/no-such-file.log")), IoError);
}

}  // namespace
}  // namespace pgmcl::io
