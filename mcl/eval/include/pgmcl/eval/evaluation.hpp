#pragma once
/// Absolute trajectory error of a localisation estimate against ground truth.
///
/// No alignment is applied (unlike evo's `-a` / Umeyama): a localiser estimates poses in the
/// map frame, and the ground truth is in the map frame, so any offset between the two is an
/// error to report, not a nuisance to remove.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "pgmcl/eval/error_stats.hpp"
#include "pgmcl/io/trajectory.hpp"

namespace pgmcl::io {

enum class Association {
  kNearest,      ///< the truth pose with the nearest stamp, within `tolerance`
  kInterpolate,  ///< truth interpolated at the estimate's stamp (exact stamps match exactly)
};

struct AteOptions {
  Association association = Association::kInterpolate;
  /// Seconds. kNearest: largest stamp difference accepted. kInterpolate: used only where
  /// interpolation is impossible (just outside the truth span, or across a gap > max_gap).
  double tolerance = 0.05;
  double max_gap = 1.0;      ///< seconds: interpolate between truth poses at most this far apart
  double time_offset = 0.0;  ///< seconds: estimate stamp + time_offset = truth stamp
  /// Converged once both errors stay at or below these for the rest of the run.
  double converged_translation = 0.5;    ///< metres
  double converged_rotation_deg = 10.0;  ///< degrees
  /// Locked on once the position error stays at or below this for the rest of the run;
  /// a larger error is "lost" (the robustness benchmark's failure threshold).
  double lost_translation = 1.0;  ///< metres
};

struct PoseError {
  double stamp = 0.0;         ///< estimate stamp, seconds
  double translation = 0.0;   ///< metres, |p_est - p_true|
  double rotation_deg = 0.0;  ///< degrees, |wrap(theta_est - theta_true)|
};

struct AteResult {
  std::size_t estimated = 0;  ///< estimate poses given
  std::size_t matched = 0;    ///< with a truth pose
  std::size_t unmatched = 0;  ///< without one (not scored)
  /// Seconds, in the truth's clock: the truth's time span, and the part of it between the
  /// first and the last matched estimate pose (what the figures score).
  double truth_from = 0.0, truth_to = 0.0;
  double covered_from = 0.0, covered_to = 0.0;
  /// Of the truth's time span, the share between the first and last matched estimate pose
  /// (1 for a truth of one instant that was matched, 0 with no match).
  double truth_covered_fraction = 0.0;
  ErrorStats translation;  ///< metres; .rms is the ATE RMSE, .max the worst error
  ErrorStats heading;      ///< degrees; .rms is the heading RMSE
  /// Seconds from the first estimate stamp to the first matched pose after which every
  /// matched pose is within both thresholds (0 if all are); empty if the last one is not.
  std::optional<double> converged_after_s;
  /// Seconds from the first estimate stamp to the first matched pose after which every
  /// position error stays within lost_translation (0: never lost); empty if the last one
  /// is lost. With it: the truth's path length up to then, and the errors from then on.
  std::optional<double> lock_on_s;
  double lock_on_travel_m = 0.0;
  ErrorStats post_lock_translation;  ///< metres
  ErrorStats post_lock_heading;      ///< degrees
  std::vector<PoseError> errors;     ///< per matched pose, in time order
};

/// Both trajectories may come in any order (they are sorted by stamp internally).
[[nodiscard]] AteResult evaluate_ate(const Trajectory& estimate, const Trajectory& truth,
                                     const AteOptions& opt = {});

/// "" when every estimate pose was matched; else "only 80 of 440 estimate poses (18 %) have
/// a ground-truth pose (...); the figures cover only those": a partial match scores part of
/// a run, and usually means the clocks differ.
[[nodiscard]] std::string ate_match_warning(const AteResult& ate, const AteOptions& opt = {});

/// "" when the matched estimate poses span (nearly) all of the truth's time; else "the
/// matched estimate poses cover only 9 % of the ground truth's time span (...)": an estimate
/// of part of the run scores only that part, however well its own poses all match.
[[nodiscard]] std::string truth_coverage_warning(const AteResult& ate);

}  // namespace pgmcl::io
