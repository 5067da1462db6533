#pragma once
// Test-only synthetic world for the engine's closed-loop tests: a room of axis-aligned
// rectangles (in the map-local frame), its rasterised occupancy grid, an exact ray caster
// against the rectangles (the "true world", so the map's discretisation error is real),
// and a loop trajectory with noisy odometry. Independent of sims/ on purpose.

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "drive_path.hpp"
#include "pgmcl/common/laser_scan.hpp"
#include "pgmcl/common/motion_model.hpp"
#include "pgmcl/common/random.hpp"
#include "pgmcl/maps/occupancy_grid.hpp"

namespace pgmcl::test {

struct Rect {
  double x0, y0, x1, y1;  // metres, map-local
  [[nodiscard]] bool contains(double x, double y) const noexcept {
    return x >= x0 && x <= x1 && y >= y0 && y <= y1;
  }
};

struct ScanSpec {
  std::size_t beams = 1081;
  double fov = 1.5 * std::numbers::pi;  // 270 deg, like the Hokuyo UTM-30LX
  double range_min = 0.1;
  double range_max = 30.0;
  double noise_sigma = 0.0;  // metres, Gaussian range noise
  Pose2 sensor_pose{0.2, 0.0, 0.0};
};

struct World {
  std::vector<Rect> rects;
  maps::OccupancyGrid grid;

  // Distance from (x, y) along `angle` to the first rectangle (slab method), or +inf.
  [[nodiscard]] double raycast(double x, double y, double angle) const noexcept {
    const double dx = std::cos(angle), dy = std::sin(angle);
    double best = std::numeric_limits<double>::infinity();
    for (const Rect& r : rects) {
      double t0 = 0.0, t1 = best;
      const double o[2] = {x, y}, d[2] = {dx, dy}, lo[2] = {r.x0, r.y0}, hi[2] = {r.x1, r.y1};
      bool hit = true;
      for (int a = 0; a < 2 && hit; ++a) {
        if (std::abs(d[a]) < 1e-12) {
          hit = o[a] >= lo[a] && o[a] <= hi[a];
        } else {
          double ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
          if (ta > tb) std::swap(ta, tb);
          t0 = std::max(t0, ta);
          t1 = std::min(t1, tb);
          hit = t0 <= t1;
        }
      }
      if (hit && t0 < best) best = t0;
    }
    return best;
  }

