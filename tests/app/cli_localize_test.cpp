// `pgmcl localize` end to end on a synthetic room: map -> perturb -> localize -> outputs.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <thread>

#include "cli_test_util.hpp"
#include "pgmcl/io/carmen_writer.hpp"
#include "pgmcl/io/tum.hpp"

namespace pgmcl {
namespace {

using cli_test::run_pgmcl;
using cli_test::RunResult;
using cli_test::TempDir;

using cli_test::prepare_localize_case;

constexpr const char* kSmall =
    " --set filter.particles=300 --set filter.global_particles=3000 --set "
    "filter.kld.min_particles=100";

TEST(CliLocalize, TracksTheSyntheticRoomAndWritesEveryOutput) {
  TempDir dir("cli_localize_room");
  prepare_localize_case(dir);
  const RunResult r = run_pgmcl(
      std::string("localize --map room.yaml --log raw.log --truth truth.tum --out out --quiet "
                  "--seed 3") +
          kSmall,
      dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("ATE RMSE"), std::string::npos) << r.out;
  for (const char* f :
       {"trajectory.tum", "metrics.yaml", "config.yaml", "overlay.png", "error.png"}) {
    EXPECT_TRUE(std::filesystem::exists(dir.file(std::string("out/") + f))) << f;
  }
  const io::Trajectory est = io::read_tum(dir.file("out/trajectory.tum"));
  EXPECT_EQ(est.size(), 60u);  // one pose per scan, at the scan's stamp
  EXPECT_DOUBLE_EQ(est.front().stamp, 1.0);
  const YAML::Node m = YAML::LoadFile(dir.file("out/metrics.yaml"));
  EXPECT_LT(m["ate_rmse_m"].as<double>(), 0.05);
  EXPECT_LT(m["heading_rmse_deg"].as<double>(), 2.0);
  EXPECT_EQ(m["updates"].as<int>() + m["skipped_updates"].as<int>(), 60);
  EXPECT_GT(m["beams_used_mean"].as<double>(), 50.0);
  EXPECT_GT(m["update_ms_p95"].as<double>(), 0.0);
  // The effective configuration is written back, overrides included.
  const YAML::Node c = YAML::LoadFile(dir.file("out/config.yaml"));
  EXPECT_EQ(c["filter"]["particles"].as<int>(), 300);
  EXPECT_EQ(c["seed"].as<int>(), 3);
  // The summary gives the particle range and says KLD-sampling set it, and the update time
  // as mean, median, p95 and max.
  EXPECT_NE(r.out.find("particles " + std::to_string(m["particles_min"].as<int>()) + ".." +
                       std::to_string(m["particles_max"].as<int>())),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find(") set by KLD-sampling within 100..20000 (filter.particles 300 is only the "
                       "start)"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find(" ms/update (median "), std::string::npos) << r.out;
  EXPECT_GE(m["update_ms_max"].as<double>(), m["update_ms_p95"].as<double>());
  EXPECT_LE(m["update_ms_median"].as<double>(), m["update_ms_p95"].as<double>());
  // Without KLD the count is fixed and nothing is said about it.
  const RunResult fixed = run_pgmcl(std::string("localize --map room.yaml --log raw.log --truth "
                                                "truth.tum --out out2 --quiet --set "
                                                "filter.kld.enabled=false") +
                                        kSmall,
                                    dir);
  ASSERT_EQ(fixed.code, 0) << fixed.err;
  EXPECT_NE(fixed.out.find("particles 300..300 (mean 300)"), std::string::npos) << fixed.out;
  EXPECT_EQ(fixed.out.find("KLD"), std::string::npos) << fixed.out;
}

TEST(CliLocalize, MoreThreadsThanCoresWarns) {
  TempDir dir("cli_localize_threads");
  prepare_localize_case(dir);
  const std::string over = std::to_string(std::thread::hardware_concurrency() + 1);
  const RunResult r = run_pgmcl(
      "localize --map room.yaml --log raw.log --out out --quiet --threads " + over + kSmall, dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("pgmcl: warning: threads = " + over + " is more than the "),
            std::string::npos)
      << r.err;
  const RunResult one = run_pgmcl(
      std::string("localize --map room.yaml --log raw.log --out out --quiet --threads 1") + kSmall,
      dir);
  EXPECT_EQ(one.err.find("is more than the"), std::string::npos) << one.err;
}

TEST(CliLocalize, ALogWithoutOdometryIsBadInputNotABadCommandLine) {
  TempDir dir("cli_localize_no_odom");
  prepare_localize_case(dir);
  // RAWLASER1 scans carry no pose, and there is no ODOM message: nothing to localise.
  io::CarmenLog log = io::read_carmen(dir.file("raw.log"));
  log.odometry.clear();
  for (auto& s : log.scans) {
    s.message = io::LaserMessage::kRawLaser1;
    s.has_poses = false;
  }
  io::write_carmen(dir.file("no_odom.log"), log);
  const RunResult r = run_pgmcl("localize --map room.yaml --log no_odom.log --quiet", dir);
  EXPECT_EQ(r.code, 1) << r.err;  // mcl/app/README.md: 2 is for a bad command line only
  EXPECT_NE(r.err.find("no laser scan with odometry"), std::string::npos) << r.err;
}

TEST(CliLocalize, GlobalLocalisationFindsTheRobot) {
  TempDir dir("cli_localize_global");
  prepare_localize_case(dir);
  const RunResult r = run_pgmcl(
      std::string("localize --map room.yaml --log raw.log --truth truth.tum --global --out out "
                  "--quiet") +
          kSmall,
      dir);
  ASSERT_EQ(r.code, 0) << r.err;
  // The first estimate comes from a cloud over the whole room, not from the truth.
  const io::Trajectory est = io::read_tum(dir.file("out/trajectory.tum"));
  const io::Trajectory truth = io::read_tum(dir.file("truth.tum"));
  ASSERT_EQ(est.size(), truth.size());
  auto dist = [](const Pose2& a, const Pose2& b) { return std::hypot(a.x - b.x, a.y - b.y); };
  EXPECT_GT(dist(est.front().pose, truth.front().pose), 0.3);
  // The rectangle looks the same from a pose and from its half-turn mirror about the room's
  // centre, so global localisation may settle on either; it must settle on one of them.
  const cli_test::Room room;
  const double cx = 0.5 * (room.x0 + room.x1), cy = 0.5 * (room.y0 + room.y1);
  const Pose2& t = truth.back().pose;
  const Pose2 mirror{2 * cx - t.x, 2 * cy - t.y, wrap_angle(t.theta + M_PI)};
  const Pose2& e = est.back().pose;
  EXPECT_LT(std::min(dist(e, t), dist(e, mirror)), 0.3)
      << "final estimate " << e.x << ", " << e.y << " truth " << t.x << ", " << t.y;
}

TEST(CliLocalize, BadConfigAndOptionsAreReportedPrecisely) {
  TempDir dir("cli_localize_errors");
  prepare_localize_case(dir);
  cli_test::write_text(dir.file("cfg.yaml"), "filter:\n  particels: 100\n");
  RunResult r = run_pgmcl("localize --map room.yaml --log raw.log --config cfg.yaml", dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("pgmcl: error: cfg.yaml:2: filter.particels: unknown key"),
            std::string::npos)
      << r.err;

  r = run_pgmcl("localize --map room.yaml --log raw.log --set filter.resample_threshold=2", dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("filter.resample_threshold"), std::string::npos) << r.err;

  r = run_pgmcl("localize --map room.yaml --log raw.log --init 1,2", dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--init: expected X,Y,THETA"), std::string::npos) << r.err;

  r = run_pgmcl("localize --map room.yaml --log raw.log --init 1,2,0 --global", dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("excludes"), std::string::npos) << r.err;

  cli_test::write_text(dir.file("bad_map.yaml"), "image: nothere.pgm\nresolution: 0.05\n");
  r = run_pgmcl("localize --map bad_map.yaml --log raw.log", dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("bad_map.yaml"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("origin"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace pgmcl
