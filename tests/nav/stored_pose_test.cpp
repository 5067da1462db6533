// Pose persistence: amcl's six keys, exact round trips, errors naming line and key.
#include "pgmcl/nav/stored_pose.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "temp_files.hpp"

namespace pgmcl::nav {
namespace {

std::string error_of(const std::string& text) {
  try {
    (void)parse_stored_pose(text, "pose.yaml");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(StoredPose, RoundTripIsExact) {
  const StoredPose p{{1.0 / 3.0, -2e-7, 3.0}, 0.0123456789, 1e-300, 0.25};
  const std::string text = format_stored_pose(p);
  EXPECT_NE(text.find("initial_pose_a: 3\n"), std::string::npos) << text;
  const StoredPose q = parse_stored_pose(text, "x");
  EXPECT_EQ(q.pose.x, p.pose.x);
  EXPECT_EQ(q.pose.y, p.pose.y);
  EXPECT_EQ(q.pose.theta, p.pose.theta);
  EXPECT_EQ(q.cov_xx, p.cov_xx);
  EXPECT_EQ(q.cov_yy, p.cov_yy);
  EXPECT_EQ(q.cov_aa, p.cov_aa);
}

TEST(StoredPose, OfTakesTheDiagonal) {
  Eigen::Matrix3d c;
  c << 0.5, 0.1, 0.0, 0.1, 0.7, 0.0, 0.0, 0.0, -1e-18;
  const StoredPose p = StoredPose::of({1, 2, 3}, c);
  EXPECT_EQ(p.cov_xx, 0.5);
  EXPECT_EQ(p.cov_yy, 0.7);
  EXPECT_EQ(p.cov_aa, 0.0);  // round-off below zero clamped
  EXPECT_EQ(p.covariance()(1, 1), 0.7);
  EXPECT_EQ(p.covariance()(0, 1), 0.0);
}

TEST(StoredPose, ErrorsNameLineAndKey) {
  const std::string good = format_stored_pose({{1, 2, 0.5}, 0.1, 0.1, 0.01});
  EXPECT_EQ(error_of(good + "initial_pose_x: 4\n"),
            "pose.yaml:8: initial_pose_x: repeated (first on line 2)");
  EXPECT_EQ(error_of("initial_pose_x: 1\ninitial_pose_y: 2\n"),
            "pose.yaml:2: initial_pose_a: missing");
  EXPECT_EQ(error_of("initial_pose_x: one\n"),
            "pose.yaml:1: initial_pose_x: expected a finite number, got 'one'");
  EXPECT_EQ(error_of("initial_pose_x: nan\n"),
            "pose.yaml:1: initial_pose_x: expected a finite number, got 'nan'");
  EXPECT_EQ(error_of("# c\ninitial_cov_xx: -0.1\n"),
            "pose.yaml:2: initial_cov_xx: a variance must be >= 0");
  EXPECT_NE(error_of("initial_pose_z: 1\n").find("pose.yaml:1: initial_pose_z: unknown key"),
            std::string::npos);
  EXPECT_NE(error_of("just words\n").find("expected 'key: value'"), std::string::npos);
}

TEST(StoredPose, SaveAndLoadAFile) {
  const testkit::TempDir dir("stored_pose");
  const std::string path = (dir.path() / "last_pose.yaml").string();
  EXPECT_FALSE(load_stored_pose(path).has_value());
  const StoredPose p{{4.5, -1.25, -2.0}, 0.04, 0.09, 0.0025};
  save_stored_pose(path, p);
  save_stored_pose(path, p);  // replacing works
  const auto q = load_stored_pose(path);
  ASSERT_TRUE(q);
  EXPECT_EQ(q->pose.x, 4.5);
  EXPECT_EQ(q->cov_aa, 0.0025);
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
  std::ofstream(path) << "initial_pose_x: 1\n";
  EXPECT_THROW((void)load_stored_pose(path), std::invalid_argument);
  EXPECT_THROW(save_stored_pose((dir.path() / "no/such/dir/p.yaml").string(), p),
               std::runtime_error);
}

}  // namespace
}  // namespace pgmcl::nav
