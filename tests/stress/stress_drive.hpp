#pragma once
// Test-only driving for the Localizer stress tests: turn-then-drive paths through
// waypoints and perturbed odometry (tests/support/drive_path.hpp), and a loop that feeds scans from
// stress_world.hpp's Scanner and records the estimate's error against the truth.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <stdexcept>
#include <utility>
#include <vector>

#include "drive_path.hpp"
#include "pgmcl/common/motion_model.hpp"
#include "pgmcl/mcl/localizer.hpp"
#include "stress_world.hpp"

namespace pgmcl::stress {

using testkit::waypoint_path;

/// Odometry for a true path: each increment perturbed by the model (noise in variance form).
inline std::vector<Pose2> noisy_odometry(const std::vector<Pose2>& truth, const MotionNoise& noise,
                                         std::uint64_t seed, Pose2 start = {-3.0, 7.0, 2.5}) {
  return testkit::noisy_odometry(truth, noise, seed, start);
}

struct RunErrors {
  std::vector<double> xy;     // metres, per step
  std::vector<double> theta;  // radians, per step
  std::size_t measured = 0;
  std::size_t rejected = 0;  // updates that threw std::invalid_argument
  double rmse_xy = 0.0;      // over steps >= score_from
  double max_xy = 0.0;
  double max_theta = 0.0;
  bool all_finite = true;  // estimate, covariances, n_eff, weights at every step
};

[[nodiscard]] inline bool finite(const Pose2& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta);
}

[[nodiscard]] inline bool result_finite(const UpdateResult& r) {
  return finite(r.estimate) && finite(r.mean) && r.covariance.allFinite() &&
         r.mean_covariance.allFinite() && std::isfinite(r.n_eff) && std::isfinite(r.w_slow) &&
         std::isfinite(r.w_fast);
}

[[nodiscard]] inline bool weights_finite(const ParticlesView& pv) {
  double sum = 0.0;
  for (std::size_t i = 0; i < pv.size(); ++i) {
    if (!std::isfinite(pv.weight[i]) || pv.weight[i] < 0.0 || !std::isfinite(pv.x[i]) ||
        !std::isfinite(pv.y[i]) || !(std::abs(pv.theta[i]) <= 3.1415927f))
      return false;
    sum += pv.weight[i];
  }
  return std::abs(sum - 1.0) < 1e-9;
}

/// Optional per-step overrides for drive().
struct DriveHooks {
  /// Edits step k's scan before it is fed (hostile scans).
  std::function<void(std::size_t, LaserScan&)> scan;
  /// Step k's stamp; default 0.1 k seconds.
  std::function<double(std::size_t)> stamp;
};

[[nodiscard]] inline DriveHooks on_scan(std::function<void(std::size_t, LaserScan&)> f) {
  DriveHooks h;
  h.scan = std::move(f);
  return h;
}
[[nodiscard]] inline DriveHooks with_stamps(std::function<double(std::size_t)> f,
                                            std::function<void(std::size_t, LaserScan&)> g = {}) {
  DriveHooks h;
  h.stamp = std::move(f);
  h.scan = std::move(g);
  return h;
}

/// Feeds steps [0, truth.size()) to `loc`; scans come from `scanner` at truth[k] (map-local).
/// Errors are against origin ∘ truth[k]. A step whose update throws std::invalid_argument
/// is counted in `rejected` and scored with the previous result (the filter did not move).
inline RunErrors drive(Localizer& loc, const Scanner& scanner, const maps::OccupancyGrid& grid,
                       const std::vector<Pose2>& truth, const std::vector<Pose2>& odom,
                       std::uint64_t noise_seed, std::size_t score_from = 0,
                       const DriveHooks& hooks = {}) {
  RunErrors e;
  Rng noise(noise_seed);
  testkit::ErrorScore score;
  for (std::size_t k = 0; k < truth.size(); ++k) {
    const double stamp = hooks.stamp ? hooks.stamp(k) : 0.1 * static_cast<double>(k);
    LaserScan scan = scanner.scan(truth[k], noise);
    if (hooks.scan) hooks.scan(k, scan);
    UpdateResult r;
    try {
      r = loc.update(odom[k], scan, stamp);
    } catch (const std::invalid_argument&) {
      ++e.rejected;
      r = loc.last_result();
    }
    e.measured += r.measured() ? 1 : 0;
    e.all_finite = e.all_finite && result_finite(r) && weights_finite(loc.particles());
    const Pose2 gt = grid.origin().compose(truth[k]);
    const double dxy = testkit::xy_error(r.estimate, gt);
    const double dth = testkit::theta_error(r.estimate, gt);
    e.xy.push_back(dxy);
    e.theta.push_back(dth);
    if (k >= score_from) score.add(dxy, dth);
  }
  e.rmse_xy = score.rmse_xy();
  e.max_xy = score.max_xy;
  e.max_theta = score.max_theta;
  return e;
}

[[nodiscard]] inline Eigen::Matrix3d diag_cov(double sxy, double sth) {
  Eigen::Matrix3d c = Eigen::Matrix3d::Zero();
  c.diagonal() << sxy * sxy, sxy * sxy, sth * sth;
  return c;
}

}  // namespace pgmcl::stress
