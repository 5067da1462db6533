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
  std::vector<Pose2> cloud{{2.5, 2.5, 0.0}};
  const Canvas c = render_overlay(g, OverlayData{truth, est, cloud, ""});
  const MapFrame f(g);
  const PixelPoint mid_truth = f.to_pixel(2.5, 1.0), mid_est = f.to_pixel(2.5, 4.0);
  const PixelPoint particle = f.to_pixel(2.5, 2.5);
  EXPECT_EQ(c.at(static_cast<int>(mid_truth.x), static_cast<int>(mid_truth.y)), colors::kGreen);
  EXPECT_EQ(c.at(static_cast<int>(mid_est.x), static_cast<int>(mid_est.y)), colors::kRed);
  EXPECT_EQ(c.at(static_cast<int>(particle.x), static_cast<int>(particle.y)), colors::kOrange);
  // y up in the world is up in the picture.
  EXPECT_LT(mid_est.y, mid_truth.y);
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
  PlotSeries bad{"bad", {1.0}, {}, colors::kRed};
  p.series = {bad};
  EXPECT_THROW((void)render_line_plot(p), std::invalid_argument);
}

}  // namespace
}  // namespace pgmcl::app
