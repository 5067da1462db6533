#include "pgmcl/io/odometry_pairing.hpp"

#include <algorithm>
#include <map>
#include <utility>

namespace pgmcl::io {
namespace {

/// The kept ODOM messages (monotonic_odometry) with their file lines.
Trajectory kept_odometry(const CarmenLog& log, std::vector<std::size_t>* lines,
                         std::size_t* dropped) {
  Trajectory t;
  t.reserve(log.odometry.size());
  std::size_t n_dropped = 0;
  for (const OdomRecord& r : log.odometry) {
    if (!t.empty() && r.stamp < t.back().stamp) {
      ++n_dropped;
      continue;
    }
    t.push_back({r.stamp, r.pose});
    if (lines != nullptr) lines->push_back(r.line);
  }
  if (dropped != nullptr) *dropped = n_dropped;
  return t;
}

}  // namespace

Trajectory monotonic_odometry(const CarmenLog& log, std::size_t* dropped) {
  return kept_odometry(log, nullptr, dropped);
}

PairedScans pair_odometry(const CarmenLog& log, const PairingOptions& opt) {
  PairedScans out;
  std::vector<std::size_t> lines;
  const Trajectory odom = kept_odometry(log, &lines, &out.report.odom_dropped);
  out.report.odom_used = odom.size();
  std::map<std::pair<LaserMessage, double>, std::size_t> scans_at;
  for (const CarmenScan& s : log.scans) ++scans_at[{s.message, s.stamp}];
  const auto stamp_less = [](const StampedPose& p, double t) { return p.stamp < t; };
  out.scans.reserve(log.scans.size());
  for (std::size_t i = 0; i < log.scans.size(); ++i) {
    const CarmenScan& s = log.scans[i];
    PairedScan p;
    p.scan_index = i;
    const auto first = std::lower_bound(odom.begin(), odom.end(), s.stamp, stamp_less);
    std::size_t odom_at = 0;
    for (auto it = first; it != odom.end() && it->stamp == s.stamp; ++it) ++odom_at;
    const bool shared = odom_at >= 2 || scans_at[{s.message, s.stamp}] >= 2;
    // The last kept ODOM line before the scan's (lines are in file order).
    const auto before = std::lower_bound(lines.begin(), lines.end(), s.line);
    if (shared && s.line > 0 && before != lines.begin()) {
      const auto k = static_cast<std::size_t>(before - lines.begin()) - 1;
      if (odom[k].stamp <= s.stamp && s.stamp - odom[k].stamp <= opt.max_gap) {
        p.odom = odom[k].pose;
        p.source = OdomSource::kInterpolated;
        ++out.report.interpolated;
        if (out.report.shared_stamps++ == 0) out.report.first_shared_line = s.line;
        out.scans.push_back(p);
        continue;
      }
    }
    if (const auto pose = interpolate_at(odom, s.stamp, opt.max_gap)) {
      p.odom = *pose;
      p.source = OdomSource::kInterpolated;
      ++out.report.interpolated;
    } else if (s.has_poses) {
      p.odom = s.odom_pose;
      p.source = OdomSource::kScanFields;
      ++out.report.scan_fields;
    } else {
      ++out.report.unpaired;
    }
    out.scans.push_back(p);
  }
  return out;
}

}  // namespace pgmcl::io
