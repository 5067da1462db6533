#pragma once
/// The SLAM benchmark metric of Kümmerle et al., "On measuring the accuracy of SLAM
/// algorithms", Autonomous Robots 27(4), 2009: the error of relative poses between pairs of
/// scans, eps = sum over relations of (delta_est (-) delta_ref)^2, split into translation and
/// rotation. Relation files hold `t1 t2 x y z roll pitch yaw` per line: the pose of the scan
/// at t2 in the frame of the scan at t1 (pgmcl uses x, y and yaw).
///
/// The paper's tables report the mean and standard deviation of the absolute translational
/// (m) and rotational (deg) errors, and of their squares (m^2, deg^2); evaluate_relations
/// gives all four.

#include <cstddef>
#include <vector>

#include "pgmcl/eval/error_stats.hpp"
#include "pgmcl/io/relations.hpp"
#include "pgmcl/io/trajectory.hpp"

namespace pgmcl::io {

struct RelationOptions {
  /// Seconds: estimate stamp + time_offset = relation stamp (kIntelRelationsTimeOffset for
  /// the intel log).
  double time_offset = 0.0;
  /// Seconds: a relation end matches the estimate pose with the nearest stamp if it is at
  /// most this far. The intel log's relative stamps carry ~6 significant digits (10 ms at the
  /// end of the log), hence 20 ms.
  double tolerance = 0.02;
  /// Instead of the nearest pose, interpolate the estimate at the relation stamps (within its
  /// span, between poses at most max_gap apart; else the nearest-within-tolerance rule).
  bool interpolate = false;
  double max_gap = 1.0;  ///< seconds, interpolation only
};

struct RelationError {
  double t1 = 0.0, t2 = 0.0;  ///< relation stamps
  double translation = 0.0;   ///< metres, |trans(delta_est (-) delta_ref)|
  double rotation = 0.0;      ///< degrees, |rot(delta_est (-) delta_ref)|
};

struct RelationResult {
  std::size_t relations = 0;  ///< given
  std::size_t matched = 0;    ///< both ends found in the estimate
  /// |t2 - t1| <= tolerance: the two ends cannot be told apart by stamp, so not scored.
  /// (intel.relations has 69 relations less than 50 ms apart that still move 0.3 m or turn
  /// 27 deg; matched by stamp they would compare a pose with itself.)
  std::size_t degenerate = 0;
  std::size_t unmatched = 0;          ///< relations - matched - degenerate
  ErrorStats translation;             ///< metres
  ErrorStats translation_sq;          ///< square metres
  ErrorStats rotation;                ///< degrees
  ErrorStats rotation_sq;             ///< square degrees
  double max_time_error = 0.0;        ///< seconds, largest stamp difference of a nearest match
  std::vector<RelationError> errors;  ///< per matched relation, in input order
};

/// Scores an estimated trajectory (any order; sorted internally) against the relations.
/// delta_est = est(t1)^-1 * est(t2); error = delta_ref^-1 * delta_est.
[[nodiscard]] RelationResult evaluate_relations(const Trajectory& estimate,
                                                const std::vector<Relation>& relations,
                                                const RelationOptions& opt = {});

}  // namespace pgmcl::io
