#pragma once
/// Which readings of a scan the measurement update scores.
///
/// Policy (documented in one place so the counts in UpdateResult mean one thing):
///  1. A reading is *invalid* when it is NaN or Inf, below the scan's range_min, at or
///     beyond the scan's range_max ("no return"), or beyond the likelihood's max_range
///     (outside the support of the uniform term). Invalid readings carry no usable
///     geometry for a likelihood-field model (Probabilistic Robotics, Table 6.3 discards
///     max-range readings the same way), so they are skipped and counted, never an error.
///  2. The selection then picks from the *valid* readings, in scan order, so a budget of
///     N beams is never wasted on readings that would be skipped anyway.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "pgmcl/common/laser_scan.hpp"

namespace pgmcl {

enum class BeamSelectionMode : std::uint8_t {
  kAll,       ///< every valid reading
  kStride,    ///< every `stride`-th valid reading, starting with the first
  kMaxBeams,  ///< at most `max_beams` valid readings, evenly spread over the valid ones
};

struct BeamSelection {
  BeamSelectionMode mode = BeamSelectionMode::kMaxBeams;
  std::size_t stride = 1;       ///< for kStride; >= 1
  std::size_t max_beams = 120;  ///< for kMaxBeams; >= 1
};

/// True when reading `r` is usable under the policy above.
[[nodiscard]] inline bool valid_range(float r, double range_min, double range_max,
                                      double model_max_range) noexcept {
  const double d = static_cast<double>(r);
  // NaN fails every comparison, so it is rejected by the first test.
  return d >= range_min && d < range_max && d <= model_max_range;
}

/// Indices of the valid readings of `scan`, in order (step 1 of the policy).
void valid_beam_indices(const LaserScan& scan, double model_max_range,
                        std::vector<std::uint32_t>& out);

/// Applies `sel` to the valid indices (step 2 of the policy); `out` is overwritten.
/// kMaxBeams picks index floor((k + 0.5) * n / max_beams) of the valid list for
/// k = 0..max_beams-1, i.e. the centres of max_beams equal slices.
void select_beams(std::span<const std::uint32_t> valid, const BeamSelection& sel,
                  std::vector<std::uint32_t>& out);

}  // namespace pgmcl
