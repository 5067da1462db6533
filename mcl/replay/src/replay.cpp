#include "pgmcl/replay/replay.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "pgmcl/io/errors.hpp"
#include "pgmcl/io/odometry_pairing.hpp"
#include "pgmcl/io/values.hpp"
#include "pgmcl/mcl/localizer.hpp"

namespace pgmcl::replay {
namespace {

std::string format_pose(const Pose2& p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.3f, %.3f, %.1f deg)", p.x, p.y,
                p.theta * 180.0 / std::numbers::pi);
  return buf;
}

/// Puts the filter in its initial belief; returns how it started, for messages.
std::string start_filter(Localizer& loc, const ReplayJob& job, double first_stamp,
                         std::vector<std::string>& warnings) {
  if (job.init.kind == InitialBelief::Kind::kPose) {
    loc.set_pose(job.init.pose, covariance_of(job.init));
    return "given pose " + format_pose(job.init.pose);
  }
  if (job.init.kind == InitialBelief::Kind::kTruth) {
    std::optional<Pose2> start;
    if (job.truth) {
      io::Trajectory sorted = *job.truth;
      io::sort_by_stamp(sorted);
      start = io::interpolate_at(sorted, first_stamp, 1.0);
      if (!start) {
        if (const auto i = io::nearest_index(sorted, first_stamp, 0.5)) start = sorted[*i].pose;
      }
    }
    if (start) {
      loc.set_pose(*start, covariance_of(job.init));
      return "ground truth at the first scan " + format_pose(*start);
    }
    char buf[160];
    std::snprintf(buf, sizeof buf,
                  "no ground-truth pose at the first scan (t = %.3f); starting with global "
                  "localisation",
                  first_stamp);
    warnings.emplace_back(buf);
  }
  return "global localisation";
}

/// Updates that reported `converged` while more than 1 m off (AteOptions::lost_translation).
void count_false_convergence(const std::vector<UpdateRow>& rows, const io::AteResult& ate,
                             io::AccuracyMetrics& a) {
  const double lost = io::AteOptions{}.lost_translation;
  std::size_t run = 0, j = 0;
  for (const UpdateRow& u : rows) {
    while (j < ate.errors.size() && ate.errors[j].stamp < u.stamp) ++j;
    const bool matched = j < ate.errors.size() && ate.errors[j].stamp == u.stamp;
    const bool wrong = matched && u.skipped == SkipReason::kNone && u.converged &&
                       ate.errors[j].translation > lost;
    run = wrong ? run + 1 : 0;
    a.false_converged += wrong ? 1 : 0;
    a.false_converged_run = std::max(a.false_converged_run, run);
  }
}

}  // namespace

Eigen::Matrix3d covariance_of(const InitialBelief& b) {
  const double sy = b.sigma_y >= 0.0 ? b.sigma_y : b.sigma_xy;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  cov(0, 0) = b.sigma_xy * b.sigma_xy;
  cov(1, 1) = sy * sy;
  cov(2, 2) = b.sigma_theta * b.sigma_theta;
  return cov;
}

UpdateRow UpdateRow::of(double stamp, const UpdateResult& r) {
  UpdateRow u;
  u.stamp = stamp;
  u.estimate = r.estimate;
  u.skipped = r.skipped;
  u.converged = r.converged;
  u.fit = r.fit;
  u.n_eff = r.n_eff;
  u.evidence = r.alternative_evidence;
  u.particles = r.particles;
  u.competitors = r.competitors;
  u.seeded = r.seeded;
  u.injected = r.injected;
  u.switched = r.switched;
  u.searched = r.searched;
  return u;
}

ReplayResult run(const ReplayJob& job, const ReplayHooks& hooks) {
  if (job.map == nullptr || job.log == nullptr)
    throw std::invalid_argument("replay::run: the job needs a map and a log");
  const auto wall0 = std::chrono::steady_clock::now();
  const io::CarmenLog& log = *job.log;
  const io::PairedScans paired = io::pair_odometry(log);
  std::size_t usable = 0;
  double first_stamp = 0.0;
  for (const auto& p : paired.scans) {
    if (p.source == io::OdomSource::kNone) continue;
    if (usable++ == 0) first_stamp = log.scans[p.scan_index].stamp;
  }
  if (usable == 0) {
    throw io::UsageError(job.log_name +
                         ": no laser scan with odometry (need ODOM messages or FLASER/"
                         "ROBOTLASER1 scans, which carry their odometry pose)");
  }

  Localizer loc(*job.map, job.config);
  ReplayResult out;
  out.start = start_filter(loc, job, first_stamp, out.warnings);
  if (hooks.on_start) hooks.on_start(out.start, usable);

  io::MetricsAccumulator acc;
  out.rows.reserve(usable);
  out.trajectory.reserve(usable);
  std::size_t done = 0, out_of_order = 0, unpaired = 0;
  double last_stamp = -std::numeric_limits<double>::infinity();
  for (const io::PairedScan& p : paired.scans) {
    if (hooks.stop != nullptr && hooks.stop->load(std::memory_order_relaxed)) {
      out.complete = false;
      break;
    }
    if (p.source == io::OdomSource::kNone) {
      ++unpaired;
      continue;
    }
    const io::CarmenScan& s = log.scans[p.scan_index];
    if (s.stamp < last_stamp) {
      ++out_of_order;  // a scan stamped before its predecessor cannot be filtered in order
      continue;
    }
    last_stamp = s.stamp;
    UpdateResult r;
    try {
      r = loc.update(p.odom, s.scan, s.stamp);
    } catch (const std::invalid_argument& e) {
      throw io::FormatError(job.log_name, s.line, std::string(io::message_name(s.message)),
                            std::string("rejected by the filter: ") + e.what());
    }
    out.trajectory.push_back({s.stamp, r.estimate});
    out.rows.push_back(UpdateRow::of(s.stamp, r));
    if (r.skipped == SkipReason::kNone) {
      acc.add_update(r.timings.total_ms, r.particles, r.beams_used, r.fit, r.converged);
    } else {
      acc.add_skipped();
    }
    ++done;
    if (hooks.on_update) hooks.on_update(done, usable, r);
  }
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  out.metrics = acc.summarise(wall_s);
  if (out_of_order > 0) {
    out.warnings.push_back(job.log_name + ": skipped " + std::to_string(out_of_order) +
                           " scan(s) stamped before the previous one");
  }
  if (unpaired > 0) {
    out.warnings.push_back(job.log_name + ": skipped " + std::to_string(unpaired) +
                           " scan(s) without odometry");
  }

  if (job.truth && !out.trajectory.empty()) {
    out.ate = io::evaluate_ate(out.trajectory, *job.truth);
    out.metrics.accuracy = io::accuracy_metrics(*out.ate);
    count_false_convergence(out.rows, *out.ate, *out.metrics.accuracy);
  }
  if (job.relations && !out.trajectory.empty()) {
    io::RelationOptions ro;
    ro.time_offset = job.relations_time_offset;
    out.metrics.relations =
        io::relations_metrics(io::evaluate_relations(out.trajectory, *job.relations, ro));
  }
  const ParticlesView pv = loc.particles();
  out.particles.reserve(pv.size());
  for (std::size_t i = 0; i < pv.size(); ++i) out.particles.push_back(pv.global_pose(i));
  out.weights.assign(pv.weight.begin(), pv.weight.end());
  return out;
}

}  // namespace pgmcl::replay
