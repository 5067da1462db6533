#pragma once
// Analytic scenes rasterised in code for the simulator tests (no map files).

#include <algorithm>
#include <cmath>
#include <limits>

#include "pgmcl/maps/occupancy_grid.hpp"

namespace pgmcl::sims::test {

/// A rectangular room: a free interior surrounded by a `wall`-cells-thick border.
/// In the map-local frame the free interior is [wall*res, (w-wall)*res] x [wall*res,
/// (h-wall)*res].
inline maps::OccupancyGrid square_room(int w, int h, double res, Pose2 origin = {}, int wall = 1) {
  maps::OccupancyGrid g(w, h, res, origin, maps::kFree);
  for (int r = 0; r < h; ++r) {
    for (int c = 0; c < w; ++c) {
      if (c < wall || r < wall || c >= w - wall || r >= h - wall) g.set(c, r, maps::kOccupied);
    }
  }
  return g;
}

/// Sets every cell whose centre lies in the disc (cx, cy, radius) [map-local metres] to
/// `value`. Cell-centre rasterisation moves the boundary by at most half a cell diagonal.
inline void fill_disc(maps::OccupancyGrid& g, double cx, double cy, double radius,
                      std::int8_t value) {
  const double res = g.resolution();
  for (int r = 0; r < g.height(); ++r) {
    for (int c = 0; c < g.width(); ++c) {
      const double x = (c + 0.5) * res - cx, y = (r + 0.5) * res - cy;
      if (x * x + y * y <= radius * radius) g.set(c, r, value);
    }
  }
}

/// Sets the cells of the closed cell rectangle [c0, c1] x [r0, r1] to `value`.
inline void fill_cells(maps::OccupancyGrid& g, int c0, int r0, int c1, int r1, std::int8_t value) {
  for (int r = r0; r <= r1; ++r) {
    for (int c = c0; c <= c1; ++c) g.set(c, r, value);
  }
}

/// Exact oracle: distance along the ray (x, y, dx, dy) [map-local metres] to the first
/// blocking cell square, by slab tests against every blocking cell (brute force).
/// Returns infinity when nothing is hit.
inline double brute_force_range(const maps::OccupancyGrid& g, double x, double y, double dx,
                                double dy) {
  const double res = g.resolution();
  double best = std::numeric_limits<double>::infinity();
  for (int r = 0; r < g.height(); ++r) {
    for (int c = 0; c < g.width(); ++c) {
      if (!g.occupied(c, r)) continue;
      double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
      const double lo[2] = {c * res, r * res}, hi[2] = {(c + 1) * res, (r + 1) * res};
      const double o[2] = {x, y}, d[2] = {dx, dy};
      bool miss = false;
      for (int k = 0; k < 2 && !miss; ++k) {
        if (d[k] == 0.0) {
          if (o[k] < lo[k] || o[k] > hi[k]) miss = true;
          continue;
        }
        double a = (lo[k] - o[k]) / d[k], b = (hi[k] - o[k]) / d[k];
        if (a > b) std::swap(a, b);
        t0 = std::max(t0, a);
        t1 = std::min(t1, b);
        if (t0 > t1) miss = true;
      }
      if (!miss) best = std::min(best, t0);
    }
  }
  return best;
}

/// Distance from (x, y) along (dx, dy) to the inside of the axis-aligned box boundary
/// [x0, x1] x [y0, y1] (the start lies inside).
inline double range_to_box_wall(double x, double y, double dx, double dy, double x0, double y0,
                                double x1, double y1) {
  double t = std::numeric_limits<double>::infinity();
  if (dx > 0) t = std::min(t, (x1 - x) / dx);
  if (dx < 0) t = std::min(t, (x0 - x) / dx);
  if (dy > 0) t = std::min(t, (y1 - y) / dy);
  if (dy < 0) t = std::min(t, (y0 - y) / dy);
  return t;
}

/// Max-norm (L-infinity) distance from (x, y) to the circle (cx, cy, radius): the half side
/// h of the smallest axis-aligned square around (x, y) that meets the circle. Found by
/// bisection on h: a square meets the circle iff its nearest point lies inside the circle
/// and its farthest corner outside.
inline double max_norm_distance_to_circle(double x, double y, double cx, double cy, double radius) {
  auto meets = [&](double h) {
    const double nx = std::max(0.0, std::abs(x - cx) - h), ny = std::max(0.0, std::abs(y - cy) - h);
    const double fx = std::abs(x - cx) + h, fy = std::abs(y - cy) + h;
    return std::hypot(nx, ny) <= radius && std::hypot(fx, fy) >= radius;
  };
  double lo = 0.0, hi = radius + std::hypot(x - cx, y - cy);
  if (meets(lo)) return 0.0;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (meets(mid) ? hi : lo) = mid;
  }
  return hi;
}

}  // namespace pgmcl::sims::test