  // Scan seen from the robot at map-local pose `robot`.
  [[nodiscard]] LaserScan scan(const Pose2& robot, const ScanSpec& spec, Rng* rng = nullptr) const {
    LaserScan s;
    s.angle_min = -spec.fov / 2;
    s.angle_increment = spec.fov / static_cast<double>(spec.beams - 1);
    s.range_min = spec.range_min;
    s.range_max = spec.range_max;
    s.sensor_pose = spec.sensor_pose;
    const Pose2 sensor = robot.compose(spec.sensor_pose);
    s.ranges.resize(spec.beams);
    for (std::size_t i = 0; i < spec.beams; ++i) {
      double r = raycast(sensor.x, sensor.y, sensor.theta + s.beam_angle(i));
      if (rng != nullptr && spec.noise_sigma > 0.0 && std::isfinite(r))
        r += rng->normal(spec.noise_sigma);
      s.ranges[i] =
          r < spec.range_max ? static_cast<float>(r) : std::numeric_limits<float>::infinity();
    }
    return s;
  }
};

// Marks a cell occupied when it overlaps a rectangle, as a map built from scans would
// (the cell holding the hit is occupied), so surfaces fall inside boundary cells rather
// than on their edges; cells inside the free region become free, the rest stay unknown.
inline void rasterise(World& w, const Rect& free_region) {
  const double res = w.grid.resolution();
  for (int r = 0; r < w.grid.height(); ++r) {
    for (int c = 0; c < w.grid.width(); ++c) {
      const double x0 = c * res, y0 = r * res, x1 = x0 + res, y1 = y0 + res;
      bool occ = false;
      for (const Rect& rect : w.rects)
        occ = occ || (x0 < rect.x1 && x1 > rect.x0 && y0 < rect.y1 && y1 > rect.y0);
      if (occ)
        w.grid.set(c, r, maps::kOccupied);
      else if (free_region.contains(x0 + 0.5 * res, y0 + 0.5 * res))
        w.grid.set(c, r, maps::kFree);
    }
  }
}

// A 10 m x 8 m room (map-local [0.5, 10.5] x [0.5, 8.5]) with asymmetric furniture, on a
// grid of the given resolution covering [0, 11] x [0, 9], placed at `origin` globally.
// All coordinates are shifted by (13, 31) mm so no surface lies on a 5 cm cell edge.
inline World make_room(double resolution, const Pose2& origin = {}) {
  World w;
  w.rects = {
      {0.5, 0.5, 10.5, 0.6}, {0.5, 8.4, 10.5, 8.5},   // bottom, top walls
      {0.5, 0.5, 0.6, 8.5},  {10.4, 0.5, 10.5, 8.5},  // left, right walls
      {2.5, 5.5, 3.5, 7.0},                           // box A
      {7.0, 1.0, 7.7, 1.5},                           // box B
      {4.5, 0.6, 4.6, 3.5},  {4.5, 3.4, 6.5, 3.5},    // L-shaped wall
      {8.0, 6.0, 8.3, 6.3},                           // pillar
      {1.2, 2.0, 1.6, 2.3},                           // small box C
  };
  for (Rect& r : w.rects) {
    r.x0 += 0.013, r.x1 += 0.013;
    r.y0 += 0.031, r.y1 += 0.031;
  }
  w.grid = maps::OccupancyGrid(static_cast<int>(std::lround(11.0 / resolution)),
                               static_cast<int>(std::lround(9.0 / resolution)), resolution, origin,
                               maps::kUnknown);
  rasterise(w, {0.613, 0.631, 10.413, 8.431});
  return w;
}

// A small 4 m x 3 m room for fine maps (5 mm cells stay ~0.6 M cells).
inline World make_small_room(double resolution, const Pose2& origin = {}) {
  World w;
  w.rects = {
      {0.2, 0.2, 4.2, 0.25}, {0.2, 3.15, 4.2, 3.2}, {0.2, 0.2, 0.25, 3.2},
      {4.15, 0.2, 4.2, 3.2}, {1.0, 2.2, 1.6, 2.6},  {3.0, 0.6, 3.3, 1.0},
  };
  w.grid = maps::OccupancyGrid(static_cast<int>(std::lround(4.4 / resolution)),
                               static_cast<int>(std::lround(3.4 / resolution)), resolution, origin,
                               maps::kUnknown);
  rasterise(w, {0.25, 0.25, 4.15, 3.15});
  return w;
}

// Ground-truth poses (map-local) along a closed loop through the big room's free space:
// rotate in place towards the next waypoint in <= `turn_step` increments, then drive in
// <= `step` increments.
inline std::vector<Pose2> loop_trajectory(double step = 0.1, double turn_step = 0.15) {
  return testkit::waypoint_path(
      {{2.0, 4.5}, {9.0, 4.5}, {9.0, 7.6}, {5.0, 7.6}, {1.5, 7.6}, {1.5, 4.5}, {2.0, 4.5}}, step,
      turn_step);
}

// Noisy odometry for a ground-truth path: each increment is perturbed by the motion model.
inline std::vector<Pose2> noisy_odometry(const std::vector<Pose2>& truth, const MotionNoise& noise,
                                         std::uint64_t seed,
                                         const Pose2& odom_start = {1.0, -2.0, 0.3}) {
  return testkit::noisy_odometry(truth, noise, seed, odom_start);
}

// Eight 40 cm "people" the map does not show, 0.9-1.7 m around `robot` (two draws of `rng`
// each), added to `scene`: they hide most of the walls.
inline void add_crowd(World& scene, const Pose2& robot, Rng& rng) {
  for (int i = 0; i < 8; ++i) {
    const double angle = robot.theta + 2.0 * std::numbers::pi * (i + 0.3 * rng.uniform()) / 8.0;
    const double d = 0.9 + 0.8 * rng.uniform();
    const double x = robot.x + d * std::cos(angle), y = robot.y + d * std::sin(angle);
    scene.rects.push_back({x - 0.2, y - 0.2, x + 0.2, y + 0.2});
  }
}

}  // namespace pgmcl::test
