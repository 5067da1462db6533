// `pgmcl perturb-map`: erased blocks, thickened and blurred walls, seeds, refusals.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "cli_test_util.hpp"
#include "perturb_test_util.hpp"
#include "pgmcl/map_io/map_io.hpp"

namespace pgmcl::perturb_test {
namespace {

using maps::kFree;
using maps::kOccupied;
using maps::kUnknown;
using maps::OccupancyGrid;

/// 200 x 200 cells at 5 cm: free, with walls along every row and column = 5 (mod 10), so
/// each 0.5 m block holds exactly 19 wall cells; the top 20 rows are unknown.
OccupancyGrid lattice_map() {
  OccupancyGrid g(200, 200, 0.05, {-1.0, 2.0, 0.0}, kFree);
  for (int r = 0; r < 200; ++r) {
    for (int c = 0; c < 200; ++c) {
      if (r >= 180) {
        g.set(c, r, kUnknown);
      } else if (r % 10 == 5 || c % 10 == 5) {
        g.set(c, r, kOccupied);
      }
    }
  }
  return g;
}

/// A room like a SLAM map: free inside, unknown outside, 1-cell walls: the border (unknown
/// behind it), an interior wall with an open end, a diagonal wall and a pillar.
OccupancyGrid room_map() {
  OccupancyGrid g(80, 60, 0.05, {}, kUnknown);
  for (int r = 9; r <= 50; ++r) {
    for (int c = 9; c <= 70; ++c) {
      const bool border = r == 9 || r == 50 || c == 9 || c == 70;
      g.set(c, r, border ? kOccupied : kFree);
    }
  }
  for (int r = 10; r <= 35; ++r) g.set(40, r, kOccupied);
  for (int k = 0; k < 16; ++k) g.set(15 + k, 15 + k, kOccupied);
  g.set(55, 40, kOccupied);
  return g;
}

/// Saves `in` as in.yaml (+ in.pgm) in `dir` and runs `perturb-map --map in.yaml <args>`.
RunResult perturb_map(const TempDir& dir, const OccupancyGrid& in, const std::string& args) {
  maps::save_map(in, dir.file("in.yaml"));
  return run_pgmcl("perturb-map --map in.yaml " + args, dir);
}

TEST(CliPerturbMap, EraseFreesTheWallsOfTheRequestedFractionOfBlocks) {
  TempDir dir("cli_perturb_map_erase");
  const OccupancyGrid in = lattice_map();
  const RunResult r = perturb_map(dir, in, "--out out.yaml --erase 0.3,0.5 --seed 2");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("erased 108 of 360 wall blocks"), std::string::npos) << r.out;
  EXPECT_NE(read_text(dir.file("out.yaml")).find("mode: trinary"), std::string::npos);
  const OccupancyGrid out = maps::load_map(dir.file("out.yaml"));
  std::size_t walls = 0, kept = 0;
  for (int by = 0; by < 18; ++by) {
    for (int bx = 0; bx < 20; ++bx) {
      int left = 0;
      for (int row = by * 10; row < by * 10 + 10; ++row) {
        for (int col = bx * 10; col < bx * 10 + 10; ++col) {
          const std::int8_t a = in.at(col, row), b = out.at(col, row);
          walls += a == kOccupied ? 1 : 0;
          left += b == kOccupied ? 1 : 0;
          // Only walls change, and only to free.
          if (a != kOccupied) {
            EXPECT_EQ(b, a);
          } else {
            EXPECT_TRUE(b == kOccupied || b == kFree);
          }
        }
      }
      EXPECT_TRUE(left == 0 || left == 19) << bx << " " << by;  // a block goes as a whole
      kept += static_cast<std::size_t>(left);
    }
  }
  EXPECT_NEAR(1.0 - static_cast<double>(kept) / static_cast<double>(walls), 0.3, 0.01);
  // Same seed, same map; another seed erases other blocks.
  const std::string image = read_text(dir.file("out.pgm"));
  ASSERT_EQ(
      run_pgmcl("perturb-map --map in.yaml --out again.yaml --erase 0.3,0.5 --seed 2", dir).code,
      0);
  EXPECT_EQ(read_text(dir.file("again.pgm")), image);
  ASSERT_EQ(
      run_pgmcl("perturb-map --map in.yaml --out other.yaml --erase 0.3,0.5 --seed 3", dir).code,
      0);
  EXPECT_NE(read_text(dir.file("other.pgm")), image);
}

/// Length of the run of obstacle cells (100) along `row` that contains column `col`.
int obstacle_run(const OccupancyGrid& g, int row, int col) {
  if (g.at(col, row) != kOccupied) return 0;
  int lo = col, hi = col;
  while (lo > 0 && g.at(lo - 1, row) == kOccupied) --lo;
  while (hi + 1 < g.width() && g.at(hi + 1, row) == kOccupied) ++hi;
  return hi - lo + 1;
}

TEST(CliPerturbMap, ThickenAndBlurGiveFuzzyWallsThatStillLoadAsObstacles) {
  TempDir dir("cli_perturb_map_fuzzy");
  const OccupancyGrid in = room_map();
  const RunResult r = perturb_map(dir, in, "--out fuzzy.yaml --thicken 1 --blur 1");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string yaml = read_text(dir.file("fuzzy.yaml"));
  EXPECT_NE(yaml.find("image: fuzzy.png\n"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("mode: scale\n"), std::string::npos) << yaml;
  const OccupancyGrid out = maps::load_map(dir.file("fuzzy.yaml"));
  int fuzzy = 0;
  for (int row = 0; row < in.height(); ++row) {
    for (int col = 0; col < in.width(); ++col) {
      const std::int8_t a = in.at(col, row), b = out.at(col, row);
      // Every wall cell, the pillar and the wall ends included, is still an obstacle.
      if (a == kOccupied) {
        EXPECT_EQ(b, kOccupied) << col << " " << row;
      }
      EXPECT_EQ(a == kUnknown, b == kUnknown) << col << " " << row;  // unknown stays unknown
      fuzzy += b > kFree && b < kOccupied ? 1 : 0;
    }
  }
  EXPECT_GT(fuzzy, 200);  // a halo of in-between probabilities along the walls
  // Across a wall with free space on both sides: 3 obstacle cells, then the halo.
  EXPECT_EQ(obstacle_run(out, 20, 40), 3);
  EXPECT_GT(out.at(38, 20), kFree);
  EXPECT_LT(out.at(38, 20), 65);
  // A wall with unknown behind it thickens into the free side only: 2 cells.
  EXPECT_EQ(obstacle_run(out, 30, 9), 2);
  // Far from every wall the map stays free.
  EXPECT_EQ(out.at(60, 20), kFree);
  EXPECT_EQ(out.at(25, 45), kFree);
  // --thicken alone stays trinary.
  ASSERT_EQ(run_pgmcl("perturb-map --map in.yaml --out thick.yaml --thicken 2", dir).code, 0);
  const OccupancyGrid thick = maps::load_map(dir.file("thick.yaml"));
  EXPECT_EQ(obstacle_run(thick, 20, 40), 5);
  EXPECT_NE(read_text(dir.file("thick.yaml")).find("image: thick.pgm"), std::string::npos);
}

TEST(CliPerturbMap, BadValuesAndOverwritingTheInputAreRefused) {
  TempDir dir("cli_perturb_map_bad");
  maps::save_map(room_map(), dir.file("a.yaml"), "b.pgm");
  const std::string yaml = read_text(dir.file("a.yaml")), image = read_text(dir.file("b.pgm"));
  expect_usage_errors(
      dir, "perturb-map --map a.yaml ",
      {
          {"--out x.yaml --erase 1.5,0.5", "--erase: FRACTION must be in [0, 1], got 1.5"},
          {"--out x.yaml --erase 0.3", "--erase: expected FRACTION,BLOCK_M, got '0.3'"},
          {"--out x.yaml --erase 0.3,0", "--erase: BLOCK_M must be > 0, got 0"},
          {"--out x.yaml --erase 0.3,0.01", "--erase: BLOCK_M 0.01 m is less than half a cell"},
          {"--out x.yaml --blur -1", "--blur: SIGMA_CELLS must be in [0, 100], got -1"},
          {"--out x.yaml --blur inf", "--blur: expected SIGMA_CELLS, got 'inf'"},
          {"--out x.yaml --thicken 1.5", "--thicken: CELLS must be a whole number in [0, 1000]"},
          {"--out a.yaml --blur 1", "a.yaml is also the input --map a.yaml"},
          {"--out ./sub/../a.yaml --thicken 1", "is also the input --map a.yaml"},
          {"--out b.yaml --thicken 1", "b.pgm is also the input --map's image b.pgm"},
      },
      {"x.yaml"});
  EXPECT_EQ(read_text(dir.file("a.yaml")), yaml);
  EXPECT_EQ(read_text(dir.file("b.pgm")), image);
}

}  // namespace
}  // namespace pgmcl::perturb_test
