#include "pgmcl/sensor_model/kernel_table.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "detail/normal_mass.hpp"
#include "pgmcl/sensor_model/planar_gaussian_beam_model.hpp"

namespace pgmcl::sensor_model {
namespace {

// 8-point Gauss-Legendre on [-1, 1] (Abramowitz & Stegun, Table 25.4): exact for polynomials
// of degree <= 15.
constexpr std::array<double, 4> kGlNode{0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                                        0.9602898564975363};
constexpr std::array<double, 4> kGlWeight{0.3626837833783620, 0.3137066458778873,
                                          0.2223810344533745, 0.1012285362903763};
constexpr double kClipSigmas = 10.0;  // N(0,1) mass beyond 10 sigma is 1.5e-23
constexpr int kMaxPanels = 20000;

[[noreturn]] void bad_spec(const char* field, double value, const char* why) {
  std::ostringstream os;
  os << "KernelSpec: " << field << " = " << value << " " << why;
  throw std::invalid_argument(os.str());
}

}  // namespace

void KernelSpec::validate() const {
  auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (!positive(sigma_along)) bad_spec("sigma_along", sigma_along, "must be finite and > 0 (m)");
  if (!positive(sigma_across)) bad_spec("sigma_across", sigma_across, "must be finite and > 0 (m)");
  if (!positive(cell_size)) bad_spec("cell_size", cell_size, "must be finite and > 0 (m)");
  if (!std::isfinite(beam_angle)) bad_spec("beam_angle", beam_angle, "must be finite (rad)");
  if (radius < 0 || radius > 1000) bad_spec("radius", radius, "must be in [0, 1000] cells");
  if (!(std::abs(offset_x) <= 0.5 * cell_size))
    bad_spec("offset_x", offset_x, "must be within half a cell of the centre (m)");
  if (!(std::abs(offset_y) <= 0.5 * cell_size))
    bad_spec("offset_y", offset_y, "must be within half a cell of the centre (m)");
  if (discretisation != Discretisation::kPointwise &&
      discretisation != Discretisation::kCellIntegrated)
    bad_spec("discretisation", static_cast<int>(discretisation), "is not a known value");
}

double gaussian_rect_mass(double sigma_along, double sigma_across, double beam_angle, double x0,
                          double x1, double y0, double y1) noexcept {
  const double c = std::cos(beam_angle), s = std::sin(beam_angle);
  const double a2 = sigma_along * sigma_along, b2 = sigma_across * sigma_across;
  // Map-frame covariance R diag(a^2, b^2) R^T of Eq. (6).
  const double sxx = a2 * c * c + b2 * s * s;
  const double sxy = (a2 - b2) * c * s;
  const double sx = std::sqrt(sxx);
  const double slope = sxy / sxx;                     // E[y | x] = slope * x
  const double sc = sigma_along * sigma_across / sx;  // sd(y | x), >= min sigma
  const double lo = std::max(x0, -kClipSigmas * sx), hi = std::min(x1, kClipSigmas * sx);
  if (!(lo < hi) || !(y0 < y1)) return 0.0;

  double scale = sx;
  if (slope != 0.0) scale = std::min(scale, sc / std::abs(slope));
  const int panels =
      std::clamp(static_cast<int>(std::ceil((hi - lo) / (0.5 * scale))), 1, kMaxPanels);
  const double h = (hi - lo) / panels;
  const double norm = 1.0 / (std::sqrt(2.0 * std::numbers::pi) * sx);
  auto integrand = [&](double x) {
    const double u = x / sx, m = slope * x;
    return norm * std::exp(-0.5 * u * u) * detail::normal_mass((y0 - m) / sc, (y1 - m) / sc);
  };
  double total = 0.0;
  for (int p = 0; p < panels; ++p) {
    const double mid = lo + (p + 0.5) * h, half = 0.5 * h;
    double sum = 0.0;
    for (std::size_t k = 0; k < kGlNode.size(); ++k)
      sum +=
          kGlWeight[k] * (integrand(mid - half * kGlNode[k]) + integrand(mid + half * kGlNode[k]));
    total += half * sum;
  }
  return total;
}

KernelTable make_kernel_table(const KernelSpec& spec) {
  spec.validate();
  KernelTable t;
  t.radius = spec.radius;
  const int n = t.side();
  t.mass.assign(static_cast<std::size_t>(n) * static_cast<std::size_t>(n), 0.0);
  const double cell = spec.cell_size;

  if (spec.discretisation == Discretisation::kPointwise) {
    const PlanarGaussianBeamModel model(spec.sigma_along, spec.sigma_across);
    // Work in log space relative to the largest value so tiny sigmas cannot underflow all cells.
    double top = -std::numeric_limits<double>::infinity();
    for (int dy = -t.radius; dy <= t.radius; ++dy)
      for (int dx = -t.radius; dx <= t.radius; ++dx) {
        const double l = model.log_pdf_map(dx * cell - spec.offset_x, dy * cell - spec.offset_y,
                                           spec.beam_angle);
        t.mass[static_cast<std::size_t>((dy + t.radius) * n + (dx + t.radius))] = l;
        top = std::max(top, l);
      }
    double sum = 0.0;
    for (double& v : t.mass) sum += (v = std::exp(v - top));
    t.captured_mass = sum * std::exp(top) * cell * cell;
    for (double& v : t.mass) v /= sum;
    return t;
  }

  double sum = 0.0;
  for (int dy = -t.radius; dy <= t.radius; ++dy)
    for (int dx = -t.radius; dx <= t.radius; ++dx) {
      const double x0 = (dx - 0.5) * cell - spec.offset_x, y0 = (dy - 0.5) * cell - spec.offset_y;
      const double m = gaussian_rect_mass(spec.sigma_along, spec.sigma_across, spec.beam_angle, x0,
                                          x0 + cell, y0, y0 + cell);
      t.mass[static_cast<std::size_t>((dy + t.radius) * n + (dx + t.radius))] = m;
      sum += m;
    }
  if (!(sum > 0.0 && std::isfinite(sum)))  // only for absurd sigmas (e.g. 1e200 m)
    throw std::invalid_argument("KernelSpec: the table captures no probability mass");
  t.captured_mass = sum;
  for (double& v : t.mass) v /= sum;
  return t;
}

}  // namespace pgmcl::sensor_model
