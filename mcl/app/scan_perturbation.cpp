#include "scan_perturbation.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace pgmcl::app {

std::vector<std::size_t> thin_scans(const io::Trajectory& truth, const ScanThinning& rule) {
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    if (!kept.empty()) {
      const io::StampedPose& last = truth[kept.back()];
      if (truth[i].stamp - last.stamp < rule.min_gap) continue;
      if (rule.by_travel) {
        const Pose2 d = last.pose.between(truth[i].pose);
        const bool moved = std::hypot(d.x, d.y) >= rule.min_travel;
        const bool turned = std::abs(d.theta) >= rule.min_turn;
        if (!moved && !turned) continue;
      }
    }
    kept.push_back(i);
  }
  return kept;
}

std::size_t drop_beams(std::vector<float>& ranges, const BeamDropout& d, float no_return,
                       Rng& rng) {
  const std::size_t n = ranges.size();
  const auto k = static_cast<std::size_t>(std::llround(d.fraction * static_cast<double>(n)));
  if (k == 0 || d.sectors < 1) return 0;
  const std::size_t s = std::min(static_cast<std::size_t>(d.sectors), k);
  // Sector lengths as equal as possible, in random order.
  std::vector<std::size_t> length(s, k / s);
  for (std::size_t j = 0; j < k % s; ++j) ++length[j];
  for (std::size_t j = s; j > 1; --j) std::swap(length[j - 1], length[rng.below(j)]);
  // Non-overlapping placements of s blocks among n - k kept readings are the ways of
  // choosing which s of the m = n - k + s slots (kept readings and blocks, in scan order)
  // are blocks: choose them uniformly (Floyd's sampling), then lay the slots out in order.
  const std::size_t m = n - k + s;
  std::vector<bool> block(m, false);
  for (std::size_t j = m - s; j < m; ++j) {
    const auto t = static_cast<std::size_t>(rng.below(j + 1));
    block[block[t] ? j : t] = true;
  }
  std::size_t beam = 0, next = 0;
  for (std::size_t slot = 0; slot < m; ++slot) {
    if (!block[slot]) {
      ++beam;
      continue;
    }
    for (std::size_t r = 0; r < length[next]; ++r) ranges[beam++] = no_return;
    ++next;
  }
  return k;
}

float no_return_reading(double range_max) noexcept {
  float f = static_cast<float>(range_max);
  if (static_cast<double>(f) < range_max) f = std::nextafter(f, std::numeric_limits<float>::max());
  return f;
}

}  // namespace pgmcl::app
