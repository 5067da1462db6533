// `pgmcl convert` (a CARMEN log as a ROS 1 bag and back) and `pgmcl localize --bag` with
// PGMCL_WITH_ROS, or a clear error in a build without ROS.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "cli_test_util.hpp"

namespace pgmcl {
namespace {

using cli_test::run_pgmcl;
using cli_test::RunResult;
using cli_test::TempDir;

#ifdef PGMCL_HAVE_ROS

TEST(CliConvert, CarmenToBagAndBack) {
  TempDir dir("cli_convert");
  io::write_carmen(dir.file("room.log"),
                   cli_test::room_log(cli_test::Room{}, cli_test::room_loop(40), 180));
  RunResult r = run_pgmcl("convert --log room.log --out out/room.bag", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out,
            "convert: wrote 40 scans to out/room.bag (/scan, /tf odom -> base_link, /tf_static "
            "base_link -> laser, /odom)\n");
  r = run_pgmcl("convert --log out/room.bag --out back.log.gz", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out, "convert: wrote 40 scans and 40 odometry poses to back.log.gz\n");
  EXPECT_NE(r.err.find("left unread: /odom (40 messages)"), std::string::npos) << r.err;
  const io::CarmenLog back = io::read_carmen(dir.file("back.log.gz"));
  ASSERT_EQ(back.scans.size(), 40u);
  EXPECT_EQ(back.scans[0].message, io::LaserMessage::kRobotLaser1);
  EXPECT_EQ(back.scans[3].stamp, 2.5);
  // Odometry from the Odometry topic and other frame names are options.
  r = run_pgmcl("convert --log room.log --out named.bag --odom-frame wheels --base-frame body",
                dir);
  ASSERT_EQ(r.code, 0) << r.err;
  r = run_pgmcl("convert --log named.bag --out n.log --odom-topic /odom --base-frame body", dir);
  EXPECT_EQ(r.code, 0) << r.err;
}

TEST(CliConvert, ErrorsNameWhatIsWrong) {
  TempDir dir("cli_convert_errors");
  io::write_carmen(dir.file("room.log"),
                   cli_test::room_log(cli_test::Room{}, cli_test::room_loop(5), 180));
  RunResult r = run_pgmcl("convert --log room.log --out other.log", dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err,
            "pgmcl: error: convert: one of --log and --out must be a ROS bag (.bag), the other "
            "a CARMEN log (.log or .clf, optionally .gz)\n");
  ASSERT_EQ(run_pgmcl("convert --log room.log --out room.bag", dir).code, 0);
  r = run_pgmcl("convert --log room.bag --out x.log --odom-frame odom_combined", dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.err,
            "pgmcl: error: room.bag: /tf: no transform odom_combined -> base_link "
            "(--odom-frame, --base-frame; edges in the bag: odom -> base_link)\n");
  cli_test::write_text(dir.file("junk.bag"), "not a bag");
  r = run_pgmcl("convert --log junk.bag --out x.log", dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.err.find("pgmcl: error: junk.bag: "), 0u) << r.err;
  // All or nothing: the failed runs above left neither x.log nor a temporary beside it.
  for (const auto& e : std::filesystem::directory_iterator(dir.path()))
    EXPECT_EQ(e.path().filename().string().find("x."), std::string::npos) << e.path();
  for (const auto& e : std::filesystem::directory_iterator(dir.path()))
    EXPECT_EQ(e.path().filename().string().find(".pgmcl-"), std::string::npos) << e.path();
  // The output may not be the input under another name.
  const std::string log_text = cli_test::read_text(dir.file("room.log"));
  std::filesystem::create_symlink("room.log", dir.file("alias.bag"));
  r = run_pgmcl("convert --log room.log --out alias.bag", dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--out: alias.bag is also the input --log room.log"), std::string::npos)
      << r.err;
  EXPECT_EQ(cli_test::read_text(dir.file("room.log")), log_text);
}

TEST(CliLocalizeBag, SameAccuracyAsTheLogItWasConvertedFrom) {
  TempDir dir("cli_localize_bag");
  cli_test::prepare_localize_case(dir);
  ASSERT_EQ(run_pgmcl("convert --log raw.log --out raw.bag", dir).code, 0);
  const std::string common =
      " --map room.yaml --truth truth.tum --quiet --seed 3 --set filter.particles=300 --set "
      "filter.kld.min_particles=100";
  RunResult r = run_pgmcl("localize --log raw.log --out log" + common, dir);
  ASSERT_EQ(r.code, 0) << r.err;
  r = run_pgmcl("localize --bag raw.bag --out bag" + common, dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const YAML::Node a = YAML::LoadFile(dir.file("log/metrics.yaml"));
  const YAML::Node b = YAML::LoadFile(dir.file("bag/metrics.yaml"));
  EXPECT_EQ(a["updates"].as<int>(), b["updates"].as<int>());
  EXPECT_LT(b["ate_rmse_m"].as<double>(), 0.05);
  // The bag's angles are float32: the runs may differ in the last bits, not in accuracy.
  EXPECT_NEAR(a["ate_rmse_m"].as<double>(), b["ate_rmse_m"].as<double>(), 0.005);
  r = run_pgmcl("localize --bag raw.bag --odom-topic /odom --out odom" + common, dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NEAR(YAML::LoadFile(dir.file("odom/metrics.yaml"))["ate_rmse_m"].as<double>(),
              b["ate_rmse_m"].as<double>(), 1e-9);
  // Exactly one of --log and --bag; bag options need --bag.
  r = run_pgmcl("localize --map room.yaml --out x --quiet", dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "pgmcl: error: localize: give the scans with --log (CARMEN) or --bag (ROS 1)\n");
  EXPECT_EQ(run_pgmcl("localize --map room.yaml --log raw.log --bag raw.bag", dir).code, 2);
  EXPECT_EQ(run_pgmcl("localize --map room.yaml --log raw.log --scan-topic /s", dir).code, 2);
  r = run_pgmcl("localize --map room.yaml --bag raw.bag --base-frame body --out x --quiet", dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("raw.bag: /tf: no transform odom -> body"), std::string::npos) << r.err;
}

#else

TEST(CliConvert, NeedsRos) {
  TempDir dir("cli_convert_no_ros");
  io::write_carmen(dir.file("room.log"),
                   cli_test::room_log(cli_test::Room{}, cli_test::room_loop(5), 180));
  const RunResult r = run_pgmcl("convert --log room.log --out room.bag", dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.err,
            "pgmcl: error: convert: this pgmcl was built without ROS 1 (PGMCL_WITH_ROS=OFF or "
            "the ROS packages missing): bags need librosbag-storage-dev\n");
  cli_test::write_text(dir.file("x.bag"), "");
  ASSERT_EQ(cli_test::map_room(dir, 10, "room.yaml").code, 0);
  const RunResult l = run_pgmcl("localize --map room.yaml --bag x.bag --quiet", dir);
  EXPECT_EQ(l.code, 1);
  EXPECT_EQ(l.err.find("pgmcl: error: localize --bag: this pgmcl was built without ROS 1"), 0u)
      << l.err;
}

#endif

}  // namespace
}  // namespace pgmcl
