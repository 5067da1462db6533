#pragma once
// Helpers shared by the pgmcl::io tests: bundled data paths, scratch files, exact comparisons.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "pgmcl/common/se2.hpp"
#include "pgmcl/maps/occupancy_grid.hpp"
#include "temp_files.hpp"

namespace pgmcl::io::test {

inline std::string data_path(const std::string& rel) {
  // Appended piece by piece: GCC 12 reports a false -Warray-bounds for
  // std::string(PGMCL_SOURCE_DIR) + "..." (seen with a 16-character checkout path).
  std::string path = PGMCL_SOURCE_DIR;
  path += "/data/";
  path += rel;
  return path;
}

using testkit::TempDir;

/// A `width` x `height` grid of free cells at `resolution` metres, placed at `origin`, whose
/// border cells are occupied: an empty walled room.
inline maps::OccupancyGrid walled_room(int width, int height, double resolution,
                                       const Pose2& origin) {
  maps::OccupancyGrid g(width, height, resolution, origin, maps::kFree);
  for (int c = 0; c < g.width(); ++c) {
    g.set(c, 0, maps::kOccupied);
    g.set(c, g.height() - 1, maps::kOccupied);
  }
  for (int r = 0; r < g.height(); ++r) {
    g.set(0, r, maps::kOccupied);
    g.set(g.width() - 1, r, maps::kOccupied);
  }
  return g;
}

/// Bit-identical, with NaN equal to NaN.
inline bool same(double a, double b) {
  return (std::isnan(a) && std::isnan(b)) || a == b;
}

inline ::testing::AssertionResult same_pose(const Pose2& a, const Pose2& b) {
  if (same(a.x, b.x) && same(a.y, b.y) && same(a.theta, b.theta)) {
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << "(" << a.x << ", " << a.y << ", " << a.theta << ") != ("
                                       << b.x << ", " << b.y << ", " << b.theta << ")";
}

}  // namespace pgmcl::io::test
