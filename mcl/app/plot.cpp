#include "plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace pgmcl::app {
namespace {

/// Heckbert's nice number: 1, 2, 5 or 10 times a power of ten, near x.
double nice_number(double x, bool round) {
  const double e = std::floor(std::log10(x));
  const double f = x / std::pow(10.0, e);
  double nf = 10.0;
  if (round) {
    nf = f < 1.5 ? 1.0 : f < 3.0 ? 2.0 : f < 7.0 ? 5.0 : 10.0;
  } else {
    nf = f <= 1.0 ? 1.0 : f <= 2.0 ? 2.0 : f <= 5.0 ? 5.0 : 10.0;
  }
  return nf * std::pow(10.0, e);
}

struct Range {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void add(double v) {
    if (!std::isfinite(v)) return;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  void settle() {
    if (!(lo <= hi)) lo = 0.0, hi = 1.0;
    if (hi - lo < 1e-12 * std::max(1.0, std::abs(hi))) {
      const double pad = std::max(std::abs(hi) * 0.1, 1e-3);
      lo -= pad;
      hi += pad;
    }
  }
};

}  // namespace

std::vector<double> nice_ticks(double lo, double hi, int target) {
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(hi > lo)) return {lo};
  target = std::max(target, 2);
  const double range = nice_number(hi - lo, false);
  const double step = nice_number(range / (target - 1), true);
  const double start = std::floor(lo / step + 1e-9) * step;
  const double end = std::ceil(hi / step - 1e-9) * step;
  std::vector<double> ticks;
  for (int i = 0; start + i * step <= end + 0.5 * step && i < 1000; ++i) {
    const double v = start + i * step;
    ticks.push_back(std::abs(v) < 1e-9 * step ? 0.0 : v);
  }
  return ticks;
}

std::string format_tick(double value, double step) {
  char buf[64];
  if (std::abs(value) >= 1e6 || (value != 0.0 && std::abs(value) < 1e-4)) {
    std::snprintf(buf, sizeof buf, "%.3g", value);
    return buf;
  }
  const int decimals =
      step > 0.0 ? std::clamp(static_cast<int>(-std::floor(std::log10(step) + 1e-9)), 0, 6) : 2;
  std::snprintf(buf, sizeof buf, "%.*f", decimals, value);
  return buf;
}

std::vector<double> log_ticks(double lo, double hi, int max_decades) {
  if (!(hi > 0.0) || !std::isfinite(hi)) return {1.0};
  const int top = static_cast<int>(std::ceil(std::log10(hi) - 1e-9));
  int bottom =
      lo > 0.0 && std::isfinite(lo) ? static_cast<int>(std::floor(std::log10(lo) + 1e-9)) : top - 1;
  bottom = std::clamp(bottom, top - std::max(max_decades, 1), top - 1);
  std::vector<double> t;
  for (int k = bottom; k <= top; ++k) t.push_back(std::pow(10.0, k));
  return t;
}

