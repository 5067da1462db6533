#include "pgmcl/sims/calibration.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "pgmcl/sensor_model/paper_constants.hpp"

namespace pgmcl::sims {
namespace {

constexpr double kPi = std::numbers::pi;
namespace paper = sensor_model::paper;

TEST(RangeSigma, PooledEstimateIsUnbiasedEvenForPairs) {
  // 5000 experiments of 2 readings each, every experiment at its own distance: the plain
  // MLE around each pair's mean would give sigma / sqrt(2); the n-1 correction removes it.
  Rng rng(1);
  std::vector<std::vector<double>> ex;
  for (int e = 0; e < 5000; ++e) {
    const double mu = rng.uniform(0.5, 20.0);
    ex.push_back({mu + rng.normal(0.005), mu + rng.normal(0.005)});
  }
  const auto est = estimate_range_sigma(ex);
  EXPECT_EQ(est.dof, 5000u);
  EXPECT_EQ(est.experiments, 5000u);
  EXPECT_NEAR(est.sigma, 0.005, 3 * est.standard_error);
  EXPECT_NEAR(est.standard_error, 0.005 / std::sqrt(10000.0), 2e-6);
  EXPECT_THROW((void)estimate_range_sigma({{1.0}, {2.0}}), std::invalid_argument);
  EXPECT_THROW((void)estimate_range_sigma({{1.0, NAN}}), std::invalid_argument);
  const auto r = beam_readings({{1.0F, 2.0F}, {1.5F, 30.0F}, {NAN, 0.05F}}, 1, 0.1, 30.0);
  EXPECT_EQ(r, std::vector<double>{2.0});
  EXPECT_THROW((void)beam_readings({{1.0F}}, 3, 0.1, 30.0), std::invalid_argument);
}

TEST(RangeSigma, RecoversEveryTable2SigmaFrom20x500SimulatedReadings) {
  // Dekan et al.'s repeatability experiment in reverse: for each surface at 0 and 45 deg,
  // simulate 20 experiments x 500 readings and recover sigma within 3 % (the standard
  // error of 9980 dof is 0.7 %).
  double worst = 0.0;
  for (const auto& row : paper::kTable2) {
    for (const bool tilted : {false, true}) {
      FlatSurfaceExperiment x;
      x.material = table2_material(row.surface).name;
      x.incidence = tilted ? kPi / 4 : 0.0;
      x.distance = tilted ? 1.5 : 1.0;
      x.seed = 10 + static_cast<std::uint64_t>(row.surface) * 2 + tilted;
      const auto est = estimate_range_sigma(simulate_flat_surface(x));
      const double truth = 1e-3 * (tilted ? row.sigma_45deg_mm : row.sigma_perpendicular_mm);
      const double err = est.sigma / truth - 1.0;
      worst = std::max(worst, std::abs(err));
      EXPECT_NEAR(est.sigma, truth, 0.03 * truth) << row.name << (tilted ? " 45" : " 0");
      EXPECT_NEAR(est.mean, x.distance, 1e-3);
      std::printf("%-24s %2d deg: simulated %.4f mm, recovered %.4f mm (%+.2f %%)\n", row.name,
                  tilted ? 45 : 0, truth * 1e3, est.sigma * 1e3, 100 * err);
    }
  }
  std::printf("worst recovery error %.2f %%\n", 100 * worst);
}

TEST(RangeSigma, AcrossBeamNoiseAddsSigmaYTanIncidenceOnATiltedSurface) {
  FlatSurfaceExperiment x;
  x.material = "shiny_black_metal";
  x.incidence = kPi / 4;
  x.noise.across_beam = true;  // sigma_y = 3 mm
  const auto est = estimate_range_sigma(simulate_flat_surface(x));
  const double expect = std::hypot(8.6743e-3, 3e-3 * std::tan(kPi / 4));
  EXPECT_NEAR(est.sigma, expect, 0.03 * expect);
}

TEST(EdgeModel, DistributionIsNormalisedAndChangeProbabilityGrowsWithSigma) {
  for (const double s : {0.05, 0.3, 1.0, 3.0}) {
    const auto p = boundary_distribution(20.4, s, 41);
    double sum = 0.0;
    for (const double x : p) sum += x;
    EXPECT_NEAR(sum, 1.0, 1e-12);
  }
  for (const double frac : {0.0, 0.1, 0.5, 0.9}) {
    double prev = -1.0;
    for (double s = 0.01; s < 20.0; s *= 1.2) {
      const double pc = boundary_change_probability(frac, s);
      EXPECT_GE(pc, prev - 1e-12) << frac << " " << s;
      prev = pc;
    }
  }
  // Edge far from any beam and tiny jitter: nothing ever changes. Edge on a beam: 50 %.
  EXPECT_NEAR(boundary_change_probability(0.5, 0.01), 0.0, 1e-12);
  EXPECT_NEAR(boundary_change_probability(0.0, 1e-4), 0.5, 1e-9);
  // Inversion round trip.
  const double pc = boundary_change_probability(0.3, 0.42);
  EXPECT_NEAR(
      sigma_beams_from_changes(static_cast<std::size_t>(std::lround(pc * 1e6)), 1000000, 0.3), 0.42,
      1e-3);
  EXPECT_THROW((void)sigma_beams_from_changes(5, 4, 0.3), std::invalid_argument);
  EXPECT_THROW((void)sigma_beams_from_changes(1, 4, 1.0), std::invalid_argument);
}

TEST(EdgeModel, BoundaryBeamAndTable3Count) {
  const std::vector<float> scan = {1.0F, 1.0F, 1.1F, 2.5F, 1.0F, 2.5F};
  EXPECT_EQ(boundary_beam(scan, 0, 1.5F), 2);
  EXPECT_EQ(boundary_beam(scan, 3, 1.5F), 2);  // first beam already off the object
  EXPECT_THROW((void)boundary_beam(scan, 6, 1.5F), std::invalid_argument);
  const std::vector<long> b = {4, 4, 5, 5, 4, 4, 4};
  EXPECT_EQ(count_boundary_changes(b), 2u);
}

TEST(EdgeModel, Equation5ReproducesTable4) {
  // Dekan et al., Table 4: y = 3 sigma sin(0.25 deg) dst from Table 4's sigma column.
  for (const auto& row : paper::kTable4) {
    const auto e =
        across_beam_estimate(row.sigma_beams, paper::kUtm30lx.angular_step(), row.distance);
    EXPECT_NEAR(e.y * 1e3, row.y_mm, 5e-3) << row.distance;
    EXPECT_NEAR(e.sigma_y, e.y / 3.0, 1e-15);
  }
}

TEST(EdgeShift, CountsRecoverTheSimulatedAcrossBeamSigma) {
  // Table 3's experiment in reverse, at the paper's four distances, with the model's
  // sigma_y = 3 mm: 10 runs x 500 scans. The edge is placed 1.5 sigma (in beam steps)
  // past the nearest beam where possible, so the count is informative (an edge half-way
  // between two beams 5 m away would almost never shift). Stated tolerances: sigma_y
  // within 10 % from the change count alone and within 6 % from the boundary MLE. Over 20
  // seeds the relative standard deviations were at most 3.1 % (count, 0.5 m) and 2.0 %
  // (MLE, 5.3 m), biases below 1.4 %: the bounds are about three standard deviations.
  const double step = paper::kUtm30lx.angular_step();
  for (const double dst : paper::kTable3Distance) {
    EdgeShiftExperiment x;
    x.distance = dst;
    const double sigma_b = 3e-3 / (dst * std::sin(step));
    x.edge_fraction = std::min(0.5, 1.5 * sigma_b);
    x.seed = 1000 + static_cast<std::uint64_t>(dst * 10);
    const auto data = simulate_edge_shift(x);
    std::size_t changes = 0, pairs = 0;
    std::vector<long> all;
    for (const auto& run : data.boundaries) {
      changes += count_boundary_changes(run);
      pairs += run.size() - 1;
      all.insert(all.end(), run.begin(), run.end());
    }
    const double from_count = sigma_beams_from_changes(changes, pairs, x.edge_fraction);
    const double from_mle = sigma_beams_mle(all, data.edge);
    const auto est_c = across_beam_estimate(from_count, step, dst);
    const auto est_m = across_beam_estimate(from_mle, step, dst);
    EXPECT_NEAR(est_c.sigma_y, 3e-3, 0.10 * 3e-3) << dst;
    EXPECT_NEAR(est_m.sigma_y, 3e-3, 0.06 * 3e-3) << dst;
    std::printf(
        "edge at %.1f m: %zu/%zu changes (%.0f per 500), sigma %.4f beams simulated,"
        " %.4f from count (sigma_y %.3f mm, %+.1f %%), %.4f by MLE (%.3f mm, %+.1f %%);"
        " Eq. (5) y = %.3f mm\n",
        dst, changes, pairs, 500.0 * changes / pairs, sigma_b, from_count, est_c.sigma_y * 1e3,
        100 * (est_c.sigma_y / 3e-3 - 1), from_mle, est_m.sigma_y * 1e3,
        100 * (est_m.sigma_y / 3e-3 - 1), est_m.y * 1e3);
  }
}

TEST(EdgeShift, NoAcrossBeamNoiseMeansNoShifts) {
  EdgeShiftExperiment x;
  x.noise.across_beam = false;
  x.runs = 1;
  x.scans = 100;
  const auto data = simulate_edge_shift(x);
  EXPECT_EQ(count_boundary_changes(data.boundaries[0]), 0u);
  EXPECT_EQ(data.boundaries[0][0], 4);  // the beam just before the edge (window half = 4)
  EdgeShiftExperiment bad;
  bad.edge_fraction = 1.0;
  EXPECT_THROW((void)simulate_edge_shift(bad), std::invalid_argument);
}

}  // namespace
}  // namespace pgmcl::sims
