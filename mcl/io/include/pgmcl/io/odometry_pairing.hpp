#pragma once
/// Pairs each scan of a CARMEN log with the robot's odometry pose at the scan's timestamp,
/// interpolated between the ODOM messages around it (linear in x, y; shortest arc in theta).
///
/// ODOM messages whose timestamp is earlier than the last one kept are dropped from the
/// interpolation (the reader reports them as backwards timestamps; the `*-corrected` logs
/// re-anchor their ODOM stream with lines stamped 0 after every scan). A scan outside the span
/// of the kept ODOM messages (or in a gap wider than max_gap) falls back to the odometry pose
/// the scan carries itself (FLASER odom_*, ROBOTLASER1 robot_pose_*); RAWLASERn scans carry
/// none and stay unpaired. Both cases are counted.
///
/// Time cannot order messages that share a stamp (ODOM and scans logged at one time, stamps
/// rounded to whole seconds): interpolation would give every scan of such a group the last
/// odometry of the group. A scan whose stamp is held by two or more ODOM messages, or by
/// another scan of its type, shares its stamp (PairingReport::shared_stamps). A log with
/// such scans has stamps too coarse to trust, also where they happen not to collide, so
/// then every scan is paired by file order: with the last ODOM message before it in the
/// file (PairingReport::by_file_order).

#include <cstddef>
#include <limits>
#include <vector>

#include "pgmcl/io/carmen.hpp"
#include "pgmcl/io/trajectory.hpp"

namespace pgmcl::io {

enum class OdomSource {
  kInterpolated,  ///< between two ODOM messages
  kScanFields,    ///< outside the ODOM span: the scan's own odometry fields
  kNone,          ///< outside the span and no pose in the scan (RAWLASERn)
};

struct PairedScan {
  std::size_t scan_index = 0;  ///< into CarmenLog::scans
  Pose2 odom{};                ///< robot odometry pose at the scan's stamp (if source != kNone)
  OdomSource source = OdomSource::kNone;
};

struct PairingReport {
  std::size_t interpolated = 0;
  std::size_t scan_fields = 0;        ///< fallbacks to the scan's own odometry fields
  std::size_t unpaired = 0;           ///< kNone
  std::size_t odom_used = 0;          ///< ODOM messages in the interpolation
  std::size_t odom_dropped = 0;       ///< ODOM messages dropped for going back in time
  std::size_t shared_stamps = 0;      ///< scans whose stamp is shared (above)
  std::size_t first_shared_line = 0;  ///< the first of them, 0 if none
  std::size_t by_file_order = 0;      ///< scans paired with the ODOM message before them
  /// Kept ODOM messages stamped like the one before (stamps rounded or repeated): time
  /// cannot place a scan between them.
  std::size_t odom_repeated_stamps = 0;
  std::size_t first_repeated_odom_line = 0;
};

struct PairingOptions {
  /// Seconds. Interpolate only between ODOM messages at most this far apart; a scan in a wider
  /// gap is treated like one outside the span.
  double max_gap = std::numeric_limits<double>::infinity();
};

struct PairedScans {
  std::vector<PairedScan> scans;  ///< one per CarmenLog::scans entry, same order
  PairingReport report;
};

/// ODOM poses with non-decreasing stamps: every message earlier than the last kept one is
/// dropped. `dropped` (optional) receives how many were.
[[nodiscard]] Trajectory monotonic_odometry(const CarmenLog& log, std::size_t* dropped = nullptr);

[[nodiscard]] PairedScans pair_odometry(const CarmenLog& log, const PairingOptions& opt = {});

}  // namespace pgmcl::io
