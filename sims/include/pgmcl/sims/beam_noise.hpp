#pragma once
/// Noisy range readings from the planar Gaussian model of Dekan et al. (Eq. (6)): along the
/// beam N(0, sigma_x(surface, incidence, range)), across it N(0, sigma_y) as a lateral shift
/// of the measured point; plus optional failure modes, each a switch with a rate.

#include <numbers>

#include "pgmcl/common/random.hpp"
#include "pgmcl/sensor_model/paper_constants.hpp"
#include "pgmcl/sims/scene.hpp"

namespace pgmcl::sims {

/// With probability `rate` the beam returns nothing (reported as range_max).
struct MaxRangeDropouts {
  bool enabled = false;
  double rate = 0.01;  ///< probability per beam, [0, 1]
};

/// With probability `rate` the beam returns early (dust, glass, people's legs): the range
/// is drawn from an exponential with rate `lambda`, truncated to [0, true range], as
/// p_short in Probabilistic Robotics, Eq. (6.7).
struct ShortReturns {
  bool enabled = false;
  double rate = 0.01;   ///< probability per beam, [0, 1]
  double lambda = 0.5;  ///< 1/m, > 0
};

/// Specular materials (SurfaceMaterial::specular, i.e. shiny black metal) at shallow angles
/// mirror the beam away: with probability `rate` no return when the incidence angle (from
/// the surface normal) is at least `min_incidence`.
struct SpecularLoss {
  bool enabled = false;
  double rate = 0.5;                              ///< probability per qualifying beam, [0, 1]
  double min_incidence = std::numbers::pi / 4.0;  ///< radians, [0, pi/2]
};

struct BeamNoise {
  /// Along-beam Gaussian: sigma = hypot(material.sigma.sigma(incidence), range_growth * r),
  /// the material's Table 2 curve (sensor_model::IncidenceSigmaModel) widened with range
  /// as sensor_model::RangeSigmaModel (Table 1's repeatability bounds).
  bool along_beam = true;
  double range_growth = 0.8e-3;  ///< m of sigma per m of range, >= 0
  /// Across-beam Gaussian (Dekan et al., Sec. 5): the footprint is shifted sideways by
  /// N(0, sigma_y); the beam is cast parallel to the nominal one through the shifted
  /// footprint, and the reading is the distance of the shifted hit point from the sensor.
  /// A LaserScan stores readings at nominal bearings, so the shifted point's bearing error
  /// (sigma_y / r) is not representable; it shows where it matters physically, as edge
  /// beams hitting the other side of an edge (Dekan et al., Table 3) and as range change
  /// sigma_y * tan(incidence) on tilted surfaces.
  bool across_beam = true;
  double sigma_y = sensor_model::paper::kSigmaAcross;  ///< metres, >= 0
  double quantum = 0.0;  ///< metres, >= 0; 0.001 mimics Table 1's 1 mm resolution; 0 = off
  MaxRangeDropouts dropouts;
  ShortReturns short_returns;
  SpecularLoss specular;

  /// Noise-free readings (every switch off).
  [[nodiscard]] static BeamNoise none() noexcept;
  /// Throws std::invalid_argument naming the field.
  void validate() const;
};

/// Range limits of the sensor producing the readings.
struct RangeLimits {
  float range_min = 0.1F;   ///< metres (readings below are kept: they are invalid, not lost)
  float range_max = 30.0F;  ///< metres; "no return" is exactly range_max
};

/// One noisy reading of the beam from (x, y) along the unit direction (dx, dy), map-local
/// frame. Returns metres in [0, range_max]. Draws from `rng` in a fixed order per beam.
[[nodiscard]] float render_beam(const Scene& scene, float x, float y, float dx, float dy,
                                const RangeLimits& limits, const BeamNoise& noise,
                                Rng& rng) noexcept;

/// Incidence angle [rad, 0..pi/2] between a beam (dx, dy) and the outward normal (nx, ny).
[[nodiscard]] float incidence_angle(float dx, float dy, float nx, float ny) noexcept;

}  // namespace pgmcl::sims
