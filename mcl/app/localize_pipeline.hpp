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
///   overlay.png     map + ground truth + estimate + final particle cloud
///   error.png       position and heading error over time (only with ground truth)

#include <optional>
#include <string>
#include <vector>

#include "pgmcl/eval/metrics.hpp"
#include "pgmcl/replay/replay.hpp"

namespace pgmcl::app {

using replay::InitialBelief;

/// A replay and where its results go.
struct LocalizeJob : replay::ReplayJob {
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
