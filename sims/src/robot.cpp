#include "pgmcl/sims/robot.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>

namespace pgmcl::sims {

namespace {

double dist(const Pose2& p, const Point2& q) noexcept {
  return std::hypot(q.x - p.x, q.y - p.y);
}

VelocityCommand turn_then_drive_to(const Pose2& pose, const Point2& target, double heading_tol,
                                   const DiffDriveLimits& lim, double dt) noexcept {
  const double d = dist(pose, target);
  const double e = wrap_angle(std::atan2(target.y - pose.y, target.x - pose.x) - pose.theta);
  const double omega = std::clamp(e / dt, -lim.max_omega, lim.max_omega);
  if (std::abs(e) > heading_tol) return {0.0, omega};
  return {std::min(lim.max_v, d / dt), omega};
}

}  // namespace

Pose2 integrate_diff_drive(const Pose2& pose, const VelocityCommand& cmd, double dt) noexcept {
  const double dth = cmd.omega * dt;
  if (std::abs(dth) < 1e-9) {
    const double s = cmd.v * dt;
    return {pose.x + s * std::cos(pose.theta + 0.5 * dth),
            pose.y + s * std::sin(pose.theta + 0.5 * dth), wrap_angle(pose.theta + dth)};
  }
  const double r = cmd.v / cmd.omega;
  return {pose.x + r * (std::sin(pose.theta + dth) - std::sin(pose.theta)),
          pose.y - r * (std::cos(pose.theta + dth) - std::cos(pose.theta)),
          wrap_angle(pose.theta + dth)};
}

FreeSpace::FreeSpace(const maps::OccupancyGrid& grid, double clearance)
    : grid_(&grid), clearance_(clearance) {
  if (!(clearance >= 0.0) || !std::isfinite(clearance)) {
    throw std::invalid_argument("FreeSpace: clearance must be finite and >= 0 (m)");
  }
}

bool FreeSpace::admissible(double x, double y) const noexcept {
  double fc = 0.0, fr = 0.0;
  grid_->global_to_cell(x, y, fc, fr);
  const double rc = clearance_ / grid_->resolution();
  const int c0 = static_cast<int>(std::floor(fc - rc)), c1 = static_cast<int>(std::floor(fc + rc));
  const int r0 = static_cast<int>(std::floor(fr - rc)), r1 = static_cast<int>(std::floor(fr + rc));
  for (int r = r0; r <= r1; ++r) {
    for (int c = c0; c <= c1; ++c) {
      // Distance from the centre to the nearest point of cell (c, r), in cells.
      const double dx = std::max({c - fc, 0.0, fc - (c + 1)});
      const double dy = std::max({r - fr, 0.0, fr - (r + 1)});
      if (dx * dx + dy * dy > rc * rc) continue;
      if (!grid_->in_bounds(c, r) || !grid_->free(c, r)) return false;
    }
  }
  return true;
}

bool FreeSpace::segment_admissible(const Point2& a, const Point2& b) const noexcept {
  const double len = std::hypot(b.x - a.x, b.y - a.y);
  const int n = static_cast<int>(std::ceil(len / (0.25 * grid_->resolution()))) + 1;
  for (int i = 0; i <= n; ++i) {
    const double f = static_cast<double>(i) / n;
    if (!admissible(a.x + f * (b.x - a.x), a.y + f * (b.y - a.y))) return false;
  }
  return true;
}

WaypointFollower::WaypointFollower(WaypointPlan plan, const Pose2& start, DiffDriveLimits limits)
    : plan_(std::move(plan)), start_{start.x, start.y}, limits_(limits) {
  finished_ = plan_.waypoints.empty();
}

const Point2& WaypointFollower::point(std::size_t i) const noexcept {
  if (i == 0) return start_;
  return plan_.waypoints[(i - 1) % plan_.waypoints.size()];
}

std::size_t WaypointFollower::last_index() const noexcept {
  return plan_.waypoints.size();
}

VelocityCommand WaypointFollower::command(const Pose2& pose, double dt) {
  if (finished_) return {};
  return plan_.controller == Controller::kPurePursuit ? pure_pursuit(pose, dt)
                                                      : turn_then_drive(pose, dt);
}

VelocityCommand WaypointFollower::turn_then_drive(const Pose2& pose, double dt) {
  while (dist(pose, point(segment_ + 1)) < plan_.goal_tolerance) {
    if (!plan_.loop && segment_ + 1 >= last_index()) {
      finished_ = true;
      return {};
    }
    ++segment_;
  }
  return turn_then_drive_to(pose, point(segment_ + 1), plan_.heading_tolerance, limits_, dt);
}

// Pure pursuit (Coulter, "Implementation of the Pure Pursuit Path Tracking Algorithm",
// CMU-RI-TR-92-01): curvature 2 y / L^2 towards the goal point where the circle of radius
// L around the robot leaves the path. Progress is monotonic: a segment is done once its end
// lies inside the circle, so sharp corners cannot trap the goal point at the robot (as a
// goal point walked from the robot's projection onto the current segment could).
VelocityCommand WaypointFollower::pure_pursuit(const Pose2& pose, double dt) {
  const double lookahead = plan_.lookahead;
  auto is_last = [&] { return !plan_.loop && segment_ + 1 >= last_index(); };
  for (std::size_t guard = 0; guard <= last_index() && !is_last(); ++guard) {
    if (dist(pose, point(segment_ + 1)) >= lookahead) break;
    ++segment_;
  }
  const Point2& end = point(segment_ + 1);
  if (is_last() && dist(pose, end) < plan_.goal_tolerance) {
    finished_ = true;
    return {};
  }
  Point2 target = end;
  if (dist(pose, end) >= lookahead) {
    // Farther intersection of the circle with segment a-b: |a + u (b - a) - p| = L.
    const Point2& a = point(segment_);
    const double ex = end.x - a.x, ey = end.y - a.y, fx = a.x - pose.x, fy = a.y - pose.y;
    const double qa = ex * ex + ey * ey, qb = 2.0 * (fx * ex + fy * ey);
    const double qc = fx * fx + fy * fy - lookahead * lookahead;
    const double disc = qb * qb - 4.0 * qa * qc;
    double u = 1.0;
    if (qa > 0.0 && disc >= 0.0) {
      u = std::clamp((-qb + std::sqrt(disc)) / (2.0 * qa), 0.0, 1.0);
    } else if (qa > 0.0) {  // off the path by more than L: head for the nearest point
      u = std::clamp(-(fx * ex + fy * ey) / qa, 0.0, 1.0);
    }
    target = {a.x + u * ex, a.y + u * ey};
  }
  const double c = std::cos(pose.theta), s = std::sin(pose.theta);
  const double tx = c * (target.x - pose.x) + s * (target.y - pose.y);
  const double ty = -s * (target.x - pose.x) + c * (target.y - pose.y);
  const double l2 = tx * tx + ty * ty;
  if (l2 < 1e-12) return {};
  if (tx <= 0.0) {  // goal point behind: turn on the spot first
    return {0.0, std::copysign(limits_.max_omega, ty)};
  }
  const double kappa = 2.0 * ty / l2;
  double v = limits_.max_v;
  if (is_last()) v = std::min(v, dist(pose, end) / dt);
  if (std::abs(kappa) * v > limits_.max_omega) v = limits_.max_omega / std::abs(kappa);
  return {v, kappa * v};
}

RandomWalker::RandomWalker(RandomWalkPlan plan, const maps::OccupancyGrid& grid,
                           DiffDriveLimits limits)
    : plan_(plan), free_(grid, plan.clearance), limits_(limits) {
  if (!(plan.min_leg > 0.0 && plan.max_leg >= plan.min_leg && std::isfinite(plan.max_leg))) {
    throw std::invalid_argument("RandomWalkPlan: need 0 < min_leg <= max_leg (m)");
  }
  if (plan.max_retries < 1) throw std::invalid_argument("RandomWalkPlan.max_retries must be >= 1");
  if (!(plan.goal_tolerance > 0.0)) {
    throw std::invalid_argument("RandomWalkPlan.goal_tolerance must be > 0 (m)");
  }
}

VelocityCommand RandomWalker::command(const Pose2& pose, double dt, Rng& rng) {
  if (goal_ && dist(pose, *goal_) < plan_.goal_tolerance) goal_.reset();
  if (!goal_) {
    const Point2 here{pose.x, pose.y};
    for (int k = 0; k < plan_.max_retries && !goal_; ++k) {
      const double a = rng.uniform(-std::numbers::pi, std::numbers::pi);
      const double len = rng.uniform(plan_.min_leg, plan_.max_leg);
      const Point2 g{pose.x + len * std::cos(a), pose.y + len * std::sin(a)};
      if (free_.segment_admissible(here, g)) goal_ = g;
    }
    // Boxed in for now: turning on the spot is always admissible.
    if (!goal_) return {0.0, limits_.max_omega};
  }
  const VelocityCommand cmd = turn_then_drive_to(pose, *goal_, 0.05, limits_, dt);
  const Pose2 next = integrate_diff_drive(pose, cmd, dt);
  if (!free_.admissible(next.x, next.y)) {
    goal_.reset();
    return {};
  }
  return cmd;
}

Pose2 apply_systematic_error(const Pose2& inc, const OdometrySettings& s) noexcept {
  const double k = 1.0 + s.wheel_radius_bias;
  const double travelled = std::hypot(inc.x, inc.y) * k;
  return {inc.x * k, inc.y * k,
          wrap_angle(inc.theta * k / (1.0 + s.wheelbase_bias) + s.yaw_drift_per_metre * travelled)};
}

}  // namespace pgmcl::sims
