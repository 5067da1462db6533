// save_map -> load_map must give back the same grid (trinary), in every image format,
// with resolution and origin bit-identical; and the saved files must be what map_saver
// writes (checked on the raw bytes, not through the loader).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "map_io_test_util.hpp"
#include "pgmcl/maps/map_io.hpp"

namespace pgmcl::maps {
namespace {

using test::TempDir;

OccupancyGrid random_trinary_grid(int w, int h, double res, Pose2 origin, unsigned seed) {
  OccupancyGrid grid(w, h, res, origin);
  std::mt19937 rng(seed);
  const std::int8_t values[] = {kUnknown, kFree, kOccupied};
  for (auto& c : grid.cells()) c = values[rng() % 3];
  return grid;
}

void expect_same_grid(const OccupancyGrid& a, const OccupancyGrid& b) {
  ASSERT_EQ(a.width(), b.width());
  ASSERT_EQ(a.height(), b.height());
  EXPECT_EQ(a.resolution(), b.resolution());  // bit-identical, not just close
  EXPECT_EQ(a.origin().x, b.origin().x);
  EXPECT_EQ(a.origin().y, b.origin().y);
  EXPECT_EQ(a.origin().theta, b.origin().theta);
  EXPECT_EQ(a.cells(), b.cells());
}

TEST(MapIoRoundTrip, TrinaryGridSurvivesEveryFormat) {
  // Awkward numbers on purpose: 0.1 + 0.2 is not 0.3, and the yaw is near -pi.
  const OccupancyGrid grid =
      random_trinary_grid(37, 23, 0.1 + 0.2, {1.25, -3.5000000000000004, -3.0}, 7);
  const TempDir dir;
  for (const std::string image : {"", "m.pgm", "m.pgm.gz", "m.png", "sub/m.pgm"}) {
    SCOPED_TRACE(image.empty() ? "<default>" : image);
    if (image.rfind("sub/", 0) == 0) std::filesystem::create_directories(dir.file("sub"));
    save_map(grid, dir.file("map.yaml"), image);
    MapLoadReport report;
    const OccupancyGrid back = load_map(dir.file("map.yaml"), &report);
    expect_same_grid(grid, back);
    EXPECT_TRUE(report.warnings.empty());
    EXPECT_EQ(report.metadata.image, image.empty() ? "map.pgm" : image);
  }
}

TEST(MapIoRoundTrip, BundledMapSurvivesSaveAndReload) {
  const OccupancyGrid willow = load_map(test::data_dir() + "/willow/willow-full.yaml");
  const TempDir dir;
  save_map(willow, dir.file("willow.yaml"), "willow.pgm.gz");
  expect_same_grid(willow, load_map(dir.file("willow.yaml")));
}

TEST(MapIoRoundTrip, SavedPgmHasMapSaverPixelValues) {
  // One row: free, occupied, unknown, 10 (<= 25: free), 50 (between: unknown),
  // 70 (>= 65: occupied), out of range -5 (unknown). Bottom row = last raster row.
  OccupancyGrid grid(7, 2, 0.05, {}, kFree);
  const std::int8_t row0[] = {kFree, kOccupied, kUnknown, 10, 50, 70, -5};
  for (int c = 0; c < 7; ++c) grid.set(c, 0, row0[c]);
  const TempDir dir;
  save_map(grid, dir.file("s.yaml"));
  const std::vector<std::uint8_t> bytes = test::read_bytes(dir.file("s.pgm"));
  ASSERT_GE(bytes.size(), 14u);
  EXPECT_EQ(std::string(bytes.begin(), bytes.begin() + 3), "P5\n");
  const std::vector<std::uint8_t> raster(bytes.end() - 14, bytes.end());
  const std::vector<std::uint8_t> expected = {254, 254, 254, 254, 254, 254, 254,  // top row
                                              254, 0,   205, 254, 205, 0,   205};
  EXPECT_EQ(raster, expected);
  // And reloading maps the in-between values to what map_server reads from those pixels.
  const OccupancyGrid back = load_map(dir.file("s.yaml"));
  const std::int8_t reread[] = {kFree, kOccupied, kUnknown, kFree, kUnknown, kOccupied, kUnknown};
  for (int c = 0; c < 7; ++c) EXPECT_EQ(back.at(c, 0), reread[c]) << c;
}

TEST(MapIoRoundTrip, SavedYamlHasMapSaverKeys) {
  const OccupancyGrid grid = random_trinary_grid(4, 3, 0.05, {2.0, 3.0, 1.0}, 1);
  const TempDir dir;
  save_map(grid, dir.file("k.yaml"));
  std::ifstream in(dir.file("k.yaml"));
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const char* line :
       {"image: k.pgm\n", "mode: trinary\n", "resolution: 0.05\n", "origin: [2.0, 3.0, 1.0]\n",
        "negate: 0\n", "occupied_thresh: 0.65\n", "free_thresh: 0.196\n"}) {
    EXPECT_NE(text.find(line), std::string::npos) << line << " not in:\n" << text;
  }
}

TEST(MapIoRoundTrip, SaveRejectsUnknownExtensionAndNonFiniteOrigin) {
  const OccupancyGrid grid = random_trinary_grid(4, 3, 0.05, {}, 1);
  const TempDir dir;
  test::expect_map_error([&] { save_map(grid, dir.file("x.yaml"), "x.bmp"); },
                         {"x.bmp", "image", "extension"});
  const OccupancyGrid bad = random_trinary_grid(4, 3, 0.05, {std::nan(""), 0.0, 0.0}, 1);
  test::expect_map_error([&] { save_map(bad, dir.file("y.yaml")); }, {"y.yaml", "origin"});
  test::expect_map_error([&] { save_map(grid, dir.file("no/such/dir/z.yaml")); }, {"z.pgm"});
}

}  // namespace
}  // namespace pgmcl::maps
