#pragma once
/// One planar laser scan as the engine receives it.

#include <cstddef>
#include <vector>

#include "pgmcl/common/se2.hpp"

namespace pgmcl {

/// Beam i points at angle_min + i * angle_increment in the sensor frame. The scan's time
/// is not part of it: Localizer::update() takes it (a log record keeps its own stamp).
/// Invalid readings (NaN, Inf, < range_min, >= range_max) are skipped by the filter and
/// counted in UpdateResult; they are never an error.
struct LaserScan {
  double angle_min = 0.0;        ///< radians, first beam in the sensor frame
  double angle_increment = 0.0;  ///< radians between consecutive beams
  double range_min = 0.1;        ///< metres; readings below are invalid
  double range_max = 30.0;       ///< metres; readings at or beyond mean "no return"
  std::vector<float> ranges;     ///< metres
  Pose2 sensor_pose{};           ///< laser pose in the robot base frame

  [[nodiscard]] std::size_t size() const noexcept { return ranges.size(); }
  [[nodiscard]] double beam_angle(std::size_t i) const noexcept {
    return angle_min + static_cast<double>(i) * angle_increment;
  }
};

}  // namespace pgmcl
