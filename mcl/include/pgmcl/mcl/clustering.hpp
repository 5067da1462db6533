#pragma once
/// Clustering of the particle set into pose hypotheses; the heaviest cluster is the best
/// hypothesis (a multi-modal cloud's overall mean can sit between modes, on no particle).
///
/// Particles are hashed into (x, y, heading) grid cells; cells that touch (differ by at
/// most one index in every dimension, headings wrapping at +/-pi) are joined by union-find.
/// This is single linkage at the cell scale: particles closer than one cell in x, y and
/// heading always share a cluster, particles more than two cells apart in some dimension
/// are only joined through a chain of occupied cells. Expected O(N).

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <span>
#include <vector>

#include "pgmcl/common/se2.hpp"

namespace pgmcl {

struct ClusterConfig {
  double cell_xy = 0.5;                               ///< metres, grid cell side in x and y
  double cell_theta = 30.0 * std::numbers::pi / 180;  ///< radians, heading cell width
};

/// One hypothesis: its share of the weight and the weighted moments of its particles
/// (as PoseEstimate: circular heading mean, covariance about it, symmetric PSD).
struct Cluster {
  double weight = 0.0;    ///< fraction of the total weight, in [0, 1]
  std::size_t count = 0;  ///< particles in the cluster
  Pose2 mean{};
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  ///< m^2, m rad, rad^2
  double heading_concentration = 0.0;  ///< mean resultant length of the headings, [0, 1]
};

/// Reusable clustering workspace: buffers grow to the largest particle count seen and are
/// then reused, so repeated calls do not allocate. Not thread-safe (one per filter).
class ParticleClusterer {
 public:
  /// Throws std::invalid_argument unless cell sizes are finite and > 0 and the heading
  /// cells number at most 65535 (round(2 pi / cell_theta) equal sectors).
  explicit ParticleClusterer(const ClusterConfig& config = {});

  /// Clusters sorted by weight, heaviest first (ties: the cluster holding the lower
  /// particle index first). The reference stays valid until the next call.
  /// Throws std::invalid_argument on size mismatch, no particles, or a non-positive total
  /// weight.
  const std::vector<Cluster>& cluster(std::span<const float> x, std::span<const float> y,
                                      std::span<const float> theta, std::span<const double> w);

  /// labels()[i] is particle i's index into the last returned clusters.
  [[nodiscard]] std::span<const std::uint32_t> labels() const noexcept { return labels_; }
  [[nodiscard]] const ClusterConfig& config() const noexcept { return config_; }

 private:
  [[nodiscard]] std::uint32_t find(std::uint32_t c) noexcept;
  [[nodiscard]] std::uint32_t lookup(std::uint64_t key) const noexcept;
  void build_cells(std::span<const float> x, std::span<const float> y,
                   std::span<const float> theta);
  void link_cells();

  ClusterConfig config_;
  double inv_xy_ = 0.0, sectors_per_radian_ = 0.0;
  std::size_t sectors_ = 1;
  std::vector<std::uint64_t> slot_keys_;   // open-addressing table: cell key
  std::vector<std::uint32_t> slot_cells_;  // ... and its cell index (UINT32_MAX = empty)
  std::vector<std::uint64_t> cell_keys_;
  std::vector<std::uint32_t> parent_;      // union-find over cells
  std::vector<std::uint32_t> cell_of_;     // particle -> cell
  std::vector<std::uint32_t> labels_;      // particle -> cluster
  std::vector<std::uint32_t> root_label_;  // root cell -> cluster (before sorting)
  std::vector<std::uint32_t> first_;       // cluster -> its first particle (reference)
  std::vector<double> cluster_w_;          // cluster -> weight sum
  std::vector<std::size_t> count_;         // cluster -> particles
  std::vector<std::array<double, 5>> first_moments_;
  std::vector<std::array<double, 4>> rel_mean_;  // dx, dy, dtheta, R from the reference
  std::vector<std::array<double, 6>> second_moments_;
  std::vector<std::uint32_t> order_;  // sorted position -> cluster
  std::vector<std::uint32_t> rank_;   // cluster -> sorted position
  std::vector<Cluster> clusters_;
};

/// One-shot convenience: ParticleClusterer(config).cluster(x, y, theta, w).
[[nodiscard]] std::vector<Cluster> cluster_particles(std::span<const float> x,
                                                     std::span<const float> y,
                                                     std::span<const float> theta,
                                                     std::span<const double> w,
                                                     const ClusterConfig& config = {});

}  // namespace pgmcl
