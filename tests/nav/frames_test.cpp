// nav/frames.hpp against hand-computed frames: planar poses, laser mounts (upside down,
// reversed scans), map->odom, ROS covariance layout.
#include "pgmcl/nav/frames.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace pgmcl::nav {
namespace {

constexpr double kPi = std::numbers::pi;

Eigen::Isometry3d transform(double x, double y, double z, const Eigen::Matrix3d& r) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Eigen::Vector3d(x, y, z);
  t.linear() = r;
  return t;
}
Eigen::Matrix3d rot_z(double a) {
  return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).matrix();
}
Eigen::Matrix3d rot_x(double a) {
  return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitX()).matrix();
}
Eigen::Matrix3d rot_y(double a) {
  return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitY()).matrix();
}

TEST(Frames, PlanarTakesXYAndTheHeadingOfTheXAxis) {
  const Pose2 p = planar(transform(1.5, -2.0, 0.7, rot_z(0.4)));
  EXPECT_DOUBLE_EQ(p.x, 1.5);
  EXPECT_DOUBLE_EQ(p.y, -2.0);
  EXPECT_NEAR(p.theta, 0.4, 1e-15);
  // A small pitch does not change the heading of the x axis's projection.
  EXPECT_NEAR(planar(transform(0, 0, 0, rot_z(-2.0) * rot_y(0.05))).theta, -2.0, 1e-12);
  const Pose2 back = planar(to_isometry({3.0, 4.0, -1.2}));
  EXPECT_DOUBLE_EQ(back.x, 3.0);
  EXPECT_DOUBLE_EQ(back.y, 4.0);
  EXPECT_NEAR(back.theta, -1.2, 1e-15);
}

TEST(Frames, SensorMountUprightAndUpsideDown) {
  const SensorMount up = sensor_mount(transform(0.2, 0.1, 0.3, rot_z(0.5)));
  EXPECT_FALSE(up.upside_down);
  EXPECT_DOUBLE_EQ(up.pose.x, 0.2);
  EXPECT_DOUBLE_EQ(up.pose.y, 0.1);
  EXPECT_NEAR(up.pose.theta, 0.5, 1e-15);
  // Rolled by pi: x axis still at yaw 0.5, z axis down.
  const SensorMount rolled = sensor_mount(transform(0.2, 0.1, 0.3, rot_z(0.5) * rot_x(kPi)));
  EXPECT_TRUE(rolled.upside_down);
  EXPECT_NEAR(rolled.pose.theta, 0.5, 1e-12);
  // Pitched by pi: x axis reversed, yaw 0.5 + pi.
  const SensorMount pitched = sensor_mount(transform(0, 0, 0, rot_z(0.5) * rot_y(kPi)));
  EXPECT_TRUE(pitched.upside_down);
  EXPECT_NEAR(wrap_angle(pitched.pose.theta - (0.5 + kPi)), 0.0, 1e-12);
}

