#include <cmath>
#include <numbers>
#include <sstream>

#include "carmen_messages.hpp"
#include "pgmcl/io/carmen.hpp"
#include "pgmcl/io/values.hpp"

namespace pgmcl::io {

std::string_view message_name(LaserMessage m) noexcept {
  return name_of(m, detail::kLaserMessageNames, "FLASER");
}

BeamLayout sick_beam_layout(std::size_t n) noexcept {
  // data/README.md: the convention was checked against the benchmark logs (maps built from
  // half a log fit the other half best with it).
  BeamLayout l;
  l.angle_min = -std::numbers::pi / 2.0;
  if (n <= 1) return l;
  const double span_steps = (n % 2 == 0) ? static_cast<double>(n) : static_cast<double>(n - 1);
  l.angle_increment = std::numbers::pi / span_steps;
  return l;
}

bool matches_sick_layout(const LaserScan& scan) noexcept {
  const BeamLayout l = sick_beam_layout(scan.size());
  constexpr double kTol = 1e-9;  // radians
  return std::abs(scan.angle_min - l.angle_min) <= kTol &&
         (scan.size() <= 1 || std::abs(scan.angle_increment - l.angle_increment) <= kTol);
}

Trajectory scan_truth(const CarmenLog& log, LaserMessage which) {
  Trajectory t;
  for (const CarmenScan& s : log.scans) {
    if (s.message != which || !s.has_poses) continue;
    t.push_back({s.stamp, s.laser_pose.compose(s.scan.sensor_pose.inverse())});
  }
  return t;
}

bool is_carmen_path(const std::string& path) {
  std::string p = path;
  if (p.size() > 3 && p.compare(p.size() - 3, 3, ".gz") == 0) p.resize(p.size() - 3);
  auto ends = [&p](const char* ext) {
    const std::string e(ext);
    return p.size() > e.size() && p.compare(p.size() - e.size(), e.size(), e) == 0;
  };
  return ends(".log") || ends(".clf");
}

Trajectory log_truth(const CarmenLog& log, const std::string& source) {
  for (const CarmenScan& s : log.scans) {
    if (s.has_poses) return scan_truth(log, s.message);
  }
  throw UsageError(source + ": no laser scans with poses to take as ground truth");
}

Trajectory truepos_trajectory(const CarmenLog& log) {
  Trajectory t;
  t.reserve(log.truepos.size());
  for (const TruePosRecord& r : log.truepos) t.push_back({r.stamp, r.true_pose});
  return t;
}

Trajectory odometry_trajectory(const CarmenLog& log) {
  Trajectory t;
  t.reserve(log.odometry.size());
  for (const OdomRecord& r : log.odometry) t.push_back({r.stamp, r.pose});
  return t;
}

std::string ParseReport::summary(std::size_t max_listed) const {
  std::ostringstream o;
  o << source << ": " << lines << " lines;";
  for (const auto& [type, n] : records) o << ' ' << type << ' ' << n;
  if (!skipped.empty()) {
    o << "; skipped";
    for (const auto& [type, n] : skipped) o << ' ' << type << ' ' << n;
  }
  o << "; malformed " << malformed << "; backwards timestamps " << backwards;
  if (!backwards_by_type.empty()) {
    o << " (";
    bool first = true;
    for (const auto& [type, n] : backwards_by_type) {
      o << (first ? "" : ", ") << type << ' ' << n;
      first = false;
    }
    o << ')';
  }
  o << "; invalid beams " << invalid_beams << '\n';
  auto list = [&](const std::vector<LineIssue>& issues, std::size_t total, const char* what) {
    for (std::size_t i = 0; i < issues.size() && i < max_listed; ++i) {
      const LineIssue& is = issues[i];
      o << "  " << source << ':' << is.line << ": " << is.message_type << ' ' << is.field << ": "
        << is.message << '\n';
    }
    if (total > max_listed) o << "  ... " << (total - max_listed) << " more " << what << '\n';
  };
  list(malformed_lines, malformed, "malformed lines");
  list(backwards_lines, backwards, "backwards timestamps");
  return o.str();
}

}  // namespace pgmcl::io
