#include "carmen_messages.hpp"

#include <cmath>
#include <string>

#include "fields.hpp"

namespace pgmcl::io::detail {
namespace {

/// `logged_theta` (optional) receives theta before wrapping.
Pose2 read_pose(FieldCursor& c, std::string_view x, std::string_view y, std::string_view theta,
                double* logged_theta = nullptr) {
  Pose2 p;
  p.x = c.finite(x);
  p.y = c.finite(y);
  const double logged = c.finite(theta);
  p.theta = wrap_angle(logged);
  if (logged_theta != nullptr) *logged_theta = logged;
  return p;
}

/// Every CARMEN message ends with "ipc_timestamp ipc_hostname logger_timestamp".
template <typename Record>
void read_tail(FieldCursor& c, double& stamp, Record& r) {
  stamp = c.finite("timestamp");
  r.host = std::string(c.text("hostname"));
  r.logger_stamp = c.finite("logger_timestamp");
  c.expect_end("logger_timestamp");
}

/// A line whose length disagrees with its declared counts is either cut short or has a wrong
/// count. If it still ends like a complete message (number, host name, number), the count is
/// wrong and we say so; otherwise the field walk reports the first missing field.
bool tail_intact(std::span<const std::string_view> t) {
  const std::size_t n = t.size();
  return n >= 3 && parse_double(t[n - 1]) && !parse_double(t[n - 2]) && parse_double(t[n - 3]);
}

void check_count(std::span<const std::string_view> t, std::size_t expected,
                 std::string_view count_field, std::size_t declared, std::string_view what) {
  if (t.size() == expected || !tail_intact(t)) return;
  const std::size_t fixed = expected - declared;
  const std::size_t held = t.size() > fixed ? t.size() - fixed : 0;
  throw FieldError{std::string(count_field), "declares " + std::to_string(declared) + " " +
                                                 std::string(what) + " but the line holds " +
                                                 std::to_string(held)};
}

void read_ranges(FieldCursor& c, std::size_t n, std::vector<float>& out) {
  out.resize(n);
  for (std::size_t i = 0; i < n; ++i) out[i] = static_cast<float>(c.number("range", i));
}

/// The header's field of view must span the readings: CARMEN writes fov = resolution ×
/// (n − 1) (some drivers resolution × n). A header that says otherwise would place every
/// beam at a wrong angle, so the line is refused rather than guessed at.
void check_field_of_view(double fov, double resolution, std::size_t n) {
  if (n < 2) return;
  const double tol = 0.5 * std::abs(resolution) + 1e-3;  // rounding of the logged values
  const double span = resolution * static_cast<double>(n - 1);
  if (std::abs(fov - span) <= tol || std::abs(fov - (span + resolution)) <= tol) return;
  std::string msg = "is ";
  append_number(msg, fov);
  msg += " rad, but angular_resolution ";
  append_number(msg, resolution);
  msg += " rad x (num_readings " + std::to_string(n) + " - 1) spans ";
  append_number(msg, span);
  msg += " rad: the header does not describe these readings";
  throw FieldError{"field_of_view", msg};
}

}  // namespace

std::pair<std::string, std::string> parse_param(std::span<const std::string_view> tokens) {
  FieldCursor c(tokens, 1);
  std::string name(c.text("name"));
  std::string value(c.text("value"));
  // The rest (timestamp host logger_timestamp, or "nohost 0" in older logs) is not used.
  return {std::move(name), std::move(value)};
}

OdomRecord parse_odom(std::span<const std::string_view> tokens) {
  FieldCursor c(tokens, 1);
  OdomRecord r;
  r.pose = read_pose(c, "x", "y", "theta", &r.logged_theta);
  r.tv = c.finite("tv");
  r.rv = c.finite("rv");
  r.accel = c.finite("accel");
  read_tail(c, r.stamp, r);
  return r;
}

TruePosRecord parse_truepos(std::span<const std::string_view> tokens) {
  FieldCursor c(tokens, 1);
  TruePosRecord r;
  r.true_pose = read_pose(c, "true_x", "true_y", "true_theta");
  r.odom_pose = read_pose(c, "odom_x", "odom_y", "odom_theta");
  read_tail(c, r.stamp, r);
  return r;
}

CarmenScan parse_flaser(std::span<const std::string_view> tokens, LaserMessage message) {
  FieldCursor c(tokens, 1);
  CarmenScan s;
  s.message = message;
  const std::size_t n = c.count("num_readings", kMaxReadings);
  check_count(tokens, 2 + n + 9, "num_readings", n, "readings");
  read_ranges(c, n, s.scan.ranges);
  s.laser_pose = read_pose(c, "x", "y", "theta");
  s.odom_pose = read_pose(c, "odom_x", "odom_y", "odom_theta", &s.logged_odom_theta);
  read_tail(c, s.stamp, s);
  const BeamLayout layout = sick_beam_layout(n);
  s.scan.angle_min = layout.angle_min;
  s.scan.angle_increment = layout.angle_increment;
  s.config.field_of_view = n > 0 ? layout.angle_increment * static_cast<double>(n - 1) : 0.0;
  return s;
}

CarmenScan parse_config_laser(std::span<const std::string_view> tokens, LaserMessage message) {
  const bool robot = message == LaserMessage::kRobotLaser1;
  FieldCursor c(tokens, 1);
  CarmenScan s;
  s.message = message;
  s.has_poses = robot;
  s.config.laser_type = c.integer("laser_type");
  s.scan.angle_min = c.finite("start_angle");
  s.config.field_of_view = c.finite("field_of_view");
  s.scan.angle_increment = c.finite("angular_resolution");
  s.scan.range_max = c.finite("maximum_range");
  if (!(s.scan.range_max > 0.0)) throw FieldError{"maximum_range", "must be > 0"};
  s.config.accuracy = c.finite("accuracy");
  s.config.remission_mode = c.integer("remission_mode");
  const std::size_t n = c.count("num_readings", kMaxReadings);

  // Two counted arrays: find num_remissions where the declared reading count puts it.
  const std::size_t tail = robot ? 6 + 5 + 3 : 3;
  const std::size_t m_pos = 9 + n;
  if (tail_intact(tokens)) {
    const auto m = m_pos < tokens.size() ? parse_integer(tokens[m_pos]) : std::nullopt;
    if (!m || *m < 0) {
      throw FieldError{"num_readings",
                       "declares " + std::to_string(n) +
                           " readings but the field after them is not a remission count"};
    }
    check_count(tokens, 10 + n + static_cast<std::size_t>(*m) + tail, "num_remissions",
                static_cast<std::size_t>(*m), "remissions");
  }
  read_ranges(c, n, s.scan.ranges);
  check_field_of_view(s.config.field_of_view, s.scan.angle_increment, n);
  const std::size_t m = c.count("num_remissions", kMaxReadings);
  s.remissions.resize(m);
  for (std::size_t j = 0; j < m; ++j)
    s.remissions[j] = static_cast<float>(c.number("remission", j));
  if (robot) {
    s.laser_pose = read_pose(c, "laser_pose_x", "laser_pose_y", "laser_pose_theta");
    s.odom_pose =
        read_pose(c, "robot_pose_x", "robot_pose_y", "robot_pose_theta", &s.logged_odom_theta);
    s.extras.tv = c.finite("laser_tv");
    s.extras.rv = c.finite("laser_rv");
    s.extras.forward_safety_dist = c.finite("forward_safety_dist");
    s.extras.side_safety_dist = c.finite("side_safety_dist");
    s.extras.turn_axis = c.finite("turn_axis");
    // CARMEN logs both poses in the same odometry frame, so their difference is the mounting.
    s.scan.sensor_pose = s.odom_pose.between(s.laser_pose);
  }
  read_tail(c, s.stamp, s);
  return s;
}

}  // namespace pgmcl::io::detail
