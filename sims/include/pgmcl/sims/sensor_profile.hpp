#pragma once
/// Laser scanner profiles as plain data: beam geometry, range limits and timing.

#include <string>
#include <vector>

#include "pgmcl/common/laser_scan.hpp"
#include "pgmcl/common/se2.hpp"
#include "pgmcl/sims/ray_caster.hpp"

namespace pgmcl::sims {

/// Beam i points at angle_min + i * angle_increment in the sensor frame (as in LaserScan).
struct SensorProfile {
  std::string name = "hokuyo_utm30lx";
  double angle_min = 0.0;        ///< radians, first beam
  double angle_increment = 0.0;  ///< radians between consecutive beams (> 0)
  int beam_count = 0;            ///< >= 1
  double range_min = 0.1;        ///< metres; shorter readings are invalid
  double range_max = 30.0;       ///< metres; "no return" is reported as exactly range_max
  double scan_rate = 40.0;       ///< Hz, scans per second
  double scan_time = 0.025;      ///< seconds per sweep (beams are simulated as simultaneous)

  [[nodiscard]] double angle_max() const noexcept {
    return angle_min + (beam_count - 1) * angle_increment;
  }
  [[nodiscard]] double beam_angle(int i) const noexcept { return angle_min + i * angle_increment; }
  [[nodiscard]] BeamFan fan() const noexcept {
    return {angle_min, angle_increment, beam_count, range_max};
  }
  /// Throws std::invalid_argument naming the offending field.
  void validate() const;

  /// A scan with this geometry; every range set to range_max ("no return").
  [[nodiscard]] LaserScan make_scan(const Pose2& sensor_pose = {}) const;
  /// A scan with this geometry and the given ranges (size must equal beam_count; throws).
  [[nodiscard]] LaserScan make_scan(std::vector<float> ranges, const Pose2& sensor_pose = {}) const;
};

/// Hokuyo UTM-30LX per Dekan et al., Table 1: 270 deg at 0.25 deg (1081 beams, -135..135
/// deg), guaranteed range 0.1-30 m, 25 ms per scan (40 Hz).
[[nodiscard]] SensorProfile utm30lx();

/// SICK LMS 2xx, 180 deg field of view centred on the x axis, both ends included:
/// 1 deg (181 beams) or 0.5 deg (361 beams). Range 0-80 m (the LMS 200's cm mode reaches
/// 81.9 m); 75 Hz at 1 deg, 37.5 Hz at 0.5 deg (two interlaced sweeps per scan).
[[nodiscard]] SensorProfile sick_lms_1deg();
[[nodiscard]] SensorProfile sick_lms_half_deg();

/// The convention of CARMEN logs (FLASER/ROBOTLASER lines carry only the reading count):
/// the first beam at -90 deg; the step is 180/n deg for even n (so 180 beams cover -90..89
/// deg and 360 beams -90..89.5 deg) and 180/(n-1) deg for odd n (181 beams: -90..90 deg).
/// Range and timing as sick_lms_1deg(). Throws std::invalid_argument for n < 2.
[[nodiscard]] SensorProfile carmen_sick(int beam_count);

/// Looks a profile up by name: "hokuyo_utm30lx", "sick_lms_1deg", "sick_lms_half_deg",
/// "carmen_sick_<n>". Throws std::invalid_argument listing the names.
[[nodiscard]] SensorProfile sensor_profile_by_name(const std::string& name);

}  // namespace pgmcl::sims
