#pragma once
/// A minimal line-plot renderer for error.png (error over time): axes, "nice" ticks with
/// labels, a legend, and one polyline per series, drawn on a Canvas (png.hpp).
/// Built in so the pictures need no external tool (gnuplot is not required anywhere).

#include <string>
#include <vector>

#include "png.hpp"

namespace pgmcl::app {

struct PlotSeries {
  std::string label;
  std::vector<double> x;  ///< same length as y; non-finite points break the line
  std::vector<double> y;
  Rgb colour = colors::kBlue;
};

struct LinePlot {
  std::string title;
  std::string x_label;
  std::string y_label;
  std::vector<PlotSeries> series;
  int width = 1000;         ///< pixels
  int height = 520;         ///< pixels
  bool y_from_zero = true;  ///< include y = 0 in the range (errors, counts)
};

/// Tick positions covering [lo, hi] with a 1-2-5 step, about `target` of them
/// (Heckbert, "Nice numbers for graph labels", Graphics Gems 1990).
[[nodiscard]] std::vector<double> nice_ticks(double lo, double hi, int target = 6);
/// A tick label with as many decimals as the step needs ("0.25", "10", "1e+03").
[[nodiscard]] std::string format_tick(double value, double step);

/// Throws std::invalid_argument when a series' x and y lengths differ.
[[nodiscard]] Canvas render_line_plot(const LinePlot& plot);
/// render_line_plot + write_png; throws IoError on failure.
void write_line_plot_png(const std::string& path, const LinePlot& plot);

}  // namespace pgmcl::app
