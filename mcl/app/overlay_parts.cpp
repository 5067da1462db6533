#include "overlay_parts.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

namespace pgmcl::app::overlay {
namespace {

/// The final cloud drawn at most this dense: a stride over the particles beyond it.
constexpr std::size_t kMaxDrawnParticles = 5000;

void draw_path(Canvas& canvas, const View& view, std::span<const Pose2> path, std::size_t from,
               std::size_t to, Rgb colour, double width) {
  if (to <= from) return;
  const std::vector<std::size_t> jumps = path_jumps(path);
  auto is_jump = [&](std::size_t i) { return std::binary_search(jumps.begin(), jumps.end(), i); };
  for (std::size_t i = std::max<std::size_t>(from, 1); i < to; ++i) {
    const PixelPoint a = view.to_pixel(path[i - 1].x, path[i - 1].y);
    const PixelPoint b = view.to_pixel(path[i].x, path[i].y);
    if (is_jump(i)) {
      canvas.dashed_line(a, b, colour, 1.0, 2.0, 4.0);
    } else {
      canvas.line(a, b, colour, width);
    }
  }
  if (to - from == 1) {
    const PixelPoint a = view.to_pixel(path[from].x, path[from].y);
    canvas.disc(a.x, a.y, width, colour);
  }
}

void draw_obstacle(Canvas& canvas, const View& view, const ObstacleDrawing& o) {
  std::vector<PixelPoint> pts;
  for (const Pose2& p : o.path) pts.push_back(view.to_pixel(p.x, p.y));
  for (std::size_t i = 1; i < pts.size(); ++i)
    canvas.dashed_line(pts[i - 1], pts[i], colors::kPurple, 1.0, 5.0, 4.0);
  if (o.path.empty()) return;
  const Pose2& end = o.path.back();
  const double w = std::max(1.5, view.line_width);
  if (o.radius > 0.0) {
    const PixelPoint c = view.to_pixel(end.x, end.y);
    canvas.ring(c.x, c.y, std::max(3.0, o.radius * view.pixels_per_metre), colors::kPurple, w);
    return;
  }
  const double c = std::cos(end.theta), s = std::sin(end.theta);
  const double hl = o.half_length, hw = o.half_width;
  const double corners[4][2] = {{hl, hw}, {-hl, hw}, {-hl, -hw}, {hl, -hw}};
  PixelPoint px[4];
  for (int k = 0; k < 4; ++k) {
    px[k] = view.to_pixel(end.x + c * corners[k][0] - s * corners[k][1],
                          end.y + s * corners[k][0] + c * corners[k][1]);
  }
  for (int k = 0; k < 4; ++k) canvas.line(px[k], px[(k + 1) % 4], colors::kPurple, w);
}

void draw_particles(Canvas& canvas, const View& view, const OverlayData& data) {
  const auto n = data.particles.size();
  if (n == 0) return;
  const bool weighted = data.weights.size() == n;
  const std::size_t stride = n / kMaxDrawnParticles + 1;
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < n; i += stride) order.push_back(i);
  double wmax = 0.0;
  if (weighted) {
    for (const std::size_t i : order) wmax = std::max(wmax, data.weights[i]);
    // Light ones first: the heavy particles end up on top.
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return data.weights[a] < data.weights[b];
    });
  }
  const double r = view.particle_radius;
  for (const std::size_t i : order) {
    const double rel = weighted && wmax > 0.0 ? data.weights[i] / wmax : 1.0;
    const PixelPoint p = view.to_pixel(data.particles[i].x, data.particles[i].y);
    canvas.disc(p.x, p.y, r + 1.0, kRim);
    canvas.disc(p.x, p.y, r, particle_colour(rel));
  }
}

}  // namespace

Rgb cell_colour(std::int8_t v, std::int8_t occupied_threshold) noexcept {
  if (v < 0) return colors::kGrey;
  if (v >= occupied_threshold) return colors::kBlack;
  // Free and in-between values as grey levels: 0 -> white, threshold -> dark.
  const int level = 255 - (v * 200) / std::max<int>(occupied_threshold, 1);
  const auto l = static_cast<std::uint8_t>(std::clamp(level, 0, 255));
  return {l, l, l};
}

