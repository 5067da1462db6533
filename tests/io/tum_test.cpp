// TUM trajectories: exact round trip, evo-compatible text, quaternion tolerance, bad lines.

#include "pgmcl/io/tum.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "io_test_util.hpp"
#include "pgmcl/io/errors.hpp"

namespace pgmcl::io {
namespace {

TEST(Tum, RoundTripPlainAndGzip) {
  Trajectory t;
  const double thetas[] = {
      0.0, 1.0 / 3.0, -2.5, std::numbers::pi, -std::numbers::pi + 1e-9, std::numbers::pi / 2};
  double stamp = 976052905.167303;
  for (const double th : thetas) {
    t.push_back({stamp, {1.0 / 7.0 + stamp * 1e-9, -1234.5678901234, th}});
    stamp += 0.0999999;
  }
  test::TempDir dir;
  for (const char* name : {"traj.txt", "traj.txt.gz"}) {
    write_tum(dir.file(name), t);
    const Trajectory back = read_tum(dir.file(name));
    ASSERT_EQ(back.size(), t.size()) << name;
    for (std::size_t i = 0; i < t.size(); ++i) {
      EXPECT_EQ(back[i].stamp, t[i].stamp) << i;  // full double precision
      EXPECT_EQ(back[i].pose.x, t[i].pose.x) << i;
      EXPECT_EQ(back[i].pose.y, t[i].pose.y) << i;
      EXPECT_NEAR(wrap_angle(back[i].pose.theta - t[i].pose.theta), 0.0, 1e-15) << i;
    }
  }
}

TEST(Tum, TextIsWhatEvoReads) {
  EXPECT_EQ(format_tum({1.5, {1.0, 2.0, 0.0}}), "1.5 1 2 0 0 0 0 1");
  EXPECT_EQ(format_tum({976052905.167303, {0.25, -3.0, std::numbers::pi}}),
            "976052905.167303 0.25 -3 0 0 0 1 6.123233995736766e-17");
  EXPECT_THROW((void)format_tum({std::nan(""), {}}), std::invalid_argument);
}

TEST(Tum, QuaternionsNeedNotBeUnitOrPositive) {
  const double yaw = 2.0;
  const double qz = std::sin(yaw / 2), qw = std::cos(yaw / 2);
  const std::string text = "# comment\n\n1 0 0 0 0 0 " + std::to_string(3 * qz) + " " +
                           std::to_string(3 * qw) + "\n2 0 0 5 0 0 " + std::to_string(-qz) + " " +
                           std::to_string(-qw) + "\r\n";
  const Trajectory t = parse_tum(text, "q.txt");
  ASSERT_EQ(t.size(), 2u);
  EXPECT_NEAR(t[0].pose.theta, yaw, 1e-6);  // std::to_string keeps 6 decimals
  EXPECT_NEAR(t[1].pose.theta, yaw, 1e-6);
  // Yaw of a rotation with roll and pitch: the Z-Y-X Euler yaw (oracle: the rotation
  // matrix's first column, atan2(R10, R00)).
  const double r = 0.3, p = -0.2, y = 1.1;
  const double cr = std::cos(r / 2), sr = std::sin(r / 2), cp = std::cos(p / 2),
               sp = std::sin(p / 2), cy = std::cos(y / 2), sy = std::sin(y / 2);
  const double qx = sr * cp * cy - cr * sp * sy, qy = cr * sp * cy + sr * cp * sy,
               qzz = cr * cp * sy - sr * sp * cy, qww = cr * cp * cy + sr * sp * sy;
  EXPECT_NEAR(yaw_from_quaternion(qx, qy, qzz, qww), y, 1e-12);
  EXPECT_NEAR(yaw_from_quaternion(7 * qx, 7 * qy, 7 * qzz, 7 * qww), y, 1e-12);
}

TEST(Tum, BadLinesNameFileLineAndField) {
  struct Case {
    const char* line2;
    const char* field;
    const char* message;
  };
  for (const Case& c : {Case{"2 0 0 0 0 0 nan 1", "qz", "not finite: 'nan'"},
                        Case{"2 0 x 0 0 0 0 1", "ty", "not a number: 'x'"},
                        Case{"2 0 0 0 0 0 0", "qw", "missing (expected 8 fields, found 7)"},
                        Case{"2 0 0 0 0 0 0 1 9", "qw", "expected 8 fields, found 9"},
                        Case{"2 0 0 0 0 0 0 0", "quaternion", ""}}) {
    const std::string text = "1 0 0 0 0 0 0 1\n" + std::string(c.line2) + "\n";
    try {
      (void)parse_tum(text, "est.txt");
      FAIL() << c.line2;
    } catch (const FormatError& e) {
      EXPECT_EQ(e.line(), 2u) << c.line2;
      EXPECT_EQ(e.field(), c.field) << c.line2;
      if (*c.message != '\0') {
        EXPECT_EQ(e.message(), c.message);
      }
      EXPECT_EQ(std::string(e.what()).rfind(std::string("est.txt:2: ") + c.field, 0), 0u);
    }
  }
  EXPECT_THROW((void)read_tum(test::data_path("no-such.tum")), IoError);
}

}  // namespace
}  // namespace pgmcl::io
