// BeamLikelihood, the per-beam function the filter runs: against the hand-computed mixture,
// against Eq. (4) and Eq. (6) of PlanarGaussianBeamModel, its floor, quantisation and errors.
#include "pgmcl/sensor_model/beam_likelihood.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "pgmcl/sensor_model/paper_constants.hpp"
#include "pgmcl/sensor_model/planar_gaussian_beam_model.hpp"

namespace pgmcl::sensor_model {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();

// ll_max, background and step from the formula in the header, evaluated by hand.
TEST(BeamLikelihood, MatchesHandComputedMixture) {
  const BeamLikelihoodParams p;
  for (double res : {0.005, 0.05}) {
    const BeamLikelihood m(p, res, 4.0);
    const double sa = std::sqrt(paper::kSigmaAlong * paper::kSigmaAlong + res * res / 12);
    const double sc = std::sqrt(paper::kSigmaAcross * paper::kSigmaAcross + res * res / 12);
    EXPECT_DOUBLE_EQ(m.sigma_along_eff(), sa);
    EXPECT_DOUBLE_EQ(m.sigma_across_eff(), sc);
    const double floor = p.w_rand / p.max_range;
    const double peak = p.w_hit / (std::sqrt(2 * kPi) * sa);
    EXPECT_NEAR(m.ll_max(), std::log(peak + floor), 1e-12);
    EXPECT_NEAR(m.ll_background(), std::log(floor), 1e-12);
    EXPECT_NEAR(m.nats_per_step(), (std::log(peak + floor) - std::log(floor)) / 255, 1e-12);
    EXPECT_NEAR(m.log_likelihood_of_m2(2.25), std::log(peak * std::exp(-1.125) + floor), 1e-12);
    EXPECT_EQ(m.quantise_m2(0.0), 0);
    EXPECT_EQ(m.quantise_m2(16.0), 255);  // reach_sigmas = 4: background from m2 = 16 on
    EXPECT_LT(m.quantise_m2(15.99), 255);
    EXPECT_EQ(m.background(), 255);
    EXPECT_NEAR(m.log_likelihood_of_q(255), std::log(floor), 1e-12);
    std::cout << "[ scale    ] res " << res << " m: sigma_eff " << sa * 1e3 << " / " << sc * 1e3
              << " mm, " << m.nats_per_step() << " nats per step\n";
  }
  // The header's figures: 0.0414 nats per step on 5 mm, 0.0376 on 5 cm.
  EXPECT_NEAR(BeamLikelihood(p, 0.005, 4.0).nats_per_step(), 0.0414, 5e-5);
  EXPECT_NEAR(BeamLikelihood(p, 0.05, 4.0).nats_per_step(), 0.0376, 5e-5);
}

// The hit term is Eq. (4) along the beam times Eq. (6)'s across-beam factor with peak 1:
// w_hit * pdf_1d(along) * exp(-across^2 / 2 sigma_y^2) = w_hit * pdf_beam * sqrt(2 pi) sigma_y.
TEST(BeamLikelihood, HitTermIsEq4AlongTimesTheUnnormalisedAcrossFactorOfEq6) {
  BeamLikelihoodParams p;
  p.w_hit = 1.0;
  p.w_rand = 0.0;
  const BeamLikelihood m(p, 0.0, 10.0);  // continuous map: the sensor's own sigmas
  EXPECT_DOUBLE_EQ(m.sigma_along_eff(), paper::kSigmaAlong);
  const auto planar = PlanarGaussianBeamModel::paper();
  for (const auto& [along, across] :
       {std::pair{0.0, 0.0}, {0.004, 0.0}, {0.0, -0.005}, {-0.011, 0.007}, {0.02, 0.01}}) {
    SCOPED_TRACE(std::to_string(along) + ", " + std::to_string(across));
    const double eq4 = PlanarGaussianBeamModel::log_pdf_1d(along, 0.0, paper::kSigmaAlong) -
                       0.5 * across * across / (paper::kSigmaAcross * paper::kSigmaAcross);
    EXPECT_NEAR(m.log_likelihood(along, across), eq4, 1e-9);
    const double eq6 =
        planar.log_pdf_beam(along, across) + std::log(std::sqrt(2 * kPi) * paper::kSigmaAcross);
    EXPECT_NEAR(m.log_likelihood(along, across), eq6, 1e-9);
  }
}

TEST(BeamLikelihood, FloorBeyondTheReachAndMonotoneQuantisation) {
  const BeamLikelihood m(BeamLikelihoodParams{}, 0.05, 3.0);
  EXPECT_DOUBLE_EQ(m.reach_m2(), 9.0);
  EXPECT_EQ(m.log_likelihood_of_m2(9.0), m.ll_background());
  EXPECT_EQ(m.log_likelihood_of_m2(kInf), m.ll_background());
  EXPECT_EQ(m.log_likelihood_of_m2(std::nan("")), m.ll_background());
  EXPECT_GT(m.log_likelihood_of_m2(8.99), m.ll_background());
  int last = 0;
  for (double m2 = 0.0; m2 < 9.0; m2 += 0.01) {
    const int q = m.quantise_m2(m2);
    ASSERT_GE(q, last) << m2;
    ASSERT_NEAR(m.log_likelihood_of_q(static_cast<std::uint8_t>(q)), m.log_likelihood_of_m2(m2),
                m.nats_per_step() / 2 + 1e-12)
        << m2;
    last = q;
  }
  // Without the uniform term the floor is the hit term at the reach; w_hit = 0 is flat.
  BeamLikelihoodParams hit_only;
  hit_only.w_hit = 1.0;
  hit_only.w_rand = 0.0;
  const BeamLikelihood h(hit_only, 0.05, 3.0);
  EXPECT_NEAR(h.ll_background(), h.ll_max() - 4.5, 1e-12);
  BeamLikelihoodParams flat;
  flat.w_hit = 0.0;
  flat.w_rand = 1.0;
  const BeamLikelihood f(flat, 0.05, 3.0);
  EXPECT_EQ(f.quantise_m2(0.0), 0);
  EXPECT_EQ(f.background(), 0);
}

TEST(BeamLikelihood, RejectsInvalidParametersNamingTheField) {
  using P = BeamLikelihoodParams;
  const std::vector<std::pair<std::string, std::function<void(P&)>>> cases = {
      {"sigma_along", [](P& p) { p.sigma_along = 0.0; }},
      {"sigma_along", [](P& p) { p.sigma_along = NAN; }},
      {"sigma_across", [](P& p) { p.sigma_across = -1e-3; }},
      {"sigma_across", [](P& p) { p.sigma_across = INFINITY; }},
      {"model_mismatch", [](P& p) { p.model_mismatch = -0.01; }},
      {"w_hit", [](P& p) { p.w_hit = 1.2; }},
      {"w_rand", [](P& p) { p.w_rand = -0.2; }},
      {"w_hit + w_rand", [](P& p) { p.w_hit = 0.9; }},
      {"max_range", [](P& p) { p.max_range = 0.0; }},
  };
  for (const auto& [field, mutate] : cases) {
    P p;
    mutate(p);
    try {
      const BeamLikelihood m(p, 0.05, 4.0);
      ADD_FAILURE() << field << ": invalid value accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(BeamLikelihood(P{}, -0.05, 4.0), std::invalid_argument);
  EXPECT_THROW(BeamLikelihood(P{}, NAN, 4.0), std::invalid_argument);
  EXPECT_THROW(BeamLikelihood(P{}, 0.05, 0.0), std::invalid_argument);
  EXPECT_THROW(BeamLikelihood(P{}, 0.05, INFINITY), std::invalid_argument);
}

}  // namespace
}  // namespace pgmcl::sensor_model
