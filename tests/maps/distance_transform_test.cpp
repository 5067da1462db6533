// Exact EDT (Felzenszwalb & Huttenlocher 2012) against a brute-force oracle: a nanoflann
// kd-tree over the obstacle cells. Squared distances are integers and must match exactly;
// the reported nearest cell must be an obstacle at exactly that distance (ties allowed).

#include "pgmcl/maps/distance_transform.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <nanoflann.hpp>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace pgmcl::maps {
namespace {

struct CellCloud {
  std::vector<std::array<double, 2>> pts;
  [[nodiscard]] std::size_t kdtree_get_point_count() const { return pts.size(); }
  [[nodiscard]] double kdtree_get_pt(std::size_t i, std::size_t dim) const { return pts[i][dim]; }
  template <class BBox>
  bool kdtree_get_bbox(BBox& /*bb*/) const {
    return false;
  }
};
using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, CellCloud>,
                                                   CellCloud, 2, std::uint32_t>;

// Random grid: obstacles with probability `density`; the rest free, unknown or grey (50,
// below the occupied threshold) so that only grid.occupied() cells count.
OccupancyGrid random_grid(int w, int h, double density, std::mt19937& rng) {
  OccupancyGrid g(w, h, 0.05);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int r = 0; r < h; ++r) {
    for (int c = 0; c < w; ++c) {
      const double x = u(rng);
      std::int8_t v = kFree;
      if (x < density) {
        v = kOccupied;
      } else if (x < density + 0.2 * (1.0 - density)) {
        v = kUnknown;
      } else if (x < density + 0.3 * (1.0 - density)) {
        v = 50;
      }
      g.set(c, r, v);
    }
  }
  return g;
}

// Checks every cell of `df` against the kd-tree over the grid's obstacle cells.
void expect_matches_brute_force(const OccupancyGrid& g, const DistanceField& df) {
  ASSERT_EQ(df.width, g.width());
  ASSERT_EQ(df.height, g.height());
  CellCloud cloud;
  for (int r = 0; r < g.height(); ++r)
    for (int c = 0; c < g.width(); ++c)
      if (g.occupied(c, r)) cloud.pts.push_back({double(c), double(r)});
  if (cloud.pts.empty()) {
    for (int r = 0; r < g.height(); ++r) {
      for (int c = 0; c < g.width(); ++c) {
        ASSERT_EQ(df.sq_dist_at(c, r), DistanceField::kInfinite);
        ASSERT_EQ(df.nearest_at(c, r), DistanceField::kNone);
        ASSERT_TRUE(std::isinf(df.distance_m(c, r, g.resolution())));
      }
    }
    return;
  }
  KdTree tree(2, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(8));
  for (int r = 0; r < g.height(); ++r) {
    for (int c = 0; c < g.width(); ++c) {
      const double q[2] = {double(c), double(r)};
      std::uint32_t idx = 0;
      double d2 = 0.0;
      ASSERT_EQ(tree.knnSearch(q, 1, &idx, &d2), 1u);
      const std::uint32_t got = df.sq_dist_at(c, r);
      ASSERT_EQ(static_cast<double>(got), d2) << "cell (" << c << ", " << r << ")";
      const std::int32_t n = df.nearest_at(c, r);
      ASSERT_GE(n, 0);
      ASSERT_LT(n, g.width() * g.height());
      const int nc = n % g.width(), nr = n / g.width();
      ASSERT_TRUE(g.occupied(nc, nr)) << "nearest of (" << c << ", " << r << ") is free";
      const auto dc = static_cast<std::uint32_t>(std::abs(nc - c));
      const auto dr = static_cast<std::uint32_t>(std::abs(nr - r));
      ASSERT_EQ(dc * dc + dr * dr, got) << "nearest of (" << c << ", " << r << ") too far";
    }
  }
}

