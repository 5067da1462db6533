#include "png_overlay.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "overlay_parts.hpp"
#include "plot.hpp"

namespace pgmcl::app {
namespace {

/// The smallest 1-2-5 length at or above `metres`.
double nice_up(double metres) {
  double v = overlay::nice_length(metres);
  while (v < metres * (1.0 - 1e-12)) v = overlay::nice_length(v * 2.5 + 1e-12);
  return v;
}

/// Where the zoomed view goes and how wide it is; zoom stays false when the cloud is big
/// enough on the whole map (or there is none).
struct ZoomChoice {
  bool zoom = false;
  Pose2 centre{};
  double metres = 0.0;
};

ZoomChoice choose_zoom(const MapFrame& frame, const OverlayData& data, int side) {
  ZoomChoice z;
  if (data.particles.empty()) return z;
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (const Pose2& p : data.particles) {
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x);
    y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
  }
  z.metres = nice_up(std::max(1.0, 2.5 * std::max(x1 - x0, y1 - y0)));
  // Worth it when the window is magnified at least three times.
  if (z.metres * frame.pixels_per_metre() * 3.0 > side) return z;
  z.zoom = true;
  z.centre =
      !data.estimate.empty() ? data.estimate.back() : Pose2{(x0 + x1) / 2.0, (y0 + y1) / 2.0, 0.0};
  return z;
}

std::vector<overlay::LegendEntry> legend_of(const OverlayData& data, bool has_jumps,
                                            const MapFrame& frame) {
  using E = overlay::LegendEntry;
  std::vector<E> l;
  const double bar = overlay::nice_length(0.15 * frame.width() / frame.pixels_per_metre());
  l.push_back({E::Swatch::kScaleBar, colors::kBlack, overlay::length_text(bar),
               bar * frame.pixels_per_metre()});
  if (!data.truth.empty()) l.push_back({E::Swatch::kThickLine, colors::kGreen, "ground truth"});
  if (!data.estimate.empty()) l.push_back({E::Swatch::kLine, colors::kRed, "estimate"});
  if (data.search_end > data.search_begin)
    l.push_back({E::Swatch::kLine, overlay::kPaleRed, "estimate before lock-on"});
  if (has_jumps)
    l.push_back({E::Swatch::kDotted, colors::kBlack, "jump (kidnap or re-localisation)"});
  if (!data.truth.empty() || !data.estimate.empty()) {
    l.push_back({E::Swatch::kStart, colors::kBlack, "start"});
    l.push_back({E::Swatch::kArrow, colors::kDarkGrey, "end and heading"});
  }
  if (!data.particles.empty()) {
    l.push_back({E::Swatch::kParticles, colors::kOrange,
                 std::to_string(data.particles.size()) + " final particles, dark = heavy"});
  }
  if (!data.obstacles.empty())
    l.push_back({E::Swatch::kObstacle, colors::kPurple, "moving obstacles: path, at the end"});
  return l;
}

/// Coordinates in metres along the bottom and left edges of an unrotated map.
void draw_ticks(Canvas& canvas, const maps::OccupancyGrid& grid, const MapFrame& frame, int mx,
                int my, int ts) {
  const double res = grid.resolution(), s = frame.pixels_per_cell();
  const double ox = grid.origin().x, oy = grid.origin().y;
  const int th = Canvas::text_height("0", ts);
  const int bottom = my + frame.height();
  // As many ticks as fit with room between their labels (a thin map gets two or three).
  const int xfit = frame.width() / (Canvas::text_width("-000.0 m", ts) + 8);
  const std::vector<double> xt = nice_ticks(ox, ox + grid.width() * res, std::clamp(xfit, 2, 8));
  const double xstep = xt.size() > 1 ? xt[1] - xt[0] : 1.0;
  for (std::size_t i = 0; i < xt.size(); ++i) {
    const double px = mx + (xt[i] - ox) / res * s;
    if (px < mx - 0.5 || px > mx + frame.width() + 0.5) continue;
    const int x = static_cast<int>(std::lround(px));
    canvas.fill_rect(x, bottom, x, bottom + 4, colors::kBlack);
    const bool last = i + 1 == xt.size() || mx + (xt[i + 1] - ox) / res * s > mx + frame.width();
    const std::string label = format_tick(xt[i], xstep) + (last ? " m" : "");
    const int w = Canvas::text_width(label, ts);
    canvas.text(std::clamp(x - w / 2, 0, canvas.width() - w), bottom + 7, label, colors::kBlack,
                ts);
  }
  const int yfit = frame.height() / th + 1;
  const std::vector<double> yt = nice_ticks(oy, oy + grid.height() * res, std::clamp(yfit, 2, 8));
  const double ystep = yt.size() > 1 ? yt[1] - yt[0] : 1.0;
  for (std::size_t i = 0; i < yt.size(); ++i) {
    const double py = bottom - (yt[i] - oy) / res * s;
    if (py < my - 0.5 || py > bottom + 0.5) continue;
    const int y = static_cast<int>(std::lround(py));
    canvas.fill_rect(mx - 5, y, mx - 1, y, colors::kBlack);
    const bool last = i + 1 == yt.size() || bottom - (yt[i + 1] - oy) / res * s < my;
    const std::string label = format_tick(yt[i], ystep) + (last ? " m" : "");
    canvas.text(mx - 8 - Canvas::text_width(label, ts), std::max(y - th / 2, my), label,
                colors::kBlack, ts);
  }
}

/// The map frame's x and y axes as a small glyph in a corner (a rotated map).
void draw_axes_glyph(Canvas& canvas, const MapFrame& frame, int x, int y, int ts) {
  const double len = 18.0 * ts;
  const PixelPoint o{x + len + 6.0 * ts, y - len - 6.0 * ts};
  canvas.fill_rect(static_cast<int>(o.x - len - 6 * ts), static_cast<int>(o.y - len - 6 * ts),
                   static_cast<int>(o.x + len + 6 * ts), static_cast<int>(o.y + len + 6 * ts),
                   colors::kWhite);
  const double ax = frame.to_screen_angle(0.0);
  canvas.arrow(o, ax, len, colors::kBlack, 1.5);
  canvas.arrow(o, ax + 1.5707963267948966, len, colors::kBlack, 1.5);
  canvas.text(static_cast<int>(o.x + (len + 3) * std::cos(ax)),
              static_cast<int>(o.y - (len + 3) * std::sin(ax)), "x", colors::kBlack, ts);
  canvas.text(static_cast<int>(o.x - (len + 3) * std::sin(ax)),
              static_cast<int>(o.y - (len + 3) * std::cos(ax)), "y", colors::kBlack, ts);
}

}  // namespace

