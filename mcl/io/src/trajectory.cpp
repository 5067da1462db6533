#include "pgmcl/io/trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

namespace pgmcl::io {
namespace {
bool stamp_less(const StampedPose& a, const StampedPose& b) noexcept {
  return a.stamp < b.stamp;
}
}  // namespace

Pose2 interpolate(const Pose2& a, const Pose2& b, double alpha) noexcept {
  const double dtheta = wrap_angle(b.theta - a.theta);
  return {a.x + alpha * (b.x - a.x), a.y + alpha * (b.y - a.y),
          wrap_angle(a.theta + alpha * dtheta)};
}

bool is_sorted_by_stamp(const Trajectory& t) noexcept {
  return std::is_sorted(t.begin(), t.end(), stamp_less);
}

void sort_by_stamp(Trajectory& t) {
  std::stable_sort(t.begin(), t.end(), stamp_less);
}

std::optional<std::size_t> nearest_index(const Trajectory& t, double stamp,
                                         double tolerance) noexcept {
  if (t.empty() || !std::isfinite(stamp)) return std::nullopt;
  const auto it = std::lower_bound(t.begin(), t.end(), stamp,
                                   [](const StampedPose& p, double s) { return p.stamp < s; });
  std::size_t best = t.size();
  double best_dt = std::numeric_limits<double>::infinity();
  if (it != t.begin()) {
    best = static_cast<std::size_t>(it - t.begin()) - 1;
    best_dt = stamp - t[best].stamp;
  }
  if (it != t.end() && it->stamp - stamp < best_dt) {
    best = static_cast<std::size_t>(it - t.begin());
    best_dt = it->stamp - stamp;
  }
  if (best == t.size() || best_dt > tolerance) return std::nullopt;
  return best;
}

std::optional<Pose2> interpolate_at(const Trajectory& t, double stamp, double max_gap) noexcept {
  if (t.empty() || !std::isfinite(stamp)) return std::nullopt;
  if (stamp < t.front().stamp || stamp > t.back().stamp) return std::nullopt;
  // First pose strictly after `stamp`; the one before it is the last pose at or before.
  const auto after = std::upper_bound(t.begin(), t.end(), stamp,
                                      [](double s, const StampedPose& p) { return s < p.stamp; });
  const auto before = std::prev(after);
  if (before->stamp == stamp || after == t.end()) return before->pose;
  const double gap = after->stamp - before->stamp;
  if (gap > max_gap) return std::nullopt;
  return interpolate(before->pose, after->pose, (stamp - before->stamp) / gap);
}

}  // namespace pgmcl::io
