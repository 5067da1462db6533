#pragma once
/// A minimal line-plot renderer for error.png (error over time): axes (linear or log),
/// "nice" ticks with labels, a legend, one polyline per series, shaded spans, event markers,
/// threshold lines and a state strip, drawn on a Canvas (png.hpp).
/// Built in so the pictures need no external tool (gnuplot is not required anywhere).

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "png.hpp"

namespace pgmcl::app {

struct PlotSeries {
  std::string label;
  std::vector<double> x;  ///< same length as y; non-finite points break the line
  std::vector<double> y;
  Rgb colour = colors::kBlue;
};

/// A vertical line at `x` with a label beside it (an event: lock-on, a kidnap).
struct PlotMarker {
  double x = 0.0;
  std::string label;
  Rgb colour = colors::kBlack;
};

/// A shaded stretch of the x axis behind the data, labelled at its top left.
struct PlotSpan {
  double x0 = 0.0, x1 = 0.0;
  std::string label;
  Rgb fill = colors::kPaleGrey;
};

/// A dashed horizontal line at `y` (a threshold), labelled at its right end.
struct PlotLevel {
  double y = 0.0;
  std::string label;
  Rgb colour = colors::kDarkGrey;
};

/// A band of coloured stretches under the x axis: a state over time (what the filter said).
struct PlotStrip {
  struct Piece {
    double x0 = 0.0, x1 = 0.0;
    Rgb colour;
  };
  std::vector<Piece> pieces;
  std::vector<std::pair<std::string, Rgb>> legend;  ///< shown with the series' legend
};

struct LinePlot {
  std::string title;
  std::string x_label;
  std::string y_label;
  std::vector<PlotSeries> series;
  int width = 1000;         ///< pixels
  int height = 520;         ///< pixels
  bool y_from_zero = true;  ///< include y = 0 in the range (errors, counts); not with y_log
  /// Logarithmic y axis (decades): for errors that span from millimetres to tens of metres.
  /// Values at or below the lowest decade are drawn on it.
  bool y_log = false;
  std::optional<std::pair<double, double>> x_range;  ///< fixed x range (aligned panels)
  std::vector<PlotSpan> spans;
  std::vector<PlotMarker> markers;
  std::vector<PlotLevel> levels;
  PlotStrip strip;
};

/// Tick positions covering [lo, hi] with a 1-2-5 step, about `target` of them
/// (Heckbert, "Nice numbers for graph labels", Graphics Gems 1990).
[[nodiscard]] std::vector<double> nice_ticks(double lo, double hi, int target = 6);
/// A tick label with as many decimals as the step needs ("0.25", "10", "1e+03").
[[nodiscard]] std::string format_tick(double value, double step);

/// Decades 10^k covering [lo, hi] (lo > 0), at most `max_decades` of them below hi.
[[nodiscard]] std::vector<double> log_ticks(double lo, double hi, int max_decades = 4);

/// Throws std::invalid_argument when a series' x and y lengths differ.
[[nodiscard]] Canvas render_line_plot(const LinePlot& plot);
/// render_line_plot + write_png; throws IoError on failure.
void write_line_plot_png(const std::string& path, const LinePlot& plot);

}  // namespace pgmcl::app
