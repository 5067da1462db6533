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

Canvas render_line_plot(const LinePlot& plot) {
  Range xr, yr;
  for (const auto& s : plot.series) {
    if (s.x.size() != s.y.size()) {
      throw std::invalid_argument("render_line_plot: series '" + s.label +
                                  "' has x and y of different lengths");
    }
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      xr.add(s.x[i]);
      yr.add(s.y[i]);
    }
  }
  if (plot.y_from_zero) yr.add(0.0);
  xr.settle();
  yr.settle();
  const std::vector<double> xt = nice_ticks(xr.lo, xr.hi, 8);
  const std::vector<double> yt = nice_ticks(yr.lo, yr.hi, 6);
  const double x0 = xt.front(), x1 = xt.back(), y0 = yt.front(), y1 = yt.back();
  const double xstep = xt.size() > 1 ? xt[1] - xt[0] : 1.0;
  const double ystep = yt.size() > 1 ? yt[1] - yt[0] : 1.0;

  Canvas canvas(std::max(plot.width, 200), std::max(plot.height, 150), colors::kWhite);
  const int ts = 2;  // text scale
  const int th = Canvas::text_height("0", ts);
  int label_w = 0;
  for (const double v : yt)
    label_w = std::max(label_w, Canvas::text_width(format_tick(v, ystep), ts));
  const int left = label_w + 20, right = canvas.width() - 20;
  const int top = 2 * th + 24, bottom = canvas.height() - 2 * th - 30;
  if (right <= left + 10 || bottom <= top + 10) return canvas;
  auto px = [&](double x) { return left + (x - x0) / (x1 - x0) * (right - left); };
  auto py = [&](double y) { return bottom - (y - y0) / (y1 - y0) * (bottom - top); };

  // Grid lines and tick labels.
  for (const double v : yt) {
    const int y = static_cast<int>(std::lround(py(v)));
    canvas.line({static_cast<double>(left), static_cast<double>(y)},
                {static_cast<double>(right), static_cast<double>(y)}, colors::kLightGrey);
    const std::string s = format_tick(v, ystep);
    canvas.text(left - 8 - Canvas::text_width(s, ts), y - th / 2, s, colors::kBlack, ts);
  }
  for (const double v : xt) {
    const int x = static_cast<int>(std::lround(px(v)));
    canvas.line({static_cast<double>(x), static_cast<double>(top)},
                {static_cast<double>(x), static_cast<double>(bottom)}, colors::kLightGrey);
    const std::string s = format_tick(v, xstep);
    canvas.text(x - Canvas::text_width(s, ts) / 2, bottom + 8, s, colors::kBlack, ts);
  }
  // Axes box.
  canvas.line({1.0 * left, 1.0 * top}, {1.0 * left, 1.0 * bottom}, colors::kBlack);
  canvas.line({1.0 * left, 1.0 * bottom}, {1.0 * right, 1.0 * bottom}, colors::kBlack);
  canvas.line({1.0 * left, 1.0 * top}, {1.0 * right, 1.0 * top}, colors::kBlack);
  canvas.line({1.0 * right, 1.0 * top}, {1.0 * right, 1.0 * bottom}, colors::kBlack);

  // Data: polylines broken at non-finite points.
  for (const auto& s : plot.series) {
    std::vector<PixelPoint> run;
    auto flush = [&] {
      canvas.polyline(run, s.colour, 2.0);
      run.clear();
    };
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) {
        flush();
        continue;
      }
      run.push_back({px(s.x[i]), py(s.y[i])});
    }
    flush();
  }

  // Title (top centre), y label (top left), x label (bottom centre), legend (top right).
  const int cw = canvas.width();
  canvas.text((cw - Canvas::text_width(plot.title, ts)) / 2, 6, plot.title, colors::kBlack, ts);
  canvas.text(left, top - th - 8, plot.y_label, colors::kDarkGrey, ts);
  canvas.text((left + right - Canvas::text_width(plot.x_label, ts)) / 2, bottom + th + 16,
              plot.x_label, colors::kDarkGrey, ts);
  int ly = top + 6;
  for (const auto& s : plot.series) {
    if (s.label.empty()) continue;
    const int w = Canvas::text_width(s.label, ts);
    canvas.fill_rect(right - w - 36, ly - 2, right - 4, ly + th + 2, colors::kWhite);
    canvas.fill_rect(right - w - 32, ly + th / 2 - 1, right - w - 14, ly + th / 2 + 1, s.colour);
    canvas.text(right - w - 8, ly, s.label, colors::kBlack, ts);
    ly += th + 8;
  }
  return canvas;
}

void write_line_plot_png(const std::string& path, const LinePlot& plot) {
  write_png(render_line_plot(plot), path);
}

}  // namespace pgmcl::app
