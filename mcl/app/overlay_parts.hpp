#pragma once
/// Private pieces of overlay.png (png_overlay.cpp): the scene drawn in any view (whole map
/// or zoom), the header with its legend, coordinates, the scale bar, the zoomed view.

#include <functional>
#include <string>
#include <vector>

#include "pgmcl/maps/occupancy_grid.hpp"
#include "png.hpp"
#include "png_overlay.hpp"

namespace pgmcl::app::overlay {

/// Map (global) coordinates to canvas pixels for one view of the scene.
struct View {
  std::function<PixelPoint(double, double)> to_pixel;
  double angle_offset = 0.0;  ///< screen angle = theta - angle_offset (grid rotation)
  double pixels_per_metre = 1.0;
  double line_width = 1.0;
  double particle_radius = 2.0;
  double arrow_length = 20.0;
};

inline constexpr Rgb kPaleRed{240, 160, 160};
inline constexpr Rgb kRim{90, 45, 0};  ///< particle outline

/// The map's cell colour for an occupancy value (map_server grey levels).
[[nodiscard]] Rgb cell_colour(std::int8_t v, std::int8_t occupied_threshold) noexcept;

/// Obstacles, paths, start marker, final cloud and end arrows, in that order (the cloud
/// over the paths, the end arrows over the cloud).
void draw_scene(Canvas& canvas, const View& view, const OverlayData& data);

/// The 1-2-5 length (metres) nearest below `metres`.
[[nodiscard]] double nice_length(double metres) noexcept;

/// "5 m", "20 cm".
[[nodiscard]] std::string length_text(double metres);

/// A scale bar of a 1-2-5 length near a fifth of `max_pixels`, on a white box with its
/// bottom-left corner at (x, y).
void draw_scale_bar(Canvas& canvas, int x, int y, double pixels_per_metre, int max_pixels,
                    int text_scale);

/// One legend entry: what its swatch draws and its text.
struct LegendEntry {
  enum class Swatch {
    kLine,
    kThickLine,
    kDashed,
    kDotted,
    kStart,
    kArrow,
    kParticles,
    kObstacle,
    kScaleBar
  };
  Swatch swatch;
  Rgb colour;
  std::string label;
  double length = 0.0;  ///< kScaleBar: the bar's length in pixels
};

/// Header lines (title, subtitle) and the legend flowing over rows `width` pixels wide.
/// Returns the height used; draws only when `canvas` is not null.
int draw_header(Canvas* canvas, int width, const std::string& title, const std::string& subtitle,
                const std::vector<LegendEntry>& legend, int text_scale);

/// The zoomed view: a square of `side` pixels covering `metres` around `centre` (global),
/// in the grid's own orientation, with its own scale bar and caption.
[[nodiscard]] Canvas render_zoom(const maps::OccupancyGrid& grid, const OverlayData& data,
                                 const Pose2& centre, double metres, int side, int text_scale);

}  // namespace pgmcl::app::overlay
