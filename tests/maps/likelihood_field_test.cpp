// LikelihoodField: every table kind against the exact oracle, the oracle against brute force
// over all obstacle cells, the tables against the EDT, plus validation, memory and reach.
//
// Tolerances (nats; step = stats().nats_per_step, ~0.04 for the paper's sigmas):
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

#include "pgmcl/maps/likelihood_field.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <iostream>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "pgmcl/maps/distance_transform.hpp"
#include "pgmcl/sensor_model/paper_constants.hpp"

namespace pgmcl::maps {
namespace {

constexpr double kPi = std::numbers::pi;
namespace paper = sensor_model::paper;

// Room with thick outer walls, an inner wall, an L corner, a filled disk (interior obstacle
// cells), a ring, scattered single obstacles and an unknown patch.
OccupancyGrid room(int w, int h, double res, unsigned seed) {
  OccupancyGrid g(w, h, res, {}, kFree);
  auto box = [&](int c0, int r0, int c1, int r1, std::int8_t v) {
    for (int r = std::max(r0, 0); r < std::min(r1, h); ++r)
      for (int c = std::max(c0, 0); c < std::min(c1, w); ++c) g.set(c, r, v);
  };
  box(0, 0, w, 4, kOccupied);
  box(0, h - 3, w, h, kOccupied);
  box(0, 0, 3, h, kOccupied);
  box(w - 5, 0, w, h, kOccupied);
  box(w / 3, h / 5, w / 3 + 2, 3 * h / 5, kOccupied);
  box(w / 2, 2 * h / 3, 4 * w / 5, 2 * h / 3 + 6, kOccupied);
  box(4 * w / 5 - 6, h / 3, 4 * w / 5, 2 * h / 3 + 6, kOccupied);
  box(w / 6, 3 * h / 4, w / 4, h - 3, kUnknown);
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) {
      const double d = std::hypot(c - 0.62 * w, r - 0.3 * h);
      if (d < 0.08 * h || std::abs(d - 0.16 * h) < 0.6) g.set(c, r, kOccupied);
    }
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> uc(0, w - 1), ur(0, h - 1);
  for (int i = 0; i < w * h / 400; ++i) g.set(uc(rng), ur(rng), kOccupied);
  return g;
}

// Brute force over every obstacle cell: squared Mahalanobis distance of Eq. (6).
struct BruteForce {
  std::vector<std::array<double, 2>> obstacles;  // cell centres, metres
  double sa, sc;
  BruteForce(const OccupancyGrid& g, const LikelihoodField& f)
      : sa(f.stats().sigma_along_eff), sc(f.stats().sigma_across_eff) {
    for (int r = 0; r < g.height(); ++r)
      for (int c = 0; c < g.width(); ++c)
        if (g.occupied(c, r))
          obstacles.push_back({(c + 0.5) * g.resolution(), (r + 0.5) * g.resolution()});
  }
  [[nodiscard]] double m2(double x, double y, double phi) const {
    const double cs = std::cos(phi), sn = std::sin(phi);
    double best = INFINITY;
    for (const auto& o : obstacles) {
      const double dx = o[0] - x, dy = o[1] - y;
      const double a = dx * cs + dy * sn, b = -dx * sn + dy * cs;
      best = std::min(best, a * a / (sa * sa) + b * b / (sc * sc));
    }
    return best;
  }
};

// Random cells within reach + 1 of an obstacle (and some anywhere), as (col, row).
std::vector<std::array<int, 2>> cells_near_obstacles(const OccupancyGrid& g, int reach, int n,
                                                     std::mt19937& rng) {
  std::vector<std::array<int, 2>> obs;
  for (int r = 0; r < g.height(); ++r)
    for (int c = 0; c < g.width(); ++c)
      if (g.occupied(c, r)) obs.push_back({c, r});
  std::uniform_int_distribution<std::size_t> pick(0, obs.size() - 1);
  std::uniform_int_distribution<int> off(-reach - 1, reach + 1);
  std::vector<std::array<int, 2>> out;
  for (int i = 0; i < n; ++i) {
    const auto& o = obs[pick(rng)];
    out.push_back({std::clamp(o[0] + off(rng), 0, g.width() - 1),
                   std::clamp(o[1] + off(rng), 0, g.height() - 1)});
  }
  return out;
}

LikelihoodFieldOptions with_kind(TableKind k) {
  LikelihoodFieldOptions o;
  o.kind = k;
  return o;
}

double ratio(const LikelihoodField& f) {
  return f.stats().sigma_along_eff / f.stats().sigma_across_eff;
}

TEST(LikelihoodField, KindNamesRoundTrip) {
  for (TableKind k : {TableKind::kIsotropic, TableKind::kOrientedBins, TableKind::kOffsetField})
    EXPECT_EQ(table_kind_from_string(to_string(k)), k);
  EXPECT_STREQ(to_string(TableKind::kOrientedBins), "oriented");
  try {
    (void)table_kind_from_string("Oriented");
    FAIL() << "case-mismatched name accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'Oriented'"), std::string::npos) << e.what();
  }
}

