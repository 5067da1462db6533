#pragma once
/// The particle set as structure-of-arrays.
///
/// Poses are float in the *map-local* grid frame (metres, origin at the outer corner of
/// cell (0, 0), see maps::OccupancyGrid): the hot loop never sees a UTM-scale coordinate,
/// so a map whose origin is at (5e5, 5e6) localises exactly like one at (0, 0). Global
/// poses are produced on the way out, in double. Log-weights are double.

#include <cstddef>
#include <span>
#include <vector>

#include "pgmcl/common/se2.hpp"

namespace pgmcl {

/// Owning SoA storage. All arrays always have the same length.
struct ParticleSet {
  std::vector<float> x;       ///< metres, map-local
  std::vector<float> y;       ///< metres, map-local
  std::vector<float> theta;   ///< radians, map-local, wrapped to (-pi, pi]
  std::vector<double> log_w;  ///< log-weights, kept normalised (log-sum-exp == 0)
  std::vector<double> w;      ///< exp(log_w), sums to 1

  [[nodiscard]] std::size_t size() const noexcept { return x.size(); }
  void resize(std::size_t n) {
    x.resize(n);
    y.resize(n);
    theta.resize(n);
    log_w.resize(n);
    w.resize(n);
  }
  /// Gives every particle the weight 1/n.
  void set_uniform_weights();
};

/// Read-only view handed out by Localizer::particles(). Valid until the next non-const
/// call on the Localizer.
struct ParticlesView {
  std::span<const float> x;        ///< metres, map-local
  std::span<const float> y;        ///< metres, map-local
  std::span<const float> theta;    ///< radians, map-local
  std::span<const double> weight;  ///< normalised, sums to 1
  Pose2 origin{};                  ///< pose of the map-local frame in the global frame

  [[nodiscard]] std::size_t size() const noexcept { return x.size(); }
  /// Particle i in the map-local frame (double).
  [[nodiscard]] Pose2 local_pose(std::size_t i) const noexcept {
    return {static_cast<double>(x[i]), static_cast<double>(y[i]), static_cast<double>(theta[i])};
  }
  /// Particle i in the global frame (double): origin ∘ local.
  [[nodiscard]] Pose2 global_pose(std::size_t i) const noexcept {
    return origin.compose(local_pose(i));
  }
};

}  // namespace pgmcl
