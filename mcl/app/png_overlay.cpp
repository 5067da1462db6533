#include "png_overlay.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace pgmcl::app {
namespace {

Rgb cell_colour(std::int8_t v, std::int8_t occupied_threshold) {
  if (v < 0) return colors::kGrey;
  if (v >= occupied_threshold) return colors::kBlack;
  // Free and in-between values as grey levels: 0 -> white, threshold -> dark.
  const int level = 255 - (v * 200) / std::max<int>(occupied_threshold, 1);
  const auto l = static_cast<std::uint8_t>(std::clamp(level, 0, 255));
  return {l, l, l};
}

}  // namespace

MapFrame::MapFrame(const maps::OccupancyGrid& grid, int max_side, int min_side) : grid_(&grid) {
  if (grid.empty()) throw std::invalid_argument("MapFrame: empty grid");
  const int side = std::max(grid.width(), grid.height());
  if (side > max_side) {
    scale_ = static_cast<double>(max_side) / side;
  } else {
    scale_ = std::max(1.0, std::floor(static_cast<double>(min_side) / side));
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
      canvas.set(i, j, cell_colour(best, occ));
    }
  }
  return canvas;
}

Canvas render_overlay(const maps::OccupancyGrid& grid, const OverlayData& data) {
  const MapFrame frame(grid);
  Canvas canvas = frame.draw_map();
  const double line_w = std::clamp(frame.width() / 400.0, 1.0, 3.0);
  auto path = [&frame](std::span<const Pose2> poses) {
    std::vector<PixelPoint> pts;
    pts.reserve(poses.size());
    for (const Pose2& p : poses) pts.push_back(frame.to_pixel(p.x, p.y));
    return pts;
  };
  const double dot = std::max(1.0, line_w * 0.75);
  for (const Pose2& p : data.particles) {
    const PixelPoint q = frame.to_pixel(p.x, p.y);
    canvas.disc(q.x, q.y, dot, colors::kOrange);
  }
  // Truth wider underneath, so it shows on both sides of an estimate that follows it.
  canvas.polyline(path(data.truth), colors::kGreen, line_w + 2.0);
  canvas.polyline(path(data.estimate), colors::kRed, line_w);
  const double arrow_len = std::max(12.0, 0.6 * frame.pixels_per_metre());
  if (!data.truth.empty()) {
    const Pose2& t = data.truth.back();
    canvas.arrow(frame.to_pixel(t.x, t.y), frame.to_screen_angle(t.theta), arrow_len,
                 colors::kGreen, line_w + 1.0);
  }
  if (!data.estimate.empty()) {
    const Pose2& e = data.estimate.back();
    canvas.arrow(frame.to_pixel(e.x, e.y), frame.to_screen_angle(e.theta), arrow_len, colors::kRed,
                 line_w + 1.0);
  }
  // Legend, top-left, on a white box so it reads over any map.
  const int scale = frame.width() >= 600 ? 2 : 1;
  const int lh = Canvas::text_height("Ag", scale) + 4 * scale;
  struct Entry {
    std::string label;
    Rgb colour;
    bool present;
  };
  const Entry entries[] = {{"ground truth", colors::kGreen, !data.truth.empty()},
                           {"estimate", colors::kRed, !data.estimate.empty()},
                           {"particles", colors::kOrange, !data.particles.empty()}};
  int rows = data.title.empty() ? 0 : 1, text_w = Canvas::text_width(data.title, scale);
  for (const auto& e : entries) {
    if (!e.present) continue;
    ++rows;
    text_w = std::max(text_w, Canvas::text_width(e.label, scale) + 14 * scale);
  }
  if (rows > 0) {
    canvas.fill_rect(2, 2, 8 * scale + text_w, 4 * scale + rows * lh, colors::kWhite);
    int y = 4 * scale;
    if (!data.title.empty()) {
      canvas.text(4 * scale, y, data.title, colors::kBlack, scale);
      y += lh;
    }
    for (const auto& e : entries) {
      if (!e.present) continue;
      canvas.fill_rect(4 * scale, y + 1, 12 * scale, y + 6 * scale, e.colour);
      canvas.text(16 * scale, y, e.label, colors::kBlack, scale);
      y += lh;
    }
  }
  return canvas;
}

void write_overlay_png(const std::string& path, const maps::OccupancyGrid& grid,
                       const OverlayData& data) {
  write_png(render_overlay(grid, data), path);
}

}  // namespace pgmcl::app