Canvas render_line_plot(const LinePlot& plot) {
  Range xr, yr;
  double y_min_positive = std::numeric_limits<double>::infinity();
  for (const auto& s : plot.series) {
    if (s.x.size() != s.y.size()) {
      throw std::invalid_argument("render_line_plot: series '" + s.label +
                                  "' has x and y of different lengths");
    }
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      xr.add(s.x[i]);
      yr.add(s.y[i]);
      if (s.y[i] > 0.0) y_min_positive = std::min(y_min_positive, s.y[i]);
    }
  }
  for (const PlotLevel& l : plot.levels) yr.add(l.y);
  if (plot.x_range) {
    xr.lo = plot.x_range->first;
    xr.hi = plot.x_range->second;
  }
  if (plot.y_from_zero && !plot.y_log) yr.add(0.0);
  xr.settle();
  yr.settle();
  const std::vector<double> xt = nice_ticks(xr.lo, xr.hi, 8);
  const std::vector<double> yt =
      plot.y_log ? log_ticks(y_min_positive, yr.hi) : nice_ticks(yr.lo, yr.hi, 6);
  const double x0 = xt.front(), x1 = xt.back();
  const double xstep = xt.size() > 1 ? xt[1] - xt[0] : 1.0;
  const double ystep = yt.size() > 1 ? yt[1] - yt[0] : 1.0;
  // Linear or log10 position of a value on the y axis.
  auto ymap = [&](double v) {
    if (!plot.y_log) return v;
    return std::log10(std::max(v, yt.front()));
  };
  const double y0 = ymap(yt.front()), y1 = ymap(yt.back());

  Canvas canvas(std::max(plot.width, 200), std::max(plot.height, 150), colors::kWhite);
  const int ts = 2;  // text scale
  const int th = Canvas::text_height("0", ts);
  auto ylabel = [&](double v) {
    if (!plot.y_log) return format_tick(v, ystep);
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return std::string(buf);
  };
  int label_w = 0;
  for (const double v : yt) label_w = std::max(label_w, Canvas::text_width(ylabel(v), ts));
  const int strip_h = plot.strip.pieces.empty() ? 0 : 12;
  const int left = label_w + 20, right = canvas.width() - 20;
  const int top = 2 * th + 24, bottom = canvas.height() - 2 * th - 30 - strip_h;
  if (right <= left + 10 || bottom <= top + 10) return canvas;
  auto px = [&](double x) { return left + (x - x0) / (x1 - x0) * (right - left); };
  auto py = [&](double y) { return bottom - (ymap(y) - y0) / (y1 - y0) * (bottom - top); };
  auto ipx = [&](double x) {
    return static_cast<int>(std::lround(std::clamp(px(x), 1.0 * left, 1.0 * right)));
  };

  // Shaded spans behind everything, with their labels at the top left.
  for (const PlotSpan& sp : plot.spans) {
    const int a = ipx(sp.x0), b = ipx(sp.x1);
    if (b <= a) continue;
    canvas.fill_rect(a, top, b, bottom, sp.fill);
  }
  // Grid lines and tick labels.
  for (const double v : yt) {
    const int y = static_cast<int>(std::lround(py(v)));
    canvas.line({static_cast<double>(left), static_cast<double>(y)},
                {static_cast<double>(right), static_cast<double>(y)}, colors::kLightGrey);
    const std::string s = ylabel(v);
    canvas.text(left - 8 - Canvas::text_width(s, ts), y - th / 2, s, colors::kBlack, ts);
  }
  for (const double v : xt) {
    const int x = static_cast<int>(std::lround(px(v)));
    canvas.line({static_cast<double>(x), static_cast<double>(top)},
                {static_cast<double>(x), static_cast<double>(bottom)}, colors::kLightGrey);
    const std::string s = format_tick(v, xstep);
    canvas.text(x - Canvas::text_width(s, ts) / 2, bottom + strip_h + 8, s, colors::kBlack, ts);
  }
  for (const PlotSpan& sp : plot.spans) {
    const int a = ipx(sp.x0), b = ipx(sp.x1);
    if (b - a > Canvas::text_width(sp.label, ts) + 8)
      canvas.text(a + 4, top + 4, sp.label, colors::kDarkGrey, ts);
  }
  // Axes box.
  canvas.frame_rect(left, top, right, bottom, colors::kBlack);

  // Threshold lines, then the data: polylines broken at non-finite points.
  for (const PlotLevel& l : plot.levels) {
    const double y = py(l.y);
    if (y < top || y > bottom) continue;
    canvas.dashed_line({1.0 * left, y}, {1.0 * right, y}, l.colour, 1.0, 8.0, 5.0);
    const int w = Canvas::text_width(l.label, ts);
    // Below the line in the upper half, above it in the lower half: inside the box.
    const int ty =
        y < (top + bottom) / 2.0 ? static_cast<int>(y) + 4 : static_cast<int>(y) - th - 3;
    canvas.text(right - w - 4, ty, l.label, l.colour, ts);
  }
  for (const auto& s : plot.series) {
    // Few points in view: each is marked, so a straight stretch reads as a gap in the data.
    std::size_t in_view = 0;
    for (const double x : s.x) in_view += x >= x0 && x <= x1 ? 1 : 0;
    const bool sparse = in_view < 80;
    std::vector<PixelPoint> run;
    auto flush = [&] {
      canvas.polyline(run, s.colour, 2.0);
      run.clear();
    };
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      // Outside a fixed x range (a panel showing part of the run) is a break as well.
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i]) || s.x[i] < x0 || s.x[i] > x1) {
        flush();
        continue;
      }
      run.push_back({px(s.x[i]), std::clamp(py(s.y[i]), 1.0 * top, 1.0 * bottom)});
      if (sparse) canvas.disc(run.back().x, run.back().y, 3.0, s.colour);
    }
    flush();
  }
  // Data points inside a label's box: a label goes where it hides the fewest.
  auto points_in = [&](int bx0, int by0, int bx1, int by1) {
    int n = 0;
    for (const auto& s : plot.series)
      for (std::size_t i = 0; i < s.x.size(); ++i) {
        if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i]) || s.x[i] < x0 || s.x[i] > x1)
          continue;
        const double qx = px(s.x[i]), qy = std::clamp(py(s.y[i]), 1.0 * top, 1.0 * bottom);
        n += qx >= bx0 && qx <= bx1 && qy >= by0 && qy <= by1 ? 1 : 0;
      }
    return n;
  };
  // Event markers over the data, labels inside the plot at its bottom, or below the span
  // labels at its top when the data runs along the bottom there.
  for (const PlotMarker& m : plot.markers) {
    const double x = px(m.x);
    if (x < left - 0.5 || x > right + 0.5) continue;
    canvas.line({x, 1.0 * top}, {x, 1.0 * bottom}, m.colour, 2.0);
    const int w = Canvas::text_width(m.label, ts);
    const int tx = x + 6 + w <= right ? static_cast<int>(x) + 6 : static_cast<int>(x) - 6 - w;
    const int low = bottom - th - 6, high = top + th + 12;
    const int ty = points_in(tx - 2, low - 2, tx + w + 1, low + th + 1) >
                           points_in(tx - 2, high - 2, tx + w + 1, high + th + 1)
                       ? high
                       : low;
    canvas.fill_rect(tx - 2, ty - 2, tx + w + 1, ty + th + 1, colors::kWhite);
    canvas.text(tx, ty, m.label, m.colour, ts);
  }
  // The state strip under the axis.
  for (const PlotStrip::Piece& p : plot.strip.pieces) {
    if (p.x1 < x0 || p.x0 > x1) continue;
    const int a = ipx(p.x0), b = std::max(ipx(p.x1), ipx(p.x0));
    canvas.fill_rect(a, bottom + 3, b, bottom + strip_h, p.colour);
  }

  // Title (top centre), y label (top left), x label (bottom centre); the legend on the
  // y label's row, right-aligned, so it never covers data.
  const int cw = canvas.width();
  canvas.text((cw - Canvas::text_width(plot.title, ts)) / 2, 6, plot.title, colors::kBlack, ts);
  canvas.text(left, top - th - 8, plot.y_label, colors::kDarkGrey, ts);
  canvas.text((left + right - Canvas::text_width(plot.x_label, ts)) / 2, bottom + strip_h + th + 16,
              plot.x_label, colors::kDarkGrey, ts);
  std::vector<std::pair<std::string, Rgb>> legend;
  for (const auto& s : plot.series)
    if (!s.label.empty()) legend.emplace_back(s.label, s.colour);
  for (const auto& e : plot.strip.legend) legend.push_back(e);
  int lx = right;
  const int ly = top - th - 8;
  for (auto it = legend.rbegin(); it != legend.rend(); ++it) {
    const int w = Canvas::text_width(it->first, ts);
    lx -= w;
    canvas.text(lx, ly, it->first, colors::kBlack, ts);
    canvas.fill_rect(lx - 22, ly + th / 2 - 2, lx - 6, ly + th / 2 + 2, it->second);
    lx -= 40;
  }
  return canvas;
}

void write_line_plot_png(const std::string& path, const LinePlot& plot) {
  write_png(render_line_plot(plot), path);
}

}  // namespace pgmcl::app
