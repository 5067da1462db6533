#include "pgmcl/mcl/beam_selection.hpp"

#include <algorithm>

namespace pgmcl {

void valid_beam_indices(const LaserScan& scan, double model_max_range,
                        std::vector<std::uint32_t>& out) {
  out.clear();
  const std::size_t n = scan.ranges.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (valid_range(scan.ranges[i], scan.range_min, scan.range_max, model_max_range))
      out.push_back(static_cast<std::uint32_t>(i));
  }
}

void select_beams(std::span<const std::uint32_t> valid, const BeamSelection& sel,
                  std::vector<std::uint32_t>& out) {
  out.clear();
  const std::size_t n = valid.size();
  switch (sel.mode) {
    case BeamSelectionMode::kAll:
      out.assign(valid.begin(), valid.end());
      return;
    case BeamSelectionMode::kStride: {
      const std::size_t stride = std::max<std::size_t>(sel.stride, 1);
      for (std::size_t i = 0; i < n; i += stride) out.push_back(valid[i]);
      return;
    }
    case BeamSelectionMode::kMaxBeams: {
      const std::size_t k = std::max<std::size_t>(sel.max_beams, 1);
      if (n <= k) {
        out.assign(valid.begin(), valid.end());
        return;
      }
      // Centre of slice j of k equal slices: floor((2j + 1) n / 2k), strictly increasing
      // because n > k, so no index repeats.
      for (std::size_t j = 0; j < k; ++j) out.push_back(valid[((2 * j + 1) * n) / (2 * k)]);
      return;
    }
  }
}

}  // namespace pgmcl
