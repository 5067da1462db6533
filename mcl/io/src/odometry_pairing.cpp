#include "pgmcl/io/odometry_pairing.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
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
  for (std::size_t k = 1; k < odom.size(); ++k) {
    if (odom[k].stamp != odom[k - 1].stamp) continue;
    if (out.report.odom_repeated_stamps++ == 0) out.report.first_repeated_odom_line = lines[k];
  }
  std::map<std::pair<LaserMessage, double>, std::size_t> scans_at;
  for (const CarmenScan& s : log.scans) ++scans_at[{s.message, s.stamp}];
  const auto stamp_less = [](const StampedPose& p, double t) { return p.stamp < t; };
  for (const CarmenScan& s : log.scans) {
    const auto first = std::lower_bound(odom.begin(), odom.end(), s.stamp, stamp_less);
    const bool two_odom = first != odom.end() && first->stamp == s.stamp &&
                          std::next(first) != odom.end() && std::next(first)->stamp == s.stamp;
    if (two_odom || scans_at[{s.message, s.stamp}] >= 2) {
      if (out.report.shared_stamps++ == 0) out.report.first_shared_line = s.line;
    }
  }
  const bool file_order = out.report.shared_stamps > 0;
  out.scans.reserve(log.scans.size());
  for (std::size_t i = 0; i < log.scans.size(); ++i) {
    const CarmenScan& s = log.scans[i];
    PairedScan p;
    p.scan_index = i;
    // The last kept ODOM line before the scan's (lines are in file order).
    const auto before = std::lower_bound(lines.begin(), lines.end(), s.line);
    if (file_order && s.line > 0 && before != lines.begin()) {
      const auto k = static_cast<std::size_t>(before - lines.begin()) - 1;
      // Coarse stamps may put that ODOM message "after" the scan in time; the file knows.
      if (std::abs(s.stamp - odom[k].stamp) <= opt.max_gap) {
        p.odom = odom[k].pose;
        p.source = OdomSource::kInterpolated;
        ++out.report.interpolated;
        ++out.report.by_file_order;
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
