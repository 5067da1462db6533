// PoseSearch: branch and bound against an exhaustive search over the same leaves, and the
// true pose of a synthetic scan found among the candidates.
#include "pgmcl/mcl/pose_search.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>

#include "pgmcl/maps/likelihood_field.hpp"
#include "pgmcl/mcl/beam_selection.hpp"
#include "pgmcl/mcl/localizer.hpp"
#include "pgmcl/mcl/measurement_model.hpp"
#include "synthetic_world.hpp"

namespace pgmcl {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

struct Fixture {
  test::World world = test::make_room(0.05);
  std::shared_ptr<const maps::LikelihoodField> field;
  std::vector<std::uint32_t> free_cells;
  MeasurementModel model;
  Fixture()
      : field(std::make_shared<const maps::LikelihoodField>(
            world.grid, sensor_model::BeamLikelihoodParams{.model_mismatch = 0.05})),
        free_cells(free_cell_indices(world.grid)),
        model(field) {}

  // Prepares the scan seen from `robot` (map-local) with 180 beams over 360 degrees.
  void prepare(const Pose2& robot) {
    test::ScanSpec spec;
    spec.beams = 180;
    spec.fov = 2.0 * std::numbers::pi * 179.0 / 180.0;
    const LaserScan scan = world.scan(robot, spec);
    std::vector<std::uint32_t> valid, selected;
    valid_beam_indices(scan, 30.0, valid);
    select_beams(valid, BeamSelection{}, selected);
    model.prepare(scan, selected);
  }

  // A search over the room's free cells, given the scan seen from `robot`.
  PoseSearch search_from(const Pose2& robot) {
    prepare(robot);
    PoseSearch search(*field, free_cells);
    EXPECT_TRUE(search.set_scan(model.beams()));
    return search;
  }
};

// Exhaustive: every leaf with free space at every heading the search tries, scored by
// pooled_cost at the leaf centre (the same pooled table and rounding, with edge checks).
std::uint32_t exhaustive_best(const Fixture& f, const PoseSearch& search) {
  std::uint32_t brute = std::numeric_limits<std::uint32_t>::max();
  const double leaf = search.leaf_size();
  const int n_angles = static_cast<int>(std::ceil(2.0 * std::numbers::pi / search.angle_step()));
  const int cols = static_cast<int>(std::ceil(11.0 / leaf)),
            rows = static_cast<int>(std::ceil(9.0 / leaf));
  const int per_leaf = static_cast<int>(std::lround(leaf / 0.05));
  std::vector<bool> leaf_free(static_cast<std::size_t>(cols * rows), false);
  for (std::uint32_t c : f.free_cells) {
    const int col = static_cast<int>(c % 220) / per_leaf,
              row = static_cast<int>(c / 220) / per_leaf;
    leaf_free[static_cast<std::size_t>(row * cols + col)] = true;
  }
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      if (!leaf_free[static_cast<std::size_t>(r * cols + c)]) continue;
      for (int a = 0; a < n_angles; ++a) {
        const double th = -std::numbers::pi + 2.0 * std::numbers::pi * (a + 0.5) / n_angles;
        brute = std::min(brute, search.pooled_cost((c + 0.5) * leaf, (r + 0.5) * leaf, th));
      }
    }
  return brute;
}

TEST(PoseSearch, BranchAndBoundFindsTheExhaustiveOptimum) {
  Fixture f;
  const Pose2 robot{3.1, 4.3, 0.4};
  PoseSearch search = f.search_from(robot);
  PoseSearchQuery q;
  q.max_candidates = 1;
  const PoseSearchResult best = search.search(q);
  ASSERT_EQ(best.candidates.size(), 1u);
  EXPECT_EQ(best.candidates[0].cost, exhaustive_best(f, search));
  // The optimum lies at the true pose (the room is asymmetric): a leaf's pooled window
  // spans two leaves, so within 1.5 leaves and a heading step.
  const double leaf = search.leaf_size();
  EXPECT_NEAR(best.candidates[0].x, robot.x, 1.5 * leaf);
  EXPECT_NEAR(best.candidates[0].y, robot.y, 1.5 * leaf);
  EXPECT_LT(std::abs(wrap_angle(best.candidates[0].theta - robot.theta)), search.angle_step());
}

