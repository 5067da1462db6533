#pragma once
/// Exact Euclidean distance transform of an occupancy grid, with the nearest obstacle cell.
///
/// Felzenszwalb & Huttenlocher, "Distance Transforms of Sampled Functions", Theory of
/// Computing 8 (2012), Section 2-3: the squared EDT is separable; a 1D transform along
/// every column, then the 1D lower envelope of parabolas along every row. The argmin is
/// carried through both passes, so each cell also knows which obstacle cell is nearest.
/// Distances are between cell centres, in cells; squared distances are exact integers.

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "pgmcl/maps/occupancy_grid.hpp"

namespace pgmcl::maps {

/// Result of euclidean_distance_transform(). Row-major: index = row * width + col.
struct DistanceField {
  /// Squared distance of a cell when the grid holds no obstacle at all.
  static constexpr std::uint32_t kInfinite = std::numeric_limits<std::uint32_t>::max();
  /// Nearest-obstacle index when the grid holds no obstacle at all.
  static constexpr std::int32_t kNone = -1;

  int width = 0;
  int height = 0;
  std::vector<std::uint32_t> sq_dist;  ///< cells^2 to the nearest obstacle cell centre
  std::vector<std::int32_t> nearest;   ///< row * width + col of that obstacle cell, or kNone

  [[nodiscard]] std::size_t index(int col, int row) const noexcept {
    return static_cast<std::size_t>(row) * static_cast<std::size_t>(width) +
           static_cast<std::size_t>(col);
  }
  [[nodiscard]] std::uint32_t sq_dist_at(int col, int row) const noexcept {
    return sq_dist[index(col, row)];
  }
  [[nodiscard]] std::int32_t nearest_at(int col, int row) const noexcept {
    return nearest[index(col, row)];
  }
  /// Distance in metres for a grid of resolution `resolution`; +infinity without obstacles.
  [[nodiscard]] double distance_m(int col, int row, double resolution) const noexcept;
};

/// EDT of `grid`: obstacles are cells with grid.occupied(); unknown cells are not obstacles.
/// Parallel over columns, then rows (OpenMP when available). Memory: 8 bytes per cell.
/// Throws std::length_error when width * height exceeds INT32_MAX or width^2 + height^2
/// does not fit the 32-bit squared distances.
[[nodiscard]] DistanceField euclidean_distance_transform(const OccupancyGrid& grid);

/// Same on a row-major mask (non-zero = obstacle) of width * height bytes.
/// Throws std::invalid_argument when the mask size does not match or a size is not positive.
[[nodiscard]] DistanceField euclidean_distance_transform(std::span<const std::uint8_t> obstacle,
                                                         int width, int height);

}  // namespace pgmcl::maps
