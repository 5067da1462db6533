#pragma once
/// Dekan et al.'s experiments in reverse: estimate the model's sigmas from repeated readings.
///  (1) Along the beam (Sec. 4, Table 2): repeated readings of a flat surface, pooled over
///      experiments -> sigma_x by maximum likelihood.
///  (2) Across the beam (Table 3, Table 4, Eq. (5)): how often the boundary beam of an
///      object edge changes between scans -> sigma in beam steps -> y and sigma_y.
/// The estimators take plain readings, so a command can run them on recorded data; the
/// simulate_* functions produce such readings from the simulator for testing.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "pgmcl/sims/beam_noise.hpp"
#include "pgmcl/sims/sensor_profile.hpp"
#include "pgmcl/sims/surfaces.hpp"

namespace pgmcl::sims {

// ---- (1) Along-beam sigma -------------------------------------------------------------

struct RangeSigmaEstimate {
  double sigma = 0.0;           ///< metres: pooled estimate, see estimate_range_sigma
  double standard_error = 0.0;  ///< metres: sigma / sqrt(2 * dof) (Gaussian readings)
  double mean = 0.0;            ///< metres: mean of all readings
  std::size_t readings = 0;
  std::size_t experiments = 0;  ///< experiments with at least 2 readings
  std::size_t dof = 0;          ///< readings - experiments
};

/// Each experiment holds repeated readings of one beam at a fixed setup (Dekan et al.: 20
/// experiments of 500). Each has its own unknown mean, so the Gaussian MLE of sigma pools
/// the squared deviations from each experiment's own mean; dividing by the degrees of
/// freedom sum(n_e - 1) instead of sum(n_e) is the n-1 (REML) correction that removes the
/// bias of estimating the means. Experiments with fewer than 2 readings add nothing.
/// Throws std::invalid_argument for non-finite readings or fewer than 1 degree of freedom.
[[nodiscard]] RangeSigmaEstimate estimate_range_sigma(
    const std::vector<std::vector<double>>& experiments);

/// The readings of beam `beam` from recorded scans, dropping invalid ones (NaN, below
/// range_min, at or beyond range_max). Throws std::invalid_argument if a scan is too short.
[[nodiscard]] std::vector<double> beam_readings(const std::vector<std::vector<float>>& scans,
                                                std::size_t beam, double range_min,
                                                double range_max);

/// Simulated version of Dekan et al.'s repeatability experiment: a flat surface of
/// `material` at `distance` along the beam, tilted to `incidence`.
struct FlatSurfaceExperiment {
  std::string material = "cardboard_box";  ///< a name in `materials`
  std::vector<SurfaceMaterial> materials = default_materials();
  double incidence = 0.0;  ///< radians from the surface normal, [0, pi/2)
  double distance = 1.0;   ///< metres along the beam, (0, 25]
  int experiments = 20;
  int readings = 500;  ///< per experiment
  /// The sensor's noise. Default: along-beam only and no range growth, i.e. the material's
  /// Table 2 sigma exactly. With across_beam on, a tilted surface adds
  /// sigma_y * tan(incidence) in quadrature, as a real 45 deg measurement would.
  BeamNoise noise = [] {
    BeamNoise n;
    n.across_beam = false;
    n.range_growth = 0.0;
    return n;
  }();
  std::uint64_t seed = 1;  ///< experiment e draws from Rng::for_block(seed, e, 3)
};
[[nodiscard]] std::vector<std::vector<double>> simulate_flat_surface(
    const FlatSurfaceExperiment& x);

// ---- (2) Across-beam sigma from edge shifts ---------------------------------------------

/// The boundary beam of one scan: starting at `first_beam` (which should see the object,
/// range < split_range) and walking to higher indices, the last beam before the first one
/// that does not (range >= split_range, or NaN). Returns first_beam - 1 when first_beam
/// itself misses. Throws std::invalid_argument if first_beam is out of range.
[[nodiscard]] long boundary_beam(std::span<const float> ranges, std::size_t first_beam,
                                 float split_range);

/// Dekan et al., Table 3's statistic: the number of consecutive scan pairs whose boundary
/// beams differ.
[[nodiscard]] std::size_t count_boundary_changes(std::span<const long> boundaries);

/// The boundary model behind the inversion. Beams are indexed from the object side,
/// beam j at position j; the edge lies at position `edge` (e.g. 4.3: between beams 4 and 5,
/// 0.3 steps past beam 4). Each beam independently hits the object iff j + e_j < edge,
/// e_j ~ N(0, sigma_beams) (its footprint shifted sideways, in beam steps). The boundary is
/// B = (first missing beam) - 1, so P(B = b) = prod_{j <= b} h_j * (1 - h_{b+1}) with
/// h_j = Phi((edge - j) / sigma_beams). Returned for b = -1 .. count - 1 (index b + 1);
/// the beams from `count` on are taken to miss.
[[nodiscard]] std::vector<double> boundary_distribution(double edge, double sigma_beams, int count);
/// Probability that two independent scans have different boundaries: 1 - sum_b P(B=b)^2.
[[nodiscard]] double boundary_change_probability(double edge, double sigma_beams);

/// Inverts boundary_change_probability for sigma_beams by bisection, given `changes` out of
/// `pairs` consecutive pairs and the edge position's fraction past the last sure beam.
/// The edge position must be known (from the set-up geometry): the count alone cannot tell
/// a wide jitter from an edge lying close to a beam, which is why Table 3's counts spread
/// so much between runs at one distance. Throws std::invalid_argument for pairs == 0,
/// changes > pairs or an edge fraction outside [0, 1).
[[nodiscard]] double sigma_beams_from_changes(std::size_t changes, std::size_t pairs,
                                              double edge_fraction);

/// Maximum-likelihood sigma_beams from the boundary indices themselves (every scan, not
/// just whether it changed), under the same model; `edge` in the boundaries' index frame.
/// Throws std::invalid_argument for an empty input.
[[nodiscard]] double sigma_beams_mle(std::span<const long> boundaries, double edge);

struct AcrossBeamEstimate {
  double sigma_beams = 0.0;  ///< boundary jitter in angular steps (Table 4's sigma column)
  double y = 0.0;            ///< metres: Eq. (5), y = 3 sigma sin(d) dst
  double sigma_y = 0.0;      ///< metres: y / 3, the lateral footprint sigma at dst
};
/// Dekan et al., Eq. (5) (sensor_model::boundary_shift) for a beam step `angular_step`
/// [rad] at `distance` [m].
[[nodiscard]] AcrossBeamEstimate across_beam_estimate(double sigma_beams, double angular_step,
                                                      double distance);

/// Simulated version of Dekan et al.'s edge experiment (Table 3): an object whose edge lies
/// `distance` metres away between the sensor's centre beam k and beam k+1, a background
/// surface `background_gap` metres behind it. Only a window of beams around the edge is
/// rendered (the others cannot see the edge).
struct EdgeShiftExperiment {
  double distance = 1.5;        ///< metres to the edge, (0, 25]
  double edge_fraction = 0.5;   ///< where the edge lies between beams k and k+1, [0, 1)
  double background_gap = 1.0;  ///< metres, > 0
  int runs = 10;
  int scans = 500;  ///< per run
  SensorProfile sensor = utm30lx();
  BeamNoise noise{};       ///< both Gaussian terms on by default (sigma_y = 3 mm)
  std::uint64_t seed = 1;  ///< run r, scan s draws from Rng::for_block(seed, r * scans + s, 4)
};
struct EdgeShiftData {
  std::vector<std::vector<long>> boundaries;  ///< per run, per scan, in the window's frame
  double edge = 0.0;                          ///< edge position in the window's frame
  std::size_t window = 0;                     ///< beams rendered
  float split_range = 0.0F;                   ///< metres: object/background threshold used
};
[[nodiscard]] EdgeShiftData simulate_edge_shift(const EdgeShiftExperiment& x);

}  // namespace pgmcl::sims
