#pragma once
/// A whole localisation run in memory: a CARMEN log replayed through pgmcl::Localizer, with
/// what the filter said about itself at every update and, given ground truth or benchmark
/// relations, its accuracy. `pgmcl localize`, `pgmcl run` and the Python module share this
/// loop; files, pictures and the terminal are theirs.

#include <Eigen/Core>
#include <atomic>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "pgmcl/common/se2.hpp"
#include "pgmcl/eval/evaluation.hpp"
#include "pgmcl/eval/metrics.hpp"
#include "pgmcl/io/carmen.hpp"
#include "pgmcl/io/relations.hpp"
#include "pgmcl/io/trajectory.hpp"
#include "pgmcl/maps/occupancy_grid.hpp"
#include "pgmcl/mcl/localizer_config.hpp"
#include "pgmcl/mcl/update_result.hpp"

namespace pgmcl::replay {

/// How the filter starts.
struct InitialBelief {
  enum class Kind { kGlobal, kPose, kTruth } kind = Kind::kGlobal;
  Pose2 pose{};              ///< kPose: mean, global frame
  double sigma_xy = 0.25;    ///< metres (kPose, kTruth)
  double sigma_theta = 0.1;  ///< radians (kPose, kTruth)
  double sigma_y = -1.0;     ///< metres; < 0: sigma_xy
};

/// The diagonal covariance (m², m², rad²) of a belief's standard deviations.
[[nodiscard]] Eigen::Matrix3d covariance_of(const InitialBelief& b);

struct ReplayJob {
  const maps::OccupancyGrid* map = nullptr;
  const io::CarmenLog* log = nullptr;
  std::string log_name;  ///< for messages
  LocalizerConfig config{};
  InitialBelief init{};
  std::optional<io::Trajectory> truth;
  std::optional<std::vector<io::Relation>> relations;
  double relations_time_offset = 0.0;  ///< seconds: estimate stamp + offset = relation stamp
};

/// What the filter said about itself at one update (a row of updates.csv).
struct UpdateRow {
  double stamp = 0.0;
  Pose2 estimate{};  ///< global frame
  SkipReason skipped = SkipReason::kNone;
  bool converged = false;
  double fit = 0.0;
  double n_eff = 0.0;
  double evidence = 0.0;  ///< UpdateResult::alternative_evidence
  std::size_t particles = 0, competitors = 0, seeded = 0, injected = 0;
  bool switched = false, searched = false;
  double rotation_noise_factor = 1.0, translation_noise_factor = 1.0;  ///< UpdateResult's
  [[nodiscard]] static UpdateRow of(double stamp, const UpdateResult& r);
};

struct ReplayHooks {
  /// Called once the filter holds its initial belief, with how it started and the number
  /// of updates to come.
  std::function<void(const std::string&, std::size_t)> on_start;
  /// Called after every update with (updates done, updates in all, its result).
  std::function<void(std::size_t, std::size_t, const UpdateResult&)> on_update;
  /// Polled before every update: once true, the run stops and returns what is done.
  const std::atomic<bool>* stop = nullptr;
};

struct ReplayResult {
  io::Trajectory trajectory;  ///< one pose per update (per scan with odometry), global frame
  std::vector<UpdateRow> rows;
  io::RunMetrics metrics;             ///< accuracy / relations filled when given truth / relations
  std::optional<io::AteResult> ate;   ///< with truth
  std::vector<Pose2> particles;       ///< the final cloud, global frame
  std::vector<double> weights;        ///< its normalised weights
  std::string start;                  ///< how the filter started, for messages
  std::vector<std::string> warnings;  ///< skipped scans and the like, for the caller to report
                                      ///< (also in metrics.warnings)
  bool complete = true;               ///< false when stopped by ReplayHooks::stop
};

/// Runs the job. Throws io::UsageError when the log has no scan with odometry and
/// io::FormatError (log name and line) for a scan the Localizer rejects; the Localizer's
/// constructor errors (config, map) pass through as std::invalid_argument.
[[nodiscard]] ReplayResult run(const ReplayJob& job, const ReplayHooks& hooks = {});

}  // namespace pgmcl::replay
