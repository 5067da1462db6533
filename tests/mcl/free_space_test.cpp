// FreeSpace (mcl/src/free_space.hpp): the rays of a scan that cross cells the map does not
// show as free. Sphere tracing over the clearance grid must count (and name) exactly what a
// fine walk along every ray counts, and a scan seen from the right pose crosses no wall while the
// same scan from a pose beyond a wall crosses many.
#include "free_space.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <utility>
#include <vector>

#include "pgmcl/common/random.hpp"
#include "pgmcl/mcl/localizer.hpp"
#include "synthetic_world.hpp"

namespace pgmcl {
namespace {

constexpr double kRes = 0.05;
constexpr float kMargin = 3.0f;  // cells

// The oracle: a ray is blocked when its segment up to the margin meets the square of any
// cell that is not free (slab test against every cell of its bounding box, off-map cells
// included).
bool segment_meets_cell(double x0, double y0, double x1, double y1, int col, int row) {
  double t0 = 0.0, t1 = 1.0;
  const double o[2] = {x0, y0}, d[2] = {x1 - x0, y1 - y0};
  const double lo[2] = {static_cast<double>(col), static_cast<double>(row)};
  for (int a = 0; a < 2; ++a) {
    if (std::abs(d[a]) < 1e-12) {
      if (o[a] < lo[a] || o[a] > lo[a] + 1.0) return false;
      continue;
    }
    double ta = (lo[a] - o[a]) / d[a], tb = (lo[a] + 1.0 - o[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  return true;
}

std::size_t walked(const maps::OccupancyGrid& grid, const Pose2& pose, const PreparedBeams& b,
                   float sensor_x, float sensor_y) {
  const double c = std::cos(pose.theta), s = std::sin(pose.theta);
  const double px = pose.x / kRes, py = pose.y / kRes;
  const double sx = px + c * sensor_x - s * sensor_y, sy = py + s * sensor_x + c * sensor_y;
  std::size_t blocked = 0;
  for (std::size_t j = 0; j < b.size(); ++j) {
    const double ex = px + c * b.ex[j] - s * b.ey[j], ey = py + s * b.ex[j] + c * b.ey[j];
    const double len = std::hypot(ex - sx, ey - sy), stop = len - kMargin;
    if (!(stop > 0.0)) continue;
    const double qx = sx + (ex - sx) * stop / len, qy = sy + (ey - sy) * stop / len;
    bool hit = false;
    for (int row = static_cast<int>(std::floor(std::min(sy, qy)));
         !hit && row <= static_cast<int>(std::floor(std::max(sy, qy))); ++row)
      for (int col = static_cast<int>(std::floor(std::min(sx, qx)));
           !hit && col <= static_cast<int>(std::floor(std::max(sx, qx))); ++col)
        hit = !(grid.in_bounds(col, row) && grid.free(col, row)) &&
              segment_meets_cell(sx, sy, qx, qy, col, row);
    blocked += hit ? 1 : 0;
  }
  return blocked;
}

// Endpoints of the beams a scanner at `pose` would see in `world`, in the base frame (cells).
PreparedBeams beams_seen_from(const test::World& world, const Pose2& pose, float sensor_x,
                              int count) {
  PreparedBeams b;
  for (int k = 0; k < count; ++k) {
    const double a = -std::numbers::pi + 2.0 * std::numbers::pi * (k + 0.5) / count;
    const double sxm = pose.x + std::cos(pose.theta) * sensor_x * kRes;
    const double sym = pose.y + std::sin(pose.theta) * sensor_x * kRes;
    const double r = world.raycast(sxm, sym, pose.theta + a);
    b.ex.push_back(static_cast<float>(sensor_x + r * std::cos(a) / kRes));
    b.ey.push_back(static_cast<float>(r * std::sin(a) / kRes));
  }
  return b;
}

TEST(FreeSpace, SphereTracingCountsWhatAnExactSegmentTestCounts) {
  const test::World world = test::make_room(kRes);
  const std::vector<std::uint32_t> free = free_cell_indices(world.grid);
  const detail::FreeSpace fs(world.grid.width(), world.grid.height(), kRes, free, kMargin);
  Rng rng(3);
  std::size_t total = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const Pose2 pose{rng.uniform() * 11.0, rng.uniform() * 9.0,
                     (rng.uniform() * 2.0 - 1.0) * std::numbers::pi};
    PreparedBeams b;
    for (int k = 0; k < 20; ++k) {  // random endpoints up to 6 m away
      const double a = rng.uniform() * 2.0 * std::numbers::pi, r = rng.uniform() * 120.0;
      b.ex.push_back(static_cast<float>(r * std::cos(a)));
      b.ey.push_back(static_cast<float>(r * std::sin(a)));
    }
    const std::size_t want = walked(world.grid, pose, b, 4.0f, 0.0f);
    EXPECT_EQ(fs.blocked_beams(pose, b, 4.0f, 0.0f), want) << "trial " << trial;
    // The same beams by index: each one alone is blocked by the oracle.
    std::vector<std::uint32_t> which;
    fs.blocked_beam_indices(pose, b, 4.0f, 0.0f, which);
    EXPECT_EQ(which.size(), want) << "trial " << trial;
    for (const std::uint32_t j : which) {
      PreparedBeams one;
      one.ex = {b.ex[j]};
      one.ey = {b.ey[j]};
      EXPECT_EQ(walked(world.grid, pose, one, 4.0f, 0.0f), 1u)
          << "trial " << trial << " beam " << j;
    }
    total += want;
  }
  EXPECT_GT(total, 200u);  // the random rays do cross walls
}

TEST(FreeSpace, RightPoseCrossesNoWallAPoseBeyondOneCrossesMany) {
  const test::World world = test::make_room(kRes);
  const std::vector<std::uint32_t> free = free_cell_indices(world.grid);
  const detail::FreeSpace fs(world.grid.width(), world.grid.height(), kRes, free, kMargin);
  const Pose2 truth{3.0, 2.5, 0.3};
  const PreparedBeams b = beams_seen_from(world, truth, 4.0f, 120);
  const std::size_t right = fs.blocked_beams(truth, b, 4.0f, 0.0f);
  // Two metres to the right, behind the L-shaped wall: the scan passes through it.
  const std::size_t beyond = fs.blocked_beams({truth.x + 2.0, truth.y, truth.theta}, b, 4.0f, 0.0f);
  std::printf("  blocked rays of 120: %zu at the right pose, %zu beyond the wall\n", right, beyond);
  EXPECT_LE(right, 6u);  // a twentieth: rays grazing a wall's rasterised cells
  EXPECT_GE(beyond, 30u);
  EXPECT_TRUE(fs.is_free(truth.x, truth.y));
  EXPECT_FALSE(fs.is_free(4.56, 2.0));  // inside the L-shaped wall
  EXPECT_FALSE(fs.is_free(-1.0, 2.0));  // off the map
}

}  // namespace
}  // namespace pgmcl
