#pragma once
/// The localisation run shared by `pgmcl localize` and `pgmcl run`: replay a CARMEN log
/// through pgmcl::Localizer (pgmcl::replay) and write the results.
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
///   overlay.png     map + ground truth + estimate + final particle cloud (png_overlay.hpp)
///   error.png       position and heading error over time, lock-on, what the filter said
///                   (only with ground truth; run_pictures.hpp)

#include <optional>
#include <string>
#include <vector>

#include "pgmcl/eval/metrics.hpp"
#include "pgmcl/replay/replay.hpp"
#include "png_overlay.hpp"

namespace pgmcl::app {

using replay::InitialBelief;

/// A replay and where its results go.
struct LocalizeJob : replay::ReplayJob {
  std::string out_dir;
  std::string title;     ///< the run's name: overlay.png's title
  std::string map_name;  ///< the map file, for overlay.png's header
  bool quiet = false;
  std::vector<ObstacleDrawing> obstacles;  ///< simulated moving obstacles, for overlay.png
  std::vector<double> events;              ///< kidnap stamps (simulated), for error.png
};

/// Runs the job; returns the metrics also written to metrics.yaml. Throws on bad input
/// (no scans with odometry, a scan the Localizer rejects) naming the log file and line.
io::RunMetrics run_localization(const LocalizeJob& job);

/// "X,Y,THETA[,SX,SY,STH]" from --init (metres, radians). Throws UsageError.
[[nodiscard]] InitialBelief parse_init(const std::string& text);

/// The name of a `localize` run: its output folder's name ("intel-global" for --out
/// out/intel-global), or the log's file name for the default folder.
[[nodiscard]] std::string run_title(const std::string& out_dir, const std::string& log);

/// One line for the terminal: updates, timing (mean, median, p95, max), particle counts and
/// whether KLD-sampling set them, accuracy and lock-on.
[[nodiscard]] std::string summary_line(const io::RunMetrics& m, const std::string& out_dir,
                                       const LocalizerConfig& config);

}  // namespace pgmcl::app
