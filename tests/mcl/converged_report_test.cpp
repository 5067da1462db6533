// EstimateConfig::converged_fit_ratio: `converged` is withdrawn while the scan fits the
// estimate far worse than the map usually fits there, and nothing else changes.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cstddef>
#include <numbers>
#include <vector>

#include "pgmcl/common/random.hpp"
#include "pgmcl/mcl/localizer.hpp"
#include "synthetic_world.hpp"

namespace pgmcl {
namespace {

// The room's loop, tracked from the truth, 60 scans. From `crowd_from` on, eight 40 cm
// "people" stand 0.9-1.7 m around the robot; from `kidnap_from` on, the scans come from
// `kidnap_shift` (robot frame) away from where the odometry says the robot is.
std::vector<UpdateResult> run(double fit_ratio, std::size_t crowd_from, std::size_t kidnap_from,
                              const Pose2& kidnap_shift = {}) {
  const test::World world = test::make_room(0.05);
  const auto truth = test::loop_trajectory(0.5, 15 * std::numbers::pi / 180.0);
  const auto odom = test::noisy_odometry(truth, MotionNoise{}, 3);
  test::ScanSpec spec;
  spec.noise_sigma = 0.01;
  LocalizerConfig cfg;
  cfg.seed = 5;
  cfg.estimate.converged_fit_ratio = fit_ratio;
  Localizer loc(world.grid, cfg);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  cov.diagonal() << 0.01, 0.01, 0.003;
  loc.set_pose(truth[0], cov);
  Rng noise(9), crowd(11);
  std::vector<UpdateResult> out;
  for (std::size_t k = 0; k < std::min<std::size_t>(60, truth.size()); ++k) {
    test::World scene = world;
    const Pose2 p = k >= kidnap_from ? truth[k].compose(kidnap_shift) : truth[k];
    if (k >= crowd_from) test::add_crowd(scene, p, crowd);
    out.push_back(loc.update(odom[k], scene.scan(p, spec, &noise), 0.1 * static_cast<double>(k)));
  }
  return out;
}

// The default ratio.
const double kRatio = EstimateConfig{}.converged_fit_ratio;

TEST(ConvergedReport, ACrowdHidingTheWallsWithdrawsItAndChangesNothingElse) {
  const std::vector<UpdateResult> gated = run(kRatio, 20, 1000), plain = run(0.0, 20, 1000);
  ASSERT_EQ(gated.size(), plain.size());
  std::size_t withdrawn = 0, converged_before = 0;
  for (std::size_t i = 0; i < gated.size(); ++i) {
    const UpdateResult &g = gated[i], &p = plain[i];
    // Only the report differs: the filter's own state follows the cluster alone.
    ASSERT_EQ(g.estimate.x, p.estimate.x) << "step " << i;
    ASSERT_EQ(g.estimate.theta, p.estimate.theta) << "step " << i;
    ASSERT_EQ(g.n_eff, p.n_eff) << "step " << i;
    ASSERT_EQ(g.fit, p.fit) << "step " << i;
    EXPECT_FALSE(g.converged && !p.converged) << "step " << i;
    if (i < 20) {
      EXPECT_EQ(g.converged, p.converged) << "step " << i << ": the scan fits as usual";
      converged_before += p.converged ? 1 : 0;
    }
    if (p.converged && !g.converged) {
      ++withdrawn;
      EXPECT_GE(i, 20u) << "withdrawn before the crowd came";
      // The room fits all but a few beams when clear: its usual fit is at most 1.
      EXPECT_LT(g.fit, kRatio) << "step " << i;
    }
  }
  EXPECT_GE(converged_before, 10u);
  EXPECT_GT(withdrawn, 0u) << "the crowd no longer lowers the fit enough";
}

TEST(ConvergedReport, AKidnappedRobotIsNotReportedConvergedOnItsFirstMisfittingScan) {
  // 1.5 m sideways and a quarter turn: the estimate stays where the odometry puts it.
  const std::vector<UpdateResult> gated = run(kRatio, 1000, 30, {0.0, 1.5, std::numbers::pi / 2});
  const std::vector<UpdateResult> plain = run(0.0, 1000, 30, {0.0, 1.5, std::numbers::pi / 2});
  ASSERT_TRUE(plain[29].converged);
  ASSERT_TRUE(gated[29].converged);
  EXPECT_TRUE(plain[30].converged) << "the cluster alone no longer says converged: the "
                                      "test shows nothing";
  EXPECT_FALSE(gated[30].converged) << "fit " << gated[30].fit;
}

TEST(ConvergedReport, RatioOutsideZeroToOneNamesTheField) {
  LocalizerConfig cfg;
  cfg.estimate.converged_fit_ratio = 1.5;
  try {
    cfg.validate();
    FAIL() << "a ratio above 1 was accepted";
  } catch (const InvalidConfigField& e) {
    EXPECT_EQ(e.field(), "estimate.converged_fit_ratio");
  }
}

}  // namespace
}  // namespace pgmcl
