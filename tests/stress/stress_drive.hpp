#pragma once
// Test-only driving for the Localizer stress tests: turn-then-drive paths through
// waypoints, odometry perturbed by the motion model, and a loop that feeds scans from
// stress_world.hpp's Scanner and records the estimate's error against the truth.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <stdexcept>
#include <utility>
#include <vector>

#include "pgmcl/mcl/localizer.hpp"
#include "pgmcl/mcl/motion_model.hpp"
#include "stress_world.hpp"

namespace pgmcl::stress {

/// Map-local poses along `waypoints` (x, y): rotate in place in <= turn_step, then drive in
/// <= step. The heading at the start is `theta0`.
inline std::vector<Pose2> waypoint_path(const std::vector<std::pair<double, double>>& waypoints,
                                        double step, double turn_step, double theta0 = 0.0) {
  std::vector<Pose2> out;
  Pose2 p{waypoints.front().first, waypoints.front().second, wrap_angle(theta0)};
  out.push_back(p);
  for (std::size_t k = 1; k < waypoints.size(); ++k) {
    const auto [tx, ty] = waypoints[k];
    const double heading = std::atan2(ty - p.y, tx - p.x);
    double dth = wrap_angle(heading - p.theta);
    while (std::abs(dth) > 1e-9) {
      const double d = std::clamp(dth, -turn_step, turn_step);
      p.theta = wrap_angle(p.theta + d);
      dth -= d;
      out.push_back(p);
    }
    double dist = std::hypot(tx - p.x, ty - p.y);
    while (dist > 1e-9) {
      const double d = std::min(step, dist);
      p.x += d * std::cos(heading);
      p.y += d * std::sin(heading);
      dist -= d;
      out.push_back(p);
    }
  }
  return out;
}

/// Odometry for a true path: each increment perturbed by the model (noise in variance form).
inline std::vector<Pose2> noisy_odometry(const std::vector<Pose2>& truth, const MotionNoise& noise,
                                         std::uint64_t seed, Pose2 start = {-3.0, 7.0, 2.5}) {
  Rng rng(seed);
  std::vector<Pose2> odom{start};
  for (std::size_t k = 1; k < truth.size(); ++k)
    odom.push_back(odom.back().compose(sample_noisy_increment(MotionModelKind::kDifferentialDrive,
                                                              noise, truth[k - 1], truth[k], rng)));
  return odom;
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
  double sq = 0.0;
  std::size_t scored = 0;
  for (std::size_t k = 0; k < truth.size(); ++k) {
    const double stamp = hooks.stamp ? hooks.stamp(k) : 0.1 * static_cast<double>(k);
    LaserScan scan = scanner.scan(truth[k], noise, stamp);
    if (hooks.scan) hooks.scan(k, scan);
    UpdateResult r;
    try {
      r = loc.update(odom[k], scan, stamp);
    } catch (const std::invalid_argument&) {
      ++e.rejected;
      r = loc.last_result();
    }
    e.measured += r.measured ? 1 : 0;
    e.all_finite = e.all_finite && result_finite(r) && weights_finite(loc.particles());
    const Pose2 gt = grid.origin().compose(truth[k]);
    const double dxy = std::hypot(r.estimate.x - gt.x, r.estimate.y - gt.y);
    const double dth = std::abs(wrap_angle(r.estimate.theta - gt.theta));
    e.xy.push_back(dxy);
    e.theta.push_back(dth);
    if (k >= score_from) {
      sq += dxy * dxy;
      ++scored;
      e.max_xy = std::max(e.max_xy, dxy);
      e.max_theta = std::max(e.max_theta, dth);
    }
  }
  e.rmse_xy = scored > 0 ? std::sqrt(sq / static_cast<double>(scored)) : 0.0;
  return e;
}

[[nodiscard]] inline Eigen::Matrix3d diag_cov(double sxy, double sth) {
  Eigen::Matrix3d c = Eigen::Matrix3d::Zero();
  c.diagonal() << sxy * sxy, sxy * sxy, sth * sth;
  return c;
}

}  // namespace pgmcl::stress
