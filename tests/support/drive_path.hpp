#pragma once
// Test-only driving shared by the engine (tests/mcl) and stress (tests/stress) suites:
// turn-then-drive ground-truth paths, odometry perturbed by the motion model, and the
// error score of an estimate against the truth. The suites differ only in their worlds,
// waypoints and odometry start poses, which are parameters here.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "pgmcl/common/motion_model.hpp"
#include "pgmcl/common/random.hpp"
#include "pgmcl/common/se2.hpp"

namespace pgmcl::testkit {

/// Map-local poses along `waypoints` (x, y; metres): rotate in place towards the next
/// waypoint in <= `turn_step` radians, then drive to it in <= `step` metres. The heading at
/// the start is `theta0` (radians).
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

/// Odometry for a true path starting at `start` (the odometry frame is arbitrary): each
/// increment is perturbed by the differential-drive model (Probabilistic Robotics,
/// Table 5.6; noise in variance form).
inline std::vector<Pose2> noisy_odometry(const std::vector<Pose2>& truth, const MotionNoise& noise,
                                         std::uint64_t seed, const Pose2& start) {
  Rng rng(seed);
  std::vector<Pose2> odom{start};
  for (std::size_t k = 1; k < truth.size(); ++k) {
    const Pose2 inc = sample_noisy_increment(MotionModelKind::kDifferentialDrive, noise,
                                             truth[k - 1], truth[k], rng);
    odom.push_back(odom.back().compose(inc));
  }
  return odom;
}

/// Position error, metres.
[[nodiscard]] inline double xy_error(const Pose2& a, const Pose2& b) {
  return std::hypot(a.x - b.x, a.y - b.y);
}
/// Heading error, radians in [0, pi].
[[nodiscard]] inline double theta_error(const Pose2& a, const Pose2& b) {
  return std::abs(wrap_angle(a.theta - b.theta));
}

/// RMSE and maxima of the errors over the scored steps of a run.
struct ErrorScore {
  std::size_t scored = 0;
  double sum_sq_xy = 0.0;  ///< square metres
  double max_xy = 0.0;     ///< metres
  double max_theta = 0.0;  ///< radians

  void add(double dxy, double dtheta) {
    sum_sq_xy += dxy * dxy;
    ++scored;
    max_xy = std::max(max_xy, dxy);
    max_theta = std::max(max_theta, dtheta);
  }
  /// Metres; 0 when nothing was scored.
  [[nodiscard]] double rmse_xy() const {
    return scored > 0 ? std::sqrt(sum_sq_xy / static_cast<double>(scored)) : 0.0;
  }
};

}  // namespace pgmcl::testkit
