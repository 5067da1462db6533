#include "pgmcl/io/odometry_pairing.hpp"

namespace pgmcl::io {

Trajectory monotonic_odometry(const CarmenLog& log, std::size_t* dropped) {
  Trajectory t;
  t.reserve(log.odometry.size());
  std::size_t n_dropped = 0;
  for (const OdomRecord& r : log.odometry) {
    if (!t.empty() && r.stamp < t.back().stamp) {
      ++n_dropped;
      continue;
    }
    t.push_back({r.stamp, r.pose});
  }
  if (dropped != nullptr) *dropped = n_dropped;
  return t;
}

PairedScans pair_odometry(const CarmenLog& log, const PairingOptions& opt) {
  PairedScans out;
  const Trajectory odom = monotonic_odometry(log, &out.report.odom_dropped);
  out.report.odom_used = odom.size();
  out.scans.reserve(log.scans.size());
  for (std::size_t i = 0; i < log.scans.size(); ++i) {
    const CarmenScan& s = log.scans[i];
    PairedScan p;
    p.scan_index = i;
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
