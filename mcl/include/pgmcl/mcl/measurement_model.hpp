#pragma once
/// Measurement update hot loop: scores particles against a scan with the planar Gaussian
/// beam likelihood (Dekan et al., Eq. (6)) read from precomputed maps::LikelihoodField
/// tables.
///
/// Per scan, prepare() turns each selected reading into its endpoint (r cos a, r sin a)
/// and unit direction in the robot *base* frame (the sensor mount is composed in once,
/// here), in cells, as float SoA. Per particle, the hot loop only rotates and translates
/// those endpoints by the particle pose, reads one byte q per beam and sums q in uint32:
/// exact and order-independent, so any thread count gives bitwise the same sums.
/// The table kind is dispatched ONCE per call into the kernel of maps/table_kernels.hpp:
/// no per-beam branch on configuration, no virtual call, no allocation.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "pgmcl/common/laser_scan.hpp"
#include "pgmcl/maps/likelihood_field.hpp"
#include "pgmcl/maps/table_kernels.hpp"

namespace pgmcl {

/// Selected beams of one scan in the base frame, in cells (SoA, float).
struct PreparedBeams {
  std::vector<float> ex;   ///< endpoint x, cells, base frame
  std::vector<float> ey;   ///< endpoint y, cells, base frame
  std::vector<float> ux;   ///< unit direction x, base frame (offset-field kind)
  std::vector<float> uy;   ///< unit direction y, base frame (offset-field kind)
  std::vector<float> bin;  ///< direction in orientation bins, in [0, bins) (oriented kind)
  float reach = 0.0f;      ///< max over beams of |ex| + |ey|, cells (bounds any rotation)

  [[nodiscard]] std::size_t size() const noexcept { return ex.size(); }
  /// The arrays as the table kernels read them (maps/table_kernels.hpp).
  [[nodiscard]] maps::BeamArrays arrays() const noexcept {
    return {ex.data(), ey.data(), ux.data(), uy.data(), bin.data(), ex.size(), reach};
  }
};

/// Result of scoring one pose.
struct PoseScore {
  std::uint32_t sum_q = 0;       ///< sum of quantised values over the prepared beams
  std::uint32_t background = 0;  ///< beams that read the background (beyond reach / off map)
  /// Beams whose endpoint lies within kFitSigmas effective sigmas of a mapped obstacle
  /// (q <= the table's value at that Mahalanobis distance): readings the map explains.
  std::uint32_t fitting = 0;
};

/// A beam "fits the map" when its endpoint is within this many effective sigmas of an
/// obstacle: 3 sigma keeps 99 % of the readings of a correctly placed scan.
inline constexpr double kFitSigmas = 3.0;

/// Bound to one table; cheap to copy (shares the table). Thread-safe for concurrent const
/// calls once prepared.
class MeasurementModel {
 public:
  /// Throws std::invalid_argument for a null field.
  explicit MeasurementModel(std::shared_ptr<const maps::LikelihoodField> field);

  /// Prepares `selected` readings of `scan` (indices into scan.ranges, all valid).
  /// Reuses the buffers: no allocation once they have grown to the largest scan.
  void prepare(const LaserScan& scan, std::span<const std::uint32_t> selected);

  [[nodiscard]] const PreparedBeams& beams() const noexcept { return beams_; }
  [[nodiscard]] const maps::LikelihoodField& field() const noexcept { return *field_; }

  /// Serial reference: sum_q[i] for particle i at map-local pose (x[i], y[i], theta[i]).
  void score_serial(std::span<const float> x, std::span<const float> y,
                    std::span<const float> theta, std::span<std::uint32_t> sum_q) const noexcept;
  /// OpenMP path with `threads` threads (num_threads clause; 0 = OpenMP's default). Runs
  /// the very same per-particle code as score_serial, so the sums are bitwise identical.
  void score_parallel(std::span<const float> x, std::span<const float> y,
                      std::span<const float> theta, std::span<std::uint32_t> sum_q,
                      int threads) const noexcept;
  /// score_serial() for particles [begin, end) only (sum_q indexed like x): a unit of work
  /// for a caller that schedules the particles itself.
  void score_block(std::span<const float> x, std::span<const float> y, std::span<const float> theta,
                   std::size_t begin, std::size_t end,
                   std::span<std::uint32_t> sum_q) const noexcept;
  /// One map-local pose, also counting beams that fell on background.
  [[nodiscard]] PoseScore score_pose(double x, double y, double theta) const noexcept;

  /// Per-beam log-likelihood summed over the prepared beams for a given sum_q:
  ///   ll = beams * ll_max - nats_per_step * sum_q   (Dekan et al., Eq. (6), quantised).
  [[nodiscard]] double log_likelihood(std::uint32_t sum_q) const noexcept {
    const sensor_model::BeamLikelihood& m = field_->model();
    return static_cast<double>(beams_.size()) * m.ll_max() -
           m.nats_per_step() * static_cast<double>(sum_q);
  }

 private:
  std::shared_ptr<const maps::LikelihoodField> field_;
  PreparedBeams beams_;
  std::uint8_t fit_q_ = 0;
};

}  // namespace pgmcl
