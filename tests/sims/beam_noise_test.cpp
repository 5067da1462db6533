#include "pgmcl/sims/beam_noise.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "scenes.hpp"

namespace pgmcl::sims {
namespace {

constexpr double kPi = std::numbers::pi;

struct Stats {
  double mean = 0.0, sd = 0.0;
};
Stats stats(const std::vector<double>& v) {
  double s = 0.0, ss = 0.0;
  for (const double x : v) s += x;
  const double m = s / static_cast<double>(v.size());
  for (const double x : v) ss += (x - m) * (x - m);
  return {m, std::sqrt(ss / static_cast<double>(v.size() - 1))};
}

// An empty free grid; surfaces come from box obstacles, which are exactly flat.
struct Bench {
  maps::OccupancyGrid grid{100, 100, 0.05, {-2.5, -2.5, 0.0}, maps::kFree};
  RayCaster rc{grid};
  SurfaceField surf{SurfaceLayout{}, grid};
  Scene scene{rc, surf};
  /// A wall whose face is at distance `d` along local +x from (2.5, 2.5), tilted so the
  /// beam along +x meets it at `incidence`.
  void wall(double d, double incidence, const std::string& material) {
    scene.clear_obstacles();
    const double nx = -std::cos(incidence), ny = std::sin(incidence);  // outward normal
    const double half = 0.05;
    scene.add(BoxShape{static_cast<float>(2.5 + d - half * nx), static_cast<float>(2.5 - half * ny),
                       static_cast<float>(-nx), static_cast<float>(-ny), static_cast<float>(half),
                       1.0F, surf.index_of(material, "test")});
  }
  std::vector<double> readings(int n, const BeamNoise& noise, std::uint64_t seed) const {
    Rng rng(seed);
    std::vector<double> out;
    for (int i = 0; i < n; ++i) {
      out.push_back(render_beam(scene, 2.5F, 2.5F, 1.0F, 0.0F, {0.1F, 30.0F}, noise, rng));
    }
    return out;
  }
};

TEST(BeamNoise, NoiseFreeReadingIsTheGeometricRange) {
  Bench b;
  b.wall(1.7, 0.6, "fabric");
  const auto r = b.readings(5, BeamNoise::none(), 1);
  for (const double x : r) EXPECT_NEAR(x, 1.7, 1e-5);
}

TEST(BeamNoise, AlongBeamSigmaFollowsTable2AtZeroAnd45Degrees) {
  Bench b;
  BeamNoise n;
  n.across_beam = false;
  n.range_growth = 0.0;
  for (const char* m : {"cardboard_box", "shiny_black_metal", "average"}) {
    for (const double inc : {0.0, kPi / 4}) {
      b.wall(2.0, inc, m);
      const auto s = stats(b.readings(20000, n, 3));
      const auto& mat = b.surf.material(b.surf.index_of(m, "t"));
      const double expect = mat.sigma.sigma(inc);
      EXPECT_NEAR(s.sd, expect, 0.03 * expect) << m << " at " << inc;
      EXPECT_NEAR(s.mean, 2.0, 4 * expect / std::sqrt(20000.0));
    }
  }
  // The paper's endpoints, for the record: cardboard 4.6533 / 5.9321 mm.
  const auto card = b.surf.material(b.surf.index_of("cardboard_box", "t"));
  EXPECT_NEAR(card.sigma.sigma(0.0), 4.6533e-3, 1e-9);
  EXPECT_NEAR(card.sigma.sigma(kPi / 4), 5.9321e-3, 1e-9);
}

TEST(BeamNoise, RangeGrowthWidensFarReadings) {
  Bench b;
  BeamNoise n;
  n.across_beam = false;
  b.wall(2.0, 0.0, "average");  // the grid is 5 m wide; 2 m is as far as it goes
  n.range_growth = 5e-3;        // exaggerated so the growth term dominates
  const auto s = stats(b.readings(20000, n, 4));
  const double expect = std::hypot(5.6894e-3, 5e-3 * 2.0);
  EXPECT_NEAR(s.sd, expect, 0.03 * expect);
}

TEST(BeamNoise, AcrossBeamShiftShowsAsSigmaYTanIncidenceOnTiltedWalls) {
  Bench b;
  BeamNoise n;
  n.along_beam = false;
  for (const double inc : {kPi / 4, kPi / 3}) {
    b.wall(2.0, inc, "average");
    const auto s = stats(b.readings(20000, n, 5));
    const double expect = 3e-3 * std::tan(inc);
    EXPECT_NEAR(s.sd, expect, 0.03 * expect) << inc;
  }
  // Perpendicular wall: only the second-order hypot(r, shift) effect, far below 0.1 mm.
  b.wall(2.0, 0.0, "average");
  EXPECT_LT(stats(b.readings(5000, n, 6)).sd, 1e-5);
}

TEST(BeamNoise, DropoutsSpecularLossAndShortReturnsHitTheirRates) {
  Bench b;
  BeamNoise n = BeamNoise::none();
  n.dropouts = {true, 0.1};
  b.wall(2.0, 0.0, "average");
  const int count = 20000;
  auto frac_max = [&](const BeamNoise& nn, std::uint64_t seed) {
    const auto r = b.readings(count, nn, seed);
    return static_cast<double>(std::count(r.begin(), r.end(), 30.0)) / count;
  };
  const double sd = std::sqrt(0.1 * 0.9 / count);
  EXPECT_NEAR(frac_max(n, 7), 0.1, 4 * sd);

  n = BeamNoise::none();
  n.specular = {true, 0.3, kPi / 4};
  b.wall(2.0, kPi / 3, "shiny_black_metal");
  EXPECT_NEAR(frac_max(n, 8), 0.3, 4 * std::sqrt(0.3 * 0.7 / count));
  b.wall(2.0, kPi / 6, "shiny_black_metal");  // below min_incidence
  EXPECT_EQ(frac_max(n, 9), 0.0);
  b.wall(2.0, kPi / 3, "white_shiny");  // not specular
  EXPECT_EQ(frac_max(n, 10), 0.0);

  n = BeamNoise::none();
  n.short_returns = {true, 0.2, 0.5};
  b.wall(2.0, 0.0, "average");
  const auto r = b.readings(count, n, 11);
  std::vector<double> shorts;
  for (const double x : r) {
    if (x < 2.0 - 1e-4) shorts.push_back(x);
    EXPECT_LE(x, 2.0 + 1e-5);
  }
  EXPECT_NEAR(static_cast<double>(shorts.size()) / count, 0.2, 4 * std::sqrt(0.16 / count));
  // Mean of Exp(lambda) truncated to [0, R]: 1/lambda - R / (exp(lambda R) - 1).
  const double expect = 1 / 0.5 - 2.0 / std::expm1(0.5 * 2.0);
  EXPECT_NEAR(stats(shorts).mean, expect, 0.03);
}

TEST(BeamNoise, QuantumRoundsToMillimetres) {
  Bench b;
  BeamNoise n;
  n.quantum = 1e-3;
  b.wall(1.2345, 0.2, "fabric");
  for (const double x : b.readings(200, n, 12)) {
    EXPECT_NEAR(x * 1000.0, std::round(x * 1000.0), 1e-3);
  }
}

TEST(BeamNoise, NoHitGivesRangeMaxAndValidationNamesFields) {
  Bench b;
  b.scene.clear_obstacles();
  EXPECT_EQ(b.readings(3, BeamNoise{}, 13).front(), 30.0);
  BeamNoise n;
  n.dropouts.rate = 1.5;
  try {
    n.validate();
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("dropouts.rate"), std::string::npos);
  }
  n = BeamNoise{};
  n.sigma_y = -1;
  EXPECT_THROW(n.validate(), std::invalid_argument);
  EXPECT_NO_THROW(BeamNoise{}.validate());
  EXPECT_NEAR(incidence_angle(1.0F, 0.0F, -1.0F, 0.0F), 0.0F, 1e-6);
  EXPECT_NEAR(incidence_angle(1.0F, 0.0F, -std::sqrt(0.5F), std::sqrt(0.5F)), kPi / 4, 1e-6);
}

}  // namespace
}  // namespace pgmcl::sims
