#include "localize_pipeline.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <optional>

#include "app_util.hpp"
#include "cli_errors.hpp"
#include "interrupt.hpp"
#include "pgmcl/config/config_yaml.hpp"
#include "pgmcl/eval/evaluation.hpp"
#include "pgmcl/io/errors.hpp"
#include "pgmcl/io/tum.hpp"
#include "pgmcl/io/values.hpp"
#include "png_overlay.hpp"
#include "progress.hpp"
#include "run_checks.hpp"
#include "run_pictures.hpp"

namespace pgmcl::app {
namespace {

constexpr double kRadToDeg = 180.0 / std::numbers::pi;

void write_updates_csv(const std::string& path, const std::vector<replay::UpdateRow>& rows,
                       const io::Trajectory* truth) {
  io::Trajectory sorted;
  if (truth) {
    sorted = *truth;
    io::sort_by_stamp(sorted);
  }
  std::ofstream f(path);
  if (!f) throw io::IoError(path + ": cannot create file");
  f << "stamp,x,y,theta,skipped,converged,fit,n_eff,particles,competitors,evidence,seeded,"
       "injected,switched,searched,rotation_noise_factor,translation_noise_factor,"
       "error_m,error_deg\n";
  char buf[512];
  for (const replay::UpdateRow& u : rows) {
    double e = std::nan(""), eth = std::nan("");
    if (truth) {
      if (const auto t = io::interpolate_at(sorted, u.stamp, 1.0)) {
        e = std::hypot(t->x - u.estimate.x, t->y - u.estimate.y);
        eth = std::abs(wrap_angle(t->theta - u.estimate.theta)) * kRadToDeg;
      }
    }
    std::snprintf(
        buf, sizeof buf,
        "%.6f,%.4f,%.4f,%.5f,%d,%d,%.3f,%.1f,%zu,%zu,%.2f,%zu,%zu,%d,%d,%.2f,%.2f,%.4f,%.2f\n",
        u.stamp, u.estimate.x, u.estimate.y, u.estimate.theta, static_cast<int>(u.skipped),
        u.converged ? 1 : 0, u.fit, u.n_eff, u.particles, u.competitors, u.evidence, u.seeded,
        u.injected, u.switched ? 1 : 0, u.searched ? 1 : 0, u.rotation_noise_factor,
        u.translation_noise_factor, e, eth);
    f << buf;
  }
  f.close();
  if (!f) throw io::IoError(path + ": write failed");
}

}  // namespace

InitialBelief parse_init(const std::string& text) {
  const std::vector<double> v =
      io::parse_number_list(text, "--init", {3, 6}, "X,Y,THETA[,SX,SY,STH] (m, m, rad)");
  InitialBelief b;
  b.kind = InitialBelief::Kind::kPose;
  b.pose = {v[0], v[1], v[2]};
  if (v.size() == 6) {
    if (!(v[3] > 0.0 && v[4] > 0.0 && v[5] > 0.0)) {
      throw io::UsageError("--init: SX, SY and STH must be > 0, got '" + text + "'");
    }
    b.sigma_xy = v[3];
    b.sigma_y = v[4];
    b.sigma_theta = v[5];
  }
  return b;
}

LocalizeOutputs register_localize_outputs(OutputFiles& files, const std::string& dir,
                                          const std::string& option) {
  if (dir.empty()) throw io::UsageError(option + ": the output folder is empty");
  const std::filesystem::path d(dir);
  LocalizeOutputs o;
  o.dir = dir;
  o.trajectory = files.add((d / "trajectory.tum").string(), option);
  o.metrics = files.add((d / "metrics.yaml").string(), option);
  o.config = files.add((d / "config.yaml").string(), option);
  o.updates = files.add((d / "updates.csv").string(), option);
  o.overlay = files.add((d / "overlay.png").string(), option);
  o.error_png_target = (d / "error.png").string();
  o.error_png = files.add(o.error_png_target, option);
  return o;
}

void warn(LocalizeJob& job, const std::string& w) {
  std::fprintf(stderr, "pgmcl: warning: %s\n", w.c_str());
  job.warnings.push_back(w);
}

void check_job(LocalizeJob& job, const std::string& map_name, const std::string& what) {
  for (const std::string& w : check_map_for_localisation(*job.map, map_name, job.config)) {
    warn(job, w);
  }
  if (job.init.kind == InitialBelief::Kind::kPose) {
    if (const std::string w = heading_warning(job.init.pose.theta, what); !w.empty()) warn(job, w);
  }
  for (const std::string& w : check_initial_belief(job.init, *job.map, what)) warn(job, w);
  job.init.pose.theta = wrap_angle(job.init.pose.theta);
  if (const std::string w = threads_warning(job.config.threads); !w.empty()) warn(job, w);
}

io::RunMetrics run_localization(const LocalizeJob& job, const LocalizeOutputs& out,
                                OutputFiles& files) {
  std::optional<Progress> progress;
  replay::ReplayHooks hooks;
  hooks.on_start = [&](const std::string& start, std::size_t updates) {
    if (!job.quiet) std::fprintf(stderr, "localize: start: %s\n", start.c_str());
    progress.emplace(Progress::on_stderr("localize", updates, job.quiet));
  };
  hooks.on_update = [&](std::size_t done, std::size_t, const UpdateResult& r) {
    char extra[96];
    std::snprintf(extra, sizeof extra, "%zu particles%s", r.particles,
                  r.converged ? ", converged" : "");
    progress->update(done, extra);
  };
  hooks.stop = &stop_flag();
  replay::ReplayResult run = [&] {
    try {
      return replay::run(job, hooks);
    } catch (const io::UsageError& e) {
      // A log without odometry is bad input (exit 1), not a bad command line (exit 2).
      throw std::runtime_error(e.what());
    }
  }();
  if (progress) progress->finish();
  for (const std::string& w : run.warnings) std::fprintf(stderr, "pgmcl: warning: %s\n", w.c_str());
  // The run's own warnings are in its metrics already; those found before it go first.
  io::RunMetrics& metrics = run.metrics;
  metrics.warnings.insert(metrics.warnings.begin(), job.warnings.begin(), job.warnings.end());

  io::write_tum(out.trajectory, run.trajectory);
  write_text_file(out.metrics, io::metrics_yaml(metrics));
  write_updates_csv(out.updates, run.rows, job.truth ? &*job.truth : nullptr);
  write_text_file(out.config, io::localizer_config_yaml(job.config));
  std::vector<Pose2> est, truth_path;
  est.reserve(run.trajectory.size());
  for (const auto& t : run.trajectory) est.push_back(t.pose);
  if (job.truth) {
    io::Trajectory sorted = *job.truth;
    io::sort_by_stamp(sorted);
    for (const auto& t : sorted) truth_path.push_back(t.pose);
  }
  const io::AteResult* ate = run.ate ? &*run.ate : nullptr;
  const auto [search_begin, search_end] = search_range(run.trajectory, ate, job.events);
  OverlayData overlay{truth_path,   est,        run.particles,
                      run.weights,  job.title,  overlay_subtitle(run, job.log_name, job.map_name),
                      search_begin, search_end, job.obstacles};
  write_overlay_png(out.overlay, *job.map, overlay);
  if (ate && !ate->errors.empty()) {
    ErrorPlotData e{ate, run.rows, run.trajectory.front().stamp, job.events};
    write_png(render_error_plot(e), out.error_png);
  } else {
    files.drop(out.error_png_target);
  }
  files.keep_when_interrupted();
  files.commit();
  return metrics;
}

int finish_exit_code(const io::RunMetrics& m, const std::string& out_dir) {
  mark_interrupt_handled();
  if (m.complete) return kExitOk;
  std::fprintf(stderr,
               "pgmcl: interrupted by %s after %zu update(s); wrote the run so far to %s "
               "(metrics.yaml: complete: false)\n",
               signal_name(interrupt_signal()), m.updates + m.skipped_updates, out_dir.c_str());
  return interrupted_exit_code();
}

std::string run_title(const std::string& out_dir, const std::string& log) {
  const std::filesystem::path out = std::filesystem::path(out_dir).lexically_normal();
  std::string name = out.filename().string();
  if (name.empty()) name = out.parent_path().filename().string();  // "dir/"
  if (name.empty() || name == "." || name == "pgmcl-out")
    name = std::filesystem::path(log).filename().string();
  return name;
}

std::string summary_line(const io::RunMetrics& m, const std::string& out_dir,
                         const LocalizerConfig& config) {
  char buf[512];
  int n =
      std::snprintf(buf, sizeof buf,
                    "localize: %zu updates (%zu skipped), %.2f ms/update (median %.2f, p95 "
                    "%.2f, max %.1f%s), particles %zu..%zu (mean %.0f)",
                    m.updates, m.skipped_updates, m.update_ms_mean, m.update_ms_median,
                    m.update_ms_p95, m.update_ms_max,
                    m.update_ms_mean > m.update_ms_p95 ? "; a few slow updates lift the mean" : "",
                    m.particles_min, m.particles_max, m.particles_mean);
  std::string s(buf, static_cast<std::size_t>(std::max(n, 0)));
  // KLD-sampling, not filter.particles, decides the count once the filter runs: say so when
  // the count moved, so "filter.particles=5000" running at 527 is no surprise.
  const auto& kld = config.filter.kld;
  if (kld.enabled && m.updates > 0 &&
      (m.particles_min != m.particles_max || m.particles_min != config.filter.particles)) {
    n = std::snprintf(buf, sizeof buf,
                      " set by KLD-sampling within %zu..%zu (filter.particles %zu is only the "
                      "start)",
                      kld.min_particles, kld.max_particles, config.filter.particles);
    s.append(buf, static_cast<std::size_t>(std::max(n, 0)));
  }
  n = std::snprintf(buf, sizeof buf, ", %.0f beams, fit %.2f, converged on %.0f %% of updates",
                    m.beams_used_mean, m.fit_mean, 100.0 * m.converged_fraction);
  s.append(buf, static_cast<std::size_t>(std::max(n, 0)));
  if (m.rotation_noise_factor > 1.0 || m.translation_noise_factor > 1.0) {
    n = std::snprintf(buf, sizeof buf,
                      ", odometry noisier than the model: variances x%.1f (rotation), x%.1f "
                      "(translation) by the end",
                      m.rotation_noise_factor, m.translation_noise_factor);
    s.append(buf, static_cast<std::size_t>(std::max(n, 0)));
  }
  if (m.accuracy) {
    const auto& a = *m.accuracy;
    n = std::snprintf(buf, sizeof buf, "; ATE RMSE %.3f m (max %.3f), heading RMSE %.2f deg",
                      a.ate_rmse_m, a.ate_max_m, a.heading_rmse_deg);
    s.append(buf, static_cast<std::size_t>(std::max(n, 0)));
    if (a.lock_on_s) {
      n = std::snprintf(buf, sizeof buf,
                        "; locked on (within 1 m from then on) at %.1f s after %.1f m, then ATE "
                        "%.3f m (max %.3f); wrongly converged on %zu updates",
                        *a.lock_on_s, a.lock_on_travel_m, a.post_lock_ate_rmse_m,
                        a.post_lock_ate_max_m, a.false_converged);
    } else {
      n = std::snprintf(buf, sizeof buf, "; lost (more than 1 m off) at the end");
    }
    s.append(buf, static_cast<std::size_t>(std::max(n, 0)));
  }
  if (m.relations) {
    n = std::snprintf(buf, sizeof buf, "; relations %.3f m / %.2f deg (%zu)", m.relations->trans_m,
                      m.relations->rot_deg, m.relations->used);
    s.append(buf, static_cast<std::size_t>(std::max(n, 0)));
  }
  s += "; wrote " + out_dir;
  return s;
}

}  // namespace pgmcl::app
