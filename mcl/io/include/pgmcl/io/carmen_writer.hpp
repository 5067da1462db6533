#pragma once
/// Writing CARMEN logs (plain, or gzip when the path ends in ".gz"). Numbers are written in
/// their shortest exact form, so read_carmen(write_carmen(log)) gives back the same values.

#include <string>
#include <string_view>

#include "pgmcl/io/carmen.hpp"
#include "pgmcl/io/line_io.hpp"

namespace pgmcl::io {

/// One line per record, without the newline. Throw std::invalid_argument for what the format
/// cannot hold: a host name or PARAM with spaces, or a FLASER/RLASER scan whose angles are not
/// the SICK layout for its beam count (write it as ROBOTLASER1).
[[nodiscard]] std::string format_param(std::string_view name, std::string_view value);
[[nodiscard]] std::string format_odom(const OdomRecord& r);
[[nodiscard]] std::string format_truepos(const TruePosRecord& r);
/// Written as scan.message says.
[[nodiscard]] std::string format_scan(const CarmenScan& s);

/// Builds a record for an engine/simulator scan taken at robot (odometry) pose `odom_pose`:
/// FLASER when FLASER reproduces the scan (SICK angles, laser mounted facing forward on the
/// robot's x axis), else ROBOTLASER1, which logs start angle, resolution, maximum range and
/// the laser pose. laser_pose = odom_pose * scan.sensor_pose; both stamps are `stamp`.
/// For FLASER, also put set_front_laser_params() into the log's params so the reader restores
/// range_max and the mounting offset.
[[nodiscard]] CarmenScan make_scan_record(const LaserScan& scan, double stamp,
                                          const Pose2& odom_pose, std::string host = "pgmcl");
/// PARAM robot_front_laser_max = scan.range_max, robot_frontlaser_offset = scan.sensor_pose.x.
void set_front_laser_params(std::map<std::string, std::string>& params, const LaserScan& scan);

/// Streams records to a file in the order they are written.
class CarmenWriter {
 public:
  /// Writes a short header comment. Throws IoError if the file cannot be created.
  explicit CarmenWriter(std::string path);

  void comment(std::string_view text);  ///< "# text"
  void param(std::string_view name, std::string_view value) {
    out_.write_line(format_param(name, value));
  }
  void odom(const OdomRecord& r) { out_.write_line(format_odom(r)); }
  void truepos(const TruePosRecord& r) { out_.write_line(format_truepos(r)); }
  void scan(const CarmenScan& s) { out_.write_line(format_scan(s)); }
  /// Flushes and closes; throws IoError on failure.
  void close() { out_.close(); }

 private:
  LineWriter out_;
};

/// Writes a whole log: params (sorted by name), then ODOM, TRUEPOS and laser records merged.
/// If every record carries a source line number (a log that was read from a file) they keep
/// the file order; otherwise they are ordered by timestamp (stable; at equal stamps ODOM, then
/// TRUEPOS, then lasers), which is what a simulator's in-memory log needs.
void write_carmen(const std::string& path, const CarmenLog& log);

}  // namespace pgmcl::io
