// `pgmcl localize` end to end on a synthetic room: map -> perturb -> localize -> outputs.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <string>

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
