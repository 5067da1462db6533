#pragma once
/// `pgmcl perturb-map`'s map conditions, on an occupancy grid (cells -1, 0 .. 100). Applied
/// in this order by the command: erase_blocks, thicken_walls, blur_known_cells.

#include <cstddef>

#include "pgmcl/common/random.hpp"
#include "pgmcl/maps/occupancy_grid.hpp"

namespace pgmcl::app {

struct EraseResult {
  std::size_t blocks_with_walls = 0;  ///< blocks holding at least one occupied cell
  std::size_t blocks_erased = 0;      ///< round(fraction * blocks_with_walls) of them
  std::size_t cells_erased = 0;       ///< occupied cells turned free
};

/// Sparse structure: the grid is tiled into block x block cells from cell (0, 0); of the
/// blocks holding occupied cells (grid.occupied()), round(fraction * count) chosen uniformly
/// at random have every occupied cell set free (walls missing from the map that the scans
/// still see). fraction in [0, 1], block >= 1.
EraseResult erase_blocks(maps::OccupancyGrid& grid, int block, double fraction, Rng& rng);

/// Dilation: every known cell within `cells` cells (Chebyshev distance, a square of side
/// 2 * cells + 1) of an occupied cell becomes occupied (100). Unknown cells stay unknown.
/// Returns the number of cells made occupied.
std::size_t thicken_walls(maps::OccupancyGrid& grid, int cells);

/// Gaussian blur of the occupancy probability p = v / 100 over the known cells only (a
/// normalised convolution: unknown cells neither contribute nor change), sigma in cells,
/// kernel truncated at ceil(3 sigma); the result is written back as round(100 p). sigma > 0.
void blur_known_cells(maps::OccupancyGrid& grid, double sigma);

}  // namespace pgmcl::app
