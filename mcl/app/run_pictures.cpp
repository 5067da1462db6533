#include "run_pictures.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <limits>

#include "plot.hpp"

namespace pgmcl::app {
namespace {

constexpr Rgb kSearchFill{236, 236, 236};
constexpr Rgb kLostFill{252, 226, 226};
constexpr Rgb kNotConverged{205, 205, 205};
constexpr Rgb kConverged{60, 170, 80};
constexpr Rgb kFalselyConverged{220, 30, 30};

std::string fmt(const char* f, double a, double b = 0.0, double c = 0.0) {
  char buf[200];
  std::snprintf(buf, sizeof buf, f, a, b, c);
  return buf;
}

/// Colour per update of what the filter said, from one update's stamp to the next.
PlotStrip filter_state_strip(const ErrorPlotData& d) {
  PlotStrip strip;
  const double lost = io::AteOptions{}.lost_translation;
  const auto& errors = d.ate->errors;
  std::size_t j = 0;
  bool any_false = false;
  for (std::size_t i = 0; i < d.rows.size(); ++i) {
    const replay::UpdateRow& u = d.rows[i];
    while (j < errors.size() && errors[j].stamp < u.stamp) ++j;
    const bool off =
        j < errors.size() && errors[j].stamp == u.stamp && errors[j].translation > lost;
    Rgb c = kNotConverged;
    if (u.converged) c = off ? kFalselyConverged : kConverged;
    any_false = any_false || (u.converged && off);
    const double x0 = u.stamp - d.t0;
    const double x1 = i + 1 < d.rows.size() ? d.rows[i + 1].stamp - d.t0 : x0;
    if (!strip.pieces.empty() && strip.pieces.back().colour == c) {
      strip.pieces.back().x1 = x1;
    } else {
      strip.pieces.push_back({x0, x1, c});
    }
  }
  strip.legend = {{"filter says: converged", kConverged}, {"not converged", kNotConverged}};
  if (any_false) strip.legend.emplace_back("converged, >1 m off", kFalselyConverged);
  return strip;
}

/// The errors from `from` seconds on (a panel shows only its own stretch).
PlotSeries series_of(const io::AteResult& ate, double t0, double from, bool heading) {
  // No label: each panel has one series, named by its title.
  PlotSeries s{"", {}, {}, heading ? colors::kBlue : colors::kRed};
  for (const io::PoseError& e : ate.errors) {
    if (e.stamp - t0 < from - 1e-9) continue;
    s.x.push_back(e.stamp - t0);
    s.y.push_back(heading ? e.rotation_deg : e.translation);
  }
  return s;
}

}  // namespace

Canvas render_error_plot(const ErrorPlotData& d) {
  const io::AteResult& ate = *d.ate;
  const double lost = io::AteOptions{}.lost_translation;
  const double end = ate.errors.empty() ? 1.0 : ate.errors.back().stamp - d.t0;
  const bool searched = ate.lock_on_s && *ate.lock_on_s > 0.0;
  const bool is_lost = !ate.lock_on_s;
  const int w = 1000, h = 330;
  const PlotStrip strip = filter_state_strip(d);
  auto panel = [&](const std::string& title, const std::string& unit, double from, double to,
                   bool heading) {
    LinePlot p;
    p.title = title;
    p.x_label = "time since the first scan [s]";
    p.y_label = unit;
    p.series = {series_of(ate, d.t0, from, heading)};
    p.x_range = std::pair{from, to};
    p.width = w;
    p.height = h;
    if (!heading) {
      p.height += 12;
      p.strip = strip;
      for (const double e : d.events) p.markers.push_back({e - d.t0, "kidnap", colors::kPurple});
    }
    return p;
  };
  std::vector<LinePlot> panels;
  if (searched) {
    // The search, on a log axis over a stretch a few times its length; then the run after
    // lock-on on linear axes, where the tracking error is visible.
    const double t = *ate.lock_on_s;
    const double shown = std::min(end, std::max(4.0 * t, 30.0));
    // The search starts at the last kidnap before lock-on, else at the start (global).
    double from = 0.0;
    for (const double e : d.events)
      if (e - d.t0 < t) from = std::max(from, e - d.t0);
    LinePlot p =
        from > 0.0
            ? panel(fmt("Kidnapped at %.1f s, locked on again at %.1f s: position error, log "
                        "scale",
                        from, t),
                    "metres", 0.0, shown, false)
            : panel(fmt("Global search: position error over the first %.0f s, log scale "
                        "(locked on at %.1f s)",
                        shown, t),
                    "metres", 0.0, shown, false);
    p.y_log = true;
    p.levels.push_back({lost, "1 m: lock-on threshold", colors::kDarkGrey});
    p.spans.push_back({from, t, from > 0.0 ? "re-localising" : "before lock-on", kSearchFill});
    p.markers.push_back({t, fmt("locked on at %.1f s", t), colors::kBlack});
    panels.push_back(p);
    panels.push_back(panel(
        fmt("After lock-on: position error (RMSE %.3f m, max %.3f m); whole run %.3f m",
            ate.post_lock_translation.rms, ate.post_lock_translation.max, ate.translation.rms),
        "metres", t, end, false));
    panels.push_back(panel(fmt("After lock-on: heading error (RMSE %.2f deg, whole run %.2f deg)",
                               ate.post_lock_heading.rms, ate.heading.rms),
                           "degrees", t, end, true));
  } else if (is_lost) {
    double lost_from = 0.0;
    for (const io::PoseError& e : ate.errors)
      if (e.translation <= lost) lost_from = e.stamp - d.t0;
    LinePlot p =
        panel(fmt("Position error, log scale (ATE RMSE %.3f m, max %.1f m): lost at the end",
                  ate.translation.rms, ate.translation.max),
              "metres", 0.0, end, false);
    p.y_log = true;
    p.levels.push_back({lost, "1 m: lost threshold", colors::kDarkGrey});
    p.spans.push_back({lost_from, end, "lost from here on", kLostFill});
    panels.push_back(p);
    panels.push_back(
        panel(fmt("Heading error (RMSE %.2f deg, max %.1f deg)", ate.heading.rms, ate.heading.max),
              "degrees", 0.0, end, true));
  } else {
    panels.push_back(panel(fmt("Position error (ATE RMSE %.3f m, max %.3f m; within 1 m "
                               "throughout)",
                               ate.translation.rms, ate.translation.max),
                           "metres", 0.0, end, false));
    panels.push_back(
        panel(fmt("Heading error (RMSE %.2f deg, max %.1f deg)", ate.heading.rms, ate.heading.max),
              "degrees", 0.0, end, true));
  }
  int total = 0;
  for (const LinePlot& p : panels) total += p.height;
  Canvas c(w, total);
  int y = 0;
  for (const LinePlot& p : panels) {
    c.blit(render_line_plot(p), 0, y);
    y += p.height;
  }
  return c;
}

std::pair<std::size_t, std::size_t> search_range(const io::Trajectory& trajectory,
                                                 const io::AteResult* ate,
                                                 std::span<const double> events) {
  if (ate == nullptr || !ate->lock_on_s || *ate->lock_on_s <= 0.0 || trajectory.empty())
    return {0, 0};
  const double t = trajectory.front().stamp + *ate->lock_on_s;
  double from = -std::numeric_limits<double>::infinity();
  for (const double e : events)
    if (e < t) from = std::max(from, e);
  auto index_at = [&](double stamp) {
    std::size_t i = 0;
    while (i < trajectory.size() && trajectory[i].stamp < stamp) ++i;
    return i;
  };
  return {index_at(from), index_at(t)};
}

std::string overlay_subtitle(const replay::ReplayResult& run, const std::string& log,
                             const std::string& map) {
  const io::RunMetrics& m = run.metrics;
  std::string s;
  if (!log.empty()) s += std::filesystem::path(log).filename().string();
  if (!map.empty()) s += " on " + std::filesystem::path(map).filename().string();
  if (!s.empty()) s += ", ";
  s += "start: " + run.start + ". " + std::to_string(m.updates) + " updates";
  if (m.accuracy) {
    const io::AccuracyMetrics& a = *m.accuracy;
    s += fmt(", ATE RMSE %.3f m (max %.3f m)", a.ate_rmse_m, a.ate_max_m);
    if (!a.lock_on_s) {
      s += ", lost at the end";
    } else if (*a.lock_on_s > 0.0) {
      s += fmt(", locked on at %.1f s, then %.3f m", *a.lock_on_s, a.post_lock_ate_rmse_m);
    }
  }
  s += ". Final cloud " + std::to_string(run.particles.size()) + " particles.";
  if (!m.complete) s += " Interrupted: the run so far.";
  return s;
}

}  // namespace pgmcl::app
