#pragma once
/// The planar Gaussian beam model of Dekan et al., "Probabilistic model of laser
/// rangefinder": an axis-aligned bivariate Gaussian in the beam's own frame, Eq. (6), with
/// sigma_x along the beam (range noise) and sigma_y across it (angular/boundary noise).

#include <cmath>
#include <span>

namespace pgmcl::sensor_model {

/// A point expressed in a beam's frame: dx along the beam, dy across it (left positive).
struct BeamOffset {
  double dx = 0.0;  ///< metres, along the beam
  double dy = 0.0;  ///< metres, across the beam
};

/// Rotates a map-frame offset (ex, ey) from the expected endpoint into the frame of a beam
/// pointing at angle phi (radians, map frame): dx = e . u, dy = e . n with u = (cos, sin).
[[nodiscard]] inline BeamOffset to_beam_frame(double ex, double ey, double phi) noexcept {
  const double c = std::cos(phi), s = std::sin(phi);
  return {c * ex + s * ey, -s * ex + c * ey};
}

class PlanarGaussianBeamModel {
 public:
  /// sigma_x along the beam, sigma_y across it, metres. Throws std::invalid_argument unless
  /// both are finite and > 0.
  PlanarGaussianBeamModel(double sigma_x, double sigma_y);

  /// The paper's final model (Sec. 5): sigma_x = 5.6894 mm, sigma_y = 3 mm.
  [[nodiscard]] static PlanarGaussianBeamModel paper();

  [[nodiscard]] double sigma_x() const noexcept { return sigma_x_; }  ///< metres
  [[nodiscard]] double sigma_y() const noexcept { return sigma_y_; }  ///< metres

  /// Dekan et al., Eq. (4): the 1D Gaussian density. Throws std::invalid_argument for
  /// sigma <= 0 or non-finite.
  [[nodiscard]] static double pdf_1d(double x, double mu, double sigma);
  /// log of Eq. (4), computed directly in log space (no underflow far in the tails).
  [[nodiscard]] static double log_pdf_1d(double x, double mu, double sigma);

  /// Squared Mahalanobis distance (dx/sigma_x)^2 + (dy/sigma_y)^2 in the beam frame.
  [[nodiscard]] double mahalanobis_sq(double dx, double dy) const noexcept {
    return dx * dx * inv_var_x_ + dy * dy * inv_var_y_;
  }
  /// Dekan et al., Eq. (6) in the beam frame with mu = 0: density per m^2 of the endpoint
  /// offset (dx along the beam, dy across).
  [[nodiscard]] double pdf_beam(double dx, double dy) const noexcept {
    return std::exp(log_pdf_beam(dx, dy));
  }
  /// log of Eq. (6): -0.5 * mahalanobis_sq - log(2 pi sigma_x sigma_y). Stable for any
  /// offset (a 40-sigma miss gives about -800, where pdf_beam underflows to 0).
  [[nodiscard]] double log_pdf_beam(double dx, double dy) const noexcept {
    return -0.5 * mahalanobis_sq(dx, dy) - log_norm_;
  }

  /// Eq. (6) for a beam at angle phi (radians, map frame); (ex, ey) is the map-frame offset
  /// of a point from the expected endpoint. Rotated into the beam frame first.
  [[nodiscard]] double pdf_map(double ex, double ey, double phi) const noexcept {
    return std::exp(log_pdf_map(ex, ey, phi));
  }
  [[nodiscard]] double log_pdf_map(double ex, double ey, double phi) const noexcept {
    const BeamOffset b = to_beam_frame(ex, ey, phi);
    return log_pdf_beam(b.dx, b.dy);
  }

  /// Sum of log_pdf_beam over a scan (e.g. the 1081 UTM-30LX beams), accumulated in double:
  /// the joint log-likelihood of independent beams, which a product of pdf_beam values
  /// would underflow. Spans must have equal length (checked; std::invalid_argument).
  [[nodiscard]] double log_pdf_sum(std::span<const double> dx, std::span<const double> dy) const;

 private:
  double sigma_x_;
  double sigma_y_;
  double inv_var_x_;
  double inv_var_y_;
  double log_norm_;  // log(2 pi sigma_x sigma_y)
};

/// Dekan et al., Eq. (5): the boundary shift y = 3 * sigma * sin(d) * dst. sigma is in units
/// of the angular step (Table 4's sigma column), d the angular step in radians, dst the
/// distance; y comes out in dst's unit. 3 sigma covers 99.7 % of the boundary jitter.
/// Throws std::invalid_argument for negative or non-finite inputs.
[[nodiscard]] double boundary_shift(double sigma_beams, double angular_step, double distance);

}  // namespace pgmcl::sensor_model
