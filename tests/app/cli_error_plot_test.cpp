// error.png: the panels a tracking, a global and a lost run get, the log axis, and the strip
// of what the filter said about itself.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "plot.hpp"
#include "run_pictures.hpp"

namespace pgmcl::app {
namespace {

int count_colour(const Canvas& c, Rgb colour) {
  int n = 0;
  for (int y = 0; y < c.height(); ++y)
    for (int x = 0; x < c.width(); ++x) n += c.at(x, y) == colour;
  return n;
}

/// 200 poses 0.5 s apart with the given position error; lock-on as evaluate_ate defines it.
struct FakeRun {
  io::AteResult ate;
  std::vector<replay::UpdateRow> rows;
};

FakeRun make_run(double (*error)(double t), bool converged_always) {
  FakeRun r;
  for (int i = 0; i < 200; ++i) {
    const double t = 100.0 + 0.5 * i;
    r.ate.errors.push_back({t, error(t - 100.0), 1.0});
    replay::UpdateRow u;
    u.stamp = t;
    u.converged = converged_always || t - 100.0 > 20.0;
    r.rows.push_back(u);
  }
  double lock = 0.0;
  bool lost = false;
  for (const auto& e : r.ate.errors) {
    if (e.translation > 1.0) lock = e.stamp - 100.0 + 0.5;
  }
  lost = r.ate.errors.back().translation > 1.0;
  if (!lost) r.ate.lock_on_s = lock;
  r.ate.translation.rms = 0.5;
  return r;
}

TEST(CliErrorPlot, TrackingGetsTwoLinearPanelsAndTheFilterStrip) {
  const FakeRun r = make_run([](double t) { return 0.02 + 0.01 * std::sin(t); }, true);
  ASSERT_EQ(*r.ate.lock_on_s, 0.0);
  const Canvas c = render_error_plot({&r.ate, r.rows, 100.0, {}});
  EXPECT_EQ(c.height(), 342 + 330);
  EXPECT_GT(count_colour(c, Rgb{60, 170, 80}), 500);       // converged all along
  EXPECT_EQ(count_colour(c, Rgb{220, 30, 30}) > 0, true);  // the error line itself
}

TEST(CliErrorPlot, AGlobalStartGetsTheSearchOnALogAxisThenTheRunAfterLockOn) {
  // 10 m off for 12 s, then 3 cm: the search panel, then position and heading after it.
  const FakeRun r = make_run([](double t) { return t < 12.0 ? 10.0 : 0.03; }, false);
  ASSERT_TRUE(r.ate.lock_on_s);
  EXPECT_NEAR(*r.ate.lock_on_s, 12.0, 0.5);
  const Canvas c = render_error_plot({&r.ate, r.rows, 100.0, {}});
  EXPECT_EQ(c.height(), 342 + 342 + 330);
  EXPECT_GT(count_colour(c, Rgb{236, 236, 236}), 2000);  // the shaded search
  EXPECT_GT(count_colour(c, Rgb{205, 205, 205}), 100);   // not converged at first
}

TEST(CliErrorPlot, ALostRunShadesWhereItWasLostAndMarksKidnaps) {
  const FakeRun r = make_run([](double t) { return t < 50.0 ? 0.03 : 8.0; }, true);
  ASSERT_FALSE(r.ate.lock_on_s);
  const Canvas c = render_error_plot({&r.ate, r.rows, 100.0, {150.0}});
  EXPECT_EQ(c.height(), 342 + 330);
  EXPECT_GT(count_colour(c, Rgb{252, 226, 226}), 2000);  // "lost from here on"
  EXPECT_GT(count_colour(c, Rgb{220, 30, 30}), 100);     // converged while 8 m off
  EXPECT_GT(count_colour(c, colors::kPurple), 50);       // the kidnap marker
}

TEST(CliErrorPlot, LogTicksAreDecadesCappedBelowTheTop) {
  EXPECT_EQ(log_ticks(0.004, 12.0), (std::vector<double>{0.01, 0.1, 1.0, 10.0, 100.0}));
  EXPECT_EQ(log_ticks(0.02, 0.5), (std::vector<double>{0.01, 0.1, 1.0}));
  // A log plot puts 0.01 and 1 an equal distance either side of 0.1.
  LinePlot p;
  p.y_log = true;
  p.series = {PlotSeries{"", {0.0, 1.0, 2.0}, {0.01, 0.1, 1.0}, colors::kRed}};
  const Canvas c = render_line_plot(p);
  std::vector<int> ys;
  for (int y = 0; y < c.height(); ++y)
    for (int x = 0; x < c.width(); ++x)
      if (c.at(x, y) == colors::kRed && (ys.empty() || ys.back() != y)) ys.push_back(y);
  ASSERT_GT(ys.size(), 100u);
  // A straight line on a log axis: the red pixels span the plot height evenly, so the
  // middle row of the red run is red at the middle column.
  int xmin = c.width(), xmax = 0;
  for (int y = 0; y < c.height(); ++y)
    for (int x = 0; x < c.width(); ++x)
      if (c.at(x, y) == colors::kRed) xmin = std::min(xmin, x), xmax = std::max(xmax, x);
  EXPECT_EQ(c.at((xmin + xmax) / 2, (ys.front() + ys.back()) / 2), colors::kRed);
}

TEST(CliOverlayHeader, NamesTheFilesAndSaysWhenTheRunWasInterrupted) {
  replay::ReplayResult run;
  run.start = "global localisation";
  run.metrics.updates = 12;
  const std::string whole = overlay_subtitle(run, "logs/raw.log.gz", "maps/map.yaml");
  EXPECT_EQ(whole,
            "raw.log.gz on map.yaml, start: global localisation. 12 updates. Final cloud 0 "
            "particles.");
  run.metrics.complete = false;
  EXPECT_EQ(overlay_subtitle(run, "raw.log", "map.yaml"),
            "raw.log on map.yaml, start: global localisation. 12 updates. Final cloud 0 "
            "particles. Interrupted: the run so far.");
}

}  // namespace
}  // namespace pgmcl::app
