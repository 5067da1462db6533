#pragma once
/// overlay.png: the map with the ground truth, the estimate and the final particle cloud,
/// under a header (the run's name, its key figures, a legend) and with coordinates in
/// metres, a scale bar and, when the final cloud is too small to see on the whole map, a
/// zoomed view of it.

#include <cstddef>
#include <span>
#include <string>
#include <vector>

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

/// A moving obstacle of a simulated run: where its centre went and its footprint.
struct ObstacleDrawing {
  std::vector<Pose2> path;   ///< centre over the run, in time order; theta = a box's yaw
  double radius = 0.0;       ///< metres: a disc; 0 for a box
  double half_length = 0.0;  ///< metres, a box along its yaw
  double half_width = 0.0;   ///< metres
};

/// What overlay.png shows; any span may be empty.
struct OverlayData {
  std::span<const Pose2> truth;      ///< ground truth path (green)
  std::span<const Pose2> estimate;   ///< filter estimate path (red)
  std::span<const Pose2> particles;  ///< final particle cloud, drawn on top
  std::span<const double> weights;   ///< their weights (any scale); empty: all equal
  std::string title;                 ///< the run's name (header, first line)
  std::string subtitle;              ///< its key figures (header, second line)
  /// Estimate poses [begin, end) come from a search (a global start, a kidnap) before
  /// lock-on: drawn thin and pale, so the settled path reads.
  std::size_t search_begin = 0;
  std::size_t search_end = 0;
  std::vector<ObstacleDrawing> obstacles;  ///< simulated moving obstacles (purple)
};

/// Where render_overlay put the map and the zoomed view, in canvas pixels.
struct OverlayLayout {
  int map_x = 0, map_y = 0;  ///< top-left pixel of the map picture
  bool zoom = false;         ///< the zoomed view of the final cloud is drawn
  int zoom_x = 0, zoom_y = 0, zoom_side = 0;
  double zoom_metres = 0.0;  ///< side of the zoomed window
};

/// Colour of a particle whose weight is `relative` (0..1) of the heaviest: pale to dark.
[[nodiscard]] Rgb particle_colour(double relative) noexcept;

/// Arrow length in pixels for a picture whose longer side is `side` pixels: the same share
/// of every picture, so a 5 mm map and a 5 cm map get arrows of the same look.
[[nodiscard]] double arrow_pixels(int side) noexcept;

/// Splits a path where one step is a jump (a kidnap, a re-localisation): longer than
/// max(1 m, 10 x the median step). Returns the index of each pose that starts a new piece.
[[nodiscard]] std::vector<std::size_t> path_jumps(std::span<const Pose2> path);

[[nodiscard]] Canvas render_overlay(const maps::OccupancyGrid& grid, const OverlayData& data,
                                    OverlayLayout* layout = nullptr);
/// render_overlay + write_png; throws IoError on failure.
void write_overlay_png(const std::string& path, const maps::OccupancyGrid& grid,
                       const OverlayData& data);

}  // namespace pgmcl::app
