// Canvas, PNG writing, map overlay and line plots: pixel-level checks against the geometry
// they were asked to draw, and a PNG round trip through stb_image.
#include <gtest/gtest.h>
#include <stb/stb_image.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "cli_test_util.hpp"
#include "overlay_parts.hpp"
#include "pgmcl/io/errors.hpp"
#include "plot.hpp"
#include "png.hpp"
#include "png_overlay.hpp"

namespace pgmcl::app {
namespace {

int count_colour(const Canvas& c, Rgb colour, int x0 = 0, int y0 = 0, int x1 = -1, int y1 = -1) {
  if (x1 < 0) x1 = c.width() - 1;
  if (y1 < 0) y1 = c.height() - 1;
  int n = 0;
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) n += c.at(x, y) == colour;
  return n;
}

TEST(CliPictures, DiscAndLineCoverTheirGeometry) {
  Canvas c(100, 80);
  c.disc(50.0, 40.0, 10.0, colors::kRed);
  // Pixels inside radius 9.5 are red, outside 10.5 are not.
  for (int y = 0; y < c.height(); ++y) {
    for (int x = 0; x < c.width(); ++x) {
      const double d = std::hypot(x - 50.0, y - 40.0);
      if (d < 9.5) {
        EXPECT_EQ(c.at(x, y), colors::kRed) << x << "," << y;
      } else if (d > 10.5) {
        EXPECT_EQ(c.at(x, y), colors::kWhite) << x << "," << y;
      }
    }
  }
  Canvas l(100, 80);
  l.line({5.0, 5.0}, {95.0, 75.0}, colors::kBlue, 1.0);
  // Every column between the endpoints has exactly the pixel nearest the line set.
  for (int x = 5; x <= 95; ++x) {
    const double y = 5.0 + (x - 5.0) * 70.0 / 90.0;
    EXPECT_EQ(l.at(x, static_cast<int>(std::lround(y))), colors::kBlue) << x;
  }
  EXPECT_EQ(l.at(50, 10), colors::kWhite);
  // Clipping: drawing off-canvas neither crashes nor paints.
  Canvas off(10, 10);
  off.line({-100.0, -100.0}, {-50.0, -20.0}, colors::kRed, 3.0);
  off.disc(1e12, 5.0, 3.0, colors::kRed);
  EXPECT_EQ(count_colour(off, colors::kRed), 0);
}

TEST(CliPictures, TextDrawsInsideItsReportedBox) {
  Canvas c(200, 60);
  const std::string s = "ATE 0.05 m";
  const int w = Canvas::text_width(s, 2), h = Canvas::text_height(s, 2);
  EXPECT_GT(w, 50);
  EXPECT_GT(h, 8);
  c.text(10, 10, s, colors::kBlack, 2);
  const int inside = count_colour(c, colors::kBlack, 10, 10, 10 + w, 10 + h + 4);
  EXPECT_GT(inside, 60);
  EXPECT_EQ(count_colour(c, colors::kBlack), inside);
}

TEST(CliPictures, PngRoundTripsThroughStbImage) {
  Canvas c(37, 23, colors::kGrey);
  c.set(0, 0, Rgb{1, 2, 3});
  c.set(36, 22, Rgb{250, 128, 7});
  const cli_test::TempDir dir("cli_pictures_png");
  const auto path = dir.file("c.png");
  write_png(c, path);
  int w = 0, h = 0, n = 0;
  unsigned char* data = stbi_load(path.c_str(), &w, &h, &n, 3);
  ASSERT_NE(data, nullptr);
  EXPECT_EQ(w, 37);
  EXPECT_EQ(h, 23);
  std::vector<unsigned char> px(data, data + static_cast<std::size_t>(w) * h * 3);
  stbi_image_free(data);
  EXPECT_EQ(std::vector<unsigned char>(c.data().begin(), c.data().end()), px);
  EXPECT_THROW(write_png(c, "/nonexistent-dir/x.png"), io::IoError);
  // A full disk: stb ignores fwrite's result; write_png does not.
  try {
    write_png(c, "/dev/full");
    ADD_FAILURE() << "a write to /dev/full succeeded";
  } catch (const io::IoError& e) {
    EXPECT_NE(std::string(e.what()).find("No space left on device"), std::string::npos) << e.what();
  }
}

TEST(CliPictures, MapFramePutsWorldPointsOnTheirCells) {
  // A rotated grid: cell colours in the picture must follow the map, and to_pixel must land
  // on the picture of the cell containing the point.
  maps::OccupancyGrid g(40, 30, 0.1, Pose2{2.0, -1.0, 0.7}, maps::kUnknown);
  for (int r = 0; r < 30; ++r)
    for (int c = 0; c < 40; ++c) g.set(c, r, (c + 2 * r) % 3 == 0 ? maps::kOccupied : maps::kFree);
  const MapFrame f(g, 2000, 400);
  EXPECT_EQ(f.pixels_per_cell(), 10.0);
  const Canvas pic = f.draw_map();
  for (int r = 0; r < 30; r += 3) {
    for (int c = 0; c < 40; c += 7) {
      double gx = 0, gy = 0;
      g.cell_center_global(c, r, gx, gy);
      const PixelPoint p = f.to_pixel(gx, gy);
      const Rgb expect = g.at(c, r) == maps::kOccupied ? colors::kBlack : colors::kWhite;
      EXPECT_EQ(pic.at(static_cast<int>(std::lround(p.x)), static_cast<int>(std::lround(p.y))),
                expect)
          << c << "," << r;
    }
  }
  // Shrinking keeps an isolated occupied cell visible.
  maps::OccupancyGrid big(5000, 100, 0.05, Pose2{}, maps::kFree);
  big.set(2501, 50, maps::kOccupied);
  const MapFrame fb(big, 1000, 400);
  EXPECT_EQ(fb.width(), 1000);
  EXPECT_EQ(count_colour(fb.draw_map(), colors::kBlack), 1);
}

TEST(CliPictures, OverlayDrawsPathsAndParticles) {
  maps::OccupancyGrid g(100, 100, 0.05, Pose2{}, maps::kFree);
  std::vector<Pose2> truth{{1.0, 1.0, 0.0}, {4.0, 1.0, 0.0}}, est{{1.0, 4.0, 0.0}, {4.0, 4.0, 0.0}};
  // One particle on each path: the final cloud is drawn over the paths.
  std::vector<Pose2> cloud{{2.0, 1.0, 0.0}, {3.0, 4.0, 0.0}};
  OverlayData d;
  d.truth = truth;
  d.estimate = est;
  d.particles = cloud;
  OverlayLayout lay;
  const Canvas c = render_overlay(g, d, &lay);
  const MapFrame f(g);
  auto at = [&](double x, double y) {
    const PixelPoint p = f.to_pixel(x, y);
    return c.at(static_cast<int>(std::lround(p.x)) + lay.map_x,
                static_cast<int>(std::lround(p.y)) + lay.map_y);
  };
  EXPECT_EQ(at(2.5, 1.0), colors::kGreen);
  EXPECT_EQ(at(2.5, 4.0), colors::kRed);
  EXPECT_EQ(at(2.0, 1.0), particle_colour(1.0));
  EXPECT_EQ(at(3.0, 4.0), particle_colour(1.0));
  // y up in the world is up in the picture.
  EXPECT_LT(f.to_pixel(2.5, 4.0).y, f.to_pixel(2.5, 1.0).y);
}

TEST(CliPictures, OverlayHeaderAndCoordinatesStayOffTheMap) {
  // A small free map: the title, figures and legend sit above it, coordinates beside it,
  // so every map pixel away from the paths is still the map's white.
  maps::OccupancyGrid g(60, 40, 0.05, Pose2{-1.0, -1.0, 0.0}, maps::kFree);
  std::vector<Pose2> truth{{0.5, 0.2, 0.0}, {1.5, 0.2, 0.0}};
  OverlayData d;
  d.truth = truth;
  d.estimate = truth;
  d.title = "a-run-name";
  d.subtitle = "the key figures of the run, long enough to wrap onto a second line of text";
  OverlayLayout lay;
  const Canvas c = render_overlay(g, d, &lay);
  const MapFrame f(g);
  EXPECT_GT(lay.map_y, 60);  // title, figures, legend rows
  EXPECT_GT(lay.map_x, 20);  // y coordinates
  int header_ink = 0;
  for (int y = 0; y < lay.map_y - 6; ++y)
    for (int x = 0; x < c.width(); ++x) header_ink += c.at(x, y) != colors::kWhite;
  EXPECT_GT(header_ink, 500);
  // The map's upper half is untouched (the paths run along its bottom).
  const PixelPoint path_top = f.to_pixel(0.0, 0.5);
  for (int y = 0; y < static_cast<int>(path_top.y); ++y)
    for (int x = 0; x < f.width(); ++x)
      ASSERT_EQ(c.at(x + lay.map_x, y + lay.map_y), colors::kWhite) << x << "," << y;
  // An estimate that leaves the map is clipped at its edge: outside the map, only the
  // legend's red swatch is red, as with an estimate inside it.
  auto red_outside = [&](const Canvas& a) {
    int n = 0;
    for (int y = 0; y < a.height(); ++y)
      for (int x = 0; x < a.width(); ++x) {
        const bool inside = x >= lay.map_x && x < lay.map_x + f.width() && y >= lay.map_y &&
                            y < lay.map_y + f.height();
        n += !inside && a.at(x, y) == colors::kRed;
      }
    return n;
  };
  const int legend_red = red_outside(c);
  EXPECT_GT(legend_red, 0);
  std::vector<Pose2> astray{{0.5, 0.5, 0.0}, {40.0, 60.0, 0.0}, {-30.0, 0.4, 0.0}};
  d.estimate = astray;
  EXPECT_EQ(red_outside(render_overlay(g, d, &lay)), legend_red);
  // Tick labels in the left and bottom margins.
  int margin_ink = 0;
  for (int y = lay.map_y; y < lay.map_y + f.height(); ++y)
    for (int x = 0; x < lay.map_x - 6; ++x) margin_ink += c.at(x, y) == colors::kBlack;
  EXPECT_GT(margin_ink, 20);
}

TEST(CliPictures, OverlayTickLabelsOnAThinMapDoNotTouch) {
  // A 40 x 4 m corridor: its y labels, one text line each, with blank rows between them.
  maps::OccupancyGrid g(800, 80, 0.05, Pose2{0.0, -1.0, 0.0}, maps::kFree);
  OverlayLayout lay;
  const Canvas c = render_overlay(g, OverlayData{}, &lay);
  const MapFrame f(g);
  auto row_has_ink = [](const Canvas& a, int x0, int x1, int y) {
    for (int x = x0; x < x1; ++x)
      if (a.at(x, y) == colors::kBlack) return true;
    return false;
  };
  Canvas probe(200, 60, colors::kWhite);
  probe.text(0, 0, "-0.5 m", colors::kBlack, 2);
  int label_rows = 0;
  for (int y = 0; y < probe.height(); ++y) label_rows += row_has_ink(probe, 0, probe.width(), y);
  std::vector<int> runs;  // heights of the runs of rows with ink in the left margin
  int run = 0;
  for (int y = lay.map_y; y < lay.map_y + f.height() + label_rows; ++y) {
    if (row_has_ink(c, 0, lay.map_x - 6, y)) {
      ++run;
    } else if (run > 0) {
      runs.push_back(run);
      run = 0;
    }
  }
  if (run > 0) runs.push_back(run);
  ASSERT_GE(runs.size(), 2u);
  for (const int h : runs) EXPECT_LE(h, label_rows);
}

TEST(CliPictures, OverlayZoomsOnASmallFinalCloudOnly) {
  maps::OccupancyGrid g(800, 800, 0.05, Pose2{}, maps::kFree);  // 40 m
  std::vector<Pose2> est{{5.0, 5.0, 0.0}, {20.0, 20.0, 0.5}};
  std::vector<Pose2> tight, spread;
  std::vector<double> w;
  for (int i = 0; i < 50; ++i) {
    tight.push_back({20.0 + 0.004 * i, 20.0 - 0.003 * i, 0.5});
    spread.push_back({1.0 + 0.7 * i, 38.0 - 0.7 * i, 0.0});
    w.push_back(i == 49 ? 1.0 : 0.1);
  }
  OverlayData d;
  d.estimate = est;
  d.particles = tight;
  d.weights = w;
  OverlayLayout lay;
  const Canvas c = render_overlay(g, d, &lay);
  ASSERT_TRUE(lay.zoom);
  EXPECT_GT(lay.zoom_x, lay.map_x + 700);
  EXPECT_EQ(lay.zoom_metres, 1.0);
  // Heavy and light particles in the zoomed view, in their two shades.
  int heavy = 0, light = 0;
  for (int y = lay.zoom_y; y < lay.zoom_y + lay.zoom_side; ++y) {
    for (int x = lay.zoom_x; x < lay.zoom_x + lay.zoom_side; ++x) {
      heavy += c.at(x, y) == particle_colour(1.0);
      light += c.at(x, y) == particle_colour(0.1);
    }
  }
  EXPECT_GT(heavy, 5);
  EXPECT_GT(light, 100);
  d.particles = spread;
  (void)render_overlay(g, d, &lay);
  EXPECT_FALSE(lay.zoom);
}

TEST(CliPictures, OverlayArrowsAreSizedForThePictureNotInMetres) {
  // The same 800-cell picture of a 4 m (5 mm) and a 40 m (5 cm) map: the end arrow has the
  // same length in pixels on both (it was 0.6 m: 120 px on the lab map, 12 px here).
  auto red_pixels = [](double res) {
    maps::OccupancyGrid g(800, 800, res, Pose2{}, maps::kFree);
    std::vector<Pose2> est{{400 * res, 400 * res, 0.0}};
    OverlayData d;
    d.estimate = est;
    const Canvas c = render_overlay(g, d);
    int n = 0;
    for (int y = 0; y < c.height(); ++y)
      for (int x = 0; x < c.width(); ++x) n += c.at(x, y) == colors::kRed;
    return n;
  };
  const int fine = red_pixels(0.005), coarse = red_pixels(0.05);
  EXPECT_GT(fine, 50);
  EXPECT_EQ(fine, coarse);
  EXPECT_DOUBLE_EQ(arrow_pixels(1000), 30.0);
}

TEST(CliPictures, OverlayBreaksPathsAtJumpsAndDrawsObstacles) {
  std::vector<Pose2> path;
  for (int i = 0; i < 20; ++i) path.push_back({0.1 * i, 0.0, 0.0});
  for (int i = 0; i < 20; ++i) path.push_back({10.0 + 0.1 * i, 5.0, 0.0});  // a kidnap
  EXPECT_EQ(path_jumps(path), std::vector<std::size_t>{20});
  EXPECT_TRUE(path_jumps(std::span(path).first(20)).empty());
  maps::OccupancyGrid g(300, 200, 0.05, Pose2{-1.0, -2.0, 0.0}, maps::kFree);
  OverlayData d;
  d.truth = path;
  ObstacleDrawing person;
  person.radius = 0.25;
  person.path = {{2.0, 4.0, 0.0}, {4.0, 4.0, 0.0}};
  d.obstacles = {person};
  OverlayLayout lay;
  const Canvas c = render_overlay(g, d, &lay);
  const MapFrame f(g);
  // Midway along the jump: not the thick green line (a thin dotted one at most).
  const PixelPoint mid = f.to_pixel(6.0, 2.5);
  int green = 0;
  for (int dy = -2; dy <= 2; ++dy)
    for (int dx = -2; dx <= 2; ++dx)
      green += c.at(static_cast<int>(mid.x) + lay.map_x + dx,
                    static_cast<int>(mid.y) + lay.map_y + dy) == colors::kGreen;
  EXPECT_LT(green, 8);
  int purple = 0;
  for (int y = lay.map_y; y < c.height(); ++y)
    for (int x = 0; x < c.width(); ++x) purple += c.at(x, y) == colors::kPurple;
  EXPECT_GT(purple, 30);
}

TEST(CliPictures, OverlayDrawsTheSearchAndItsJumpToLockOnPale) {
  // A global start: three poses of a search far from the track, then the jump to the right
  // place at lock-on (pose 3) and the settled path.
  std::vector<Pose2> est{{8.0, 8.0, 0.0}, {8.1, 8.0, 0.0}, {8.2, 8.0, 0.0}};
  for (int i = 0; i < 20; ++i) est.push_back({1.0 + 0.1 * i, 1.0, 0.0});
  maps::OccupancyGrid g(200, 200, 0.05, Pose2{}, maps::kFree);
  OverlayData d;
  d.estimate = est;
  d.search_begin = 0;
  d.search_end = 3;
  OverlayLayout lay;
  const Canvas c = render_overlay(g, d, &lay);
  const MapFrame f(g);
  auto around = [&](double x, double y, Rgb colour) {
    const PixelPoint p = f.to_pixel(x, y);
    return count_colour(
        c, colour, static_cast<int>(p.x) + lay.map_x - 3, static_cast<int>(p.y) + lay.map_y - 3,
        static_cast<int>(p.x) + lay.map_x + 3, static_cast<int>(p.y) + lay.map_y + 3);
  };
  EXPECT_GT(around(2.0, 1.0, colors::kRed), 0);  // the settled path
  EXPECT_EQ(around(8.1, 8.0, colors::kRed), 0);  // the search, its first pose included
  EXPECT_GT(around(8.1, 8.0, overlay::kPaleRed), 0);
  EXPECT_EQ(around(4.6, 4.5, colors::kRed), 0);  // midway along the jump to lock-on
}

TEST(CliPictures, NiceTicksAreOneTwoFiveStepsCoveringTheRange) {
  struct Case {
    double lo, hi;
  };
  for (const Case k :
       {Case{0.0, 1.0}, Case{0.013, 0.871}, Case{-3.2, 117.0}, Case{5.0, 5.4}, Case{0.0, 2345.0}}) {
    const auto t = nice_ticks(k.lo, k.hi, 6);
    ASSERT_GE(t.size(), 3u) << k.lo << " " << k.hi;
    EXPECT_LE(t.front(), k.lo);
    EXPECT_GE(t.back(), k.hi);
    const double step = t[1] - t[0];
    const double mant = step / std::pow(10.0, std::floor(std::log10(step * (1 + 1e-9))));
    EXPECT_TRUE(std::abs(mant - 1) < 1e-9 || std::abs(mant - 2) < 1e-9 || std::abs(mant - 5) < 1e-9)
        << step;
    EXPECT_LE(t.size(), 12u);
  }
  EXPECT_EQ(format_tick(0.25, 0.05), "0.25");
  EXPECT_EQ(format_tick(20.0, 10.0), "20");
  EXPECT_EQ(format_tick(-0.1, 0.1), "-0.1");
}

TEST(CliPictures, LinePlotPutsDataWhereTheAxesSay) {
  LinePlot p;
  p.title = "error";
  p.x_label = "time [s]";
  p.y_label = "m";
  PlotSeries s{"", {0.0, 10.0}, {0.0, 1.0}, colors::kRed};
  p.series = {s};
  const Canvas c = render_line_plot(p);
  // The diagonal from (0, 0) to (10, 1) fills a straight run of red pixels: the midpoint
  // of the red pixels' bounding box must itself be red (it is on the line).
  int xmin = c.width(), xmax = -1, ymin = c.height(), ymax = -1;
  for (int y = 0; y < c.height(); ++y)
    for (int x = 0; x < c.width(); ++x)
      if (c.at(x, y) == colors::kRed) {
        xmin = std::min(xmin, x), xmax = std::max(xmax, x);
        ymin = std::min(ymin, y), ymax = std::max(ymax, y);
      }
  ASSERT_GT(xmax, xmin + 200);
  ASSERT_GT(ymax, ymin + 100);
  EXPECT_EQ(c.at((xmin + xmax) / 2, (ymin + ymax) / 2), colors::kRed);
  // (0, 0) is bottom-left: the lowest red pixel is at the left end.
  EXPECT_TRUE(c.at(xmin + 1, ymax - 1) == colors::kRed || c.at(xmin + 1, ymax) == colors::kRed);
  // A marker's label does not hide data running along the bottom after it (lock-on, then a
  // small error): only the marker's own line crosses the data.
  PlotSeries low{"", {}, {}, colors::kRed};
  for (int i = 0; i <= 1000; ++i) {
    low.x.push_back(0.01 * i);
    low.y.push_back(i < 500 ? 1.0 : 0.03);
  }
  p.series = {low};
  const int unmarked = count_colour(render_line_plot(p), colors::kRed);
  p.markers = {{6.0, "locked on at 6.0 s", colors::kBlack}};
  const int marked = count_colour(render_line_plot(p), colors::kRed);
  EXPECT_LT(unmarked - marked, 20) << unmarked << " " << marked;
  PlotSeries bad{"bad", {1.0}, {}, colors::kRed};
  p.series = {bad};
  EXPECT_THROW((void)render_line_plot(p), std::invalid_argument);
}

}  // namespace
}  // namespace pgmcl::app
