// LikelihoodField accuracy: every table kind against the exact oracle, the oracle against
// brute force over all obstacle cells, the tables against the EDT.
//
// Tolerances (nats; step = model().nats_per_step(), ~0.04 for the paper's sigmas):
//  - quantisation: step/2; the offset field's m2 LUT adds <= 0.25 * reach^2 / 4096 < 0.002;
//  - isotropic (one sigma, sigma_along_eff): the oracle's m2 lies in [m2_iso, r^2 m2_iso],
//    r = sigma_along_eff / sigma_across_eff (the across term is under-weighted);
//  - oriented, bin b sampled at its centre: exact there; at any angle within the bin the
//    table's m2 lies in [m2 / (1 + e), m2 (1 + e)], e = (r^2 - 1) sin(pi / 2K);
//  - offset (Euclidean-nearest obstacle, Mahalanobis at lookup): at cell centres the table's
//    m2 lies in [m2, r^2 m2]; anywhere in the cell sqrt(m2_table) <= r sqrt(m2) + sqrt(2)
//    res / sigma_across_eff (triangle inequality over the cell's half-diagonal).
// Tables sample at cell centres (the within-cell position is what the res^2/12 term models),
// so the isotropic and oriented comparisons are made at cell centres.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "likelihood_field_test_util.hpp"
#include "pgmcl/maps/distance_transform.hpp"
#include "pgmcl/maps/likelihood_field.hpp"

