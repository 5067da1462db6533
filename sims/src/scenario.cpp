#include "pgmcl/sims/scenario.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace pgmcl::sims {

namespace {

[[noreturn]] void fail(const std::string& field, const std::string& what) {
  throw std::invalid_argument("Scenario." + field + ": " + what);
}

void require_positive(double v, const std::string& field, const char* unit) {
  if (!(v > 0.0) || !std::isfinite(v)) fail(field, std::string("must be finite and > 0 ") + unit);
}

bool finite_pose(const Pose2& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta);
}

bool inside(const maps::OccupancyGrid& grid, const Pose2& p) {
  double c = 0.0, r = 0.0;
  grid.global_to_cell(p.x, p.y, c, r);
  return c >= 0.0 && r >= 0.0 && c < grid.width() && r < grid.height();
}

}  // namespace

void Scenario::validate(const maps::OccupancyGrid& grid) const {
  if (grid.empty()) fail("map", "the occupancy grid is empty");
  try {
    sensor.validate();
    noise.validate();
  } catch (const std::invalid_argument& e) {
    fail("sensor/noise", e.what());
  }
  if (!finite_pose(sensor_mount)) fail("sensor_mount", "must be finite");
  if (!(scan_rate >= 0.0) || !std::isfinite(scan_rate)) fail("scan_rate", "must be >= 0 Hz");
  require_positive(control_rate, "control_rate", "(Hz)");
  require_positive(limits.max_v, "limits.max_v", "(m/s)");
  require_positive(limits.max_omega, "limits.max_omega", "(rad/s)");
  if (!(duration >= 0.0) || !std::isfinite(duration)) fail("duration", "must be >= 0 s");
  if (!finite_pose(start) || !inside(grid, start)) fail("start", "must lie inside the map");
  for (std::size_t i = 0; i < discs.size(); ++i) {
    const std::string f = "discs[" + std::to_string(i) + "]";
    require_positive(discs[i].radius, f + ".radius", "(m)");
    discs[i].path.validate("Scenario." + f + ".path");
  }
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const std::string f = "boxes[" + std::to_string(i) + "]";
    require_positive(boxes[i].half_length, f + ".half_length", "(m)");
    require_positive(boxes[i].half_width, f + ".half_width", "(m)");
    if (!std::isfinite(boxes[i].yaw)) fail(f + ".yaw", "must be finite");
    boxes[i].path.validate("Scenario." + f + ".path");
  }
  // Material names resolve (SurfaceField and Scene throw with the field name).
  const SurfaceField field(surfaces, grid);
  for (std::size_t i = 0; i < discs.size(); ++i) {
    (void)field.index_of(discs[i].material, "Scenario.discs[" + std::to_string(i) + "].material");
  }
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    (void)field.index_of(boxes[i].material, "Scenario.boxes[" + std::to_string(i) + "].material");
  }
  if (motion == MotionMode::kWaypoints) {
    require_positive(waypoints.lookahead, "waypoints.lookahead", "(m)");
    require_positive(waypoints.goal_tolerance, "waypoints.goal_tolerance", "(m)");
    require_positive(waypoints.heading_tolerance, "waypoints.heading_tolerance", "(rad)");
    for (std::size_t i = 0; i < waypoints.waypoints.size(); ++i) {
      const auto& w = waypoints.waypoints[i];
      if (!std::isfinite(w.x) || !std::isfinite(w.y)) {
        fail("waypoints.waypoints[" + std::to_string(i) + "]", "must be finite");
      }
    }
  }
  const FreeSpace free(grid, random_walk.clearance);
  if (motion == MotionMode::kRandomWalk && !free.admissible(start.x, start.y)) {
    fail("start", "a random walk must start in free space with random_walk.clearance around it");
  }
  for (std::size_t i = 0; i < kidnaps.size(); ++i) {
    const std::string f = "kidnaps[" + std::to_string(i) + "]";
    if (!(kidnaps[i].time >= 0.0) || !std::isfinite(kidnaps[i].time)) fail(f + ".time", ">= 0 s");
    if (!finite_pose(kidnaps[i].pose) || !inside(grid, kidnaps[i].pose)) {
      fail(f + ".pose", "must lie inside the map");
    }
    if (motion == MotionMode::kRandomWalk &&
        !free.admissible(kidnaps[i].pose.x, kidnaps[i].pose.y)) {
      fail(f + ".pose", "a random walk must be kidnapped into free space");
    }
  }
  const auto& o = odometry;
  if (!(o.alphas.a1 >= 0 && o.alphas.a2 >= 0 && o.alphas.a3 >= 0 && o.alphas.a4 >= 0 &&
        o.alphas.a5 >= 0)) {
    fail("odometry.alphas", "must all be >= 0 (variance form)");
  }
  if (!(o.wheel_radius_bias > -1.0) || !(o.wheelbase_bias > -1.0) ||
      !std::isfinite(o.wheel_radius_bias) || !std::isfinite(o.wheelbase_bias) ||
      !std::isfinite(o.yaw_drift_per_metre)) {
    fail("odometry", "biases must be finite and > -1, yaw_drift_per_metre finite");
  }
  if (o.origin && !finite_pose(*o.origin)) fail("odometry.origin", "must be finite");
}