TEST(PoseSearch, AScanPastThePaddedReachIsBoundedWithEdgeChecks) {
  // The pyramid's levels are padded for readings within the range model's support (30 m
  // here); a reading from farther (a sensor mounted far off the base) takes the checked
  // path, which must find the same optimum, the far endpoint reading background.
  Fixture f;
  f.prepare({3.1, 4.3, 0.4});
  PreparedBeams beams = f.model.beams();
  beams.ex[0] = 800.0f;  // cells: 40 m ahead; the first beam is always among those searched
  beams.ey[0] = 0.0f;
  beams.reach = std::max(beams.reach, 800.0f);
  PoseSearch search(*f.field, f.free_cells);
  ASSERT_TRUE(search.set_scan(beams));
  PoseSearchQuery q;
  q.max_candidates = 1;
  const PoseSearchResult best = search.search(q);
  ASSERT_EQ(best.candidates.size(), 1u);
  EXPECT_EQ(best.candidates[0].cost, exhaustive_best(f, search));
}

TEST(PoseSearch, CandidatesAreDistinctAndSortedAndRespectTheWindow) {
  Fixture f;
  const Pose2 robot{7.9, 2.6, -2.0};
  PoseSearch search = f.search_from(robot);
  PoseSearchQuery q;
  q.max_candidates = 10;
  const PoseSearchResult r = search.search(q);
  ASSERT_EQ(r.candidates.size(), 10u);
  for (std::size_t i = 1; i < r.candidates.size(); ++i)
    EXPECT_LE(r.candidates[i - 1].cost, r.candidates[i].cost);
  for (std::size_t i = 0; i < r.candidates.size(); ++i)
    for (std::size_t j = i + 1; j < r.candidates.size(); ++j) {
      const auto& a = r.candidates[i];
      const auto& b = r.candidates[j];
      const bool near = std::abs(a.x - b.x) < q.separation_xy &&
                        std::abs(a.y - b.y) < q.separation_xy &&
                        std::abs(wrap_angle(a.theta - b.theta)) < q.separation_theta;
      EXPECT_FALSE(near) << i << " " << j;
    }
  EXPECT_NEAR(r.candidates[0].x, robot.x, 1.5 * search.leaf_size());
  EXPECT_NEAR(r.candidates[0].y, robot.y, 1.5 * search.leaf_size());

  // A window 2 m and 40 deg around a pose 1.5 m and 30 deg off finds the true pose.
  PoseSearchQuery w;
  w.windowed = true;
  w.x = robot.x + 1.0;
  w.y = robot.y - 1.1;
  w.theta = robot.theta + 30 * kDeg;
  w.half_xy = 2.0;
  w.half_theta = 40 * kDeg;
  w.max_candidates = 1;
  const PoseSearchResult local = search.search(w);
  ASSERT_EQ(local.candidates.size(), 1u);
  EXPECT_NEAR(local.candidates[0].x, robot.x, 1.5 * search.leaf_size());
  EXPECT_NEAR(local.candidates[0].y, robot.y, 1.5 * search.leaf_size());
  EXPECT_LT(local.lookups, r.lookups);
  // A window that excludes the true pose returns candidates inside it only.
  w.x = 2.0, w.y = 2.0, w.half_xy = 0.5, w.max_candidates = 5;
  for (const PoseCandidate& c : search.search(w).candidates) {
    EXPECT_LE(std::abs(c.x - 2.0), 0.5 + 1e-9);
    EXPECT_LE(std::abs(c.y - 2.0), 0.5 + 1e-9);
  }
}

TEST(PoseSearch, BudgetTruncatesAndSlicesCoverTheMap) {
  Fixture f;
  PoseSearch search = f.search_from({5.2, 6.1, 1.0});
  PoseSearchQuery q;
  q.max_candidates = 1;
  const PoseSearchResult full = search.search(q);
  q.budget = full.lookups / 10;
  const PoseSearchResult cut = search.search(q);
  EXPECT_TRUE(cut.truncated);
  EXPECT_FALSE(full.truncated);
  // The best over the slices equals the best over the whole map.
  std::uint32_t best = std::numeric_limits<std::uint32_t>::max();
  q.budget = 0;
  const std::size_t roots = search.root_count();
  ASSERT_GT(roots, 1u);
  for (std::size_t b = 0; b < roots; b += 2) {
    q.root_begin = b;
    q.root_end = b + 2;
    for (const PoseCandidate& c : search.search(q).candidates) best = std::min(best, c.cost);
  }
  EXPECT_EQ(best, full.candidates[0].cost);
}

}  // namespace
}  // namespace pgmcl
