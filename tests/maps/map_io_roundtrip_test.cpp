// save_map -> load_map must give back the same grid (trinary), in every image format,
// with resolution and origin bit-identical; and the saved files must be what map_saver
// writes (checked on the raw bytes, not through the loader).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "map_io_test_util.hpp"
#include "pgmcl/map_io/map_io.hpp"

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

/// What map_server's scale rule reads back from a cell saved in scale mode.
std::int8_t reloaded_scale_value(std::int8_t v) {
  if (v < 0) return kUnknown;  // transparent: only an alpha channel makes grey 205 unknown
  const double occ = 1.0 - static_cast<double>(std::lround(255.0 * (100 - v) / 100.0)) / 255.0;
  if (occ > 0.65) return kOccupied;
  if (occ < 0.196) return kFree;
  return static_cast<std::int8_t>(std::rint((occ - 0.196) / (0.65 - 0.196) * 100.0));
}

// Scale mode keeps probabilities: each cell is written as grey (100 - v) / 100 and reloaded
// through map_server's scale rule; unknown cells are transparent, so they need a PNG.
TEST(MapIoRoundTrip, ScaleModeKeepsIntermediateProbabilities) {
  OccupancyGrid grid(8, 2, 0.05, {1.0, 2.0, 0.0}, kFree);
  const std::int8_t row0[] = {kFree, kOccupied, kUnknown, 10, 30, 50, 66, 90};
  for (int c = 0; c < 8; ++c) grid.set(c, 0, row0[c]);
  const TempDir dir;
  save_map(grid, dir.file("s.yaml"), "", MapMode::kScale);
  const std::string yaml = testkit::read_text(dir.file("s.yaml"));
  EXPECT_NE(yaml.find("image: s.png\n"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("mode: scale\n"), std::string::npos) << yaml;
  const OccupancyGrid back = load_map(dir.file("s.yaml"));
  for (int c = 0; c < 8; ++c) {
    EXPECT_EQ(back.at(c, 0), reloaded_scale_value(row0[c])) << "cell value " << int{row0[c]};
  }
  EXPECT_EQ(back.at(2, 0), kUnknown);
  EXPECT_EQ(back.at(5, 0), 67);  // 50 % -> grey 128 -> occ 0.498
  EXPECT_EQ(back.at(7, 0), kOccupied);
  EXPECT_EQ(back.at(3, 1), kFree);
  // -1/0/100 grids reload identically in scale mode too, and a PGM is fine when no cell is
  // unknown.
  const OccupancyGrid tri = random_trinary_grid(9, 5, 0.05, {}, 3);
  save_map(tri, dir.file("t.yaml"), "", MapMode::kScale);
  expect_same_grid(tri, load_map(dir.file("t.yaml")));
  OccupancyGrid known(3, 3, 0.05, {}, kFree);
  known.set(1, 1, 40);
  save_map(known, dir.file("k.yaml"), "k.pgm", MapMode::kScale);
  EXPECT_EQ(load_map(dir.file("k.yaml")).at(1, 1), reloaded_scale_value(40));
}

TEST(MapIoRoundTrip, ScaleModeRefusesPgmWithUnknownCellsAndRawIsRefused) {
  OccupancyGrid grid(3, 3, 0.05, {}, kFree);
  grid.set(0, 0, kUnknown);
  const TempDir dir;
  test::expect_map_error([&] { save_map(grid, dir.file("a.yaml"), "a.pgm", MapMode::kScale); },
                         {"a.pgm", "alpha", ".png"});
  test::expect_map_error([&] { save_map(grid, dir.file("b.yaml"), "b.pgm", MapMode::kRaw); },
                         {"b.pgm", "mode", "raw"});
  EXPECT_FALSE(std::filesystem::exists(dir.file("a.yaml")));
  EXPECT_FALSE(std::filesystem::exists(dir.file("b.pgm")));
}

}  // namespace
}  // namespace pgmcl::maps
