#pragma once
// Test-only readers of the likelihood tables: q as the production kernels read it for one
// endpoint, and the exact (unquantised) model against the Mahalanobis-nearest obstacle.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "pgmcl/maps/likelihood_field.hpp"
#include "pgmcl/maps/occupancy_grid.hpp"
#include "pgmcl/maps/table_kernels.hpp"
#include "pgmcl/sensor_model/beam_likelihood.hpp"

namespace pgmcl::testkit {

// q the table kernels read for an endpoint at fractional cell (col, row) of a beam pointing
// at `direction` (radians, grid frame): a one-beam scan at a pose with heading 0.
inline std::uint8_t table_q(const maps::LikelihoodField& f, float col, float row,
                            double direction) {
  const float ex = 0.0f, ey = 0.0f;
  const auto ux = static_cast<float>(std::cos(direction));
  const auto uy = static_cast<float>(std::sin(direction));
  const float bin = f.kind() == maps::TableKind::kOrientedBins
                        ? maps::direction_in_bins(direction, f.oriented().bins)
                        : 0.0f;
  const maps::BeamArrays beams{&ex, &ey, &ux, &uy, &bin, 1, 0.0f};
  std::uint32_t q = 0;
  maps::with_kernel(f, beams, 0, [&](const auto& k) {
    q = k.template score<false, true>(col, row, 0.0f, nullptr);
  });
  return static_cast<std::uint8_t>(q);
}

// The direction (radians) at the centre of plane `bin` of an oriented table.
inline double bin_centre(const maps::LikelihoodField& f, int bin) {
  return (bin + 0.5) * std::numbers::pi / f.oriented().bins;
}

// Plain per-beam readers of each table kind, one endpoint at fractional cell (col, row) at a
// time: the straightforward code the kernels' chunked passes must reproduce byte for byte.
inline bool off_map(int c, int r, int width, int height) {
  return static_cast<unsigned>(c) >= static_cast<unsigned>(width) ||
         static_cast<unsigned>(r) >= static_cast<unsigned>(height);
}
inline std::uint8_t reference_q(const maps::IsotropicView& v, float col, float row) {
  const int c = maps::floor_to_cell(col), r = maps::floor_to_cell(row);
  if (off_map(c, r, v.width, v.height)) return v.background;
  return v.q[static_cast<std::size_t>(r) * static_cast<std::size_t>(v.width) +
             static_cast<std::size_t>(c)];
}
inline std::uint8_t reference_q(const maps::OrientedView& v, float col, float row, int bin) {
  const int c = maps::floor_to_cell(col), r = maps::floor_to_cell(row);
  if (off_map(c, r, v.width, v.height)) return v.background;
  return v.q[static_cast<std::size_t>(bin) * v.plane_stride +
             static_cast<std::size_t>(r) * static_cast<std::size_t>(v.width) +
             static_cast<std::size_t>(c)];
}
// (ux, uy): the unit beam direction in the grid frame.
inline std::uint8_t reference_q(const maps::OffsetView& v, float col, float row, float ux,
                                float uy) {
  const int c = maps::floor_to_cell(col), r = maps::floor_to_cell(row);
  if (off_map(c, r, v.width, v.height)) return v.background;
  const std::size_t i = 2 * (static_cast<std::size_t>(r) * static_cast<std::size_t>(v.width) +
                             static_cast<std::size_t>(c));
  if (v.off[i] == maps::OffsetView::kNoObstacle) return v.background;
  const float dx = static_cast<float>(c + v.off[i]) + 0.5f - col;
  const float dy = static_cast<float>(r + v.off[i + 1]) + 0.5f - row;
  const float along = dx * ux + dy * uy, across = dy * ux - dx * uy;
  const float idx =
      (along * along * v.inv_var_along + across * across * v.inv_var_across) * v.lut_steps_per_unit;
  return idx < static_cast<float>(v.lut_size - 1) ? v.lut[static_cast<int>(idx)]
                                                  : v.lut[v.lut_size - 1];
}

// The exact model for an endpoint at map-local metres (x, y) and a beam direction (radians):
// the obstacle cell centre of smallest Mahalanobis distance within the model's reach, through
// sensor_model::BeamLikelihood. Outside the map it still evaluates the model.
class ExactLikelihood {
 public:
  ExactLikelihood(const maps::OccupancyGrid& grid, const sensor_model::BeamLikelihood& model)
      : grid_(&grid), model_(&model) {}

  [[nodiscard]] double operator()(double x, double y, double direction) const {
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(direction))
      throw std::invalid_argument("ExactLikelihood: non-finite input");
    const double res = grid_->resolution();
    const double cs = std::cos(direction), sn = std::sin(direction);
    // Every obstacle with m2 < reach^2 lies within reach_sigmas * max(sigma) of the endpoint.
    const double r = model_->reach_sigmas() *
                         std::max(model_->sigma_along_eff(), model_->sigma_across_eff()) / res +
                     1.0;
    const double cx = x / res, cy = y / res;
    const double c0 = std::max(std::floor(cx - r), 0.0);
    const double c1 = std::min(std::ceil(cx + r), static_cast<double>(grid_->width() - 1));
    const double r0 = std::max(std::floor(cy - r), 0.0);
    const double r1 = std::min(std::ceil(cy + r), static_cast<double>(grid_->height() - 1));
    double best = std::numeric_limits<double>::infinity();
    if (c0 <= c1 && r0 <= r1) {
      for (auto row = static_cast<int>(r0); row <= static_cast<int>(r1); ++row)
        for (auto col = static_cast<int>(c0); col <= static_cast<int>(c1); ++col) {
          if (!grid_->occupied(col, row)) continue;
          const double dx = (col + 0.5) * res - x, dy = (row + 0.5) * res - y;
          best = std::min(best, model_->mahalanobis_sq(dx * cs + dy * sn, -dx * sn + dy * cs));
        }
    }
    return model_->log_likelihood_of_m2(best);
  }

 private:
  const maps::OccupancyGrid* grid_;
  const sensor_model::BeamLikelihood* model_;
};

}  // namespace pgmcl::testkit
