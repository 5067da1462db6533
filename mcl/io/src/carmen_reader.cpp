#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <utility>

#include "carmen_messages.hpp"
#include "fields.hpp"
#include "pgmcl/io/carmen.hpp"
#include "pgmcl/io/errors.hpp"
#include "pgmcl/io/line_io.hpp"

namespace pgmcl::io {
namespace {

/// SICK LMS maximum reading; used only when a log has no readings to infer it from.
constexpr double kDefaultSickRangeMax = 81.91;  ///< metres

/// Consumes lines one at a time, so files and in-memory text share one code path.
class CarmenParser {
 public:
  CarmenParser(std::string source, const CarmenReadOptions& opt) : opt_(opt) {
    log_.report.source = std::move(source);
  }

  void feed(std::string_view line, std::size_t line_no) {
    ++log_.report.lines;
    detail::split_fields(line, tokens_);
    if (tokens_.empty() || tokens_.front().front() == '#') return;
    const std::string_view type = tokens_.front();
    try {
      if (type == "PARAM") {
        auto [name, value] = detail::parse_param(tokens_);
        log_.params[std::move(name)] = std::move(value);
        count(type);
      } else if (type == "ODOM") {
        OdomRecord r = detail::parse_odom(tokens_);
        r.line = line_no;
        check_time(type, r.stamp, line_no);
        add_bytes(sizeof(OdomRecord), line_no);
        log_.odometry.push_back(std::move(r));
        count(type);
      } else if (type == "TRUEPOS") {
        TruePosRecord r = detail::parse_truepos(tokens_);
        r.line = line_no;
        check_time(type, r.stamp, line_no);
        add_bytes(sizeof(TruePosRecord), line_no);
        log_.truepos.push_back(std::move(r));
        count(type);
      } else if (const auto msg = value_of(type, detail::kLaserMessageNames)) {
        CarmenScan s = (*msg == LaserMessage::kFlaser || *msg == LaserMessage::kRlaser)
                           ? detail::parse_flaser(tokens_, *msg)
                           : detail::parse_config_laser(tokens_, *msg);
        s.line = line_no;
        for (const float r : s.scan.ranges) {
          if (!std::isfinite(r) || r < 0.0f) ++log_.report.invalid_beams;
        }
        check_time(type, s.stamp, line_no);
        add_bytes(sizeof(CarmenScan) + (s.scan.ranges.size() + s.remissions.size()) * sizeof(float),
                  line_no);
        log_.scans.push_back(std::move(s));
        count(type);
      } else {
        ++log_.report.skipped[std::string(type)];
      }
    } catch (detail::FieldError& e) {
      ++log_.report.malformed;
      if (opt_.strict) throw FormatError(log_.report.source, line_no, e.field, e.message);
      keep(log_.report.malformed_lines,
           LineIssue{line_no, std::string(type), std::move(e.field), std::move(e.message)});
    }
  }

  CarmenLog finish() {
    const double front_max =
        range_max(LaserMessage::kFlaser, opt_.front_range_max, "robot_front_laser_max");
    const double rear_max =
        range_max(LaserMessage::kRlaser, opt_.rear_range_max, "robot_rear_laser_max");
    const std::optional<double> front_param = param_number("robot_frontlaser_offset");
    const double rear_offset = param_number("robot_rearlaser_offset").value_or(0.0);
    Pose2 front_mount{front_param.value_or(0.0), 0.0, 0.0};
    if (!front_param) {
      if (const auto derived = constant_front_mount()) {
        front_mount = *derived;
        log_.report.derived_front_mount = derived;
      }
    }
    for (CarmenScan& s : log_.scans) {
      s.scan.range_min = opt_.range_min;
      if (s.message == LaserMessage::kFlaser) {
        s.scan.range_max = front_max;
        s.scan.sensor_pose = front_mount;
      } else if (s.message == LaserMessage::kRlaser) {
        s.scan.range_max = rear_max;
        s.scan.sensor_pose = {-rear_offset, 0.0, std::numbers::pi};
      }
      if (opt_.override_sensor_pose) s.scan.sensor_pose = opt_.sensor_pose;
    }
    return std::move(log_);
  }

