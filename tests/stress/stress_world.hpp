#pragma once
// Test-only worlds for the stress tests: rooms rasterised from rectangles at any resolution
// and origin, and laser scans from the sims ray caster on that same grid (so a scan is
// exactly consistent with the map up to the added range noise).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "pgmcl/common/laser_scan.hpp"
#include "pgmcl/common/random.hpp"
#include "pgmcl/maps/occupancy_grid.hpp"
#include "pgmcl/sims/ray_caster.hpp"
#include "pgmcl/sims/sensor_profile.hpp"

namespace pgmcl::stress {

struct Rect {
  double x0, y0, x1, y1;  // metres, map-local
};

struct Room {
  maps::OccupancyGrid grid;
  double width_m = 0.0;  // extent of the grid, metres
  double height_m = 0.0;
};

/// A room of `w` x `h` metres (inner walls 5 cm thick at 0.2 m from the grid edge) with
/// asymmetric furniture, on a grid of `res` metres placed at `origin`. Cells whose centre
/// lies in a rectangle are occupied, the room's interior is free, the rest unknown.
inline Room make_room(double w, double h, double res, const Pose2& origin = {}) {
  const double x0 = 0.2, y0 = 0.2, x1 = x0 + w, y1 = y0 + h, t = 0.05;
  const std::vector<Rect> rects = {
      {x0, y0, x1, y0 + t},
      {x0, y1 - t, x1, y1},  // bottom, top
      {x0, y0, x0 + t, y1},
      {x1 - t, y0, x1, y1},                                             // left, right
      {x0 + 0.2 * w, y0 + 0.6 * h, x0 + 0.35 * w, y0 + 0.75 * h},       // box
      {x0 + 0.7 * w, y0 + 0.1 * h, x0 + 0.78 * w, y0 + 0.2 * h},        // box
      {x0 + 0.5 * w, y0, x0 + 0.5 * w + t, y0 + 0.35 * h},              // wall stub
      {x0 + 0.5 * w, y0 + 0.35 * h - t, x0 + 0.65 * w, y0 + 0.35 * h},  // L corner
      {x0 + 0.85 * w, y0 + 0.7 * h, x0 + 0.88 * w, y0 + 0.74 * h},      // pillar
  };
  Room room;
  room.width_m = w + 0.4;
  room.height_m = h + 0.4;
  const int cols = static_cast<int>(std::lround(room.width_m / res));
  const int rows = static_cast<int>(std::lround(room.height_m / res));
  room.grid = maps::OccupancyGrid(cols, rows, res, origin, maps::kUnknown);
  for (int r = 0; r < rows; ++r) {
    const double y = (r + 0.5) * res;
    for (int c = 0; c < cols; ++c) {
      const double x = (c + 0.5) * res;
      bool occ = false;
      for (const Rect& q : rects) occ = occ || (x >= q.x0 && x <= q.x1 && y >= q.y0 && y <= q.y1);
      if (occ)
        room.grid.set(c, r, maps::kOccupied);
      else if (x > x0 && x < x1 && y > y0 && y < y1)
        room.grid.set(c, r, maps::kFree);
    }
  }
  return room;
}

/// Scans of the Hokuyo UTM-30LX (Dekan et al., Table 1: 1081 beams over 270 deg) cast on
/// `grid`, with Gaussian range noise of `sigma` metres on the hits.
class Scanner {
 public:
  explicit Scanner(const maps::OccupancyGrid& grid, double sigma = 0.0,
                   sims::SensorProfile profile = sims::utm30lx(), Pose2 mount = {0.1, 0.0, 0.0})
      : caster_(grid),
        origin_(grid.origin()),
        sigma_(sigma),
        profile_(std::move(profile)),
        mount_(mount) {}

  /// The scan seen from the robot at map-local pose `robot`.
  [[nodiscard]] LaserScan scan(const Pose2& robot, Rng& rng) const {
    std::vector<float> ranges(static_cast<std::size_t>(profile_.beam_count));
    const Pose2 sensor = origin_.compose(robot).compose(mount_);
    caster_.cast_scan(sensor, profile_.fan(), ranges);
    for (float& r : ranges) {
      if (r < static_cast<float>(profile_.range_max) && sigma_ > 0.0)
        r = static_cast<float>(std::max(0.0, r + rng.normal(sigma_)));
    }
    return profile_.make_scan(std::move(ranges), mount_);
  }
  [[nodiscard]] const sims::SensorProfile& profile() const noexcept { return profile_; }
  [[nodiscard]] const Pose2& mount() const noexcept { return mount_; }

 private:
  sims::RayCaster caster_;
  Pose2 origin_;
  double sigma_;
  sims::SensorProfile profile_;
  Pose2 mount_;
};

}  // namespace pgmcl::stress
