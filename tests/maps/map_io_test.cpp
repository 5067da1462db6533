// Map loading against the bundled maps in data/maps (copies of nav2's and Willow Garage's
// maps; see data/README.md). The nav2 test map is checked cell by cell against the grid
// nav2's own loader test expects.

#include "pgmcl/map_io/map_io.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "map_io_test_util.hpp"

namespace pgmcl::maps {
namespace {

using test::data_dir;

std::string testmap_dir() {
  return data_dir() + "/nav2/testmap";
}

// EXPECTED_GRID.txt lists nav2's g_valid_image_content: OccupancyGrid.data in order, so the
// first line is grid row 0, the bottom row of the image.
std::vector<int> expected_testmap() {
  std::ifstream in(testmap_dir() + "/EXPECTED_GRID.txt");
  std::vector<int> values;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ls(line);
    int v = 0;
    while (ls >> v) values.push_back(v);
  }
  return values;
}

void expect_testmap(const OccupancyGrid& grid) {
  const std::vector<int> expected = expected_testmap();
  ASSERT_EQ(expected.size(), 100u);
  ASSERT_EQ(grid.width(), 10);
  ASSERT_EQ(grid.height(), 10);
  EXPECT_DOUBLE_EQ(grid.resolution(), 0.1);
  for (int row = 0; row < 10; ++row) {
    for (int col = 0; col < 10; ++col) {
      EXPECT_EQ(grid.at(col, row), expected[static_cast<std::size_t>(row * 10 + col)])
          << "cell (" << col << ", " << row << ")";
    }
  }
  EXPECT_DOUBLE_EQ(grid.origin().x, 2.0);
  EXPECT_DOUBLE_EQ(grid.origin().y, 3.0);
  EXPECT_DOUBLE_EQ(grid.origin().theta, 1.0);
}

TEST(MapIoTestmap, PngMatchesNav2ExpectedGrid) {
  MapLoadReport report;
  const OccupancyGrid grid = load_map(testmap_dir() + "/testmap.yaml", &report);
  expect_testmap(grid);
  EXPECT_TRUE(report.warnings.empty());
  EXPECT_EQ(report.metadata.mode, MapMode::kTrinary);
  EXPECT_EQ(report.metadata.image, "testmap.png");
  EXPECT_EQ(report.image_path, testmap_dir() + "/testmap.png");
}

TEST(MapIoTestmap, PgmMatchesNav2ExpectedGrid) {
  // Same YAML, image switched to the PGM (by absolute path, which map_server also allows).
  const test::TempDir dir;
  std::ifstream in(testmap_dir() + "/testmap.yaml");
  std::string yaml((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string key = "\"testmap.png\"";
  ASSERT_NE(yaml.find(key), std::string::npos);
  std::string quoted = "\"";  // appended piecewise: GCC 12 false -Wrestrict on "x" + str
  quoted += testmap_dir();
  quoted += "/testmap.pgm\"";
  yaml.replace(yaml.find(key), key.size(), quoted);
  test::write_text(dir.file("testmap.yaml"), yaml);
  expect_testmap(load_map(dir.file("testmap.yaml")));
}

TEST(MapIoTestmap, YawedOriginPlacesCellsByHand) {
  const OccupancyGrid grid = load_map(testmap_dir() + "/testmap.yaml");
  // origin [2, 3, 1.0]: the centre of cell (col, row) is at (col + 0.5, row + 0.5) * 0.1 in
  // the grid frame, rotated by 1 rad and shifted by (2, 3).
  const double c = std::cos(1.0), s = std::sin(1.0);
  double gx = 0.0, gy = 0.0;
  grid.cell_center_global(0, 0, gx, gy);
  EXPECT_NEAR(gx, 2.0 + 0.05 * c - 0.05 * s, 1e-12);
  EXPECT_NEAR(gy, 3.0 + 0.05 * s + 0.05 * c, 1e-12);
  grid.cell_center_global(9, 0, gx, gy);  // far corner along x: 0.95 m along the yawed x axis
  EXPECT_NEAR(gx, 2.0 + 0.95 * c - 0.05 * s, 1e-12);
  EXPECT_NEAR(gy, 3.0 + 0.95 * s + 0.05 * c, 1e-12);
  grid.cell_center_global(9, 9, gx, gy);
  EXPECT_NEAR(gx, 2.0 + 0.95 * c - 0.95 * s, 1e-12);
  EXPECT_NEAR(gy, 3.0 + 0.95 * s + 0.95 * c, 1e-12);
  // And back: that point falls in the middle of cell (9, 9).
  double col = 0.0, row = 0.0;
  grid.global_to_cell(gx, gy, col, row);
  EXPECT_NEAR(col, 9.5, 1e-9);
  EXPECT_NEAR(row, 9.5, 1e-9);
}

struct BundledMap {
  const char* yaml;
  int width;
  int height;
  double resolution;
  double ox, oy;
  // Cell counts computed independently (a Python histogram of the original PGM rasters,
  // occ = 1 - v/255 against each YAML's thresholds), not by this loader.
  std::size_t occupied, free, unknown;
};

// Sizes from the PGM headers, resolution and origin from the YAML files.
const BundledMap kBundled[] = {
    {"nav2/depot.yaml", 604, 307, 0.05, 0.0, 0.0, 5947, 179481, 0},
    {"nav2/warehouse.yaml", 1006, 1674, 0.03, -15.1, -25.0, 30951, 1422292, 230801},
    {"nav2/tb3_sandbox.yaml", 384, 384, 0.05, -10.0, -10.0, 870, 7903, 138683},
    {"willow/willow-full.yaml", 584, 526, 0.1, 0.0, 0.0, 6961, 134715, 165508},
    {"willow/willow-full-0.05.yaml", 1165, 945, 0.05, 0.0, 0.0, 13459, 549308, 538158},
};

TEST(MapIoBundled, EveryGzippedMapLoadsWithItsSizeResolutionOriginAndCellCounts) {
  for (const BundledMap& m : kBundled) {
    SCOPED_TRACE(m.yaml);
    MapLoadReport report;
    const OccupancyGrid grid = load_map(data_dir() + "/" + m.yaml, &report);
    EXPECT_EQ(grid.width(), m.width);
    EXPECT_EQ(grid.height(), m.height);
    EXPECT_DOUBLE_EQ(grid.resolution(), m.resolution);
    EXPECT_DOUBLE_EQ(grid.origin().x, m.ox);
    EXPECT_DOUBLE_EQ(grid.origin().y, m.oy);
    EXPECT_DOUBLE_EQ(grid.origin().theta, 0.0);
    EXPECT_TRUE(report.warnings.empty()) << report.warnings.front();
    std::size_t occupied = 0, free = 0, unknown = 0;
    for (const std::int8_t v : grid.cells()) {
      occupied += v == kOccupied;
      free += v == kFree;
      unknown += v == kUnknown;
    }
    EXPECT_EQ(occupied, m.occupied);
    EXPECT_EQ(free, m.free);
    EXPECT_EQ(unknown, m.unknown);
  }
}

TEST(MapIoBundled, DepotFreeThreshMakesUnknownGreyFree) {
  // depot.yaml has free_thresh 0.25, and map_saver's unknown grey 205 has occ = 50/255
  // = 0.196 < 0.25, so nav2 reads it as free. Its first raster byte (the top-left pixel,
  // grid cell (0, height - 1)) is 205.
  const OccupancyGrid grid = load_map(data_dir() + "/nav2/depot.yaml");
  EXPECT_EQ(grid.at(0, grid.height() - 1), kFree);
}

TEST(MapIoBundled, ThresholdsComeFromTheYaml) {
  MapLoadReport report;
  (void)load_map(data_dir() + "/nav2/warehouse.yaml", &report);
  EXPECT_DOUBLE_EQ(report.metadata.free_thresh, 0.1);
  EXPECT_DOUBLE_EQ(report.metadata.occupied_thresh, 0.65);
  EXPECT_FALSE(report.metadata.negate);
  EXPECT_EQ(report.metadata.image, "warehouse.pgm.gz");
}

}  // namespace
}  // namespace pgmcl::maps