TEST(DistanceTransform, RandomGridsMatchKdTreeExactly) {
  std::mt19937 rng(12345);
  const int sizes[][2] = {{1, 1}, {1, 9}, {11, 1}, {2, 2}, {37, 23}, {64, 64}, {131, 97}};
  const double densities[] = {0.0, 0.0005, 0.01, 0.1, 0.5, 1.0};
  for (const auto& s : sizes) {
    for (double d : densities) {
      SCOPED_TRACE(testing::Message() << s[0] << "x" << s[1] << " density " << d);
      const OccupancyGrid g = random_grid(s[0], s[1], d, rng);
      expect_matches_brute_force(g, euclidean_distance_transform(g));
    }
  }
}

TEST(DistanceTransform, RoomsWallsAndCirclesMatchKdTree) {
  OccupancyGrid g(157, 119, 0.05, {}, kFree);
  for (int c = 0; c < g.width(); ++c) g.set(c, 0, kOccupied);  // outer walls, one gap
  for (int r = 0; r < g.height(); ++r) g.set(0, r, kOccupied);
  for (int r = 10; r < 90; ++r) g.set(60, r, kOccupied);   // an inner wall
  for (int c = 60; c < 140; ++c) g.set(c, 90, kOccupied);  // a corner
  for (int r = 0; r < g.height(); ++r)                     // a ring of radius 20
    for (int c = 0; c < g.width(); ++c) {
      const double rr = std::hypot(c - 110.0, r - 40.0);
      if (rr > 19.5 && rr < 20.5) g.set(c, r, kOccupied);
    }
  for (int r = 95; r < 119; ++r)  // unknown region: not an obstacle
    for (int c = 100; c < 157; ++c) g.set(c, r, kUnknown);
  expect_matches_brute_force(g, euclidean_distance_transform(g));
}

TEST(DistanceTransform, SingleObstacleGivesAnalyticDistances) {
  OccupancyGrid g(300, 200, 0.05, {}, kFree);
  g.set(217, 3, kOccupied);
  const DistanceField df = euclidean_distance_transform(g);
  for (int r = 0; r < g.height(); r += 7) {
    for (int c = 0; c < g.width(); c += 5) {
      const auto d2 = static_cast<std::uint32_t>((c - 217) * (c - 217) + (r - 3) * (r - 3));
      ASSERT_EQ(df.sq_dist_at(c, r), d2);
      ASSERT_EQ(df.nearest_at(c, r), 3 * 300 + 217);
    }
  }
  EXPECT_DOUBLE_EQ(df.distance_m(217 + 3, 3 + 4, 0.05), 0.25);
}

TEST(DistanceTransform, OneByOneGrids) {
  OccupancyGrid free_cell(1, 1, 0.05, {}, kFree);
  const DistanceField a = euclidean_distance_transform(free_cell);
  EXPECT_EQ(a.sq_dist_at(0, 0), DistanceField::kInfinite);
  EXPECT_EQ(a.nearest_at(0, 0), DistanceField::kNone);
  OccupancyGrid wall(1, 1, 0.05, {}, kOccupied);
  const DistanceField b = euclidean_distance_transform(wall);
  EXPECT_EQ(b.sq_dist_at(0, 0), 0u);
  EXPECT_EQ(b.nearest_at(0, 0), 0);
}

TEST(DistanceTransform, MaskOverloadAgreesAndValidates) {
  std::mt19937 rng(7);
  const OccupancyGrid g = random_grid(45, 38, 0.03, rng);
  std::vector<std::uint8_t> mask(g.size());
  for (int r = 0; r < g.height(); ++r)
    for (int c = 0; c < g.width(); ++c) mask[g.index(c, r)] = g.occupied(c, r) ? 1 : 0;
  const DistanceField a = euclidean_distance_transform(g);
  const DistanceField b = euclidean_distance_transform(mask, g.width(), g.height());
  EXPECT_EQ(a.sq_dist, b.sq_dist);
  EXPECT_EQ(a.nearest, b.nearest);
  try {
    (void)euclidean_distance_transform(mask, g.width() + 1, g.height());
    FAIL() << "size mismatch accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("expected 46 x 38"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)euclidean_distance_transform(mask, 0, 5), std::invalid_argument);
  const std::vector<std::uint8_t> none;
  EXPECT_THROW((void)euclidean_distance_transform(none, 70000, 70000), std::length_error);
}

}  // namespace
}  // namespace pgmcl::maps
