// BeamMixture: Gaussian hit (Dekan et al., Eq. (4)) + uniform + max-range box.
#include "pgmcl/sensor_model/beam_mixture.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "pgmcl/sensor_model/planar_gaussian_beam_model.hpp"

namespace pgmcl::sensor_model {
namespace {

BeamMixtureParams small_params() {
  BeamMixtureParams p;
  p.w_hit = 0.7;
  p.w_rand = 0.2;
  p.w_max = 0.1;
  p.sigma_hit = 0.02;
  p.max_range = 5.0;
  p.max_spike_width = 0.05;
  return p;
}

// Composite Simpson of the mixture over [a, b] with n (even) intervals.
double simpson(const BeamMixture& m, double expected, double a, double b, int n) {
  const double h = (b - a) / n;
  double s = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    // Evaluate just inside [a, b] so the box edge is seen from the right side.
    const double x = std::clamp(a + i * h, a + 1e-12, b - 1e-12);
    s += w * m.pdf(x, expected);
  }
  return s * h / 3.0;
}

TEST(BeamMixture, IntegratesToOneOverTheRangeForAnyExpectedRange) {
  const BeamMixture m(small_params());
  const double top = 5.0 - 0.05;  // the box starts here; integrate the two pieces separately
  for (double expected : {0.0, 0.01, 1.3, 4.97, 5.0, 7.0}) {
    const double total =
        simpson(m, expected, 0.0, top, 19800) + simpson(m, expected, top, 5.0, 2000);
    EXPECT_NEAR(total, 1.0, 1e-7) << "expected range " << expected;
  }
}

TEST(BeamMixture, TermsMatchTheirDefinitions) {
  const auto p = small_params();
  const BeamMixture m(p);
  const double mu = 2.0;
  // Mid-range: the Gaussian is untruncated to double precision.
  const double hit = p.w_hit * PlanarGaussianBeamModel::pdf_1d(2.01, mu, p.sigma_hit);
  EXPECT_NEAR(m.pdf(2.01, mu), hit + p.w_rand / p.max_range, 1e-12);
  // Far from the hit, below the box: only the uniform term.
  EXPECT_NEAR(m.pdf(4.0, mu), p.w_rand / p.max_range, 1e-15);
  // In the box: uniform + box.
  EXPECT_NEAR(m.pdf(4.99, mu), p.w_rand / p.max_range + p.w_max / p.max_spike_width, 1e-12);
  // No-return readings count as max_range.
  for (double z : {5.0, 6.0, std::numeric_limits<double>::infinity(), std::nan("")})
    EXPECT_DOUBLE_EQ(m.pdf(z, mu), m.pdf(5.0, mu)) << z;
  EXPECT_EQ(m.pdf(-0.01, mu), 0.0);
  EXPECT_EQ(m.log_pdf(-0.01, mu), -std::numeric_limits<double>::infinity());
  // Truncated at 0: with expected range 0 half the Gaussian is cut, so eta = 1/2.
  const double at0 = p.w_hit * 2.0 * PlanarGaussianBeamModel::pdf_1d(0.01, 0.0, p.sigma_hit);
  EXPECT_NEAR(m.pdf(0.01, 0.0), at0 + p.w_rand / p.max_range, 1e-10);
}

TEST(BeamMixture, LogPdfAgreesWithPdfAndStaysFiniteInTheTail) {
  const BeamMixture m(small_params());
  for (double z : {0.0, 0.5, 1.99, 2.0, 2.03, 4.96, 5.0})
    EXPECT_NEAR(m.log_pdf(z, 2.0), std::log(m.pdf(z, 2.0)), 1e-12) << z;

  auto p = small_params();
  p.w_hit = 1.0;
  p.w_rand = 0.0;
  p.w_max = 0.0;
  const BeamMixture pure(p);
  const double z = 2.0 + 50 * p.sigma_hit;  // 50 sigma: the density underflows to 0
  EXPECT_EQ(pure.pdf(z, 2.0), 0.0);
  EXPECT_NEAR(pure.log_pdf(z, 2.0), PlanarGaussianBeamModel::log_pdf_1d(z, 2.0, p.sigma_hit), 1e-9);
  // Without a hit term, a reading below the box has zero density.
  p.w_hit = 0.0;
  p.w_max = 1.0;
  EXPECT_EQ(BeamMixture(p).log_pdf(1.0, 2.0), -std::numeric_limits<double>::infinity());
}

void expect_invalid(const BeamMixtureParams& p, const std::string& needle) {
  try {
    BeamMixture m(p);
    ADD_FAILURE() << "expected std::invalid_argument mentioning " << needle;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

TEST(BeamMixture, ValidationNamesTheBadWeight) {
  auto p = small_params();
  p.w_rand = -0.1;
  expect_invalid(p, "w_rand = -0.1");
  p = small_params();
  p.w_max = 1.5;
  expect_invalid(p, "w_max");
  p = small_params();
  p.w_hit = std::nan("");
  expect_invalid(p, "w_hit");
  p = small_params();
  p.w_hit = 0.7 + 2e-9;
  expect_invalid(p, "must equal 1");
  p.w_hit = 0.7 + 1e-10;  // within 1e-9: accepted
  EXPECT_NO_THROW(BeamMixture{p});
  p = small_params();
  p.sigma_hit = 0.0;
  expect_invalid(p, "sigma_hit");
  p = small_params();
  p.max_spike_width = 6.0;
  expect_invalid(p, "max_spike_width");
  p = small_params();
  p.max_range = -1.0;
  expect_invalid(p, "max_range");
  EXPECT_NO_THROW(BeamMixture{});  // documented defaults are valid
}

}  // namespace
}  // namespace pgmcl::sensor_model
