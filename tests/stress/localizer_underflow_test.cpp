// Underflow: 1081 beams at the paper's sigmas (sigma_x = 5.6894 mm along the beam,
// sigma_y = 3 mm across; Dekan et al., Section 5) on a 5 mm map, every beam scored. With
// the plain product of beam likelihoods (tau = 1, no ESS safety net) particles a few mm
// apart differ by hundreds of nats and a scan's log-likelihoods span thousands, so exp()
// underflows for all but a handful of particles at every step. Weights must stay finite,
// N_eff >= 1, and the filter must still track scans ray-cast by sims on the same map.

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>

#include "pgmcl/mcl/localizer.hpp"
#include "stress_drive.hpp"
#include "stress_world.hpp"

namespace pgmcl::stress {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kPaperSigmaAlong = 5.6894e-3;  // metres

bool symmetric_psd(const Eigen::Matrix3d& c) {
  if (!c.allFinite() || (c - c.transpose()).cwiseAbs().maxCoeff() > 1e-12) return false;
  const double scale = std::max(1e-300, c.cwiseAbs().maxCoeff());
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(c).eigenvalues().minCoeff() >=
         -1e-12 * scale;
}

#ifdef NDEBUG
constexpr std::size_t kParticles = 2000;
#else
constexpr std::size_t kParticles = 500;  // Debug/ASan: a quarter, same code paths
#endif

struct FiveMillimetreRun {
  Room room = make_room(4.0, 3.0, 0.005);
  std::vector<Pose2> truth =
      waypoint_path({{0.7, 1.6}, {3.4, 1.6}, {3.4, 2.75}, {0.7, 2.75}, {0.7, 1.6}}, 0.05, 0.1);
  // Odometry a fifth as noisy as the filter assumes (MotionNoise defaults).
  std::vector<Pose2> odom = noisy_odometry(truth, MotionNoise{0.001, 0.0001, 0.001, 0.0001}, 17);

  LocalizerConfig config(bool plain_product) const {
    LocalizerConfig cfg;
    cfg.likelihood.beam = sensor_model::BeamLikelihoodParams{};  // paper sigmas, no model mismatch
    cfg.likelihood.selection.mode = BeamSelectionMode::kAll;
    cfg.likelihood.expected_beams = 1081;
    if (plain_product) {
      cfg.likelihood.effective_beams = 0.0;
      cfg.likelihood.tempering = 1.0;
      cfg.likelihood.min_ess_ratio = 0.0;
    }
    cfg.filter.particles = kParticles;
    cfg.filter.global_particles = kParticles;
    cfg.filter.kld.min_particles = kParticles / 4;
    cfg.filter.kld.max_particles = kParticles;
    cfg.gating.enabled = false;  // measure every 5 cm step
    return cfg;
  }
};

// Runs the loop; checks every measured step's N_eff and beam count in the scan hook (which
// sees the previous step's result) and returns the errors and the smallest N_eff.
RunErrors run_loop(const FiveMillimetreRun& run, const LocalizerConfig& cfg, double& min_neff) {
  Localizer loc(run.room.grid, cfg);
  loc.set_pose(run.truth[0], diag_cov(0.01, 1 * kDeg));
  const Scanner scanner(run.room.grid, kPaperSigmaAlong);
  min_neff = 1e300;
  const auto check = [&](const UpdateResult& r) {
    if (!r.measured()) return;
    EXPECT_EQ(r.beams_used, 1081u);
    EXPECT_GE(r.n_eff, 1.0 - 1e-9);
    min_neff = std::min(min_neff, r.n_eff);
    // A collapsed cloud (N_eff ~ 1): covariances still symmetric PSD, never NaN.
    EXPECT_TRUE(symmetric_psd(r.covariance)) << r.covariance;
    EXPECT_TRUE(symmetric_psd(r.mean_covariance)) << r.mean_covariance;
  };
  const RunErrors e = drive(loc, scanner, run.room.grid, run.truth, run.odom, 5, 0,
                            on_scan([&](std::size_t, LaserScan&) { check(loc.last_result()); }));
  check(loc.last_result());
  std::cout << "  " << run.truth.size() << " steps, " << e.measured << " measured, min N_eff "
            << min_neff << ", RMSE " << e.rmse_xy * 1000 << " mm, max " << e.max_xy * 1000
            << " mm, max heading " << e.max_theta / kDeg << " deg\n";
  return e;
}

TEST(StressUnderflow, PlainProductOf1081PaperSigmaBeamsOn5mmMapTracks) {
  const FiveMillimetreRun run;
  double min_neff = 0.0;
  const RunErrors e = run_loop(run, run.config(true), min_neff);
  EXPECT_TRUE(e.all_finite);
  EXPECT_EQ(e.measured, run.truth.size());
  EXPECT_LT(min_neff, 2.0) << "the test must collapse the weights (exp() underflow)";
  EXPECT_LT(e.rmse_xy, 0.012);
  EXPECT_LT(e.max_xy, 0.03);
  EXPECT_LT(e.max_theta, 1.0 * kDeg);
}

// The default tempering (a scan counts as 20 independent beams, ESS safety net) with the
// same paper sigmas: healthier N_eff, no worse tracking.
TEST(StressUnderflow, DefaultTemperingWithPaperSigmasOn5mmMapTracks) {
  const FiveMillimetreRun run;
  double min_neff = 0.0;
  const RunErrors e = run_loop(run, run.config(false), min_neff);
  EXPECT_TRUE(e.all_finite);
  EXPECT_GT(min_neff, 2.0);
  EXPECT_LT(e.rmse_xy, 0.012);
  EXPECT_LT(e.max_xy, 0.03);
  EXPECT_LT(e.max_theta, 1.0 * kDeg);
}

}  // namespace
}  // namespace pgmcl::stress
