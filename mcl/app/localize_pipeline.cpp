#include "localize_pipeline.hpp"

#include <Eigen/Core>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <stdexcept>

#include "app_util.hpp"
#include "cli_errors.hpp"
#include "pgmcl/config/config_yaml.hpp"
#include "pgmcl/eval/evaluation.hpp"
#include "pgmcl/io/errors.hpp"
#include "pgmcl/io/odometry_pairing.hpp"
#include "pgmcl/io/tum.hpp"
#include "pgmcl/io/values.hpp"
#include "pgmcl/mcl/localizer.hpp"
#include "plot.hpp"
#include "png_overlay.hpp"
#include "progress.hpp"

namespace pgmcl::app {
namespace {

constexpr double kRadToDeg = 180.0 / std::numbers::pi;
constexpr std::size_t kMaxDrawnParticles = 5000;

Eigen::Matrix3d belief_covariance(const InitialBelief& b) {
  const double sy = b.sigma_y >= 0.0 ? b.sigma_y : b.sigma_xy;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  cov(0, 0) = b.sigma_xy * b.sigma_xy;
  cov(1, 1) = sy * sy;
  cov(2, 2) = b.sigma_theta * b.sigma_theta;
  return cov;
}

/// Position and heading error over time, one panel each.
void write_error_png(const std::string& path, const io::AteResult& ate, double t0) {
  PlotSeries pos{"position error", {}, {}, colors::kRed};
  PlotSeries head{"heading error", {}, {}, colors::kBlue};
  for (const io::PoseError& e : ate.errors) {
    pos.x.push_back(e.stamp - t0);
    pos.y.push_back(e.translation);
    head.x.push_back(e.stamp - t0);
    head.y.push_back(e.rotation_deg);
  }
  char title[160];
  std::snprintf(title, sizeof title, "Position error (ATE RMSE %.3f m, max %.3f m)",
                ate.translation.rms, ate.translation.max);
  LinePlot p1{title, "time since first scan [s]", "metres", {pos}, 1000, 340, true};
  std::snprintf(title, sizeof title, "Heading error (RMSE %.2f deg)", ate.heading.rms);
  LinePlot p2{title, "time since first scan [s]", "degrees", {head}, 1000, 340, true};
  Canvas c(1000, 680);
  c.blit(render_line_plot(p1), 0, 0);
  c.blit(render_line_plot(p2), 0, 340);
  write_png(c, path);
}

/// One row of updates.csv: what the filter said about itself at each update.
struct UpdateRow {
  double stamp;
  Pose2 estimate;
  int skipped;
  bool converged;
  double fit, n_eff, evidence;
  std::size_t particles, competitors, seeded, injected;
  bool switched, searched;
  static UpdateRow of(double stamp, const UpdateResult& r) {
    return {stamp,
            r.estimate,
            static_cast<int>(r.skipped),
            r.converged,
            r.fit,
            r.n_eff,
            r.alternative_evidence,
            r.particles,
            r.competitors,
            r.seeded,
            r.injected,
            r.switched,
            r.searched};
  }
};

void write_updates_csv(const std::string& path, const std::vector<UpdateRow>& rows,
                       const io::Trajectory* truth) {
  io::Trajectory sorted;
  if (truth) {
    sorted = *truth;
    io::sort_by_stamp(sorted);
  }
  std::ofstream f(path);
  f << "stamp,x,y,theta,skipped,converged,fit,n_eff,particles,competitors,evidence,seeded,"
       "injected,switched,searched,error_m,error_deg\n";
  char buf[512];
  for (const UpdateRow& u : rows) {
    double e = std::nan(""), eth = std::nan("");
    if (truth) {
      if (const auto t = io::interpolate_at(sorted, u.stamp, 1.0)) {
        e = std::hypot(t->x - u.estimate.x, t->y - u.estimate.y);
        eth = std::abs(wrap_angle(t->theta - u.estimate.theta)) * kRadToDeg;
      }
    }
    std::snprintf(buf, sizeof buf,
                  "%.6f,%.4f,%.4f,%.5f,%d,%d,%.3f,%.1f,%zu,%zu,%.2f,%zu,%zu,%d,%d,%.4f,%.2f\n",
                  u.stamp, u.estimate.x, u.estimate.y, u.estimate.theta, u.skipped,
                  u.converged ? 1 : 0, u.fit, u.n_eff, u.particles, u.competitors, u.evidence,
                  u.seeded, u.injected, u.switched ? 1 : 0, u.searched ? 1 : 0, e, eth);
    f << buf;
  }
  if (!f) throw io::IoError(path + ": write failed");
}

/// Updates that reported `converged` while more than 1 m off (AteOptions::lost_translation).
void count_false_convergence(const std::vector<UpdateRow>& rows, const io::AteResult& ate,
                             io::AccuracyMetrics& a) {
  const double lost = io::AteOptions{}.lost_translation;
  std::size_t run = 0, j = 0;
  for (const UpdateRow& u : rows) {
    while (j < ate.errors.size() && ate.errors[j].stamp < u.stamp) ++j;
    const bool matched = j < ate.errors.size() && ate.errors[j].stamp == u.stamp;
    const bool wrong = matched && u.skipped == 0 && u.converged && ate.errors[j].translation > lost;
    run = wrong ? run + 1 : 0;
    a.false_converged += wrong ? 1 : 0;
    a.false_converged_run = std::max(a.false_converged_run, run);
  }
}

std::string format_pose(const Pose2& p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.3f, %.3f, %.1f deg)", p.x, p.y, p.theta * kRadToDeg);
  return buf;
}

}  // namespace