void draw_scene(Canvas& canvas, const View& view, const OverlayData& data) {
  for (const ObstacleDrawing& o : data.obstacles) draw_obstacle(canvas, view, o);
  const double w = view.line_width;
  // Truth wider underneath, so it shows on both sides of an estimate that follows it.
  draw_path(canvas, view, data.truth, 0, data.truth.size(), colors::kGreen, w + 2.0);
  const std::size_t n = data.estimate.size();
  const std::size_t s0 = std::min(data.search_begin, n),
                    s1 = std::max(s0, std::min(data.search_end, n));
  // draw_path(from, to) draws the steps into poses from..to-1: the steps into the search's
  // poses and into the lock-on pose s1 (the jump to the right place) are pale, the rest red.
  if (s0 > 0 || s1 == s0)
    draw_path(canvas, view, data.estimate, 0, std::min(s0 + 1, n), colors::kRed, w);
  if (s1 > s0) draw_path(canvas, view, data.estimate, s0 + 1, std::min(s1 + 1, n), kPaleRed, 1.0);
  draw_path(canvas, view, data.estimate, s1 + 1, n, colors::kRed, w);
  const std::span<const Pose2> first = !data.truth.empty() ? data.truth : data.estimate;
  if (!first.empty()) {
    const PixelPoint s = view.to_pixel(first.front().x, first.front().y);
    const double r = std::max(5.0, 2.0 * w + 3.0);
    canvas.disc(s.x, s.y, r, colors::kWhite);
    canvas.ring(s.x, s.y, r, colors::kBlack, std::max(2.0, w));
  }
  draw_particles(canvas, view, data);
  auto end_arrow = [&](std::span<const Pose2> path, Rgb colour, double width) {
    if (path.empty()) return;
    const Pose2& p = path.back();
    canvas.arrow(view.to_pixel(p.x, p.y), p.theta - view.angle_offset, view.arrow_length, colour,
                 width);
  };
  // Truth wider underneath here too: both arrows show when they agree.
  end_arrow(data.truth, colors::kGreen, w + 4.0);
  end_arrow(data.estimate, colors::kRed, w + 1.0);
}

double nice_length(double metres) noexcept {
  if (!(metres > 0.0) || !std::isfinite(metres)) return 1.0;
  const double e = std::pow(10.0, std::floor(std::log10(metres)));
  const double f = metres / e;
  return (f >= 5.0 ? 5.0 : f >= 2.0 ? 2.0 : 1.0) * e;
}

std::string length_text(double metres) {
  char label[32];
  if (metres >= 1.0) {
    std::snprintf(label, sizeof label, "%g m", metres);
  } else if (metres >= 0.01) {
    std::snprintf(label, sizeof label, "%g cm", metres * 100.0);
  } else {
    std::snprintf(label, sizeof label, "%g mm", metres * 1000.0);
  }
  return label;
}

void draw_scale_bar(Canvas& canvas, int x, int y, double pixels_per_metre, int max_pixels,
                    int text_scale) {
  const double metres = nice_length(0.2 * max_pixels / pixels_per_metre);
  const int len = static_cast<int>(std::lround(metres * pixels_per_metre));
  const std::string label = length_text(metres);
  const int th = Canvas::text_height("0", text_scale);
  const int tw = Canvas::text_width(label, text_scale);
  const int pad = 3 * text_scale;
  canvas.fill_rect(x, y - th - 3 * pad - 4, x + std::max(len, tw) + 2 * pad, y, colors::kWhite);
  const int by = y - pad - 2;
  canvas.fill_rect(x + pad, by - 2, x + pad + len, by, colors::kBlack);
  canvas.fill_rect(x + pad, by - 7, x + pad + 1, by, colors::kBlack);
  canvas.fill_rect(x + pad + len - 1, by - 7, x + pad + len, by, colors::kBlack);
  canvas.text(x + pad, by - 8 - th, label, colors::kBlack, text_scale);
}

