#pragma once
/// Time-stamped planar trajectories and the lookups the evaluators share: nearest stamp and
/// interpolation (linear in x, y; shortest arc in theta).

#include <cstddef>
#include <limits>
#include <optional>
#include <vector>

#include "pgmcl/common/se2.hpp"

namespace pgmcl::io {

struct StampedPose {
  double stamp = 0.0;  ///< seconds
  Pose2 pose{};
};

/// Poses in time order unless a function says otherwise.
using Trajectory = std::vector<StampedPose>;

/// a + alpha (b - a) in x and y; theta moves along the shorter arc (across +-pi if shorter).
[[nodiscard]] Pose2 interpolate(const Pose2& a, const Pose2& b, double alpha) noexcept;

[[nodiscard]] bool is_sorted_by_stamp(const Trajectory& t) noexcept;
/// Stable sort by stamp (equal stamps keep their order).
void sort_by_stamp(Trajectory& t);

/// Index of the pose whose stamp is nearest to `stamp`, if within `tolerance` seconds (ties go
/// to the earlier pose). `t` must be sorted.
[[nodiscard]] std::optional<std::size_t> nearest_index(const Trajectory& t, double stamp,
                                                       double tolerance) noexcept;

/// The pose at `stamp` interpolated between the two poses around it, if `stamp` lies within
/// the trajectory's span and those poses are at most `max_gap` seconds apart. With repeated
/// stamps the last pose at that stamp is used. `t` must be sorted.
[[nodiscard]] std::optional<Pose2> interpolate_at(
    const Trajectory& t, double stamp,
    double max_gap = std::numeric_limits<double>::infinity()) noexcept;

}  // namespace pgmcl::io
