#pragma once
/// Generalisations of Dekan et al.'s single sigma_x = 5.6894 mm (Sec. 5): by incidence angle
/// per surface (Table 2), by range (the manufacturer's bounds, Table 1), and the effective
/// sigma a grid-map filter should use (sensor + map discretisation + model mismatch).
/// None of these models is in the paper; each is a documented choice anchored to its numbers.

#include "pgmcl/sensor_model/paper_constants.hpp"

namespace pgmcl::sensor_model {

/// Mean of one column of Table 2 over the six surfaces, metres.
[[nodiscard]] constexpr double table2_mean_perpendicular() {
  double s = 0.0;
  for (const auto& r : paper::kTable2) s += r.sigma_perpendicular_mm;
  return s / paper::kTable2.size() * 1e-3;  // 4.9527 mm
}
[[nodiscard]] constexpr double table2_mean_45deg() {
  double s = 0.0;
  for (const auto& r : paper::kTable2) s += r.sigma_45deg_mm;
  return s / paper::kTable2.size() * 1e-3;  // 6.4261 mm
}

/// (1) Range sigma as a function of incidence angle, through Table 2's two points.
///
/// Model: sigma(t)^2 = sigma_normal^2 + (sigma_45^2 - sigma_normal^2) * tan(t)^2.
/// Why: a beam of finite width w hitting a surface tilted by t sees depths spread over about
/// w tan(t); treating that spread as independent of the perpendicular noise adds it in
/// quadrature. tan(0) = 0 and tan(45 deg) = 1 make the curve pass exactly through Table 2's
/// perpendicular and 45 deg values; it is flat near 0 and grows monotonically.
/// Extrapolation: beyond 45 deg the same formula, held constant past grazing_limit (tan
/// diverges at 90 deg, and near-grazing returns are mixed pixels and drop-outs, which the
/// mixture's random term models better than a wider Gaussian). For the surface average the
/// curve reaches the paper's 5.6894 mm at about 34 deg.
struct IncidenceSigmaModel {
  double sigma_normal = table2_mean_perpendicular();  ///< m, at normal incidence (4.9527 mm)
  double sigma_45 = table2_mean_45deg();              ///< m, at 45 deg (6.4261 mm)
  double grazing_limit = 70.0 * paper::kDegToRad;     ///< rad, in [45, 89] deg

  /// Table 2's row for `surface`, other fields default.
  [[nodiscard]] static IncidenceSigmaModel for_surface(Surface surface);

  /// Throws std::invalid_argument naming the field: sigmas finite, 0 < sigma_normal <=
  /// sigma_45 (a surface that improved with tilt would extrapolate to negative variance),
  /// grazing_limit within [45, 89] deg.
  void validate() const;

  /// Sigma in metres. `incidence` is the angle between the beam and the surface normal in
  /// radians; any value is folded onto [0, 90] deg (sign and beam direction do not matter).
  [[nodiscard]] double sigma(double incidence) const noexcept;
};

/// (2) Range sigma as a function of measured range, respecting Table 1's repeatability bounds
/// (sigma < 10 mm for 0.1-10 m, < 30 mm for 10-30 m, White Kent sheet).
///
/// Model: sigma(r) = hypot(sigma_short, growth * r): the paper's short-range value plus an
/// independent term growing linearly with range (weaker returns, larger phase noise), added in
/// quadrature. With the defaults: 5.6894 mm at 0, 5.745 mm at 1 m (+1 %), 9.82 mm at 10 m,
/// 24.7 mm at 30 m. growth = 0.8 mm/m is the largest round value keeping the paper's sigma
/// under the 10 mm bound at 10 m; it is a choice, not a fit (the paper gives no range data).
struct RangeSigmaModel {
  double sigma_short = paper::kSigmaAlong;  ///< m, sigma at short range (Dekan Sec. 5)
  double growth = 0.8e-3;                   ///< m of sigma per m of range, >= 0

  /// Throws std::invalid_argument naming the field.
  void validate() const;
  /// Sigma in metres at `range` metres (negative ranges count as 0).
  [[nodiscard]] double sigma(double range) const noexcept;
};

/// (3) Sigma for scoring beams against a grid map:
///   sigma_eff^2 = sigma_sensor^2 + resolution^2 / 12 + mismatch^2.
/// Why: an obstacle known only to lie somewhere in a cell of side `resolution` has a position
/// uniform over the cell, whose variance is resolution^2 / 12 per axis. The mismatch term
/// covers what neither the sensor nor the grid explains: map registration errors, unmapped
/// clutter, pose/timestamp jitter, correlated beams. Without them the paper's 5.7 mm sigma on
/// a 5 cm map charges an unavoidable half-cell (25 mm) miss about 9.7 nats per beam, some
/// 10^4 nats per 1081-beam scan, so one particle takes all the weight.
struct SensorNoiseModel {
  double sigma_along = paper::kSigmaAlong;    ///< m, sensor sigma along the beam (5.6894 mm)
  double sigma_across = paper::kSigmaAcross;  ///< m, sensor sigma across the beam (3 mm)
  /// m, along and across; a tuning default (not from the paper): 2 cm, about the accuracy
  /// of a well-built indoor map, giving ~25 mm effective sigmas on a 5 cm map.
  double mismatch_along = 0.02;
  double mismatch_across = 0.02;  ///< m

  /// Throws std::invalid_argument naming the field (sigmas > 0, mismatches >= 0, finite).
  void validate() const;
};

struct EffectiveSigma {
  double along = 0.0;   ///< m
  double across = 0.0;  ///< m
};

/// sqrt(sigma^2 + resolution^2 / 12 + mismatch^2), all metres.
[[nodiscard]] double effective_sigma(double sigma, double resolution, double mismatch) noexcept;

/// Both axes of `model` on a map of `map_resolution` metres per cell. Validates the model and
/// the resolution (finite, >= 0; 0 means a continuous map); throws std::invalid_argument.
[[nodiscard]] EffectiveSigma effective_sigma(const SensorNoiseModel& model, double map_resolution);

}  // namespace pgmcl::sensor_model
