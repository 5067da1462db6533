#include "pgmcl/maps/occupancy_grid.hpp"

namespace pgmcl::maps {

OccupancyGrid::OccupancyGrid(int width, int height, double resolution, Pose2 origin,
                             std::int8_t fill)
    : width_(width), height_(height), resolution_(resolution), origin_(origin) {
  if (width <= 0 || height <= 0) {
    throw std::invalid_argument("OccupancyGrid: width and height must be positive (got " +
                                std::to_string(width) + " x " + std::to_string(height) + ")");
  }
  if (!(resolution > 0.0) || !std::isfinite(resolution)) {
    throw std::invalid_argument("OccupancyGrid: resolution must be a positive finite number");
  }
  origin_.theta = wrap_angle(origin_.theta);
  cells_.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), fill);
}

void OccupancyGrid::global_to_cell(double gx, double gy, double& col, double& row) const noexcept {
  double lx = 0.0, ly = 0.0;
  origin_.inverse().transform_point(gx, gy, lx, ly);
  col = lx / resolution_;
  row = ly / resolution_;
}

void OccupancyGrid::cell_center_global(int col, int row, double& gx, double& gy) const noexcept {
  origin_.transform_point((col + 0.5) * resolution_, (row + 0.5) * resolution_, gx, gy);
}

}  // namespace pgmcl::maps
