#pragma once
/// `pgmcl perturb`'s scan conditions: scan thinning (fewer, farther-apart scans) and beam
/// dropout (sectors where nothing reflects).

#include <cstddef>
#include <limits>
#include <vector>

#include "pgmcl/common/random.hpp"
#include "pgmcl/io/trajectory.hpp"

namespace pgmcl::app {

/// Which scans to keep. The first scan is always kept; a later one only if every active
/// rule holds against the last kept scan.
struct ScanThinning {
  double min_gap = 0.0;     ///< seconds of log time since the last kept scan (0: inactive)
  bool by_travel = false;   ///< the travel rule is active
  double min_travel = 0.0;  ///< metres the true pose moved, or ...
  double min_turn = std::numeric_limits<double>::infinity();  ///< ... radians it turned
};

/// Indices into `truth` of the scans to keep, in order (all of them for the defaults).
[[nodiscard]] std::vector<std::size_t> thin_scans(const io::Trajectory& truth,
                                                  const ScanThinning& rule);

struct BeamDropout {
  double fraction = 0.0;  ///< of the beams of each scan, in [0, 1)
  int sectors = 3;        ///< contiguous sectors they are split into, >= 1
};

/// Replaces round(fraction * n) of the n readings by `no_return`, in at most `sectors`
/// contiguous runs at uniformly random, non-overlapping positions (runs may touch, and do
/// not wrap around the end of the scan). Returns the number of readings replaced.
std::size_t drop_beams(std::vector<float>& ranges, const BeamDropout& d, float no_return, Rng& rng);

/// The smallest float that is >= range_max as a double, so a reading written as it reads
/// back as "no return" (readings at or beyond range_max): float(80.99) is below 80.99.
[[nodiscard]] float no_return_reading(double range_max) noexcept;

}  // namespace pgmcl::app