 private:
  /// Without PARAM robot_frontlaser_offset, the mounting a log's FLASER poses imply: the
  /// laser pose seen from the odometry pose, when it is the same (within 1 mm and 0.1 deg)
  /// on every scan and at least 1 cm from the base. CARMEN writes laser = odometry ∘ mount;
  /// the SLAM-corrected logs, whose odometry fields are re-anchored, never pass this.
  [[nodiscard]] std::optional<Pose2> constant_front_mount() const {
    std::optional<Pose2> mount;
    std::size_t n = 0;
    for (const CarmenScan& s : log_.scans) {
      if (s.message != LaserMessage::kFlaser) continue;
      const Pose2 m = s.odom_pose.between(s.laser_pose);
      if (!mount) mount = m;
      if (std::hypot(m.x - mount->x, m.y - mount->y) > 1e-3 ||
          std::abs(wrap_angle(m.theta - mount->theta)) > 0.1 * std::numbers::pi / 180.0)
        return std::nullopt;
      ++n;
    }
    if (n < 2 || std::hypot(mount->x, mount->y) < 0.01) return std::nullopt;
    return mount;
  }

  void count(std::string_view type) { ++log_.report.records[std::string(type)]; }

  void add_bytes(std::size_t n, std::size_t line_no) {
    bytes_ += n;
    if (bytes_ <= opt_.max_bytes) return;
    throw FormatError(log_.report.source, line_no, "log",
                      "its records take more than " + std::to_string(opt_.max_bytes >> 20) +
                          " MiB of memory by this line (" + std::to_string(log_.scans.size()) +
                          " scans, " + std::to_string(log_.odometry.size()) +
                          " ODOM); split the log");
  }

  void keep(std::vector<LineIssue>& list, LineIssue issue) const {
    if (list.size() < opt_.max_issues) list.push_back(std::move(issue));
  }

  void check_time(std::string_view type, double stamp, std::size_t line_no) {
    auto it = last_.find(type);
    if (it == last_.end()) {
      last_.emplace(std::string(type), std::pair{stamp, line_no});
      return;
    }
    const auto [prev, prev_line] = it->second;
    it->second = {stamp, line_no};
    if (stamp >= prev) return;
    std::string msg = "goes backwards: ";
    detail::append_number(msg, stamp);
    msg += " after ";
    detail::append_number(msg, prev);
    msg += " (previous " + std::string(type) + " on line " + std::to_string(prev_line) + ")";
    ++log_.report.backwards;
    ++log_.report.backwards_by_type[std::string(type)];
    if (opt_.strict) throw FormatError(log_.report.source, line_no, "timestamp", msg);
    keep(log_.report.backwards_lines,
         LineIssue{line_no, std::string(type), "timestamp", std::move(msg)});
  }

  std::optional<double> param_number(const std::string& name) const {
    const auto it = log_.params.find(name);
    if (it == log_.params.end()) return std::nullopt;
    const auto v = detail::parse_double(it->second);
    if (!v || !std::isfinite(*v)) return std::nullopt;
    return v;
  }

  double range_max(LaserMessage which, double option, const std::string& param) const {
    if (option > 0.0) return option;
    if (const auto p = param_number(param); p && *p > 0.0) return *p;
    float largest = 0.0f;
    for (const CarmenScan& s : log_.scans) {
      if (s.message != which) continue;
      for (const float r : s.scan.ranges) {
        if (std::isfinite(r)) largest = std::max(largest, r);
      }
    }
    return largest > 0.0f ? static_cast<double>(largest) : kDefaultSickRangeMax;
  }

  const CarmenReadOptions& opt_;
  CarmenLog log_;
  std::vector<std::string_view> tokens_;
  std::size_t bytes_ = 0;
  std::map<std::string, std::pair<double, std::size_t>, std::less<>> last_;
};

}  // namespace

CarmenLog read_carmen(const std::string& path, const CarmenReadOptions& opt) {
  CarmenParser parser(path, opt);
  detail::for_each_file_line(path,
                             [&](std::string_view line, std::size_t n) { parser.feed(line, n); });
  return parser.finish();
}

CarmenLog parse_carmen(std::string_view text, const std::string& source,
                       const CarmenReadOptions& opt) {
  CarmenParser parser(source, opt);
  detail::for_each_text_line(text,
                             [&](std::string_view line, std::size_t n) { parser.feed(line, n); });
  return parser.finish();
}

}  // namespace pgmcl::io
