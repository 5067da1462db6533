#include "pgmcl/io/carmen_writer.hpp"

#include <algorithm>
#include <stdexcept>
#include <tuple>
#include <vector>

#include "fields.hpp"

namespace pgmcl::io {
namespace {

using detail::append_fixed;
using detail::append_number;

void check_word(std::string_view what, std::string_view word) {
  if (word.empty() || word.find_first_of(" \t\r\n") != std::string_view::npos) {
    throw std::invalid_argument("CARMEN " + std::string(what) + " '" + std::string(word) +
                                "' must be one non-empty word");
  }
}

void put(std::string& out, double v) {
  out += ' ';
  append_number(out, v);
}

void put_pose(std::string& out, const Pose2& p) {
  put(out, p.x);
  put(out, p.y);
  put(out, p.theta);
}

void put_tail(std::string& out, double stamp, const std::string& host, double logger_stamp) {
  check_word("host name", host);
  out += ' ';
  append_fixed(out, stamp);
  out += ' ';
  out += host;
  out += ' ';
  append_fixed(out, logger_stamp);
}

void put_array(std::string& out, const std::vector<float>& v) {
  out += ' ';
  out += std::to_string(v.size());
  for (const float x : v) {
    out += ' ';
    append_number(out, x);
  }
}

}  // namespace

std::string format_param(std::string_view name, std::string_view value) {
  check_word("PARAM name", name);
  check_word("PARAM value", value);
  // The "nohost 0" tail is what the benchmark logs use; readers ignore it.
  return "PARAM " + std::string(name) + ' ' + std::string(value) + " nohost 0";
}

std::string format_odom(const OdomRecord& r) {
  std::string out = "ODOM";
  put_pose(out, r.pose);
  put(out, r.tv);
  put(out, r.rv);
  put(out, r.accel);
  put_tail(out, r.stamp, r.host, r.logger_stamp);
  return out;
}

std::string format_truepos(const TruePosRecord& r) {
  std::string out = "TRUEPOS";
  put_pose(out, r.true_pose);
  put_pose(out, r.odom_pose);
  put_tail(out, r.stamp, r.host, r.logger_stamp);
  return out;
}

std::string format_scan(const CarmenScan& s) {
  std::string out(message_name(s.message));
  out.reserve(16 + 8 * s.scan.size());
  const LaserScan& sc = s.scan;
  if (s.message == LaserMessage::kFlaser || s.message == LaserMessage::kRlaser) {
    if (!matches_sick_layout(sc)) {
      throw std::invalid_argument(
          std::string(message_name(s.message)) + " cannot hold a " + std::to_string(sc.size()) +
          "-beam scan with these angles (not the SICK layout); write it as ROBOTLASER1");
    }
    put_array(out, sc.ranges);
    put_pose(out, s.laser_pose);
    put_pose(out, s.odom_pose);
  } else {
    out += ' ';
    out += std::to_string(s.config.laser_type);
    put(out, sc.angle_min);
    put(out, s.config.field_of_view);
    put(out, sc.angle_increment);
    put(out, sc.range_max);
    put(out, s.config.accuracy);
    out += ' ';
    out += std::to_string(s.config.remission_mode);
    put_array(out, sc.ranges);
    put_array(out, s.remissions);
    if (s.message == LaserMessage::kRobotLaser1) {
      put_pose(out, s.laser_pose);
      put_pose(out, s.odom_pose);
      put(out, s.extras.tv);
      put(out, s.extras.rv);
      put(out, s.extras.forward_safety_dist);
      put(out, s.extras.side_safety_dist);
      put(out, s.extras.turn_axis);
    }
  }
  put_tail(out, s.stamp, s.host, s.logger_stamp);
  return out;
}

CarmenScan make_scan_record(const LaserScan& scan, double stamp, const Pose2& odom_pose,
                            std::string host) {
  CarmenScan s;
  s.stamp = stamp;
  const bool flaser =
      matches_sick_layout(scan) && scan.sensor_pose.y == 0.0 && scan.sensor_pose.theta == 0.0;
  s.message = flaser ? LaserMessage::kFlaser : LaserMessage::kRobotLaser1;
  s.scan = scan;
  s.config.field_of_view =
      scan.size() > 0 ? scan.angle_increment * static_cast<double>(scan.size() - 1) : 0.0;
  s.has_poses = true;
  s.odom_pose = odom_pose;
  s.laser_pose = odom_pose.compose(scan.sensor_pose);
  s.host = std::move(host);
  s.logger_stamp = stamp;
  return s;
}

void set_front_laser_params(std::map<std::string, std::string>& params, const LaserScan& scan) {
  std::string v;
  append_number(v, scan.range_max);
  params["robot_front_laser_max"] = v;
  v.clear();
  append_number(v, scan.sensor_pose.x);
  params["robot_frontlaser_offset"] = v;
}

CarmenWriter::CarmenWriter(std::string path) : out_(std::move(path)) {
  out_.write_line("# CARMEN log written by pgmcl");
  out_.write_line("# message formats: PARAM ODOM FLASER RLASER ROBOTLASER1 RAWLASER1-4 TRUEPOS");
}

void CarmenWriter::comment(std::string_view text) {
  out_.write_line("# " + std::string(text));
}

void write_carmen(const std::string& path, const CarmenLog& log) {
  CarmenWriter w(path);
  for (const auto& [name, value] : log.params) w.param(name, value);

  // (kind, index) with a sort key; kind order gives the tie-break at equal stamps.
  struct Item {
    double key;
    int kind;  // 0 ODOM, 1 TRUEPOS, 2 laser
    std::size_t index;
  };
  std::vector<Item> items;
  items.reserve(log.odometry.size() + log.truepos.size() + log.scans.size());
  bool all_lines = true;
  for (const auto& r : log.odometry) all_lines = all_lines && r.line != 0;
  for (const auto& r : log.truepos) all_lines = all_lines && r.line != 0;
  for (const auto& r : log.scans) all_lines = all_lines && r.line != 0;
  auto key = [&](double stamp, std::size_t line) {
    return all_lines ? static_cast<double>(line) : stamp;
  };
  for (std::size_t i = 0; i < log.odometry.size(); ++i) {
    items.push_back({key(log.odometry[i].stamp, log.odometry[i].line), 0, i});
  }
  for (std::size_t i = 0; i < log.truepos.size(); ++i) {
    items.push_back({key(log.truepos[i].stamp, log.truepos[i].line), 1, i});
  }
  for (std::size_t i = 0; i < log.scans.size(); ++i) {
    items.push_back({key(log.scans[i].stamp, log.scans[i].line), 2, i});
  }
  std::stable_sort(items.begin(), items.end(), [](const Item& a, const Item& b) {
    return std::tie(a.key, a.kind) < std::tie(b.key, b.kind);
  });
  for (const Item& it : items) {
    if (it.kind == 0) w.odom(log.odometry[it.index]);
    if (it.kind == 1) w.truepos(log.truepos[it.index]);
    if (it.kind == 2) w.scan(log.scans[it.index]);
  }
  w.close();
}

}  // namespace pgmcl::io