std::vector<MotionSample> simulate_motion(const Scenario& sc, const maps::OccupancyGrid& grid) {
  sc.validate(grid);
  const double scan_rate = sc.effective_scan_rate();
  const double dt_control = 1.0 / sc.control_rate;
  std::vector<KidnapEvent> kidnaps = sc.kidnaps;
  std::stable_sort(kidnaps.begin(), kidnaps.end(),
                   [](const KidnapEvent& a, const KidnapEvent& b) { return a.time < b.time; });

  std::optional<WaypointFollower> follower;
  std::optional<RandomWalker> walker;
  if (sc.motion == MotionMode::kWaypoints) follower.emplace(sc.waypoints, sc.start, sc.limits);
  if (sc.motion == MotionMode::kRandomWalk) walker.emplace(sc.random_walk, grid, sc.limits);
  Rng rng = Rng::for_block(sc.seed, 0, 2);

  std::vector<MotionSample> out;
  Pose2 truth = sc.start, kinematic = sc.start;
  VelocityCommand cmd{};
  double t = 0.0;
  std::size_t k_control = 0, k_scan = 0, k_kidnap = 0;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  // Event times are computed as index / rate, so they never accumulate rounding.
  const double end = sc.duration * (1.0 + 1e-12);
  for (;;) {
    const double t_control = static_cast<double>(k_control) / sc.control_rate;
    const double t_scan = static_cast<double>(k_scan) / scan_rate;
    const double t_kidnap = k_kidnap < kidnaps.size() ? kidnaps[k_kidnap].time : kInf;
    const double t_next = std::min({t_control, t_scan, t_kidnap});
    if (t_next > end) break;
    if (t_next > t) {
      truth = integrate_diff_drive(truth, cmd, t_next - t);
      kinematic = integrate_diff_drive(kinematic, cmd, t_next - t);
      t = t_next;
    }
    if (t_kidnap == t_next) {
      truth = kidnaps[k_kidnap++].pose;
      truth.theta = wrap_angle(truth.theta);
      if (walker) walker->reset();
      continue;  // several kidnaps may share a time; the controller then sees the last
    }
    if (t_control == t_next) {
      if (follower) cmd = follower->command(truth, dt_control);
      if (walker) cmd = walker->command(truth, dt_control, rng);
      ++k_control;
    }
    if (t_scan == t_next) {
      out.push_back({t, truth, kinematic});
      ++k_scan;
    }
  }
  return out;
}

std::vector<Pose2> simulate_odometry(const Scenario& sc, const std::vector<MotionSample>& motion) {
  std::vector<Pose2> odom(motion.size());
  if (motion.empty()) return odom;
  odom[0] = sc.odometry.origin.value_or(sc.start);
  for (std::size_t k = 1; k < motion.size(); ++k) {
    const Pose2& a = motion[k - 1].kinematic;
    const Pose2& b = motion[k].kinematic;
    Pose2 inc = a.between(b);
    if (sc.odometry.random_noise) {
      Rng rng = Rng::for_block(sc.seed, k, 1);
      inc = sample_noisy_increment(sc.odometry.kind, sc.odometry.alphas, a, b, rng);
    }
    odom[k] = odom[k - 1].compose(apply_systematic_error(inc, sc.odometry));
  }
  return odom;
}

}  // namespace pgmcl::sims
