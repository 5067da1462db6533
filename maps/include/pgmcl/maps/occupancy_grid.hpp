#pragma once
/// Occupancy grid in ROS map_server conventions: row 0 is the bottom row (lowest y),
/// cell values are -1 (unknown), 0 (free) .. 100 (occupied).

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "pgmcl/common/se2.hpp"

namespace pgmcl::maps {

/// Cell states as in nav_msgs/OccupancyGrid.
inline constexpr std::int8_t kUnknown = -1;
inline constexpr std::int8_t kFree = 0;
inline constexpr std::int8_t kOccupied = 100;

/// A 2D occupancy grid with a metric origin.
/// The grid frame ("map-local frame") has its origin at the outer corner of cell (0, 0),
/// x along columns, y along rows. `origin` is that frame's pose in the global/map frame
/// (map_server's `origin: [x, y, yaw]`), so yaw != 0 rotates the whole grid.
class OccupancyGrid {
 public:
  OccupancyGrid() = default;
  /// Throws std::invalid_argument for non-positive sizes or resolution.
  OccupancyGrid(int width, int height, double resolution, Pose2 origin = {},
                std::int8_t fill = kUnknown);

  [[nodiscard]] int width() const noexcept { return width_; }
  [[nodiscard]] int height() const noexcept { return height_; }
  [[nodiscard]] double resolution() const noexcept { return resolution_; }  ///< metres per cell
  [[nodiscard]] const Pose2& origin() const noexcept { return origin_; }
  [[nodiscard]] std::size_t size() const noexcept { return cells_.size(); }
  [[nodiscard]] bool empty() const noexcept { return cells_.empty(); }

  [[nodiscard]] bool in_bounds(int col, int row) const noexcept {
    return col >= 0 && row >= 0 && col < width_ && row < height_;
  }
  [[nodiscard]] std::size_t index(int col, int row) const noexcept {
    return static_cast<std::size_t>(row) * static_cast<std::size_t>(width_) +
           static_cast<std::size_t>(col);
  }
  [[nodiscard]] std::int8_t at(int col, int row) const noexcept { return cells_[index(col, row)]; }
  void set(int col, int row, std::int8_t v) noexcept { cells_[index(col, row)] = v; }
  [[nodiscard]] bool occupied(int col, int row) const noexcept {
    return at(col, row) >= occupied_threshold_;
  }
  [[nodiscard]] bool free(int col, int row) const noexcept {
    const auto v = at(col, row);
    return v >= 0 && v < occupied_threshold_;
  }
  /// Cells with a value >= this count as obstacles for distance fields and ray casting.
  [[nodiscard]] std::int8_t occupied_threshold() const noexcept { return occupied_threshold_; }
  void set_occupied_threshold(std::int8_t t) noexcept { occupied_threshold_ = t; }

  [[nodiscard]] const std::vector<std::int8_t>& cells() const noexcept { return cells_; }
  [[nodiscard]] std::vector<std::int8_t>& cells() noexcept { return cells_; }

  /// Global (map-frame) pose -> map-local pose (grid frame, metres).
  [[nodiscard]] Pose2 to_local(const Pose2& global) const noexcept {
    return origin_.between(global);
  }
  /// Map-local pose -> global pose.
  [[nodiscard]] Pose2 to_global(const Pose2& local) const noexcept {
    return origin_.compose(local);
  }
  /// Global point -> fractional cell coordinates (col, row) in cell units.
  void global_to_cell(double gx, double gy, double& col, double& row) const noexcept;
  /// Centre of cell (col, row) in the global frame.
  void cell_center_global(int col, int row, double& gx, double& gy) const noexcept;

 private:
  int width_ = 0;
  int height_ = 0;
  double resolution_ = 0.05;
  Pose2 origin_{};
  std::int8_t occupied_threshold_ = 65;  // map_server's trinary output is 0/100
  std::vector<std::int8_t> cells_;
};

}  // namespace pgmcl::maps
