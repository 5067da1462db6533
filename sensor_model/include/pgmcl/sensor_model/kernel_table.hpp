#pragma once
/// Tabular form of the planar beam model (Dekan et al., Sec. 5, Table 5): the probability
/// mass of Eq. (6) over the cells around a beam endpoint, for any sigmas, cell size, beam
/// angle and radius.
///
/// Layout of the returned table (differs from the paper's print, read this): map frame,
/// row-major, row index = dy + r (map y), column index = dx + r (map x), so
/// mass[(dy + r) * (2r + 1) + (dx + r)] is the cell dx columns and dy rows from the endpoint
/// cell. At beam_angle = 0 the beam points along +x, so along-beam neighbours are dx = +/-1.
/// Dekan et al. print Table 5 with the along-beam offset vertical (their x = 41 neighbour of
/// x = 40 is the 0.1629 entry below the centre), i.e. paper[i][j] == table.at(i - 1, j - 1)
/// at beam angle 0: the paper's table is the transpose of ours.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "pgmcl/sensor_model/paper_constants.hpp"

namespace pgmcl::sensor_model {

enum class Discretisation : std::uint8_t {
  /// Eq. (6) evaluated at each cell centre, normalised over the table.
  kPointwise,
  /// Eq. (6) integrated over each cell (see gaussian_rect_mass), normalised over the table.
  kCellIntegrated,
};

struct KernelSpec {
  double sigma_along = paper::kSigmaAlong;    ///< m, along the beam (Sec. 5: 5.6894 mm)
  double sigma_across = paper::kSigmaAcross;  ///< m, across the beam (Sec. 5: 3 mm)
  double cell_size = paper::kTable5CellSize;  ///< m (Table 5: 5 mm)
  double beam_angle = 0.0;                    ///< rad, map frame, any value
  int radius = 1;                             ///< cells; the table is (2r+1) x (2r+1), r <= 1000
  Discretisation discretisation = Discretisation::kCellIntegrated;
  /// Gaussian mean relative to the centre of the endpoint cell, map frame, metres, each within
  /// [-cell_size/2, cell_size/2]. The paper centres the Gaussian on the cell (0, 0).
  double offset_x = 0.0;
  double offset_y = 0.0;

  /// Throws std::invalid_argument naming the offending field.
  void validate() const;
};

struct KernelTable {
  int radius = 0;
  std::vector<double> mass;  ///< normalised to sum 1; layout in the file comment
  /// Mass before normalising: for kCellIntegrated the exact fraction of Eq. (6) inside the
  /// table; for kPointwise the Riemann sum of pdf * cell_size^2 (an approximation of it).
  double captured_mass = 0.0;

  [[nodiscard]] int side() const noexcept { return 2 * radius + 1; }
  /// Mass of the cell (dx, dy) cells from the endpoint cell; |dx|, |dy| <= radius.
  [[nodiscard]] double at(int dx, int dy) const noexcept {
    return mass[static_cast<std::size_t>((dy + radius) * side() + (dx + radius))];
  }
};

/// Builds the table for `spec` (validated first).
[[nodiscard]] KernelTable make_kernel_table(const KernelSpec& spec);

/// Probability that a point drawn from Eq. (6) -- zero mean, sigma_along along the direction
/// beam_angle, sigma_across perpendicular to it -- falls in the map-frame rectangle
/// [x0, x1] x [y0, y1] (metres; x0 <= x1, y0 <= y1).
///
/// A rotated Gaussian is not separable in map axes, so: the inner integral over y is closed
/// form (the conditional of y given x is Gaussian; erfc), the outer integral over x uses
/// composite 8-point Gauss-Legendre on panels no wider than half the integrand's length scale
/// (min of the x-marginal sigma and the conditional sigma / |slope|), clipped to +/- 10
/// marginal sigmas. Accuracy: absolute error < 1e-13 against the erf closed form at 0 and
/// 90 deg and for isotropic sigmas at any angle (unit tests); about 1e-15 against a 2001^2
/// Simpson rule at 30-155 deg (checked once; the unit test's coarser Simpson asserts 1e-9
/// relative).
[[nodiscard]] double gaussian_rect_mass(double sigma_along, double sigma_across, double beam_angle,
                                        double x0, double x1, double y0, double y1) noexcept;

}  // namespace pgmcl::sensor_model
