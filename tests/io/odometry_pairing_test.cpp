// Pairing scans with odometry interpolated between ODOM messages.

#include "pgmcl/io/odometry_pairing.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "io_test_util.hpp"
#include "pgmcl/io/carmen.hpp"

namespace pgmcl::io {
namespace {

TEST(OdometryPairing, LinearInXYShortestArcInThetaAcrossPi) {
  // theta goes 3.0 -> -3.0: the short way is +0.283 rad through pi, not -6 rad.
  const char* text =
      "ODOM 0 0 3.0 0 0 0 10 h 10\n"
      "FLASER 2 1 1 9 9 0 7 8 0.5 9.5 h 9.5\n"  // before the first ODOM: own odom fields
      "FLASER 2 1 1 0 0 0 0 0 0 10.25 h 10.25\n"
      "FLASER 2 1 1 0 0 0 0 0 0 10.5 h 10.5\n"
      "FLASER 2 1 1 0 0 0 0 0 0 10.75 h 10.75\n"
      "ODOM 1 2 -3.0 0 0 0 11 h 11\n"
      "ODOM 5 5 0 0 0 0 0 h 0\n"  // stamped 0: dropped from the interpolation
      "ODOM 3 2 -2.0 0 0 0 12 h 12\n"
      "FLASER 2 1 1 0 0 0 0 0 0 11.5 h 11.5\n"
      "RAWLASER1 0 -1 2 1 10 0 0 2 1 1 0 13 h 13\n";  // after the span, no pose: unpaired
  const CarmenLog log = parse_carmen(text, "t");
  ASSERT_EQ(log.report.malformed, 0u) << log.report.summary();
  const PairedScans p = pair_odometry(log);
  ASSERT_EQ(p.scans.size(), 6u);
  EXPECT_EQ(p.report.odom_used, 3u);
  EXPECT_EQ(p.report.odom_dropped, 1u);
  EXPECT_EQ(p.report.interpolated, 4u);
  EXPECT_EQ(p.report.scan_fields, 1u);
  EXPECT_EQ(p.report.unpaired, 1u);

  EXPECT_EQ(p.scans[0].source, OdomSource::kScanFields);
  EXPECT_TRUE(test::same_pose(p.scans[0].odom, {7, 8, 0.5}));
  const double arc = 2 * std::numbers::pi - 6.0;
  for (int k = 1; k <= 3; ++k) {
    const double a = 0.25 * k;
    const Pose2& o = p.scans[static_cast<std::size_t>(k)].odom;
    EXPECT_EQ(p.scans[static_cast<std::size_t>(k)].source, OdomSource::kInterpolated);
    EXPECT_NEAR(o.x, a, 1e-12);
    EXPECT_NEAR(o.y, 2 * a, 1e-12);
    EXPECT_NEAR(std::abs(wrap_angle(o.theta - (3.0 + a * arc))), 0.0, 1e-12) << k;
    EXPECT_GT(std::abs(o.theta), 3.0);  // never swung through 0
  }
  EXPECT_NEAR(p.scans[2].odom.theta, std::numbers::pi - 0.0, 0.142);
  const Pose2& last = p.scans[4].odom;  // halfway from (1,2,-3) to (3,2,-2)
  EXPECT_NEAR(last.x, 2.0, 1e-12);
  EXPECT_NEAR(last.y, 2.0, 1e-12);
  EXPECT_NEAR(last.theta, -2.5, 1e-12);
  EXPECT_EQ(p.scans[5].source, OdomSource::kNone);
}

TEST(OdometryPairing, MaxGapTurnsLongGapsIntoFallbacks) {
  const char* text =
      "ODOM 0 0 0 0 0 0 0 h 0\n"
      "FLASER 1 1 0 0 0 4 4 0 5 h 5\n"
      "ODOM 10 0 0 0 0 0 10 h 10\n";
  const CarmenLog log = parse_carmen(text, "t");
  EXPECT_NEAR(pair_odometry(log).scans[0].odom.x, 5.0, 1e-12);
  PairingOptions opt;
  opt.max_gap = 2.0;
  const PairedScans p = pair_odometry(log, opt);
  EXPECT_EQ(p.scans[0].source, OdomSource::kScanFields);
  EXPECT_EQ(p.scans[0].odom.x, 4.0);
}

TEST(OdometryPairing, IntelScansAllInsideTheOdomSpan) {
  const CarmenLog log = read_carmen(test::data_path("logs/intel-corrected.log.gz"));
  std::size_t dropped = 0;
  const Trajectory odom = monotonic_odometry(log, &dropped);
  EXPECT_TRUE(is_sorted_by_stamp(odom));
  EXPECT_EQ(odom.size() + dropped, 14541u);
  const PairedScans p = pair_odometry(log);
  EXPECT_EQ(p.report.interpolated, 910u);
  EXPECT_EQ(p.report.scan_fields + p.report.unpaired, 0u);
}

}  // namespace
}  // namespace pgmcl::io

namespace pgmcl::io {
namespace {

// Stamps rounded to whole seconds: two ODOM + FLASER pairs share second 10. By time both
// scans would get the group's last odometry (x = 2); by file order each gets its own.
TEST(OdometryPairing, SharedStampsArePairedByFileOrderAndCounted) {
  const char* text =
      "ODOM 1 0 0 0 0 0 10 h 10\n"
      "FLASER 2 1 1 0 0 0 0 0 0 10 h 10\n"
      "ODOM 2 0 0 0 0 0 10 h 10\n"
      "FLASER 2 1 1 0 0 0 0 0 0 10 h 10\n"
      "ODOM 3 0 0 0 0 0 11 h 11\n"
      "ODOM 4 0 0 0 0 0 12 h 12\n"
      "FLASER 2 1 1 0 0 0 0 0 0 12 h 12\n";  // alone in its second, but the log is coarse
  const CarmenLog log = parse_carmen(text, "t");
  ASSERT_EQ(log.report.malformed, 0u) << log.report.summary();
  const PairedScans p = pair_odometry(log);
  ASSERT_EQ(p.scans.size(), 3u);
  EXPECT_EQ(p.scans[0].odom.x, 1.0);
  EXPECT_EQ(p.scans[1].odom.x, 2.0);
  EXPECT_EQ(p.scans[2].odom.x, 4.0);
  EXPECT_EQ(p.report.shared_stamps, 2u);
  EXPECT_EQ(p.report.first_shared_line, 2u);
  EXPECT_EQ(p.report.by_file_order, 3u);
  EXPECT_EQ(p.report.odom_repeated_stamps, 1u);
  EXPECT_EQ(p.report.first_repeated_odom_line, 3u);
}

// Distinct stamps keep the interpolation (and nothing is reported).
TEST(OdometryPairing, DistinctStampsAreInterpolated) {
  const char* text =
      "ODOM 0 0 0 0 0 0 10 h 10\n"
      "FLASER 2 1 1 0 0 0 0 0 0 10.5 h 10.5\n"
      "ODOM 2 0 0 0 0 0 11 h 11\n";
  const PairedScans p = pair_odometry(parse_carmen(text, "t"));
  ASSERT_EQ(p.scans.size(), 1u);
  EXPECT_DOUBLE_EQ(p.scans[0].odom.x, 1.0);
  EXPECT_EQ(p.report.shared_stamps, 0u);
  EXPECT_EQ(p.report.by_file_order, 0u);
  EXPECT_EQ(p.report.odom_repeated_stamps, 0u);
}

}  // namespace
}  // namespace pgmcl::io
