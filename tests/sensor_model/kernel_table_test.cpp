// The tabular kernel generator (Dekan et al., Sec. 5, Table 5 form) against closed forms.
#include "pgmcl/sensor_model/kernel_table.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <numeric>
#include <stdexcept>
#include <string>

#include "pgmcl/sensor_model/planar_gaussian_beam_model.hpp"

namespace pgmcl::sensor_model {
namespace {

constexpr double kPi = std::numbers::pi;

// Independent oracle: 1D normal mass via erf (fine here, no far tails).
double erf_mass(double a, double b, double sigma) {
  return 0.5 * (std::erf(b / (sigma * std::sqrt(2.0))) - std::erf(a / (sigma * std::sqrt(2.0))));
}

double table_sum(const KernelTable& t) {
  return std::accumulate(t.mass.begin(), t.mass.end(), 0.0);
}

TEST(KernelTable, CellIntegratedMatchesSeparableErfAtZeroAndNinetyDegrees) {
  struct Case {
    double sa, sc, cell;
    int r;
  };
  // Paper cells; map-sized cells much wider than sigma; and cells much narrower than sigma.
  for (const Case& k : {Case{5.6894e-3, 3e-3, 5e-3, 3}, Case{5.6894e-3, 3e-3, 0.05, 2},
                        Case{0.02, 0.004, 0.002, 6}}) {
    for (double angle : {0.0, kPi / 2}) {
      KernelSpec spec;
      spec.sigma_along = k.sa;
      spec.sigma_across = k.sc;
      spec.cell_size = k.cell;
      spec.radius = k.r;
      spec.beam_angle = angle;
      const KernelTable t = make_kernel_table(spec);
      const bool along_x = angle == 0.0;
      // Mass of cell (dx, dy) under the separable normal, sigma_along on the beam's axis.
      const auto cell_mass = [&](int dx, int dy) {
        return erf_mass((dx - 0.5) * k.cell, (dx + 0.5) * k.cell, along_x ? k.sa : k.sc) *
               erf_mass((dy - 0.5) * k.cell, (dy + 0.5) * k.cell, along_x ? k.sc : k.sa);
      };
      double captured = 0.0;
      for (int dy = -k.r; dy <= k.r; ++dy)
        for (int dx = -k.r; dx <= k.r; ++dx) captured += cell_mass(dx, dy);
      EXPECT_NEAR(t.captured_mass, captured, 1e-13);
      for (int dy = -k.r; dy <= k.r; ++dy)
        for (int dx = -k.r; dx <= k.r; ++dx)
          EXPECT_NEAR(t.at(dx, dy), cell_mass(dx, dy) / captured, 1e-13)
              << dx << "," << dy << " " << angle;
      EXPECT_NEAR(table_sum(t), 1.0, 1e-14);
    }
  }
}

TEST(KernelTable, RectMassIsotropicIsRotationInvariant) {
  for (double angle : {0.3, 1.0, 2.5, -0.7}) {
    const double m = gaussian_rect_mass(0.004, 0.004, angle, -0.001, 0.006, 0.002, 0.003);
    EXPECT_NEAR(m, erf_mass(-0.001, 0.006, 0.004) * erf_mass(0.002, 0.003, 0.004), 1e-14);
  }
}

TEST(KernelTable, RectMassAtAnAngleMatchesBruteForce) {
  const PlanarGaussianBeamModel model(5.6894e-3, 3e-3);
  const double angle = 0.52;  // about 30 deg: not separable in map axes
  const double rects[3][4] = {{-0.0025, 0.0025, -0.0025, 0.0025},
                              {0.0025, 0.0075, 0.0025, 0.0075},
                              {-0.0125, -0.0075, 0.0025, 0.0075}};
  for (const auto& r : rects) {
    const int n = 200;  // tensor-product Simpson on pdf_map, error ~ (h/sigma)^4 ~ 1e-10
    const double hx = (r[1] - r[0]) / n, hy = (r[3] - r[2]) / n;
    auto w = [](int i) { return (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0); };
    double s = 0.0;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j)
        s += w(i) * w(j) * model.pdf_map(r[0] + i * hx, r[2] + j * hy, angle);
    s /= 9.0;
    s *= hx * hy;
    EXPECT_NEAR(gaussian_rect_mass(5.6894e-3, 3e-3, angle, r[0], r[1], r[2], r[3]), s, 1e-9 * s);
  }
}

TEST(KernelTable, RectMassOverThePlaneIsOneAndAdditive) {
  for (double angle : {0.0, 0.4, 1.2, 2.0, 3.0}) {
    EXPECT_NEAR(gaussian_rect_mass(0.02, 0.001, angle, -1, 1, -1, 1), 1.0, 1e-13) << angle;
    const double whole = gaussian_rect_mass(0.02, 0.001, angle, -0.01, 0.03, -0.02, 0.01);
    const double left = gaussian_rect_mass(0.02, 0.001, angle, -0.01, 0.004, -0.02, 0.01);
    const double right = gaussian_rect_mass(0.02, 0.001, angle, 0.004, 0.03, -0.02, 0.01);
    EXPECT_NEAR(whole, left + right, 1e-14) << angle;
  }
}

TEST(KernelTable, SymmetriesUnderRotationAndReflection) {
  for (auto d : {Discretisation::kPointwise, Discretisation::kCellIntegrated}) {
    KernelSpec spec;
    spec.radius = 3;
    spec.discretisation = d;
    spec.beam_angle = 0.6;
    const KernelTable a = make_kernel_table(spec);
    spec.beam_angle = 0.6 + kPi;  // reversed beam: same ellipse
    const KernelTable rev = make_kernel_table(spec);
    spec.beam_angle = -0.6;  // mirrored in the x axis
    const KernelTable mir = make_kernel_table(spec);
    spec.beam_angle = kPi / 2 - 0.6;  // mirrored in the diagonal: transpose
    const KernelTable tr = make_kernel_table(spec);
    for (int dy = -3; dy <= 3; ++dy)
      for (int dx = -3; dx <= 3; ++dx) {
        EXPECT_NEAR(a.at(dx, dy), rev.at(dx, dy), 1e-14);
        EXPECT_NEAR(a.at(dx, dy), mir.at(dx, -dy), 1e-14);
        EXPECT_NEAR(a.at(dx, dy), tr.at(dy, dx), 1e-14);
      }
    // Along the 0.6 rad beam (up and to the right) beats across it.
    EXPECT_GT(a.at(1, 1), a.at(-1, 1));
  }
}

TEST(KernelTable, PointwiseIsEq6AtCellCentres) {
  KernelSpec spec;
  spec.discretisation = Discretisation::kPointwise;
  spec.radius = 2;
  spec.beam_angle = 1.1;
  const KernelTable t = make_kernel_table(spec);
  const PlanarGaussianBeamModel model(spec.sigma_along, spec.sigma_across);
  const double c = spec.cell_size;
  double sum = 0.0;
  for (int dy = -2; dy <= 2; ++dy)
    for (int dx = -2; dx <= 2; ++dx) sum += model.pdf_map(dx * c, dy * c, 1.1);
  for (int dy = -2; dy <= 2; ++dy)
    for (int dx = -2; dx <= 2; ++dx)
      EXPECT_NEAR(t.at(dx, dy), model.pdf_map(dx * c, dy * c, 1.1) / sum, 1e-14);
  EXPECT_NEAR(t.captured_mass, sum * c * c, 1e-12);
  EXPECT_NEAR(table_sum(t), 1.0, 1e-14);
}

TEST(KernelTable, OffsetMovesTheMean) {
  KernelSpec spec;
  spec.radius = 2;
  spec.offset_x = 0.5 * spec.cell_size;  // mean on the border of cells 0 and 1
  for (auto d : {Discretisation::kPointwise, Discretisation::kCellIntegrated}) {
    spec.discretisation = d;
    const KernelTable t = make_kernel_table(spec);
    for (int dy = -2; dy <= 2; ++dy) {
      EXPECT_NEAR(t.at(0, dy), t.at(1, dy), 1e-14);
      EXPECT_NEAR(t.at(-1, dy), t.at(2, dy), 1e-14);
    }
  }
}

TEST(KernelTable, WideTableCapturesAllTheMass) {
  KernelSpec spec;
  spec.radius = 12;  // 60 mm = 10.5 sigma_along
  spec.beam_angle = 0.8;
  EXPECT_NEAR(make_kernel_table(spec).captured_mass, 1.0, 1e-12);
  spec.radius = 0;
  const KernelTable one = make_kernel_table(spec);
  EXPECT_EQ(one.mass.size(), 1u);
  EXPECT_DOUBLE_EQ(one.at(0, 0), 1.0);
}

TEST(KernelTable, ValidationNamesTheField) {
  auto expect_invalid = [](KernelSpec s, const std::string& needle) {
    try {
      (void)make_kernel_table(s);
      ADD_FAILURE() << "expected std::invalid_argument mentioning " << needle;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  KernelSpec s;
  s.sigma_across = 0.0;
  expect_invalid(s, "sigma_across");
  s = {};
  s.cell_size = -0.005;
  expect_invalid(s, "cell_size");
  s = {};
  s.radius = -1;
  expect_invalid(s, "radius");
  s = {};
  s.beam_angle = std::nan("");
  expect_invalid(s, "beam_angle");
  s = {};
  s.offset_y = 0.003;  // more than half of the 5 mm cell
  expect_invalid(s, "offset_y");
}

}  // namespace
}  // namespace pgmcl::sensor_model
