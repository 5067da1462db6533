#include "pgmcl/sims/sensor_profile.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace pgmcl::sims {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

TEST(SensorProfile, Utm30lxFollowsTable1) {
  const auto p = utm30lx();
  EXPECT_EQ(p.beam_count, 1081);
  EXPECT_NEAR(p.angle_increment, 0.25 * kDeg, 1e-15);
  EXPECT_NEAR(p.angle_min, -135.0 * kDeg, 1e-12);
  EXPECT_NEAR(p.angle_max(), 135.0 * kDeg, 1e-12);
  EXPECT_NEAR(p.angle_max() - p.angle_min, 270.0 * kDeg, 1e-12);
  EXPECT_DOUBLE_EQ(p.range_min, 0.1);
  EXPECT_DOUBLE_EQ(p.range_max, 30.0);
  EXPECT_DOUBLE_EQ(p.scan_time, 0.025);
  EXPECT_DOUBLE_EQ(p.scan_rate, 40.0);
  EXPECT_NO_THROW(p.validate());
}

TEST(SensorProfile, SickProfilesSpan180DegreesInclusive) {
  const auto one = sick_lms_1deg();
  EXPECT_EQ(one.beam_count, 181);
  EXPECT_NEAR(one.angle_min, -90 * kDeg, 1e-12);
  EXPECT_NEAR(one.angle_max(), 90 * kDeg, 1e-12);
  const auto half = sick_lms_half_deg();
  EXPECT_EQ(half.beam_count, 361);
  EXPECT_NEAR(half.angle_increment, 0.5 * kDeg, 1e-15);
  EXPECT_NEAR(half.angle_max(), 90 * kDeg, 1e-12);
}

TEST(SensorProfile, CarmenConventionForEvenAndOddCounts) {
  const auto c180 = carmen_sick(180);
  EXPECT_NEAR(c180.angle_min, -90 * kDeg, 1e-12);
  EXPECT_NEAR(c180.angle_increment, 1.0 * kDeg, 1e-15);
  EXPECT_NEAR(c180.angle_max(), 89 * kDeg, 1e-12);
  const auto c360 = carmen_sick(360);
  EXPECT_NEAR(c360.angle_increment, 0.5 * kDeg, 1e-15);
  EXPECT_NEAR(c360.angle_max(), 89.5 * kDeg, 1e-12);
  const auto c181 = carmen_sick(181);
  EXPECT_NEAR(c181.angle_increment, 1.0 * kDeg, 1e-15);
  EXPECT_NEAR(c181.angle_max(), 90 * kDeg, 1e-12);
  const auto c361 = carmen_sick(361);
  EXPECT_NEAR(c361.angle_max(), 90 * kDeg, 1e-12);
  EXPECT_THROW((void)carmen_sick(1), std::invalid_argument);
  EXPECT_EQ(sensor_profile_by_name("carmen_sick_360").beam_count, 360);
  EXPECT_EQ(sensor_profile_by_name("sick_lms_half_deg").beam_count, 361);
  EXPECT_THROW((void)sensor_profile_by_name("lms_9000"), std::invalid_argument);
  EXPECT_THROW((void)sensor_profile_by_name("carmen_sick_x1"), std::invalid_argument);
}

TEST(SensorProfile, MakeScanCarriesGeometry) {
  const auto p = utm30lx();
  const Pose2 mount{0.2, 0.0, 0.1};
  const auto s = p.make_scan(mount);
  EXPECT_EQ(s.size(), 1081u);
  EXPECT_DOUBLE_EQ(s.beam_angle(1080), p.angle_max());
  EXPECT_FLOAT_EQ(s.ranges[0], 30.0F);
  EXPECT_DOUBLE_EQ(s.sensor_pose.x, 0.2);
  EXPECT_DOUBLE_EQ(s.range_min, 0.1);
  EXPECT_THROW((void)p.make_scan(std::vector<float>(10, 1.0F)), std::invalid_argument);
  const auto f = p.fan();
  EXPECT_EQ(f.count, 1081);
  EXPECT_DOUBLE_EQ(f.max_range, 30.0);
}

TEST(SensorProfile, ValidationNamesTheField) {
  auto p = utm30lx();
  p.range_max = 0.05;
  try {
    p.validate();
    FAIL() << "expected an exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("range_max"), std::string::npos) << e.what();
  }
  p = utm30lx();
  p.beam_count = 0;
  EXPECT_THROW(p.validate(), std::invalid_argument);
  p = utm30lx();
  p.angle_increment = 1.0;
  EXPECT_THROW(p.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace pgmcl::sims