InitialBelief parse_init(const std::string& text) {
  const std::vector<double> v =
      io::parse_number_list(text, "--init", {3, 6}, "X,Y,THETA[,SX,SY,STH] (m, m, rad)");
  InitialBelief b;
  b.kind = InitialBelief::Kind::kPose;
  b.pose = {v[0], v[1], wrap_angle(v[2])};
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

io::RunMetrics run_localization(const LocalizeJob& job) {
  const auto wall0 = std::chrono::steady_clock::now();
  const io::CarmenLog& log = *job.log;
  const io::PairedScans paired = io::pair_odometry(log);
  std::size_t usable = 0;
  for (const auto& p : paired.scans) usable += p.source != io::OdomSource::kNone;
  if (usable == 0) {
    throw io::UsageError(job.log_name +
                         ": no laser scan with odometry (need ODOM messages or FLASER/"
                         "ROBOTLASER1 scans, which carry their odometry pose)");
  }

  Localizer loc(*job.map, job.config);
  // Initial belief.
  double first_stamp = 0.0;
  for (const auto& p : paired.scans) {
    if (p.source != io::OdomSource::kNone) {
      first_stamp = log.scans[p.scan_index].stamp;
      break;
    }
  }
  std::string init_text = "global localisation";
  if (job.init.kind == InitialBelief::Kind::kPose) {
    loc.set_pose(job.init.pose, belief_covariance(job.init));
    init_text = "--init " + format_pose(job.init.pose);
  } else if (job.init.kind == InitialBelief::Kind::kTruth) {
    std::optional<Pose2> start;
    if (job.truth) {
      io::Trajectory sorted = *job.truth;
      io::sort_by_stamp(sorted);
      start = io::interpolate_at(sorted, first_stamp, 1.0);
      if (!start) {
        const auto i = io::nearest_index(sorted, first_stamp, 0.5);
        if (i) start = sorted[*i].pose;
      }
    }
    if (start) {
      loc.set_pose(*start, belief_covariance(job.init));
      init_text = "ground truth at the first scan " + format_pose(*start);
    } else {
      std::fprintf(stderr,
                   "pgmcl: warning: no ground-truth pose at the first scan (t = %.3f); "
                   "starting with global localisation\n",
                   first_stamp);
    }
  }
  if (!job.quiet) std::fprintf(stderr, "localize: start: %s\n", init_text.c_str());

  io::MetricsAccumulator acc;
  std::vector<UpdateRow> rows;
  rows.reserve(usable);
  io::Trajectory trajectory;
  trajectory.reserve(usable);
  Progress progress = Progress::on_stderr("localize", usable, job.quiet);
  std::size_t done = 0, out_of_order = 0, unpaired = 0;
  double last_stamp = -std::numeric_limits<double>::infinity();
  for (const io::PairedScan& p : paired.scans) {
    if (p.source == io::OdomSource::kNone) {
      ++unpaired;
      continue;
    }
    const io::CarmenScan& s = log.scans[p.scan_index];
    const double stamp = s.stamp;
    if (stamp < last_stamp) {
      ++out_of_order;  // a scan stamped before its predecessor cannot be filtered in order
      continue;
    }
    last_stamp = stamp;
    UpdateResult r;
    try {
      r = loc.update(p.odom, s.scan, stamp);
    } catch (const std::invalid_argument& e) {
      throw io::FormatError(job.log_name, s.line, std::string(io::message_name(s.message)),
                            std::string("rejected by the filter: ") + e.what());
    }
    trajectory.push_back({stamp, r.estimate});
    rows.push_back(UpdateRow::of(stamp, r));
    if (r.skipped == SkipReason::kNone) {
      acc.add_update(r.timings.total_ms, r.particles, r.beams_used, r.fit, r.converged);
    } else {
      acc.add_skipped();
    }
    ++done;
    char extra[96];
    std::snprintf(extra, sizeof extra, "%zu particles%s", r.particles,
                  r.converged ? ", converged" : "");
    progress.update(done, extra);
  }
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  io::RunMetrics m = acc.summarise(wall_s);
  progress.finish();
  if (out_of_order > 0) {
    std::fprintf(stderr,
                 "pgmcl: warning: %s: skipped %zu scan(s) stamped before the previous one\n",
                 job.log_name.c_str(), out_of_order);
  }
  if (unpaired > 0) {
    std::fprintf(stderr, "pgmcl: warning: %s: skipped %zu scan(s) without odometry\n",
                 job.log_name.c_str(), unpaired);
  }

  std::optional<io::AteResult> ate;
  if (job.truth) {
    ate = io::evaluate_ate(trajectory, *job.truth);
    m.accuracy = io::accuracy_metrics(*ate);
    count_false_convergence(rows, *ate, *m.accuracy);
  }
  if (job.relations) {
    io::RelationOptions ro;
    ro.time_offset = job.relations_time_offset;
    m.relations = io::relations_metrics(io::evaluate_relations(trajectory, *job.relations, ro));
  }

  // Results.
  const std::filesystem::path dir = ensure_directory(job.out_dir);
  io::write_tum((dir / "trajectory.tum").string(), trajectory);
  io::write_metrics_yaml((dir / "metrics.yaml").string(), m);
  write_updates_csv((dir / "updates.csv").string(), rows, job.truth ? &*job.truth : nullptr);
  {
    std::ofstream f(dir / "config.yaml");
    f << io::localizer_config_yaml(job.config);
    if (!f) throw io::IoError((dir / "config.yaml").string() + ": write failed");
  }
  std::vector<Pose2> est, truth_path, cloud;
  est.reserve(trajectory.size());
  for (const auto& t : trajectory) est.push_back(t.pose);
  if (job.truth) {
    for (const auto& t : *job.truth) truth_path.push_back(t.pose);
  }
  const ParticlesView pv = loc.particles();
  const std::size_t stride = pv.size() / kMaxDrawnParticles + 1;
  for (std::size_t i = 0; i < pv.size(); i += stride) cloud.push_back(pv.global_pose(i));
  write_overlay_png((dir / "overlay.png").string(), *job.map,
                    OverlayData{truth_path, est, cloud, job.title});
  if (ate && !ate->errors.empty()) {
    write_error_png((dir / "error.png").string(), *ate, trajectory.front().stamp);
  }
  return m;
}

std::string summary_line(const io::RunMetrics& m, const std::string& out_dir) {
  char buf[512];
  int n = std::snprintf(buf, sizeof buf,
                        "localize: %zu updates (%zu skipped), %.2f ms/update (p95 %.2f), "
                        "%zu..%zu particles (mean %.0f), %.0f beams, fit %.2f, converged on "
                        "%.0f %% of updates",
                        m.updates, m.skipped_updates, m.update_ms_mean, m.update_ms_p95,
                        m.particles_min, m.particles_max, m.particles_mean, m.beams_used_mean,
                        m.fit_mean, 100.0 * m.converged_fraction);
  std::string s(buf, static_cast<std::size_t>(std::max(n, 0)));
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
