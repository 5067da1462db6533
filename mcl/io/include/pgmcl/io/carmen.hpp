#pragma once
/// CARMEN log files (Radish / Freiburg SLAM benchmark), plain or gzip: records and reader.
///
/// One message per line, fields separated by spaces; every message ends with
/// `ipc_timestamp ipc_hostname logger_timestamp`. Supported messages (field layouts as written
/// by the CARMEN logger, carmen/src/logtools/writelog.c):
///   PARAM name value ...
///   ODOM x y theta tv rv accel ts host logger_ts
///   FLASER|RLASER n range[n] x y theta odom_x odom_y odom_theta ts host logger_ts
///   ROBOTLASER1 laser_type start_angle field_of_view angular_resolution maximum_range accuracy
///     remission_mode n range[n] m remission[m] laser_pose_x laser_pose_y laser_pose_theta
///     robot_pose_x robot_pose_y robot_pose_theta laser_tv laser_rv forward_safety_dist
///     side_safety_dist turn_axis ts host logger_ts
///   RAWLASER1..4 laser_type start_angle field_of_view angular_resolution maximum_range accuracy
///     remission_mode n range[n] m remission[m] ts host logger_ts
///   TRUEPOS true_x true_y true_theta odom_x odom_y odom_theta ts host logger_ts
/// Other message types (NEFF, SYNC, ...) are skipped and counted by type; `#` lines are comments.
///
/// FLASER/RLASER carry no angles: they follow the SICK LMS convention (first beam at -90 deg,
/// step 180/n deg for even n, 180/(n-1) deg for odd n), checked against the benchmark data.
/// The `*-corrected` benchmark logs store the corrected pose in FLASER `x y theta`; that pose
/// is their ground truth (see scan_truth()).

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pgmcl/common/laser_scan.hpp"
#include "pgmcl/common/se2.hpp"
#include "pgmcl/io/line_io.hpp"
#include "pgmcl/io/trajectory.hpp"

namespace pgmcl::io {

/// Which CARMEN message a scan came from (and will be written as).
enum class LaserMessage {
  kFlaser,
  kRlaser,
  kRobotLaser1,
  kRawLaser1,
  kRawLaser2,
  kRawLaser3,
  kRawLaser4
};

/// "FLASER", "ROBOTLASER1", ...
[[nodiscard]] std::string_view message_name(LaserMessage m) noexcept;

/// Beam layout of the SICK convention for an n-beam FLASER/RLASER scan.
struct BeamLayout {
  double angle_min = 0.0;        ///< radians
  double angle_increment = 0.0;  ///< radians
};
/// First beam -pi/2; step pi/n for even n, pi/(n-1) for odd n (0 for n <= 1).
[[nodiscard]] BeamLayout sick_beam_layout(std::size_t n) noexcept;
/// True if the scan's angles are the SICK layout for its beam count (within 1e-9 rad), i.e.
/// a FLASER line reproduces them.
[[nodiscard]] bool matches_sick_layout(const LaserScan& scan) noexcept;

/// The scanner configuration block of ROBOTLASER1 / RAWLASERn (carmen_laser_laser_config_t).
/// For FLASER/RLASER it is derived: start -pi/2, the SICK step, fov = step * (n - 1).
struct LaserConfig {
  int laser_type = 0;          ///< CARMEN laser type code, kept as logged
  double field_of_view = 0.0;  ///< radians (start angle and resolution live in the scan)
  double accuracy = 0.0;       ///< metres, as logged
  int remission_mode = 0;      ///< CARMEN remission mode code, kept as logged
};

/// ROBOTLASER1 motion/safety fields, kept so a log can be rewritten unchanged.
struct RobotLaserExtras {
  double tv = 0.0;                   ///< m/s
  double rv = 0.0;                   ///< rad/s
  double forward_safety_dist = 0.0;  ///< metres
  double side_safety_dist = 0.0;     ///< metres
  double turn_axis = 0.0;            ///< as logged
};

/// One laser message, stamped with its ipc timestamp; scan.angle_min / angle_increment /
/// range_max come from the SICK convention (FLASER/RLASER) or from the logged config
/// (ROBOTLASER1/RAWLASERn: start_angle, angular_resolution, maximum_range).
struct CarmenScan {
  LaserMessage message = LaserMessage::kFlaser;
  LaserScan scan;
  double stamp = 0.0;  ///< seconds (ipc timestamp)
  LaserConfig config;
  std::vector<float> remissions;  ///< ROBOTLASER1/RAWLASERn only
  bool has_poses = true;          ///< false for RAWLASERn, which log no pose
  /// FLASER `x y theta` / ROBOTLASER1 `laser_pose_*`: the laser's pose in the log frame. In
  /// the `*-corrected` logs this is the corrected (ground-truth) pose.
  Pose2 laser_pose{};
  /// FLASER `odom_*` / ROBOTLASER1 `robot_pose_*`: the robot's odometry pose.
  Pose2 odom_pose{};
  /// radians, odom_pose.theta as logged, before wrapping (a glitch of 1e6 rad wraps to any
  /// angle); 0 if not read from a file
  double logged_odom_theta = 0.0;
  RobotLaserExtras extras;  ///< ROBOTLASER1 only
  std::string host = "pgmcl";
  double logger_stamp = 0.0;  ///< seconds
  std::size_t line = 0;       ///< source line, 0 if not read from a file
};

struct OdomRecord {
  Pose2 pose{};
  double tv = 0.0;     ///< m/s
  double rv = 0.0;     ///< rad/s
  double accel = 0.0;  ///< m/s^2
  double stamp = 0.0;  ///< seconds (ipc timestamp)
  std::string host = "pgmcl";
  double logger_stamp = 0.0;
  std::size_t line = 0;
  double logged_theta = 0.0;  ///< radians, pose.theta before wrapping; 0 if not from a file
};

struct TruePosRecord {
  Pose2 true_pose{};
  Pose2 odom_pose{};
  double stamp = 0.0;  ///< seconds (ipc timestamp)
  std::string host = "pgmcl";
  double logger_stamp = 0.0;
  std::size_t line = 0;
};

/// A problem on one line. `field` is the CARMEN field name ("range[17]", "num_readings",
/// "timestamp"), or "message" when the message type itself is the problem.
struct LineIssue {
  std::size_t line = 0;
  std::string message_type;
  std::string field;
  std::string message;
};

/// What the reader saw. Counts are exact; issue details are kept up to a cap.
struct ParseReport {
  std::string source;
  std::size_t lines = 0;                       ///< lines read
  std::map<std::string, std::size_t> records;  ///< parsed messages by type (PARAM included)
  std::map<std::string, std::size_t> skipped;  ///< unknown message types by name
  std::size_t malformed = 0;                   ///< lines dropped as malformed
  std::vector<LineIssue> malformed_lines;      ///< first max_issues of them
  std::size_t backwards = 0;                   ///< timestamps earlier than the previous
                                               ///< message of the same type (record kept)
  std::map<std::string, std::size_t> backwards_by_type;
  std::vector<LineIssue> backwards_lines;  ///< first max_issues of them
  /// FLASER mounting derived from the logged laser and odometry poses (no PARAM
  /// robot_frontlaser_offset, but the same offset on every scan); see CarmenReadOptions.
  std::optional<Pose2> derived_front_mount;
  std::size_t invalid_beams = 0;  ///< NaN, Inf or negative ranges (beam kept,
                                  ///< the filter skips it)