MapFrame::MapFrame(const maps::OccupancyGrid& grid, int max_side, int min_side) : grid_(&grid) {
  if (grid.empty()) throw std::invalid_argument("MapFrame: empty grid");
  const int side = std::max(grid.width(), grid.height());
  if (side > max_side) {
    scale_ = static_cast<double>(max_side) / side;
  } else {
    // Whole pixels per cell while that reaches min_side; a fraction above 1 otherwise, so a
    // 600-cell map is not left at 600 pixels.
    const double whole = std::floor(static_cast<double>(min_side) / side);
    scale_ = whole >= 2.0 ? whole : std::max(1.0, static_cast<double>(min_side) / side);
  }
  width_ = std::max(1, static_cast<int>(std::ceil(grid.width() * scale_ - 1e-9)));
  height_ = std::max(1, static_cast<int>(std::ceil(grid.height() * scale_ - 1e-9)));
}

PixelPoint MapFrame::to_pixel(double x, double y) const noexcept {
  double col = 0.0, row = 0.0;
  grid_->global_to_cell(x, y, col, row);
  return {col * scale_ - 0.5, (grid_->height() - row) * scale_ - 0.5};
}

Canvas MapFrame::draw_map() const {
  Canvas canvas(width_, height_, colors::kGrey);
  const maps::OccupancyGrid& g = *grid_;
  const std::int8_t occ = g.occupied_threshold();
  for (int j = 0; j < height_; ++j) {
    // Image row j covers grid rows (from the top) [j / s, (j + 1) / s).
    const int top0 = static_cast<int>(std::floor(j / scale_));
    const int top1 = std::max(top0, static_cast<int>(std::ceil((j + 1) / scale_)) - 1);
    for (int i = 0; i < width_; ++i) {
      const int c0 = static_cast<int>(std::floor(i / scale_));
      const int c1 = std::max(c0, static_cast<int>(std::ceil((i + 1) / scale_)) - 1);
      // Occupied beats free beats unknown within a shrunk block.
      std::int8_t best = maps::kUnknown;
      for (int t = top0; t <= std::min(top1, g.height() - 1); ++t) {
        const int row = g.height() - 1 - t;
        for (int c = c0; c <= std::min(c1, g.width() - 1); ++c) best = std::max(best, g.at(c, row));
      }
      canvas.set(i, j, overlay::cell_colour(best, occ));
    }
  }
  return canvas;
}

Rgb particle_colour(double relative) noexcept {
  const double t = std::clamp(std::isfinite(relative) ? relative : 0.0, 0.0, 1.0);
  // Pale apricot (light particles) to burnt orange (the heaviest).
  auto mix = [t](int a, int b) { return static_cast<std::uint8_t>(std::lround(a + t * (b - a))); };
  return {mix(255, 205), mix(215, 90), mix(150, 0)};
}

double arrow_pixels(int side) noexcept {
  return std::clamp(0.03 * side, 14.0, 40.0);
}