TEST(Frames, SensorMountRefusesATiltedScanPlane) {
  EXPECT_NO_THROW((void)sensor_mount(transform(0, 0, 0, rot_y(0.09))));
  try {
    (void)sensor_mount(transform(0, 0, 0, rot_y(0.3)));
    FAIL() << "a scan plane tilted 0.3 rad was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("tilted 0.3"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW((void)sensor_mount(transform(0, 0, 0, rot_y(0.3)), 0.35));
  Eigen::Isometry3d bad = Eigen::Isometry3d::Identity();
  bad.translation().x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW((void)sensor_mount(bad), std::invalid_argument);
}

// Every beam's endpoint in the base frame, once through the full 3D transform (the
// oracle) and once through the engine's planar LaserScan (sensor_pose ∘ polar point).
TEST(Frames, ScanEndpointsMatchThe3DTransformForAnyMountAndOrder) {
  const std::vector<Eigen::Matrix3d> rotations = {rot_z(0.3), rot_z(-2.5) * rot_x(kPi),
                                                  rot_z(1.0) * rot_y(kPi), rot_z(kPi) * rot_x(kPi)};
  const std::vector<std::vector<double>> layouts = {
      {-2.0, 0.01}, {2.0, -0.01}, {0.7, -0.0437}, {-kPi, 2 * kPi / 360}};  // min, increment
  for (const auto& r : rotations) {
    const Eigen::Isometry3d base_T_laser = transform(0.31, -0.12, 0.25, r);
    const SensorMount mount = sensor_mount(base_T_laser);
    for (const auto& l : layouts) {
      std::vector<float> ranges(200);
      for (std::size_t i = 0; i < ranges.size(); ++i)
        ranges[i] = 0.5f + 0.01f * static_cast<float>(i % 37);
      const ScanView view{l[0], l[1], 0.05, 30.0, ranges};
      LaserScan scan;
      to_laser_scan(view, mount, {}, scan);
      for (std::size_t i = 0; i < ranges.size(); ++i) {
        const double a = l[0] + static_cast<double>(i) * l[1];
        const Eigen::Vector3d oracle =
            base_T_laser * Eigen::Vector3d(ranges[i] * std::cos(a), ranges[i] * std::sin(a), 0);
        double bx = 0, by = 0;
        const double b = scan.beam_angle(i);
        scan.sensor_pose.transform_point(ranges[i] * std::cos(b), ranges[i] * std::sin(b), bx, by);
        ASSERT_NEAR(bx, oracle.x(), 1e-9) << "beam " << i;
        ASSERT_NEAR(by, oracle.y(), 1e-9) << "beam " << i;
      }
    }
  }
}

TEST(Frames, ScanConversionKeepsInvalidReadingsAndAppliesRangeLimits) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const std::vector<float> ranges = {1.0f, nan, inf, -inf, 0.01f};
  LaserScan s;
  to_laser_scan({-1.0, 0.5, 0.02, 20.0, ranges}, {}, {}, s);
  ASSERT_EQ(s.ranges.size(), 5u);
  EXPECT_TRUE(std::isnan(s.ranges[1]));
  EXPECT_EQ(s.ranges[2], inf);
  EXPECT_EQ(s.ranges[3], -inf);
  EXPECT_DOUBLE_EQ(s.range_min, 0.02);
  EXPECT_DOUBLE_EQ(s.range_max, 20.0);
  to_laser_scan({-1.0, 0.5, 0.02, 20.0, ranges}, {}, {0.2, 8.0}, s);
  EXPECT_DOUBLE_EQ(s.range_min, 0.2);
  EXPECT_DOUBLE_EQ(s.range_max, 8.0);
  EXPECT_THROW(to_laser_scan({nan, 0.5, 0.02, 20.0, ranges}, {}, {}, s), std::invalid_argument);
  EXPECT_THROW(to_laser_scan({0.0, inf, 0.02, 20.0, ranges}, {}, {}, s), std::invalid_argument);
}

TEST(Frames, MapToOdomByHand) {
  // map_T_base = (2, 1, 90 deg), odom_T_base = (1, 0, 0): base is 1 m ahead of odom's
  // origin, so odom's origin is 1 m behind the base: (2, 1) - 1 m along +y = (2, 0).
  const Pose2 c = map_to_odom({2.0, 1.0, kPi / 2}, {1.0, 0.0, 0.0});
  EXPECT_NEAR(c.x, 2.0, 1e-15);
  EXPECT_NEAR(c.y, 0.0, 1e-15);
  EXPECT_NEAR(c.theta, kPi / 2, 1e-15);
  const Pose2 odom{-3.2, 7.5, 2.9}, est{10.0, -4.0, -0.3};
  const Pose2 back = map_to_odom(est, odom).compose(odom);
  EXPECT_NEAR(back.x, est.x, 1e-12);
  EXPECT_NEAR(back.y, est.y, 1e-12);
  EXPECT_NEAR(back.theta, est.theta, 1e-12);
}

TEST(Frames, RosCovarianceLayout) {
  Eigen::Matrix3d c;
  c << 1.0, 0.1, 0.2, 0.1, 2.0, 0.3, 0.2, 0.3, 3.0;
  const RosCovariance r = to_ros_covariance(c);
  for (std::size_t i = 0; i < 36; ++i) {
    const double expected = i == 0    ? 1.0
                            : i == 1  ? 0.1
                            : i == 5  ? 0.2
                            : i == 6  ? 0.1
                            : i == 7  ? 2.0
                            : i == 11 ? 0.3
                            : i == 30 ? 0.2
                            : i == 31 ? 0.3
                            : i == 35 ? 3.0
                                      : 0.0;
    EXPECT_EQ(r[i], expected) << "index " << i;
  }
  EXPECT_EQ(from_ros_covariance(r), c);
}

}  // namespace
}  // namespace pgmcl::nav