int draw_header(Canvas* canvas, int width, const std::string& title, const std::string& subtitle,
                const std::vector<LegendEntry>& legend, int text_scale) {
  const int ts = text_scale;
  const int th = Canvas::text_height("Ag", ts);
  const int gap = 4 * ts;
  int y = gap;
  if (!title.empty()) {
    if (canvas) canvas->text(gap, y, title, colors::kBlack, ts + (ts > 1 ? 1 : 0));
    y += Canvas::text_height("Ag", ts + (ts > 1 ? 1 : 0)) + gap;
  }
  if (!subtitle.empty()) {
    // Wrapped at spaces to the picture's width.
    std::string line;
    auto flush = [&] {
      if (canvas) canvas->text(gap, y, line, colors::kDarkGrey, ts);
      y += th + gap / 2;
      line.clear();
    };
    std::size_t start = 0;
    while (start < subtitle.size()) {
      std::size_t end = subtitle.find(' ', start);
      if (end == std::string::npos) end = subtitle.size();
      const std::string word = subtitle.substr(start, end - start);
      const std::string next = line.empty() ? word : line + " " + word;
      if (!line.empty() && Canvas::text_width(next, ts) > width - 2 * gap) flush();
      line = line.empty() ? word : line + " " + word;
      start = end + 1;
    }
    if (!line.empty()) flush();
    y += gap / 2;
  }
  int x = gap;
  for (const LegendEntry& e : legend) {
    const bool bar = e.swatch == LegendEntry::Swatch::kScaleBar;
    const int sw = bar ? static_cast<int>(std::lround(e.length)) + 2 : 22 * ts;  // swatch width
    const int w = sw + 4 * ts + Canvas::text_width(e.label, ts) + 6 * ts;
    if (x > gap && x + w > width - gap) {
      x = gap;
      y += th + gap;
    }
    if (canvas) {
      Canvas& c = *canvas;
      const double mid = y + th / 2.0;
      const PixelPoint a{x + 1.0, mid}, b{x + sw - 1.0, mid};
      switch (e.swatch) {
        case LegendEntry::Swatch::kLine:
          c.line(a, b, e.colour, 2.0 * ts);
          break;
        case LegendEntry::Swatch::kThickLine:
          c.line(a, b, e.colour, 3.0 * ts);
          break;
        case LegendEntry::Swatch::kDashed:
          c.dashed_line(a, b, e.colour, 1.5 * ts, 4.0 * ts, 3.0 * ts);
          break;
        case LegendEntry::Swatch::kDotted:
          c.dashed_line(a, b, e.colour, 1.0, 2.0, 4.0);
          break;
        case LegendEntry::Swatch::kStart:
          c.disc(x + sw / 2.0, mid, 2.5 * ts + 1, colors::kWhite);
          c.ring(x + sw / 2.0, mid, 2.5 * ts + 1, colors::kBlack, 2.0);
          break;
        case LegendEntry::Swatch::kArrow:
          c.arrow(a, 0.0, sw - 2.0, e.colour, 1.5 * ts);
          break;
        case LegendEntry::Swatch::kParticles:
          for (int k = 0; k < 4; ++k) {
            const double px = x + 3.0 * ts + k * (sw - 6.0 * ts) / 3.0;
            c.disc(px, mid, 2.0 * ts + 1.0, kRim);
            c.disc(px, mid, 2.0 * ts, particle_colour(0.15 + k * 0.28));
          }
          break;
        case LegendEntry::Swatch::kScaleBar: {
          const int y0 = static_cast<int>(mid);
          c.fill_rect(x + 1, y0 - 1, x + sw - 1, y0 + 1, colors::kBlack);
          c.fill_rect(x + 1, y0 - 5, x + 2, y0 + 4, colors::kBlack);
          c.fill_rect(x + sw - 2, y0 - 5, x + sw - 1, y0 + 4, colors::kBlack);
          break;
        }
        case LegendEntry::Swatch::kObstacle:
          c.dashed_line(a, {x + sw * 0.6, mid}, e.colour, 1.0, 3.0, 2.0);
          c.ring(x + sw * 0.75, mid, 3.0 * ts, e.colour, 1.5);
          break;
      }
      c.text(x + sw + 4 * ts, y, e.label, colors::kBlack, ts);
    }
    x += w;
  }
  if (!legend.empty()) y += th + gap;
  return y;
}

Canvas render_zoom(const maps::OccupancyGrid& grid, const OverlayData& data, const Pose2& centre,
                   double metres, int side, int text_scale) {
  Canvas canvas(side, side, colors::kGrey);
  const double k = side / metres;  // pixels per metre
  // Work in the grid's own frame, as the whole-map picture does.
  const Pose2 c = grid.to_local(centre);
  const double res = grid.resolution();
  const std::int8_t occ = grid.occupied_threshold();
  for (int j = 0; j < side; ++j) {
    for (int i = 0; i < side; ++i) {
      const double lx = c.x + (i + 0.5 - side / 2.0) / k;
      const double ly = c.y + (side / 2.0 - j - 0.5) / k;
      const int col = static_cast<int>(std::floor(lx / res));
      const int row = static_cast<int>(std::floor(ly / res));
      if (grid.in_bounds(col, row)) canvas.set(i, j, cell_colour(grid.at(col, row), occ));
    }
  }
  View view;
  view.to_pixel = [&grid, c, k, side](double x, double y) {
    const Pose2 l = grid.to_local(Pose2{x, y, 0.0});
    return PixelPoint{(l.x - c.x) * k + side / 2.0 - 0.5, (c.y - l.y) * k + side / 2.0 - 0.5};
  };
  view.angle_offset = grid.origin().theta;
  view.pixels_per_metre = k;
  view.line_width = 2.0;
  view.particle_radius = 2.5;
  view.arrow_length = 0.18 * side;
  draw_scene(canvas, view, data);
  draw_scale_bar(canvas, 0, side - 1, k, side, text_scale);
  canvas.frame_rect(0, 0, side - 1, side - 1, colors::kBlack, 2);
  return canvas;
}

}  // namespace pgmcl::app::overlay
