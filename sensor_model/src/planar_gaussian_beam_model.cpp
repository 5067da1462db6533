#include "pgmcl/sensor_model/planar_gaussian_beam_model.hpp"

#include <numbers>
#include <stdexcept>
#include <string>

#include "pgmcl/sensor_model/paper_constants.hpp"

namespace pgmcl::sensor_model {
namespace {

void require_positive_sigma(double sigma, const char* name) {
  if (!(std::isfinite(sigma) && sigma > 0.0))
    throw std::invalid_argument(std::string("PlanarGaussianBeamModel: ") + name + " = " +
                                std::to_string(sigma) + " must be finite and > 0 (metres)");
}

}  // namespace

PlanarGaussianBeamModel::PlanarGaussianBeamModel(double sigma_x, double sigma_y)
    : sigma_x_(sigma_x), sigma_y_(sigma_y) {
  require_positive_sigma(sigma_x, "sigma_x");
  require_positive_sigma(sigma_y, "sigma_y");
  inv_var_x_ = 1.0 / (sigma_x * sigma_x);
  inv_var_y_ = 1.0 / (sigma_y * sigma_y);
  // Eq. (6): 1 / (2 pi sqrt(sigma_x^2 sigma_y^2)).
  log_norm_ = std::log(2.0 * std::numbers::pi * sigma_x * sigma_y);
}

PlanarGaussianBeamModel PlanarGaussianBeamModel::paper() {
  return {paper::kSigmaAlong, paper::kSigmaAcross};
}

double PlanarGaussianBeamModel::pdf_1d(double x, double mu, double sigma) {
  return std::exp(log_pdf_1d(x, mu, sigma));
}

double PlanarGaussianBeamModel::log_pdf_1d(double x, double mu, double sigma) {
  require_positive_sigma(sigma, "sigma");
  const double z = (x - mu) / sigma;
  // Eq. (4): 1 / sqrt(2 pi sigma^2) * exp(-(x - mu)^2 / (2 sigma^2)).
  return -0.5 * z * z - std::log(sigma) - 0.5 * std::log(2.0 * std::numbers::pi);
}

double PlanarGaussianBeamModel::log_pdf_sum(std::span<const double> dx,
                                            std::span<const double> dy) const {
  if (dx.size() != dy.size())
    throw std::invalid_argument("PlanarGaussianBeamModel::log_pdf_sum: dx has " +
                                std::to_string(dx.size()) + " entries but dy has " +
                                std::to_string(dy.size()));
  double m = 0.0;
  for (std::size_t i = 0; i < dx.size(); ++i) m += mahalanobis_sq(dx[i], dy[i]);
  return -0.5 * m - static_cast<double>(dx.size()) * log_norm_;
}

double boundary_shift(double sigma_beams, double angular_step, double distance) {
  if (!(std::isfinite(sigma_beams) && sigma_beams >= 0.0) ||
      !(std::isfinite(angular_step) && angular_step >= 0.0) ||
      !(std::isfinite(distance) && distance >= 0.0))
    throw std::invalid_argument("boundary_shift: sigma_beams = " + std::to_string(sigma_beams) +
                                ", angular_step = " + std::to_string(angular_step) +
                                ", distance = " + std::to_string(distance) +
                                " must all be finite and >= 0");
  // Dekan et al., Eq. (5).
  return 3.0 * sigma_beams * std::sin(angular_step) * distance;
}

}  // namespace pgmcl::sensor_model
