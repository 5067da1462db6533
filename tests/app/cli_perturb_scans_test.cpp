// `pgmcl perturb` scan conditions: thinning, laser offset, beam dropout.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "cli_test_util.hpp"
#include "perturb_test_util.hpp"

namespace pgmcl::perturb_test {
namespace {

RunResult perturb(const TempDir& dir, const std::string& noise, const std::string& extra) {
  return run_perturb(dir, "--odom-noise " + noise + " --seed 4 " + extra);
}

/// Brute-force oracle of the thinning rules over the input poses (stamps 1.0 + 0.5 k).
std::vector<double> expected_stamps(const std::vector<Pose2>& poses, double gap, double travel,
                                    double turn) {
  std::vector<double> kept;
  std::size_t last = 0;
  for (std::size_t k = 0; k < poses.size(); ++k) {
    const double stamp = 1.0 + 0.5 * static_cast<double>(k);
    if (!kept.empty()) {
      const Pose2 d = poses[last].between(poses[k]);
      if (stamp - kept.back() < gap) continue;
      if (std::hypot(d.x, d.y) < travel && std::abs(d.theta) < turn) continue;
    }
    kept.push_back(stamp);
    last = k;
  }
  return kept;
}

/// Checks that the output holds exactly the scans stamped `stamps`, each with its own ranges,
/// its truth and (zero noise) the true increments between kept scans.
void expect_kept(const Output& o, const std::vector<double>& stamps,
                 const std::vector<Pose2>& poses, const io::CarmenLog& in) {
  ASSERT_EQ(o.truth.size(), stamps.size());
  ASSERT_EQ(o.raw.scans.size(), stamps.size());
  ASSERT_EQ(o.raw.odometry.size(), stamps.size());
  for (std::size_t i = 0; i < stamps.size(); ++i) {
    const auto k = static_cast<std::size_t>(std::lround((stamps[i] - 1.0) / 0.5));
    EXPECT_EQ(o.truth[i].stamp, stamps[i]) << i;
    EXPECT_EQ(o.raw.scans[i].stamp, stamps[i]) << i;
    EXPECT_EQ(o.raw.scans[i].scan.ranges, in.scans[k].scan.ranges) << i;
    EXPECT_NEAR(o.truth[i].pose.x, poses[k].x, 1e-12) << i;
    if (i == 0) continue;
    const std::size_t kp = static_cast<std::size_t>(std::lround((stamps[i - 1] - 1.0) / 0.5));
    const Pose2 t = poses[kp].between(poses[k]);
    const Pose2 d = o.raw.odometry[i - 1].pose.between(o.raw.odometry[i].pose);
    EXPECT_NEAR(d.x, t.x, 1e-9) << i;
    EXPECT_NEAR(d.y, t.y, 1e-9) << i;
  }
}

TEST(CliPerturbThinning, MinScanGapKeepsScansFarEnoughApartInLogTime) {
  TempDir dir("cli_perturb_gap");
  const auto poses = zigzag(40, 0.3, 0.4, -0.5);
  const io::CarmenLog in = cli_test::room_log(cli_test::Room{}, poses, 5);
  io::write_carmen(dir.file("in.log"), in);
  const RunResult r = perturb(dir, "0,0,0,0", "--min-scan-gap 1.2");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::vector<double> want = expected_stamps(poses, 1.2, 0.0, 0.0);
  EXPECT_EQ(want.size(), 14u);  // every third scan: 1.5 s apart
  expect_kept(read_output(dir), want, poses, in);
  EXPECT_NE(r.out.find("kept 14 of 40 scans (26 dropped)"), std::string::npos) << r.out;
}

TEST(CliPerturbThinning, MinScanTravelFollowsTheTruePoseNotTheOdometry) {
  TempDir dir("cli_perturb_travel");
  // 15 cm and 6.9 deg per step.
  const auto poses = zigzag(80, 0.0, 0.15, 0.12);
  const io::CarmenLog in = cli_test::room_log(cli_test::Room{}, poses, 5);
  io::write_carmen(dir.file("in.log"), in);
  const double inf = std::numeric_limits<double>::infinity();
  struct Case {
    std::string option;
    double travel, turn;
  };
  for (const Case& c :
       {Case{"--min-scan-travel 0.5", 0.5, inf}, Case{"--min-scan-travel 0.5,20", 0.5, 20.0 * kDeg},
        Case{"--min-scan-travel 10,13", 10.0, 13.0 * kDeg}}) {
    SCOPED_TRACE(c.option);
    ASSERT_EQ(perturb(dir, "0,0,0,0", c.option).code, 0);
    const std::vector<double> want = expected_stamps(poses, 0.0, c.travel, c.turn);
    EXPECT_LE(want.size(), poses.size() / 2);
    expect_kept(read_output(dir), want, poses, in);
    // Heavy odometry noise changes nothing about which scans are kept.
    ASSERT_EQ(perturb(dir, "0.05,0.01,0.05,0.01", c.option).code, 0);
    const Output noisy = read_output(dir);
    ASSERT_EQ(noisy.truth.size(), want.size());
    for (std::size_t i = 0; i < want.size(); ++i) EXPECT_EQ(noisy.truth[i].stamp, want[i]);
  }
}

TEST(CliPerturbLaserOffset, TruthIsTheBaseBehindTheLoggedLaserPose) {
  TempDir dir("cli_perturb_offset");
  const auto laser = cli_test::room_loop(40);
  write_log(dir, laser);
  const RunResult r = perturb(dir, "0,0,0,0", "--laser-offset 0.25");
  ASSERT_EQ(r.code, 0) << r.err;
  const Output o = read_output(dir);
  const Pose2 mount{0.25, 0.0, 0.0};
  EXPECT_EQ(o.raw.params.at("robot_frontlaser_offset"), "0.25");
  ASSERT_EQ(o.truth.size(), laser.size());
  ASSERT_EQ(o.raw.odometry.size(), laser.size());
  const io::Trajectory reread = io::scan_truth(o.raw);
  for (std::size_t i = 0; i < laser.size(); ++i) {
    // truth = laser ∘ mount^-1: the base sits 25 cm behind the laser.
    const Pose2 base = laser[i].compose(mount.inverse());
    EXPECT_NEAR(o.truth[i].pose.x, base.x, 1e-12) << i;
    EXPECT_NEAR(o.truth[i].pose.y, base.y, 1e-12) << i;
    EXPECT_NEAR(o.truth[i].pose.theta, base.theta, 1e-12) << i;
    // The reader restores the mount from the PARAM.
    const io::CarmenScan& s = o.raw.scans[i];
    EXPECT_EQ(s.scan.sensor_pose.x, 0.25);
    EXPECT_EQ(s.scan.sensor_pose.y, 0.0);
    EXPECT_EQ(s.scan.sensor_pose.theta, 0.0);
    // Zero noise: odometry ∘ mount is the logged laser pose, and the laser is where it was.
    const Pose2 l = o.raw.odometry[i].pose.compose(mount);
    EXPECT_NEAR(l.x, s.laser_pose.x, 1e-9) << i;
    EXPECT_NEAR(l.y, s.laser_pose.y, 1e-9) << i;
    EXPECT_NEAR(s.laser_pose.x, laser[i].x, 1e-9) << i;
    EXPECT_NEAR(s.laser_pose.y, laser[i].y, 1e-9) << i;
    EXPECT_NEAR(wrap_angle(s.laser_pose.theta - laser[i].theta), 0.0, 1e-9) << i;
    EXPECT_NEAR(s.odom_pose.x, o.raw.odometry[i].pose.x, 1e-12) << i;
    EXPECT_NEAR(reread[i].pose.x, base.x, 1e-9) << i;
    EXPECT_NEAR(reread[i].pose.y, base.y, 1e-9) << i;
  }
}

TEST(CliPerturbLaserOffset, RefusesALogThatAlreadyHasAnOffset) {
  TempDir dir("cli_perturb_offset_twice");
  io::CarmenLog log = cli_test::room_log(cli_test::Room{}, cli_test::room_loop(10), 5);
  log.params["robot_frontlaser_offset"] = "0.1";
  io::write_carmen(dir.file("in.log"), log);
  const RunResult r = perturb(dir, "0,0,0,0", "--laser-offset 0.25");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--laser-offset"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("robot_frontlaser_offset 0.1"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("raw.log")));
}

/// Runs of consecutive readings at or beyond range_max.
int no_return_runs(const io::CarmenScan& s, int& count) {
  int runs = 0;
  bool in_run = false;
  count = 0;
  for (const float r : s.scan.ranges) {
    const bool lost = static_cast<double>(r) >= s.scan.range_max;
    count += lost ? 1 : 0;
    runs += lost && !in_run ? 1 : 0;
    in_run = lost;
  }
  return runs;
}

TEST(CliPerturbDropout, BlanksTheFractionInAtMostSectorsRuns) {
  TempDir dir("cli_perturb_dropout");
  io::CarmenLog in = cli_test::room_log(cli_test::Room{}, cli_test::room_loop(30), 180);
  in.params["robot_front_laser_max"] = "81.9";
  io::write_carmen(dir.file("in.log"), in);
  const std::string noise = "0.01,0.001,0.01,0.001";
  ASSERT_EQ(perturb(dir, noise, "").code, 0);
  const Output plain = read_output(dir);
  struct Case {
    std::string option;
    int blanked, sectors;
  };
  for (const Case& c : {Case{"--beam-dropout 0.3,2", 54, 2}, Case{"--beam-dropout 0.25", 45, 3},
                        Case{"--beam-dropout 0.1,1", 18, 1}}) {
    SCOPED_TRACE(c.option);
    ASSERT_EQ(perturb(dir, noise, c.option).code, 0);
    const Output o = read_output(dir);
    ASSERT_EQ(o.raw.scans.size(), in.scans.size());
    std::vector<std::size_t> first_lost;
    for (std::size_t i = 0; i < o.raw.scans.size(); ++i) {
      const io::CarmenScan& s = o.raw.scans[i];
      EXPECT_EQ(s.scan.range_max, 81.9);
      int count = 0;
      EXPECT_LE(no_return_runs(s, count), c.sectors) << i;
      EXPECT_EQ(count, c.blanked) << i;
      std::size_t first = s.scan.size();
      for (std::size_t b = 0; b < s.scan.size(); ++b) {
        if (static_cast<double>(s.scan.ranges[b]) >= s.scan.range_max) {
          first = std::min(first, b);
        } else {
          EXPECT_EQ(s.scan.ranges[b], in.scans[i].scan.ranges[b]) << i << " beam " << b;
        }
      }
      first_lost.push_back(first);
      // The dropout has its own random stream: the odometry is unchanged.
      EXPECT_EQ(o.raw.odometry[i].pose.x, plain.raw.odometry[i].pose.x) << i;
    }
    std::sort(first_lost.begin(), first_lost.end());
    EXPECT_GT(std::unique(first_lost.begin(), first_lost.end()) - first_lost.begin(), 10);
  }
}

}  // namespace
}  // namespace pgmcl::perturb_test
