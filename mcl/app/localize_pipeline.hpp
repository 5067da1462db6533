#pragma once
/// The localisation run shared by `pgmcl localize` and `pgmcl run`: replay a CARMEN log
/// through pgmcl::Localizer and write the results.
///
/// Outputs in `out_dir`:
///   trajectory.tum  one pose per Localizer::update() call (= per scan with odometry),
///                   stamped with the scan time; skipped (gated) updates give the
///                   odometry-propagated estimate the filter reports for that time
///   metrics.yaml    io::RunMetrics (timing, particles, beams; accuracy with truth;
///                   relations error with relations)
///   config.yaml     the effective LocalizerConfig (every field), to rerun exactly
///   updates.csv     one row per update: estimate, skip reason, converged, fit, N_eff,
///                   particles, competing hypotheses, and the error with ground truth
///   overlay.png     map + ground truth + estimate + final particle cloud
///   error.png       position and heading error over time (only with ground truth)

#include <optional>
#include <string>
#include <vector>

#include "pgmcl/eval/metrics.hpp"
#include "pgmcl/io/carmen.hpp"
#include "pgmcl/io/relations.hpp"
#include "pgmcl/io/trajectory.hpp"
#include "pgmcl/maps/occupancy_grid.hpp"
#include "pgmcl/mcl/localizer_config.hpp"

namespace pgmcl::app {

/// How the filter starts.
struct InitialBelief {
  enum class Kind { kGlobal, kPose, kTruth } kind = Kind::kGlobal;
  Pose2 pose{};              ///< kPose: mean, global frame
  double sigma_xy = 0.25;    ///< metres (kPose, kTruth)
  double sigma_theta = 0.1;  ///< radians (kPose, kTruth)
  double sigma_y = -1.0;     ///< metres; < 0: sigma_xy
};

struct LocalizeJob {
  const maps::OccupancyGrid* map = nullptr;
  const io::CarmenLog* log = nullptr;
  std::string log_name;  ///< for messages
  LocalizerConfig config{};
  InitialBelief init{};
  std::optional<io::Trajectory> truth;
  std::optional<std::vector<io::Relation>> relations;
  double relations_time_offset = 0.0;  ///< seconds: estimate stamp + offset = relation stamp
  std::string out_dir;
  std::string title;  ///< overlay caption
  bool quiet = false;
};

/// Runs the job; returns the metrics also written to metrics.yaml. Throws on bad input
/// (no scans with odometry, a scan the Localizer rejects) naming the log file and line.
io::RunMetrics run_localization(const LocalizeJob& job);

/// "X,Y,THETA[,SX,SY,STH]" from --init (metres, radians). Throws UsageError.
[[nodiscard]] InitialBelief parse_init(const std::string& text);

/// One line for the terminal: updates, timing, accuracy.
[[nodiscard]] std::string summary_line(const io::RunMetrics& m, const std::string& out_dir);

}  // namespace pgmcl::app
