#pragma once
/// The pictures of a localisation run: overlay.png (png_overlay.hpp) and error.png, the
/// error over time in two or three panels (plot.hpp).

#include <span>
#include <string>
#include <vector>

#include "pgmcl/eval/evaluation.hpp"
#include "pgmcl/maps/occupancy_grid.hpp"
#include "pgmcl/replay/replay.hpp"
#include "png.hpp"
#include "png_overlay.hpp"

namespace pgmcl::app {

/// What error.png shows: the per-pose errors with lock-on, what the filter said about
/// itself (converged or not, per update), and events such as kidnaps.
struct ErrorPlotData {
  const io::AteResult* ate = nullptr;
  std::span<const replay::UpdateRow> rows;
  double t0 = 0.0;             ///< stamp of the first update: x = stamp - t0
  std::vector<double> events;  ///< stamps of kidnaps (simulated runs)
};

/// Tracked from the start (never more than 1 m off): position and heading error, linear.
/// A global start or a lost filter: the whole run's position error on a log axis with the
/// stretch before lock-on (or after losing track) shaded, then position and heading error
/// after lock-on, linear. Under the first panel a strip shows what the filter said:
/// converged (green), converged while more than 1 m off (red), not converged (grey).
[[nodiscard]] Canvas render_error_plot(const ErrorPlotData& data);

/// The poses of a search before lock-on, [first, second): from the start (a global start)
/// or from the last event (kidnap) before lock-on; empty when tracked from the start or
/// lost. The overlay draws them pale.
[[nodiscard]] std::pair<std::size_t, std::size_t> search_range(const io::Trajectory& trajectory,
                                                               const io::AteResult* ate,
                                                               std::span<const double> events);

/// The key figures for overlay.png's header: which log on which map (file names), how it
/// started, ATE and lock-on, the final cloud; whether a signal stopped the run.
[[nodiscard]] std::string overlay_subtitle(const replay::ReplayResult& run, const std::string& log,
                                           const std::string& map);

}  // namespace pgmcl::app
