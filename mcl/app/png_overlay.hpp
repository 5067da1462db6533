#pragma once
/// overlay.png: the map in grey levels with the ground truth, the estimate and the final
/// particle cloud drawn over it.

#include <span>
#include <string>

#include "pgmcl/common/se2.hpp"
#include "pgmcl/maps/occupancy_grid.hpp"
#include "png.hpp"

namespace pgmcl::app {

/// Maps global (map-frame) coordinates to pixels of a picture of the whole grid.
/// Small grids are magnified by an integer factor up to `min_side` pixels; large ones are
/// shrunk to at most `max_side` pixels (an occupied cell in a block wins, so thin walls
/// survive the shrinking).
class MapFrame {
 public:
  explicit MapFrame(const maps::OccupancyGrid& grid, int max_side = 2000, int min_side = 800);

  [[nodiscard]] int width() const noexcept { return width_; }
  [[nodiscard]] int height() const noexcept { return height_; }
  [[nodiscard]] double pixels_per_cell() const noexcept { return scale_; }
  [[nodiscard]] double pixels_per_metre() const noexcept { return scale_ / grid_->resolution(); }
  /// Global point -> pixel (fractional).
  [[nodiscard]] PixelPoint to_pixel(double x, double y) const noexcept;
  /// Global heading -> on-screen angle for Canvas::arrow (the grid may be rotated).
  [[nodiscard]] double to_screen_angle(double theta) const noexcept {
    return theta - grid_->origin().theta;
  }
  /// The map in grey levels: free white, occupied black, unknown grey (map_server colours).
  [[nodiscard]] Canvas draw_map() const;

 private:
  const maps::OccupancyGrid* grid_;
  double scale_ = 1.0;  // pixels per cell
  int width_ = 0;
  int height_ = 0;
};

/// What overlay.png shows; any span may be empty.
struct OverlayData {
  std::span<const Pose2> truth;      ///< ground truth path (green)
  std::span<const Pose2> estimate;   ///< filter estimate path (red), final pose as an arrow
  std::span<const Pose2> particles;  ///< final particle cloud (orange dots)
  std::string title;                 ///< drawn in the top-left corner
};

[[nodiscard]] Canvas render_overlay(const maps::OccupancyGrid& grid, const OverlayData& data);
/// render_overlay + write_png; throws IoError on failure.
void write_overlay_png(const std::string& path, const maps::OccupancyGrid& grid,
                       const OverlayData& data);

}  // namespace pgmcl::app