  /// Multi-line human-readable summary (counts, first issues).
  [[nodiscard]] std::string summary(std::size_t max_listed = 10) const;
};

/// A whole log. Records of each kind are in file order.
struct CarmenLog {
  std::map<std::string, std::string> params;  ///< PARAM name -> value (last one wins)
  std::vector<OdomRecord> odometry;
  std::vector<CarmenScan> scans;  ///< all laser messages, in file order
  std::vector<TruePosRecord> truepos;
  ParseReport report;
};

struct CarmenReadOptions {
  /// Any malformed line or backwards timestamp throws FormatError ("file:line: field: ...").
  bool strict = false;
  /// Metres. Range that means "no return" for FLASER (front) / RLASER (rear) scans, which do
  /// not log it. <= 0: PARAM robot_front_laser_max / robot_rear_laser_max if present, else the
  /// largest reading of that message type in the log (81.83 m in intel, 50 m in aces).
  double front_range_max = 0.0;
  double rear_range_max = 0.0;
  double range_min = 0.1;  ///< metres, copied into every LaserScan
  /// Mounting of the FLASER/RLASER laser on the robot. Unless overridden, CARMEN's PARAMs
  /// robot_frontlaser_offset (front: {offset, 0, 0}) and robot_rearlaser_offset (rear:
  /// {-offset, 0, pi}) are used; without the front PARAM, the offset of the FLASER laser
  /// poses from their odometry poses when it is constant (ParseReport::derived_front_mount).
  /// ROBOTLASER1 derives it per scan: robot_pose^-1 * laser_pose.
  bool override_sensor_pose = false;
  Pose2 sensor_pose{};
  std::size_t max_issues = 1000;  ///< issue details kept per category
  /// Bytes the records may take in memory; a larger log is a FormatError at the line that
  /// crosses it (a gzip bomb of valid lines, or a log to split), strict or not.
  std::size_t max_bytes = kMaxRecordBytes;
};

/// Reads a CARMEN log (plain or .gz). Throws IoError if unreadable; FormatError in strict mode.
[[nodiscard]] CarmenLog read_carmen(const std::string& path, const CarmenReadOptions& opt = {});
/// Same, from text in memory; `source` names it in messages.
[[nodiscard]] CarmenLog parse_carmen(std::string_view text, const std::string& source,
                                     const CarmenReadOptions& opt = {});

/// Robot poses from the scans' logged laser poses: laser_pose * sensor_pose^-1 (equal to
/// laser_pose for a zero mounting offset). For the `*-corrected` logs this is the ground
/// truth. Scans without poses (RAWLASERn) are left out; only messages of type `which`.
[[nodiscard]] Trajectory scan_truth(const CarmenLog& log,
                                    LaserMessage which = LaserMessage::kFlaser);
/// True for CARMEN log names: *.log, *.clf, optionally followed by .gz.
[[nodiscard]] bool is_carmen_path(const std::string& path);

/// Ground truth of a corrected log: scan_truth of the first laser message type in the log
/// that logs poses. Throws UsageError naming `source` when no scan has poses.
[[nodiscard]] Trajectory log_truth(const CarmenLog& log, const std::string& source);
/// TRUEPOS true poses.
[[nodiscard]] Trajectory truepos_trajectory(const CarmenLog& log);
/// ODOM poses in file order.
[[nodiscard]] Trajectory odometry_trajectory(const CarmenLog& log);

}  // namespace pgmcl::io
