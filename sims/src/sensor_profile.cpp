#include "pgmcl/sims/sensor_profile.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

#include "pgmcl/sensor_model/paper_constants.hpp"

namespace pgmcl::sims {

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

void require(bool ok, const std::string& profile, const std::string& what) {
  if (!ok) throw std::invalid_argument("SensorProfile '" + profile + "': " + what);
}

SensorProfile sick(std::string name, double step_deg, int count, double rate) {
  SensorProfile p;
  p.name = std::move(name);
  p.angle_min = -90.0 * kDeg;
  p.angle_increment = step_deg * kDeg;
  p.beam_count = count;
  p.range_min = 0.0;
  p.range_max = 80.0;
  p.scan_rate = rate;
  p.scan_time = 1.0 / 75.0;
  return p;
}

}  // namespace

void SensorProfile::validate() const {
  require(beam_count >= 1, name,
          "beam_count must be >= 1 (got " + std::to_string(beam_count) + ")");
  require(std::isfinite(angle_min), name, "angle_min must be finite");
  require(beam_count == 1 || (angle_increment > 0.0 && std::isfinite(angle_increment)), name,
          "angle_increment must be positive and finite");
  require(beam_count == 1 || angle_increment * (beam_count - 1) <= 2.0 * std::numbers::pi + 1e-9,
          name, "the beams span more than 360 degrees");
  require(range_min >= 0.0 && std::isfinite(range_min), name, "range_min must be >= 0");
  require(range_max > range_min && std::isfinite(range_max), name,
          "range_max must be finite and greater than range_min");
  require(scan_rate > 0.0 && std::isfinite(scan_rate), name, "scan_rate must be positive [Hz]");
  require(scan_time >= 0.0 && std::isfinite(scan_time), name, "scan_time must be >= 0 [s]");
}

LaserScan SensorProfile::make_scan(const Pose2& sensor_pose) const {
  return make_scan(
      std::vector<float>(static_cast<std::size_t>(beam_count), static_cast<float>(range_max)),
      sensor_pose);
}

LaserScan SensorProfile::make_scan(std::vector<float> ranges, const Pose2& sensor_pose) const {
  if (ranges.size() != static_cast<std::size_t>(beam_count)) {
    throw std::invalid_argument("SensorProfile '" + name + "': make_scan got " +
                                std::to_string(ranges.size()) + " ranges for " +
                                std::to_string(beam_count) + " beams");
  }
  LaserScan s;
  s.angle_min = angle_min;
  s.angle_increment = angle_increment;
  s.range_min = range_min;
  s.range_max = range_max;
  s.ranges = std::move(ranges);
  s.sensor_pose = sensor_pose;
  return s;
}

SensorProfile utm30lx() {
  constexpr auto& spec = sensor_model::paper::kUtm30lx;  // Dekan et al., Table 1
  SensorProfile p;
  p.name = "hokuyo_utm30lx";
  p.beam_count = spec.beams_per_scan;
  p.angle_increment = spec.angular_step();
  p.angle_min = -0.5 * spec.scan_angle();
  p.range_min = spec.guaranteed_range_min;
  p.range_max = spec.guaranteed_range_max;
  p.scan_time = spec.scan_time;
  p.scan_rate = 1.0 / spec.scan_time;
  return p;
}

SensorProfile sick_lms_1deg() {
  return sick("sick_lms_1deg", 1.0, 181, 75.0);
}
SensorProfile sick_lms_half_deg() {
  return sick("sick_lms_half_deg", 0.5, 361, 37.5);
}

SensorProfile carmen_sick(int beam_count) {
  if (beam_count < 2) {
    throw std::invalid_argument("carmen_sick: need at least 2 beams (got " +
                                std::to_string(beam_count) + ")");
  }
  const double step = beam_count % 2 == 0 ? 180.0 / beam_count : 180.0 / (beam_count - 1);
  return sick("carmen_sick_" + std::to_string(beam_count), step, beam_count, 75.0);
}

SensorProfile sensor_profile_by_name(const std::string& name) {
  if (name == "hokuyo_utm30lx") return utm30lx();
  if (name == "sick_lms_1deg") return sick_lms_1deg();
  if (name == "sick_lms_half_deg") return sick_lms_half_deg();
  const std::string prefix = "carmen_sick_";
  if (name.rfind(prefix, 0) == 0) {
    const std::string digits = name.substr(prefix.size());
    if (!digits.empty() && digits.size() <= 5 &&
        digits.find_first_not_of("0123456789") == std::string::npos) {
      return carmen_sick(std::stoi(digits));
    }
  }
  throw std::invalid_argument("unknown sensor profile '" + name +
                              "' (known: hokuyo_utm30lx, sick_lms_1deg, sick_lms_half_deg, "
                              "carmen_sick_<n>)");
}

}  // namespace pgmcl::sims