TEST(LikelihoodField, RejectsInvalidParametersNamingTheField) {
  const OccupancyGrid g(20, 10, 0.05, {}, kFree);
  using P = BeamLikelihoodParams;
  using O = LikelihoodFieldOptions;
  const std::vector<std::pair<std::string, std::function<void(P&, O&)>>> cases = {
      {"sigma_along", [](P& p, O&) { p.sigma_along = 0.0; }},
      {"sigma_along", [](P& p, O&) { p.sigma_along = NAN; }},
      {"sigma_across", [](P& p, O&) { p.sigma_across = -1e-3; }},
      {"sigma_across", [](P& p, O&) { p.sigma_across = INFINITY; }},
      {"model_mismatch", [](P& p, O&) { p.model_mismatch = -0.01; }},
      {"w_hit", [](P& p, O&) { p.w_hit = 1.2; }},
      {"w_rand", [](P& p, O&) { p.w_rand = -0.2; }},
      {"w_hit + w_rand", [](P& p, O&) { p.w_hit = 0.9; }},
      {"max_range", [](P& p, O&) { p.max_range = 0.0; }},
      {"orientation_bins", [](P&, O& o) { o.orientation_bins = 0; }},
      {"reach_sigmas", [](P&, O& o) { o.reach_sigmas = 0.0; }},
  };
  for (const auto& [field, mutate] : cases) {
    P p;
    O o;
    mutate(p, o);
    try {
      LikelihoodField f(g, p, o);
      ADD_FAILURE() << field << ": invalid value accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(LikelihoodField(OccupancyGrid{}, P{}), std::invalid_argument);
  P wide;  // offsets are int8: reach 4 * 0.5 m / 5 mm = 400 cells does not fit
  wide.sigma_along = wide.sigma_across = 0.5;
  EXPECT_THROW(
      LikelihoodField(OccupancyGrid(10, 10, 0.005), wide, with_kind(TableKind::kOffsetField)),
      std::invalid_argument);
}

TEST(LikelihoodField, TooLargeTableThrowsLengthErrorWithByteCount) {
  const OccupancyGrid g(300, 200, 0.005, {}, kFree);
  LikelihoodFieldOptions o = with_kind(TableKind::kOrientedBins);
  o.max_table_bytes = 300 * 200 * 16 - 1;
  try {
    LikelihoodField f(g, BeamLikelihoodParams{}, o);
    FAIL() << "table above the cap accepted";
  } catch (const std::length_error& e) {
    EXPECT_NE(std::string(e.what()).find("960000 bytes"), std::string::npos) << e.what();
  }
  o.max_table_bytes = 300 * 200 * 16;
  EXPECT_NO_THROW(LikelihoodField(g, BeamLikelihoodParams{}, o));
}

// ll_max, background and step from the formula in the header, evaluated by hand.
TEST(LikelihoodField, ModelMatchesHandComputedMixture) {
  const BeamLikelihoodParams p;
  for (double res : {0.005, 0.05}) {
    const LikelihoodField f(OccupancyGrid(8, 8, res, {}, kFree), p);
    const double sa = std::sqrt(paper::kSigmaAlong * paper::kSigmaAlong + res * res / 12);
    const double sc = std::sqrt(paper::kSigmaAcross * paper::kSigmaAcross + res * res / 12);
    EXPECT_DOUBLE_EQ(f.stats().sigma_along_eff, sa);
    EXPECT_DOUBLE_EQ(f.stats().sigma_across_eff, sc);
    const double floor = p.w_rand / p.max_range;
    const double peak = p.w_hit / (std::sqrt(2 * kPi) * sa);
    EXPECT_NEAR(f.stats().ll_max, std::log(peak + floor), 1e-12);
    EXPECT_NEAR(f.stats().ll_background, std::log(floor), 1e-12);
    EXPECT_NEAR(f.stats().nats_per_step, (std::log(peak + floor) - std::log(floor)) / 255, 1e-12);
    EXPECT_NEAR(f.log_likelihood_of_m2(2.25), std::log(peak * std::exp(-1.125) + floor), 1e-12);
    EXPECT_EQ(f.quantise_m2(0.0), 0);
    EXPECT_EQ(f.quantise_m2(16.0), 255);  // reach_sigmas = 4: background from m2 = 16 on
    EXPECT_LT(f.quantise_m2(15.99), 255);
    EXPECT_NEAR(f.log_likelihood(255), std::log(floor), 1e-12);
    std::cout << "[ scale    ] res " << res << " m: sigma_eff " << sa * 1e3 << " / " << sc * 1e3
              << " mm, " << f.stats().nats_per_step << " nats per step\n";
  }
}

TEST(LikelihoodField, ExactOracleMatchesBruteForceOverAllObstacles) {
  std::mt19937 rng(3);
  for (double res : {0.005, 0.05}) {
    const OccupancyGrid g = room(120, 90, res, 11);
    const LikelihoodField f(g, BeamLikelihoodParams{});
    const BruteForce bf(g, f);
    std::uniform_real_distribution<double> ux(-2 * res, 122 * res), uy(-2 * res, 92 * res),
        ua(-10.0, 10.0);
    int near = 0;
    for (int i = 0; i < 1500; ++i) {
      const double x = ux(rng), y = uy(rng), a = ua(rng);
      const double m2 = bf.m2(x, y, a);
      near += m2 < 16.0 ? 1 : 0;
      ASSERT_NEAR(f.exact_log_likelihood(x, y, a), f.log_likelihood_of_m2(m2), 1e-9)
          << "at (" << x << ", " << y << ") angle " << a;
    }
    EXPECT_GT(near, 30);  // the sample does exercise the Gaussian part
  }
}

// The isotropic table is the EDT distance through the model: within step/2 everywhere.
void check_isotropic_everywhere(const OccupancyGrid& g, const LikelihoodField& f) {
  const DistanceField df = euclidean_distance_transform(g);
  const IsotropicView v = f.isotropic();
  const double s = f.stats().sigma_along_eff / g.resolution();
  const double tol = f.stats().nats_per_step / 2 + 1e-9;
  for (int r = 0; r < g.height(); ++r)
    for (int c = 0; c < g.width(); ++c) {
      const double m2 = df.sq_dist_at(c, r) / (s * s);
      ASSERT_NEAR(f.log_likelihood(v.lookup(c + 0.5f, r + 0.5f)), f.log_likelihood_of_m2(m2), tol)
          << "cell (" << c << ", " << r << ")";
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
    const double s = f.stats().sigma_along_eff / res, r2 = ratio(f) * ratio(f);
    const double tol = f.stats().nats_per_step / 2 + 1e-9;
    std::uniform_real_distribution<double> ua(-kPi, kPi);
    for (const auto& [c, r] : cells_near_obstacles(g, f.stats().reach_cells, 1500, rng)) {
      const double m2_iso = df.sq_dist_at(c, r) / (s * s);
      const double ll = f.exact_log_likelihood((c + 0.5) * res, (r + 0.5) * res, ua(rng));
      ASSERT_LE(ll, f.log_likelihood_of_m2(m2_iso) + 1e-9);
      ASSERT_GE(ll, f.log_likelihood_of_m2(r2 * m2_iso) - 1e-9);
      const double table = f.log_likelihood(f.isotropic().lookup(c + 0.5f, r + 0.5f));
      ASSERT_LE(table - tol, f.log_likelihood_of_m2(m2_iso));
    }
  }
}

TEST(LikelihoodField, OrientedFallsBackToIsotropicAt5cmButNotAt5mm) {
  const LikelihoodField coarse(room(60, 40, 0.05, 1), BeamLikelihoodParams{},
                               with_kind(TableKind::kOrientedBins));
  EXPECT_NEAR(ratio(coarse), 1.0524, 1e-3);  // sqrt(5.6894^2 + 50^2/12) / sqrt(3^2 + 50^2/12)
  EXPECT_TRUE(coarse.stats().orientation_skipped);
  EXPECT_EQ(coarse.kind(), TableKind::kIsotropic);
  EXPECT_DOUBLE_EQ(coarse.stats().bytes_per_cell, 1.0);
  EXPECT_EQ(coarse.oriented().width, 0);  // the oriented view is empty: background only
  EXPECT_EQ(coarse.oriented().lookup(5.5f, 5.5f, 0), coarse.oriented().background);

  const LikelihoodField fine(room(60, 40, 0.005, 1), BeamLikelihoodParams{},
                             with_kind(TableKind::kOrientedBins));
  EXPECT_NEAR(ratio(fine), 1.763, 1e-3);  // 5.870 / 3.329 mm
  EXPECT_FALSE(fine.stats().orientation_skipped);
  EXPECT_EQ(fine.kind(), TableKind::kOrientedBins);

  LikelihoodFieldOptions strict = with_kind(TableKind::kOrientedBins);
  strict.isotropy_tolerance = 0.0;
  const LikelihoodField forced(room(60, 40, 0.05, 1), BeamLikelihoodParams{}, strict);
  EXPECT_EQ(forced.kind(), TableKind::kOrientedBins);
  EXPECT_FALSE(forced.stats().orientation_skipped);
}

// Bin centres: exact up to quantisation. Any angle in the bin: the bin-width bracket.
void check_oriented(const OccupancyGrid& g, const LikelihoodField& f, std::mt19937& rng) {
  ASSERT_EQ(f.kind(), TableKind::kOrientedBins);
  const OrientedView v = f.oriented();
  const BruteForce bf(g, f);
  const double res = g.resolution(), step = f.stats().nats_per_step;
  const double eps = (ratio(f) * ratio(f) - 1) * std::sin(kPi / (2 * v.bins));
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  for (const auto& [c, r] : cells_near_obstacles(g, f.stats().reach_cells, 250, rng)) {
    const double x = (c + 0.5) * res, y = (r + 0.5) * res;
    for (int b = 0; b < v.bins; ++b) {
      const double centre = (b + 0.5) * kPi / v.bins + (b % 2 ? kPi : 0.0);  // either sense
      ASSERT_EQ(v.bin_of(static_cast<float>(centre)), b);
      const double table = f.log_likelihood(v.lookup(c + 0.5f, r + 0.5f, b));
      ASSERT_NEAR(table, f.exact_log_likelihood(x, y, centre), step / 2 + 1e-9)
          << "cell (" << c << ", " << r << ") bin " << b;
      const double phi = (b + 0.02 + 0.96 * u01(rng)) * kPi / v.bins;
      ASSERT_EQ(v.bin_of(static_cast<float>(phi)), b);
      const double m2 = bf.m2(x, y, phi);
      ASSERT_LE(table, f.log_likelihood_of_m2(m2 / (1 + eps)) + step / 2 + 1e-9);
      ASSERT_GE(table, f.log_likelihood_of_m2(m2 * (1 + eps)) - step / 2 - 1e-9);
    }
  }
}

TEST(LikelihoodField, OrientedExactAtBinCentresAndWithinBinWidthBracket_5mm) {
  std::mt19937 rng(9);
  const OccupancyGrid g = room(160, 120, 0.005, 23);
  const LikelihoodField f(g, BeamLikelihoodParams{}, with_kind(TableKind::kOrientedBins));
  check_oriented(g, f, rng);
  EXPECT_DOUBLE_EQ(f.stats().bytes_per_cell, 16.0);
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
  const double reach = 4 * f.stats().sigma_along_eff / g.resolution();  // cells
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
  const OffsetView v = f.offset();
  const BruteForce bf(g, f);
  const double res = g.resolution(), r = ratio(f);
  const double tol = f.stats().nats_per_step / 2 + 0.002;  // + LUT bin width
  const double slack = std::sqrt(2.0) * res / f.stats().sigma_across_eff;
  std::uniform_real_distribution<double> ua(-kPi, kPi), u01(0.0, 1.0);
  double worst_centre = 0.0;
  for (const auto& [c, row] : cells_near_obstacles(g, f.stats().reach_cells, 1200, rng)) {
    const double a = ua(rng);
    const auto ux = static_cast<float>(std::cos(a)), uy = static_cast<float>(std::sin(a));
    // At the cell centre: m2_table in [m2, r^2 m2].
    double x = (c + 0.5) * res, y = (row + 0.5) * res;
    double m2 = bf.m2(x, y, a);
    double table = f.log_likelihood(v.lookup(c + 0.5f, row + 0.5f, ux, uy));
    ASSERT_LE(table, f.log_likelihood_of_m2(m2) + tol) << c << ", " << row;
    ASSERT_GE(table, f.log_likelihood_of_m2(r * r * m2) - tol) << c << ", " << row;
    worst_centre = std::max(worst_centre, std::abs(table - f.log_likelihood_of_m2(m2)));
    // Anywhere in the cell: sqrt(m2_table) <= r sqrt(m2) + sqrt(2) res / sigma_across.
    const double fc = c + u01(rng), fr = row + u01(rng);
    x = fc * res;
    y = fr * res;
    m2 = bf.m2(x, y, a);
    table = f.log_likelihood(v.lookup(static_cast<float>(fc), static_cast<float>(fr), ux, uy));
    const double bound = r * std::sqrt(m2) + slack;
    ASSERT_LE(table, f.log_likelihood_of_m2(m2) + tol) << fc << ", " << fr;
    ASSERT_GE(table, f.log_likelihood_of_m2(bound * bound) - tol) << fc << ", " << fr;
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
    EXPECT_DOUBLE_EQ(f.stats().bytes_per_cell, 2.0 + 4097.0 / (160 * 120));
  }
}

TEST(LikelihoodField, ViewsReturnBackgroundOutsideTheMapAndBeyondReach) {
  OccupancyGrid g(200, 100, 0.005, {}, kFree);
  g.set(10, 10, kOccupied);
  for (TableKind k : {TableKind::kIsotropic, TableKind::kOrientedBins, TableKind::kOffsetField}) {
    SCOPED_TRACE(to_string(k));
    const LikelihoodField f(g, BeamLikelihoodParams{}, with_kind(k));
    ASSERT_EQ(f.kind(), k);
    const std::uint8_t bg = 255;
    auto look = [&](float c, float r) -> std::uint8_t {
      switch (k) {
        case TableKind::kIsotropic:
          return f.isotropic().lookup(c, r);
        case TableKind::kOrientedBins:
          return f.oriented().lookup(c, r, 3);
        case TableKind::kOffsetField:
          return f.offset().lookup(c, r, 0.6f, 0.8f);
      }
      return 0;
    };
    EXPECT_EQ(look(10.5f, 10.5f), 0);  // on the obstacle
    EXPECT_LT(look(11.5f, 10.5f), bg);
    for (auto [c, r] : {std::pair{-0.01f, 10.5f},
                        {10.5f, -0.5f},
                        {-3000.0f, -3000.0f},
                        {200.0f, 10.5f},
                        {10.5f, 100.0f},
                        {1e9f, 1e9f},
                        {150.5f, 50.5f}})
      EXPECT_EQ(look(c, r), bg) << c << ", " << r;
    EXPECT_EQ(f.exact_log_likelihood(0.75, 0.25, 0.3), f.stats().ll_background);
    EXPECT_EQ(f.exact_log_likelihood(-1e12, 5.0, 0.3), f.stats().ll_background);
    EXPECT_EQ(f.isotropic().width == 0, k != TableKind::kIsotropic);  // other views are empty
  }
}

TEST(LikelihoodField, SingleObstacleComputesOnlyTheReachDisk) {
  OccupancyGrid g(500, 400, 0.05, {}, kFree);  // 25 m x 20 m, 200k cells
  g.set(300, 133, kOccupied);
  LikelihoodFieldOptions o;
  o.isotropy_tolerance = 0.0;
  for (TableKind k : {TableKind::kIsotropic, TableKind::kOrientedBins, TableKind::kOffsetField}) {
    SCOPED_TRACE(to_string(k));
    o.kind = k;
    const LikelihoodField f(g, BeamLikelihoodParams{}, o);
    const int R = f.stats().reach_cells;
    EXPECT_EQ(R, 2);  // ceil(4 * 15.5 mm / 50 mm)
    EXPECT_EQ(f.stats().sources_stamped, 1u);
    EXPECT_GT(f.stats().cells_computed, 1u);
    EXPECT_LE(f.stats().cells_computed, static_cast<std::size_t>((2 * R + 1) * (2 * R + 1)));
    std::size_t non_background = 0;  // by brute force over the whole table
    for (int r = 0; r < g.height(); ++r)
      for (int c = 0; c < g.width(); ++c) {
        bool any = false;
        if (k == TableKind::kIsotropic) any = f.isotropic().lookup(c + 0.5f, r + 0.5f) != 255;
        if (k == TableKind::kOffsetField)
          any = f.offset().off[2 * g.index(c, r)] != OffsetView::kNoObstacle;
        for (int b = 0; k == TableKind::kOrientedBins && b < f.oriented().bins; ++b)
          any = any || f.oriented().lookup(c + 0.5f, r + 0.5f, b) != 255;
        non_background += any ? 1u : 0u;
      }
    EXPECT_EQ(f.stats().cells_computed, non_background);
  }
}

// Not a timed assertion: prints build times for the report, and checks the tables are right.
TEST(LikelihoodField, BuildTimes50mBy50mAt5cmWithRandomWalls) {
  OccupancyGrid g(1000, 1000, 0.05, {}, kFree);
  std::mt19937 rng(53);
  std::uniform_int_distribution<int> pos(0, 999), len(20, 200), thick(2, 5), dir(0, 1);
  for (int i = 0; i < 300; ++i) {
    const int c0 = pos(rng), r0 = pos(rng), l = len(rng), t = thick(rng);
    const bool horiz = dir(rng) == 0;
    for (int a = 0; a < l; ++a)
      for (int b = 0; b < t; ++b) {
        const int c = horiz ? c0 + a : c0 + b, r = horiz ? r0 + b : r0 + a;
        if (c < 1000 && r < 1000) g.set(c, r, kOccupied);
      }
  }
  LikelihoodFieldOptions o;
  o.isotropy_tolerance = 0.0;
  for (TableKind k : {TableKind::kIsotropic, TableKind::kOrientedBins, TableKind::kOffsetField}) {
    o.kind = k;
    const LikelihoodField f(g, BeamLikelihoodParams{}, o);
    std::cout << "[ build    ] 50 m x 50 m @ 5 cm, " << to_string(k) << ": "
              << f.stats().build_seconds * 1e3 << " ms, " << f.stats().bytes_per_cell
              << " bytes/cell, " << f.stats().cells_computed << " cells computed, "
              << f.stats().sources_stamped << " obstacle cells stamped\n";
    if (k == TableKind::kIsotropic) check_isotropic_everywhere(g, f);
  }
}

}  // namespace
}  // namespace pgmcl::maps
