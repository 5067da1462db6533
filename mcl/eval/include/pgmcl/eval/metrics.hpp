#pragma once
/// metrics.yaml: what a localisation run measured about itself (timing, particle counts,
/// beams) and, when ground truth or benchmark relations are given, its accuracy.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "pgmcl/eval/evaluation.hpp"
#include "pgmcl/eval/relations_error.hpp"
#include "pgmcl/io/relations.hpp"

namespace pgmcl::io {

/// Accuracy against a ground-truth trajectory (see the evaluation API).
struct AccuracyMetrics {
  double ate_rmse_m = 0.0;        ///< absolute trajectory error, RMSE of position, metres
  double ate_max_m = 0.0;         ///< largest position error, metres
  double heading_rmse_deg = 0.0;  ///< RMSE of wrapped heading error, degrees
  /// Seconds from the first estimate until the error stays small; nullopt if never.
  std::optional<double> converged_after_s;
  std::size_t matched = 0;        ///< estimate poses matched to ground truth
  double matched_fraction = 0.0;  ///< of the estimate poses (1: the whole run is scored)
  /// Of the truth's time span, the share the matched estimate poses span (1: all of it).
  double truth_covered_fraction = 0.0;
  /// Lock-on (AteResult): seconds from the first estimate until the position error stays
  /// within 1 m (0: never lost; nullopt: lost at the end), the truth's path length until
  /// then, and the errors after it.
  std::optional<double> lock_on_s;
  double lock_on_travel_m = 0.0;
  double post_lock_ate_rmse_m = 0.0;
  double post_lock_ate_max_m = 0.0;
  double post_lock_heading_rmse_deg = 0.0;
  /// Updates on which the filter reported `converged` while more than 1 m off, and the
  /// longest run of them: what the filter said about itself that was not true.
  std::size_t false_converged = 0;
  std::size_t false_converged_run = 0;
};

/// Kümmerle et al. (2009) relations error.
struct RelationsMetrics {
  double trans_m = 0.0;  ///< mean translational error of the relations, metres
  double rot_deg = 0.0;  ///< mean rotational error, degrees
  std::size_t used = 0;  ///< relations whose two stamps matched estimate poses
  /// Sample standard deviations: the paper's tables give "mean ± std" of both errors.
  double trans_std_m = 0.0;
  double rot_std_deg = 0.0;
};

struct RunMetrics {
  std::size_t updates = 0;          ///< measurement updates performed
  std::size_t skipped_updates = 0;  ///< scans the filter skipped (gating, bad scan)
  double update_ms_mean = 0.0;      ///< per-update wall time, milliseconds
  double update_ms_p95 = 0.0;       ///< 95th percentile (nearest rank), milliseconds
  /// Median and slowest update, milliseconds: a few slow updates (a global search) raise the
  /// mean above the p95, and these show it.
  double update_ms_median = 0.0;
  double update_ms_max = 0.0;
  double wall_s = 0.0;              ///< whole run, seconds
  double particles_mean = 0.0;      ///< over performed updates
  std::size_t particles_min = 0;    ///< over performed updates
  std::size_t particles_max = 0;    ///< over performed updates
  double beams_used_mean = 0.0;     ///< over performed updates
  double fit_mean = 0.0;            ///< UpdateResult::fit over performed updates
  double converged_fraction = 0.0;  ///< of performed updates that reported `converged`
  /// UpdateResult's motion-noise factors at the run's last update: how much noisier than the
  /// configured model the odometry turned out (1 = not noisier, or not adapted).
  double rotation_noise_factor = 1.0;
  double translation_noise_factor = 1.0;
  /// false: the run was stopped (SIGINT, SIGTERM) and these figures cover its first part.
  bool complete = true;
  /// What was reported as a warning during the run (skipped scans, doubtful inputs).
  std::vector<std::string> warnings;
  std::optional<AccuracyMetrics> accuracy;
  std::optional<RelationsMetrics> relations;
};

/// The metrics.yaml figures of an ATE evaluation (RMSE and max of the position error,
/// RMSE of the heading error, convergence time).
[[nodiscard]] AccuracyMetrics accuracy_metrics(const AteResult& ate);
/// The metrics.yaml figures of a relations evaluation (mean absolute errors, as in
/// Kümmerle et al. 2009's tables).
[[nodiscard]] RelationsMetrics relations_metrics(const RelationResult& rel);

/// Collects per-update figures during a run.
class MetricsAccumulator {
 public:
  void add_update(double update_ms, std::size_t particles, std::size_t beams_used, double fit = 0.0,
                  bool converged = false);
  void add_skipped() { ++skipped_; }
  /// The motion-noise factors in use (UpdateResult's); the last call's are reported.
  void set_noise_factors(double rotation, double translation) {
    rotation_noise_factor_ = rotation;
    translation_noise_factor_ = translation;
  }
  /// Means and the p95 so far; accuracy and relations are left empty.
  [[nodiscard]] RunMetrics summarise(double wall_s) const;

 private:
  std::vector<double> update_ms_;
  double particles_sum_ = 0.0;
  std::size_t particles_min_ = 0, particles_max_ = 0;
  double beams_sum_ = 0.0;
  double fit_sum_ = 0.0;
  std::size_t converged_ = 0;
  std::size_t skipped_ = 0;
  double rotation_noise_factor_ = 1.0, translation_noise_factor_ = 1.0;
};

/// One figure of metrics.yaml. Counts are whole numbers; `kNull` is a figure that does not
/// exist (converged_after_s of a run that never converged), written `null`; `kFlag` is
/// `true` / `false` (`complete`), held in `count` as 1 / 0.
struct MetricEntry {
  enum class Kind { kCount, kReal, kNull, kFlag } kind = Kind::kReal;
  std::string key;
  std::size_t count = 0;  ///< kCount, kFlag
  double real = 0.0;      ///< kReal
};

/// The figures of metrics.yaml in its order, keys as listed there: the one list that the
/// YAML, the table and the Python bindings' dict are made from. `run_figures` as below.
[[nodiscard]] std::vector<MetricEntry> metrics_entries(const RunMetrics& m,
                                                       bool run_figures = true);

/// Nearest-rank percentile (p in [0, 100]) of unsorted values; 0 for an empty input.
[[nodiscard]] double percentile(std::vector<double> values, double p);

/// The YAML text of metrics.yaml (keys as in RunMetrics; accuracy and relations keys:
/// ate_rmse_m, ate_max_m, heading_rmse_deg, converged_after_s (null if never), truth_matched,
/// truth_matched_fraction, truth_covered_fraction,
/// relations_trans_m, relations_rot_deg, relations_trans_std_m, relations_rot_std_deg,
/// relations_used; `complete` and, when there are any, the `warnings` list). `run_figures`
/// false leaves out the filter's own figures (updates .. beams_used_mean, complete,
/// warnings), for evaluating a trajectory file.
[[nodiscard]] std::string metrics_yaml(const RunMetrics& m, bool run_figures = true);
/// Writes metrics_yaml(m, run_figures) to `path`; throws IoError on failure.
void write_metrics_yaml(const std::string& path, const RunMetrics& m, bool run_figures = true);

/// Human-readable two-column table of the same figures (for `pgmcl eval` and summaries).
[[nodiscard]] std::string metrics_table(const RunMetrics& m, bool run_figures = true);

}  // namespace pgmcl::io