std::vector<std::size_t> path_jumps(std::span<const Pose2> path) {
  std::vector<std::size_t> jumps;
  if (path.size() < 2) return jumps;
  std::vector<double> steps;
  steps.reserve(path.size() - 1);
  for (std::size_t i = 1; i < path.size(); ++i)
    steps.push_back(std::hypot(path[i].x - path[i - 1].x, path[i].y - path[i - 1].y));
  std::vector<double> sorted = steps;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2),
                   sorted.end());
  const double limit = std::max(1.0, 10.0 * sorted[sorted.size() / 2]);
  for (std::size_t i = 0; i < steps.size(); ++i)
    if (steps[i] > limit) jumps.push_back(i + 1);
  return jumps;
}

Canvas render_overlay(const maps::OccupancyGrid& grid, const OverlayData& data,
                      OverlayLayout* layout) {
  const MapFrame frame(grid);
  const int ts = 2;
  const int th = Canvas::text_height("0", ts);
  const bool rotated = std::abs(grid.origin().theta) > 1e-12;
  // Margins for the coordinates (left: the widest y label).
  int left = 10, bottom = 10;
  if (!rotated) {
    left = Canvas::text_width("-000.0 m", ts) + 12;
    bottom = th + 14;
  }
  const int zoom_side = std::clamp(frame.height() / 2, 260, 400);
  const ZoomChoice zoom = choose_zoom(frame, data, zoom_side);
  const int zoom_caption = 2 * th + 12;
  const int zoom_w = zoom.zoom ? zoom_side + 24 : 0;
  const int width = std::max(left + frame.width() + zoom_w + 10, 760);
  const bool jumps = !path_jumps(data.truth).empty() || !path_jumps(data.estimate).empty();
  const std::vector<overlay::LegendEntry> legend = legend_of(data, jumps, frame);
  const int header = overlay::draw_header(nullptr, width, data.title, data.subtitle, legend, ts);
  const int body = std::max(frame.height() + bottom, zoom.zoom ? zoom_side + zoom_caption : 0);
  Canvas canvas(width, header + 6 + body + 6, colors::kWhite);
  overlay::draw_header(&canvas, width, data.title, data.subtitle, legend, ts);
  const int mx = left, my = header + 6;
  // The scene is drawn on the map's own canvas: a path that leaves the map (an estimate
  // gone astray) is clipped at its edge instead of running over the header and margins.
  Canvas map_canvas = frame.draw_map();
  overlay::View view;
  view.to_pixel = [&frame](double x, double y) { return frame.to_pixel(x, y); };
  view.angle_offset = grid.origin().theta;
  view.pixels_per_metre = frame.pixels_per_metre();
  view.line_width = std::clamp(frame.width() / 400.0, 1.0, 3.0);
  view.particle_radius = std::max(2.0, view.line_width);
  view.arrow_length = arrow_pixels(std::max(frame.width(), frame.height()));
  overlay::draw_scene(map_canvas, view, data);
  if (zoom.zoom) {  // the zoomed window's outline on the whole map
    const double half = zoom.metres / 2.0 * frame.pixels_per_metre();
    const PixelPoint c = view.to_pixel(zoom.centre.x, zoom.centre.y);
    map_canvas.frame_rect(static_cast<int>(c.x - half) - 2, static_cast<int>(c.y - half) - 2,
                          static_cast<int>(c.x + half) + 2, static_cast<int>(c.y + half) + 2,
                          colors::kBlue, 2);
  }
  canvas.blit(map_canvas, mx, my);
  canvas.frame_rect(mx - 1, my - 1, mx + frame.width(), my + frame.height(), colors::kDarkGrey);

  if (rotated) {
    draw_axes_glyph(canvas, frame, mx + frame.width() - 70 * ts, my + frame.height() - 4, ts);
  } else {
    draw_ticks(canvas, grid, frame, mx, my, ts);
  }
  OverlayLayout out{mx, my, false, 0, 0, 0, 0.0};
  if (zoom.zoom) {  // the zoomed view beside the map
    const int zx = mx + frame.width() + 20, zy = my;
    canvas.blit(overlay::render_zoom(grid, data, zoom.centre, zoom.metres, zoom_side, ts), zx, zy);
    canvas.frame_rect(zx - 2, zy - 2, zx + zoom_side + 1, zy + zoom_side + 1, colors::kBlue, 2);
    const int factor =
        static_cast<int>(std::lround(zoom_side / zoom.metres / frame.pixels_per_metre()));
    canvas.text(zx, zy + zoom_side + 6, "blue box, zoomed x" + std::to_string(factor),
                colors::kBlack, ts);
    canvas.text(zx, zy + zoom_side + th + 10, "(end of the run)", colors::kDarkGrey, ts);
    out.zoom = true;
    out.zoom_x = zx;
    out.zoom_y = zy;
    out.zoom_side = zoom_side;
    out.zoom_metres = zoom.metres;
  }
  if (layout) *layout = out;
  return canvas;
}

void write_overlay_png(const std::string& path, const maps::OccupancyGrid& grid,
                       const OverlayData& data) {
  write_png(render_overlay(grid, data), path);
}

}  // namespace pgmcl::app
