// Dekan et al., Eqs. (4)-(6): the 1D and planar Gaussian and their log forms.
#include "pgmcl/sensor_model/planar_gaussian_beam_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "pgmcl/sensor_model/paper_constants.hpp"

namespace pgmcl::sensor_model {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(PlanarGaussianBeamModel, Pdf1dMatchesEq4AndIntegratesToOne) {
  const double sigma = 0.0056894, mu = 1.25;
  EXPECT_DOUBLE_EQ(PlanarGaussianBeamModel::pdf_1d(mu, mu, sigma),
                   1.0 / std::sqrt(2 * kPi * sigma * sigma));
  EXPECT_NEAR(PlanarGaussianBeamModel::pdf_1d(mu + sigma, mu, sigma) /
                  PlanarGaussianBeamModel::pdf_1d(mu, mu, sigma),
              std::exp(-0.5), 1e-12);  // (mu + sigma) - mu is not exactly sigma
  // Simpson over +/- 10 sigma.
  const int n = 2000;
  const double a = mu - 10 * sigma, h = 20 * sigma / n;
  double s = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    s += w * PlanarGaussianBeamModel::pdf_1d(a + i * h, mu, sigma);
  }
  EXPECT_NEAR(s * h / 3.0, 1.0, 1e-12);
}

TEST(PlanarGaussianBeamModel, PlanarPdfIsProductOfEq4Marginals) {
  const auto m = PlanarGaussianBeamModel::paper();
  EXPECT_DOUBLE_EQ(m.sigma_x(), 5.6894e-3);
  EXPECT_DOUBLE_EQ(m.sigma_y(), 3e-3);
  for (double dx : {-0.02, -0.004, 0.0, 0.007}) {
    for (double dy : {-0.01, 0.0, 0.002, 0.009}) {
      const double expect = PlanarGaussianBeamModel::pdf_1d(dx, 0.0, m.sigma_x()) *
                            PlanarGaussianBeamModel::pdf_1d(dy, 0.0, m.sigma_y());
      EXPECT_NEAR(m.pdf_beam(dx, dy), expect, 1e-12 * expect) << dx << " " << dy;
    }
  }
  EXPECT_DOUBLE_EQ(m.pdf_beam(0, 0), 1.0 / (2 * kPi * 5.6894e-3 * 3e-3));
}

TEST(PlanarGaussianBeamModel, PlanarPdfIntegratesToOne) {
  const PlanarGaussianBeamModel m(0.004, 0.0015);
  const int n = 400;  // midpoint rule over +/- 9 sigma in each direction
  const double hx = 18 * m.sigma_x() / n, hy = 18 * m.sigma_y() / n;
  double s = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      s += m.pdf_beam(-9 * m.sigma_x() + (i + 0.5) * hx, -9 * m.sigma_y() + (j + 0.5) * hy);
  EXPECT_NEAR(s * hx * hy, 1.0, 1e-9);
}

TEST(PlanarGaussianBeamModel, MapFrameRotatesIntoBeamFrame) {
  const auto m = PlanarGaussianBeamModel::paper();
  // Beam along +x: map offsets are beam offsets.
  EXPECT_DOUBLE_EQ(m.pdf_map(0.004, -0.002, 0.0), m.pdf_beam(0.004, -0.002));
  // Beam along +y: a map +y offset is along the beam, a map +x offset is to its right.
  EXPECT_NEAR(m.log_pdf_map(0.001, 0.006, kPi / 2), m.log_pdf_beam(0.006, -0.001), 1e-12);
  // Any angle: place a beam-frame offset (a, b) in the map and read it back.
  for (double phi : {-3.0, -1.1, 0.3, 2.2, 7.5}) {
    const double a = 0.005, b = -0.0025;
    const double ex = std::cos(phi) * a - std::sin(phi) * b;
    const double ey = std::sin(phi) * a + std::cos(phi) * b;
    EXPECT_NEAR(m.log_pdf_map(ex, ey, phi), m.log_pdf_beam(a, b), 1e-12) << phi;
    // The model is symmetric under reversing the beam (phi + pi).
    EXPECT_NEAR(m.log_pdf_map(ex, ey, phi + kPi), m.log_pdf_beam(a, b), 1e-12) << phi;
  }
  // Along-beam misses cost less than across-beam misses (sigma_x > sigma_y).
  EXPECT_GT(m.pdf_map(0.0, 0.005, kPi / 2), m.pdf_map(0.005, 0.0, kPi / 2));
}

TEST(PlanarGaussianBeamModel, LogPdfIsStableFarInTheTails) {
  const auto m = PlanarGaussianBeamModel::paper();
  const double dx = 40 * m.sigma_x();
  EXPECT_EQ(m.pdf_beam(dx, 40 * m.sigma_y()), 0.0);  // underflows
  const double expect = -0.5 * 3200.0 - std::log(2 * kPi * m.sigma_x() * m.sigma_y());
  EXPECT_NEAR(m.log_pdf_beam(dx, 40 * m.sigma_y()), expect, 1e-9);
  EXPECT_NEAR(PlanarGaussianBeamModel::log_pdf_1d(1.0, 0.0, 1e-3),
              -0.5e6 - std::log(1e-3) - 0.5 * std::log(2 * kPi), 1e-6);
}

TEST(PlanarGaussianBeamModel, LogPdfSumOverAFullScanWherePdfProductUnderflows) {
  const auto m = PlanarGaussianBeamModel::paper();
  const int n = paper::kUtm30lx.beams_per_scan;
  std::vector<double> dx(n), dy(n);
  double product = 1.0, sum = 0.0;
  for (int i = 0; i < n; ++i) {
    dx[i] = 6 * m.sigma_x() * std::sin(0.01 * i);
    dy[i] = 6 * m.sigma_y() * std::cos(0.013 * i);
    product *= m.pdf_beam(dx[i], dy[i]);
    sum += m.log_pdf_beam(dx[i], dy[i]);
  }
  EXPECT_EQ(product, 0.0);
  const double got = m.log_pdf_sum(dx, dy);
  EXPECT_TRUE(std::isfinite(got));
  EXPECT_NEAR(got, sum, 1e-9 * std::abs(sum));
  EXPECT_THROW((void)m.log_pdf_sum(dx, std::span<const double>(dy).first(3)),
               std::invalid_argument);
}

TEST(PlanarGaussianBeamModel, RejectsBadSigmasNamingThem) {
  try {
    PlanarGaussianBeamModel bad(0.005, -1.0);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("sigma_y"), std::string::npos) << e.what();
  }
  EXPECT_THROW(PlanarGaussianBeamModel(0.0, 0.003), std::invalid_argument);
  EXPECT_THROW(PlanarGaussianBeamModel(NAN, 0.003), std::invalid_argument);
  EXPECT_THROW((void)PlanarGaussianBeamModel::pdf_1d(0.0, 0.0, 0.0), std::invalid_argument);
}

TEST(BoundaryShift, Eq5AndValidation) {
  const double d = 0.25 * kPi / 180;
  EXPECT_DOUBLE_EQ(boundary_shift(1.0, d, 2.0), 3.0 * std::sin(d) * 2.0);
  EXPECT_DOUBLE_EQ(boundary_shift(0.0, d, 2.0), 0.0);
  EXPECT_THROW((void)boundary_shift(-0.1, d, 1.0), std::invalid_argument);
  EXPECT_THROW((void)boundary_shift(0.1, d, INFINITY), std::invalid_argument);
}

}  // namespace
}  // namespace pgmcl::sensor_model