namespace pgmcl::maps {
namespace {

using lf_test::BeamLikelihoodParams;
using lf_test::BruteForce;
using lf_test::cells_near_obstacles;
using lf_test::check_isotropic_everywhere;
using lf_test::ratio;
using lf_test::room;
using lf_test::table_q;
using lf_test::with_kind;
using testkit::ExactLikelihood;
constexpr double kPi = std::numbers::pi;

TEST(LikelihoodField, ExactOracleMatchesBruteForceOverAllObstacles) {
  std::mt19937 rng(3);
  for (double res : {0.005, 0.05}) {
    const OccupancyGrid g = room(120, 90, res, 11);
    const LikelihoodField f(g, BeamLikelihoodParams{});
    const BruteForce bf(g, f);
    const ExactLikelihood exact(g, f.model());
    std::uniform_real_distribution<double> ux(-2 * res, 122 * res), uy(-2 * res, 92 * res),
        ua(-10.0, 10.0);
    int near = 0;
    for (int i = 0; i < 1500; ++i) {
      const double x = ux(rng), y = uy(rng), a = ua(rng);
      const double m2 = bf.m2(x, y, a);
      near += m2 < 16.0 ? 1 : 0;
      ASSERT_NEAR(exact(x, y, a), f.model().log_likelihood_of_m2(m2), 1e-9)
          << "at (" << x << ", " << y << ") angle " << a;
    }
    EXPECT_GT(near, 30);  // the sample does exercise the Gaussian part
  }
}

TEST(LikelihoodField, IsotropicWithinHalfStepOfEdtAndWithinAnisotropyBracketOfOracle) {
  std::mt19937 rng(5);
  for (double res : {0.005, 0.05}) {
    const OccupancyGrid g = room(160, 120, res, 17);
    const LikelihoodField f(g, BeamLikelihoodParams{});
    ASSERT_EQ(f.kind(), TableKind::kIsotropic);
    check_isotropic_everywhere(g, f);
    const DistanceField df = euclidean_distance_transform(g);
    const ExactLikelihood exact(g, f.model());
    const double s = f.model().sigma_along_eff() / res, r2 = ratio(f) * ratio(f);
    const double tol = f.model().nats_per_step() / 2 + 1e-9;
    std::uniform_real_distribution<double> ua(-kPi, kPi);
    for (const auto& [c, r] : cells_near_obstacles(g, f.stats().reach_cells, 1500, rng)) {
      const double m2_iso = df.sq_dist_at(c, r) / (s * s);
      const double ll = exact((c + 0.5) * res, (r + 0.5) * res, ua(rng));
      ASSERT_LE(ll, f.model().log_likelihood_of_m2(m2_iso) + 1e-9);
      ASSERT_GE(ll, f.model().log_likelihood_of_m2(r2 * m2_iso) - 1e-9);
      const double table = f.model().log_likelihood_of_q(table_q(f, c + 0.5f, r + 0.5f, 0.0));
      ASSERT_LE(table - tol, f.model().log_likelihood_of_m2(m2_iso));
    }
  }
}

// Bin centres: exact up to quantisation. Any angle in the bin: the bin-width bracket.
void check_oriented(const OccupancyGrid& g, const LikelihoodField& f, std::mt19937& rng) {
  ASSERT_EQ(f.kind(), TableKind::kOrientedBins);
  const OrientedView v = f.oriented();
  const BruteForce bf(g, f);
  const ExactLikelihood exact(g, f.model());
  const double res = g.resolution(), step = f.model().nats_per_step();
  const double eps = (ratio(f) * ratio(f) - 1) * std::sin(kPi / (2 * v.bins));
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  for (const auto& [c, r] : cells_near_obstacles(g, f.stats().reach_cells, 250, rng)) {
    const double x = (c + 0.5) * res, y = (r + 0.5) * res;
    for (int b = 0; b < v.bins; ++b) {
      const double centre = (b + 0.5) * kPi / v.bins + (b % 2 ? kPi : 0.0);  // either sense
      ASSERT_EQ(static_cast<int>(direction_in_bins(centre, v.bins)), b);
      const double table = f.model().log_likelihood_of_q(table_q(f, c + 0.5f, r + 0.5f, centre));
      ASSERT_NEAR(table, exact(x, y, centre), step / 2 + 1e-9)
          << "cell (" << c << ", " << r << ") bin " << b;
      const double phi = (b + 0.02 + 0.96 * u01(rng)) * kPi / v.bins;
      ASSERT_EQ(static_cast<int>(direction_in_bins(phi, v.bins)), b);
      const double m2 = bf.m2(x, y, phi);
      ASSERT_LE(table, f.model().log_likelihood_of_m2(m2 / (1 + eps)) + step / 2 + 1e-9);
      ASSERT_GE(table, f.model().log_likelihood_of_m2(m2 * (1 + eps)) - step / 2 - 1e-9);
    }
  }
}

TEST(LikelihoodField, OrientedExactAtBinCentresAndWithinBinWidthBracket_5mm) {
  std::mt19937 rng(9);
  const OccupancyGrid g = room(160, 120, 0.005, 23);
  const LikelihoodField f(g, BeamLikelihoodParams{}, with_kind(TableKind::kOrientedBins));
  check_oriented(g, f, rng);
  EXPECT_EQ(f.stats().bytes, 16u * g.size());
  // Paper sigmas: interior obstacle cells are provably never nearest, so only boundary
  // cells are stamped (the disk and the thick walls have interior cells).
  std::size_t obstacles = 0;
  for (auto v : g.cells()) obstacles += v >= g.occupied_threshold() ? 1u : 0u;
  EXPECT_LT(f.stats().sources_stamped, obstacles);
}

TEST(LikelihoodField, OrientedStrongAnisotropyStampsInteriorCellsAndStaysExact) {
  std::mt19937 rng(13);
  const OccupancyGrid g = room(100, 80, 0.005, 29);
  BeamLikelihoodParams p;
  p.sigma_along = 0.03;  // ratio ~10: an interior cell can be the Mahalanobis-nearest
  p.sigma_across = 0.003;
  LikelihoodFieldOptions o = with_kind(TableKind::kOrientedBins);
  o.orientation_bins = 8;
  const LikelihoodField f(g, p, o);
  std::size_t obstacles = 0;
  for (auto v : g.cells()) obstacles += v >= g.occupied_threshold() ? 1u : 0u;
  EXPECT_EQ(f.stats().sources_stamped, obstacles);
  check_oriented(g, f, rng);
}

TEST(LikelihoodField, OrientedForcedOn5cmMapMatchesOracle) {
  std::mt19937 rng(31);
  const OccupancyGrid g = room(160, 120, 0.05, 37);
  LikelihoodFieldOptions o = with_kind(TableKind::kOrientedBins);
  o.isotropy_tolerance = 0.0;
  check_oriented(g, LikelihoodField(g, BeamLikelihoodParams{}, o), rng);
}

TEST(LikelihoodField, OffsetFieldPointsAtAnEuclideanNearestObstacle) {
  const OccupancyGrid g = room(160, 120, 0.005, 41);
  const LikelihoodField f(g, BeamLikelihoodParams{}, with_kind(TableKind::kOffsetField));
  ASSERT_EQ(f.kind(), TableKind::kOffsetField);
  const DistanceField df = euclidean_distance_transform(g);
  const OffsetView v = f.offset();
  const double reach = 4 * f.model().sigma_along_eff() / g.resolution();  // cells
  for (int r = 0; r < g.height(); ++r)
    for (int c = 0; c < g.width(); ++c) {
      const auto i = 2 * g.index(c, r);
      if (df.sq_dist_at(c, r) >= reach * reach) {
        ASSERT_EQ(v.off[i], OffsetView::kNoObstacle) << "(" << c << ", " << r << ")";
        continue;
      }
      ASSERT_NE(v.off[i], OffsetView::kNoObstacle) << "(" << c << ", " << r << ")";
      const int oc = c + v.off[i], orow = r + v.off[i + 1];
      ASSERT_TRUE(g.occupied(oc, orow));
      ASSERT_EQ(static_cast<std::uint32_t>(v.off[i] * v.off[i] + v.off[i + 1] * v.off[i + 1]),
                df.sq_dist_at(c, r));
    }
}

void check_offset(const OccupancyGrid& g, const LikelihoodField& f, std::mt19937& rng) {
  ASSERT_EQ(f.kind(), TableKind::kOffsetField);
  const BruteForce bf(g, f);
  const double res = g.resolution(), r = ratio(f);
  const double tol = f.model().nats_per_step() / 2 + 0.002;  // + LUT bin width
  const double slack = std::sqrt(2.0) * res / f.model().sigma_across_eff();
  std::uniform_real_distribution<double> ua(-kPi, kPi), u01(0.0, 1.0);
  double worst_centre = 0.0;
  for (const auto& [c, row] : cells_near_obstacles(g, f.stats().reach_cells, 1200, rng)) {
    const double a = ua(rng);
    // At the cell centre: m2_table in [m2, r^2 m2].
    double x = (c + 0.5) * res, y = (row + 0.5) * res;
    double m2 = bf.m2(x, y, a);
    double table = f.model().log_likelihood_of_q(table_q(f, c + 0.5f, row + 0.5f, a));
    ASSERT_LE(table, f.model().log_likelihood_of_m2(m2) + tol) << c << ", " << row;
    ASSERT_GE(table, f.model().log_likelihood_of_m2(r * r * m2) - tol) << c << ", " << row;
    worst_centre = std::max(worst_centre, std::abs(table - f.model().log_likelihood_of_m2(m2)));
    // Anywhere in the cell: sqrt(m2_table) <= r sqrt(m2) + sqrt(2) res / sigma_across.
    const double fc = c + u01(rng), fr = row + u01(rng);
    x = fc * res;
    y = fr * res;
    m2 = bf.m2(x, y, a);
    table = f.model().log_likelihood_of_q(
        table_q(f, static_cast<float>(fc), static_cast<float>(fr), a));
    const double bound = r * std::sqrt(m2) + slack;
    ASSERT_LE(table, f.model().log_likelihood_of_m2(m2) + tol) << fc << ", " << fr;
    ASSERT_GE(table, f.model().log_likelihood_of_m2(bound * bound) - tol) << fc << ", " << fr;
  }
  std::cout << "[ offset   ] res " << res << ": max |table - oracle| at cell centres "
            << worst_centre << " nats (Euclidean- vs Mahalanobis-nearest + quantisation)\n";
}

TEST(LikelihoodField, OffsetWithinMahalanobisAndCellBrackets_5mmAnd5cm) {
  std::mt19937 rng(43);
  for (double res : {0.005, 0.05}) {
    const OccupancyGrid g = room(160, 120, res, 47);
    const LikelihoodField f(g, BeamLikelihoodParams{}, with_kind(TableKind::kOffsetField));
    check_offset(g, f, rng);
    EXPECT_EQ(f.stats().bytes, 2u * g.size() + 4097u);
  }
}

}  // namespace
}  // namespace pgmcl::maps
