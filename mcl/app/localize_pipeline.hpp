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
///   error.png       position and heading error over time (only with ground truth; an
///                   earlier run's error.png is removed otherwise)
/// All of them or none: they are registered before the run (OutputFiles) and renamed into
/// place together at the end. A SIGINT / SIGTERM stops the replay; the run so far is then
/// written with `complete: false` in metrics.yaml.

#include <optional>
#include <string>
#include <vector>

#include "output_files.hpp"
#include "pgmcl/eval/metrics.hpp"
#include "pgmcl/replay/replay.hpp"

namespace pgmcl::app {

using replay::InitialBelief;

/// The files of a localisation run, registered with an OutputFiles: `staged` paths are
/// where they are written, `dir` where they end up.
struct LocalizeOutputs {
  std::string dir;
  std::string trajectory, metrics, config, updates, overlay, error_png;  ///< staged
  std::string error_png_target;
};

/// Registers the run's outputs in `dir` (named `option` in messages) before any work.
[[nodiscard]] LocalizeOutputs register_localize_outputs(OutputFiles& files, const std::string& dir,
                                                        const std::string& option);

/// A replay and what to say about it.
struct LocalizeJob : replay::ReplayJob {
  std::string title;  ///< overlay caption
  bool quiet = false;
  /// Warnings found before the run (log, map, start), already printed; metrics.yaml lists
  /// them with the run's own.
  std::vector<std::string> warnings;
};

/// Runs the job (stopped early by SIGINT / SIGTERM, interrupt.hpp), writes the outputs and
/// commits `files`; returns the metrics also written to metrics.yaml (`complete` false when
/// stopped). Throws on bad input (no scans with odometry, a scan the Localizer rejects)
/// naming the log file and line; nothing is written then.
io::RunMetrics run_localization(const LocalizeJob& job, const LocalizeOutputs& out,
                                OutputFiles& files);

/// Prints "pgmcl: warning: <w>" and keeps it for metrics.yaml.
void warn(LocalizeJob& job, const std::string& w);

/// The checks before the filter starts (run_checks.hpp) on the job's map and start, with
/// the start named `what` ("--init", "FILE: init"); start warnings are reported via warn().
/// Wraps the start heading into (-π, π].
void check_job(LocalizeJob& job, const std::string& map_name, const std::string& what);

/// The exit code of a finished run: 0, or 128 + signal when it was stopped (after saying
/// so on stderr).
[[nodiscard]] int finish_exit_code(const io::RunMetrics& m, const std::string& out_dir);

/// "X,Y,THETA[,SX,SY,STH]" from --init (metres, radians; THETA as given, check_job wraps
/// it). Throws UsageError.
[[nodiscard]] InitialBelief parse_init(const std::string& text);

/// One line for the terminal: updates, timing, accuracy.
[[nodiscard]] std::string summary_line(const io::RunMetrics& m, const std::string& out_dir);

}  // namespace pgmcl::app
