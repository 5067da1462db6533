// LikelihoodField: names, validation, the model's constants, size limits, the isotropic
// fallback, the kernels outside the map, work skipping (cells_computed) and build times.
// Accuracy against the exact oracle: likelihood_field_accuracy_test.cpp.

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

#include "likelihood_field_test_util.hpp"
#include "pgmcl/maps/distance_transform.hpp"
#include "pgmcl/sensor_model/paper_constants.hpp"

namespace pgmcl::maps {
namespace {

using lf_test::BeamLikelihoodParams;
using lf_test::check_isotropic_everywhere;
using lf_test::ratio;
using lf_test::room;
using lf_test::table_q;
using lf_test::with_kind;
using testkit::bin_centre;
constexpr double kPi = std::numbers::pi;
namespace paper = sensor_model::paper;

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

// The tables rasterise sensor_model::BeamLikelihood at the grid's resolution: the same
// constants, and around a lone obstacle every isotropic entry is the model's quantised value
// at the distance between cell centres (sigma_along_eff, see LikelihoodField).
TEST(LikelihoodField, TablesHoldTheSensorModelsQuantisedFunction) {
  BeamLikelihoodParams p;
  p.model_mismatch = 0.01;
  for (double res : {0.005, 0.05}) {
    SCOPED_TRACE(res);
    OccupancyGrid g(41, 41, res, {}, kFree);
    g.set(20, 20, kOccupied);
    LikelihoodFieldOptions o;
    o.reach_sigmas = 3.5;
    const LikelihoodField f(g, p, o);
    const sensor_model::BeamLikelihood m(p, res, 3.5);
    EXPECT_EQ(f.model().sigma_along_eff(), m.sigma_along_eff());
    EXPECT_EQ(f.model().sigma_across_eff(), m.sigma_across_eff());
    EXPECT_EQ(f.model().ll_max(), m.ll_max());
    EXPECT_EQ(f.model().nats_per_step(), m.nats_per_step());
    EXPECT_EQ(f.model().background(), m.background());
    const double s = m.sigma_along_eff();
    int inside = 0;
    for (int r = 0; r < g.height(); ++r)
      for (int c = 0; c < g.width(); ++c) {
        const double d2 = ((c - 20) * (c - 20) + (r - 20) * (r - 20)) * res * res;
        const std::uint8_t want = m.quantise_m2(d2 / (s * s));
        inside += want < m.background() ? 1 : 0;
        ASSERT_EQ(table_q(f, c + 0.5f, r + 0.5f, 0.3), want) << c << ", " << r;
      }
    EXPECT_GT(inside, 1);
  }
}

TEST(LikelihoodField, OrientedFallsBackToIsotropicAt5cmButNotAt5mm) {
  const LikelihoodField coarse(room(60, 40, 0.05, 1), BeamLikelihoodParams{},
                               with_kind(TableKind::kOrientedBins));
  EXPECT_NEAR(ratio(coarse), 1.0524, 1e-3);  // sqrt(5.6894^2 + 50^2/12) / sqrt(3^2 + 50^2/12)
  EXPECT_TRUE(coarse.stats().orientation_skipped);
  EXPECT_EQ(coarse.kind(), TableKind::kIsotropic);
  EXPECT_EQ(coarse.stats().bytes, 60u * 40u);
  EXPECT_EQ(coarse.oriented().width, 0);  // the oriented view is empty: background only

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

TEST(LikelihoodField, KernelsReadBackgroundOutsideTheMapAndBeyondReach) {
  OccupancyGrid g(200, 100, 0.005, {}, kFree);
  g.set(10, 10, kOccupied);
  for (TableKind k : {TableKind::kIsotropic, TableKind::kOrientedBins, TableKind::kOffsetField}) {
    SCOPED_TRACE(to_string(k));
    const LikelihoodField f(g, BeamLikelihoodParams{}, with_kind(k));
    ASSERT_EQ(f.kind(), k);
    const std::uint8_t bg = 255;
    auto look = [&](float c, float r) { return table_q(f, c, r, std::atan2(0.8, 0.6)); };
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
    const testkit::ExactLikelihood exact(g, f.model());
    EXPECT_EQ(exact(0.75, 0.25, 0.3), f.model().ll_background());
    EXPECT_EQ(exact(-1e12, 5.0, 0.3), f.model().ll_background());
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
        if (k == TableKind::kIsotropic) any = table_q(f, c + 0.5f, r + 0.5f, 0.0) != 255;
        if (k == TableKind::kOffsetField)
          any = f.offset().off[2 * g.index(c, r)] != OffsetView::kNoObstacle;
        for (int b = 0; k == TableKind::kOrientedBins && b < f.oriented().bins; ++b)
          any = any || table_q(f, c + 0.5f, r + 0.5f, bin_centre(f, b)) != 255;
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
              << f.stats().build_seconds * 1e3 << " ms, "
              << static_cast<double>(f.stats().bytes) / static_cast<double>(g.size())
              << " bytes/cell, " << f.stats().cells_computed << " cells computed, "
              << f.stats().sources_stamped << " obstacle cells stamped\n";
    if (k == TableKind::kIsotropic) check_isotropic_everywhere(g, f);
  }
}

}  // namespace
}  // namespace pgmcl::maps
