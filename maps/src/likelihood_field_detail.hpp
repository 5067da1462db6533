#pragma once
// Private to the maps library: the table builders behind LikelihoodField.
//
// All kinds are built by stamping a small precomputed kernel around obstacle cells, organised
// as a row gather: each output row collects the stamps of the obstacle cells in the rows
// within reach, so rows are independent (OpenMP over rows, no write races) and cells out of
// every obstacle's reach are written once (the background fill) and never visited again.
// A run of consecutive source cells in a row is stamped as a whole: the min of a
// quasi-convex stamp row over a window is its minimum inside the window or the window end
// nearer to it, so a run costs (length + stamp width) per stamp row, not their product.
// Only "boundary" obstacle cells are stamped (those with a non-obstacle or off-map cell among
// their 8 neighbours) when that provably gives the exact minimum, see
// interior_cells_never_nearest().

#include <array>
#include <cstdint>
#include <vector>

#include "pgmcl/maps/likelihood_field.hpp"

namespace pgmcl::maps::detail {

/// A quadratic form on cell offsets: Q(dx, dy) = a dx^2 + 2 b dx dy + c dy^2 (1/cells^2).
struct CellMetric {
  double a = 1.0, b = 0.0, c = 1.0;
  [[nodiscard]] double operator()(double dx, double dy) const noexcept {
    return a * dx * dx + 2.0 * b * dx * dy + c * dy * dy;
  }
  /// Metric of Eq. (6) for beam direction phi, sigmas in cells.
  [[nodiscard]] static CellMetric beam(double phi, double sigma_along, double sigma_across);
};

/// True when, for every offset v within reach (Q(v) < reach_m2) with max(|vx|, |vy|) >= 2,
/// some king move e gives Q(v - e) < Q(v). Then an obstacle cell whose 8 neighbours are all
/// obstacles is never the unique Q-nearest obstacle of a non-obstacle cell (its neighbour
/// o + e is nearer), so stamping boundary cells only gives the exact minimum. Always true for
/// the Euclidean metric; can fail for strongly anisotropic kernels.
[[nodiscard]] bool interior_cells_never_nearest(const CellMetric& q, double reach_m2, int reach);

/// Result of the single O(cells) pass over the grid.
struct ObstacleScan {
  /// Per row: runs [first, last] of consecutive columns to stamp, left to right.
  std::vector<std::vector<std::array<std::int32_t, 2>>> runs;
  std::size_t sources_total = 0;
};

/// How the scan initialises the table while it reads the grid.
enum class TableInit : std::uint8_t { kBytes, kOffsets };

/// Reads the grid once: fills the stamp sources (boundary cells, or
/// all obstacle cells when `all_obstacles`), and initialises the table: kBytes writes q = 0
/// on obstacles and `background` elsewhere into each of `planes` planes of `table`;
/// kOffsets writes (0, 0) on obstacles and (kNoObstacle, 0) elsewhere into `offsets`.
ObstacleScan scan_obstacles(const OccupancyGrid& grid, bool all_obstacles, TableInit init,
                            std::uint8_t* table, int planes, std::uint8_t background,
                            std::int8_t* offsets);

/// A (2R+1)^2 stamp of q values indexed by the offset v = cell - obstacle, with the span of
/// columns per stamp row that can hold a value below background. Each stamp row is
/// quasi-convex in vx (q is monotone in m2, m2 is convex in vx), with its minimum at argmin.
struct Stamp {
  int reach = 0;
  std::vector<std::uint8_t> q;  ///< q[(vy + R) * (2R + 1) + (vx + R)]
  std::vector<int> lo, hi;      ///< per vy + R: vx range with q < background (lo > hi: none)
  std::vector<int> argmin;      ///< per vy + R: a vx of the row's minimum, in [lo, hi]
};

/// Min-stamps `stamps[p]` into plane p (plane stride width * height) around every source.
/// Returns the number of cells with a non-background value in any plane.
std::size_t stamp_min(const ObstacleScan& scan, const std::vector<Stamp>& stamps, int width,
                      int height, std::uint8_t background, std::uint8_t* table);

/// Offset field: for each cell within reach_cells2 (squared cells, strict) of a source, the
/// offset (dcol, drow) to the Euclidean-nearest one. Returns the cells set.
std::size_t stamp_offsets(const ObstacleScan& scan, int reach, double reach_cells2, int width,
                          int height, std::int8_t* offsets);

}  // namespace pgmcl::maps::detail
