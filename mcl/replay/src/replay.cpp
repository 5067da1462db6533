#include "pgmcl/replay/replay.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
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

/// Faster than any robot these logs come from: a step that implies more is a glitch. Stamps
/// can be coarse (whole seconds) or shared, so a step is timed over at least kMinJumpTime.
constexpr double kMaxSpeed = 10.0;    ///< m/s
constexpr double kMinJumpTime = 1.0;  ///< seconds
/// Below this mean fit (UpdateResult::fit) the scans hardly matched the map: a tracked run
/// on a right map scores 0.9 and more (0.81 at worst over bench/robustness's 320 runs),
/// while a wrong map can still reach 0.4 once the filter finds the places fitting best.
constexpr double kLowFit = 0.5;
/// Updates after which a filter that never once converged is worth a warning.
constexpr std::size_t kConvergenceUpdates = 50;

/// Faster than any mobile robot turns (about 3 rad/s at most); timed over kMinJumpTime it is
/// also above the 2π by which a wrapped heading steps when it wraps.
constexpr double kMaxTurnRate = 10.0;  ///< rad/s

/// Steps of one kind (metres or radians) past their limit, and the largest of them.
struct StepTally {
  std::size_t count = 0;
  double largest = 0.0, largest_dt = 0.0;
  std::size_t largest_line = 0;

  void add(double step, double dt, std::size_t line) {
    ++count;
    if (step > largest) {
      largest = step;
      largest_dt = dt;
      largest_line = line;
    }
  }
  void merge(const StepTally& other) {
    count += other.count;
    if (other.largest > largest) {
      largest = other.largest;
      largest_dt = other.largest_dt;
      largest_line = other.largest_line;
    }
  }
};

/// How far one odometry pose is from the next: metres driven, or radians turned (headings
/// as given, so an unwrapped glitch keeps its size).
double distance_between(const Pose2& a, const Pose2& b) {
  return std::hypot(b.x - a.x, b.y - a.y);
}
double turn_between(const Pose2& a, const Pose2& b) {
  return std::abs(b.theta - a.theta);
}

/// Counts steps between consecutive odometry records that no robot makes: `step` of them
/// beyond `max_rate` per second.
struct JumpCounter {
  double (*step)(const Pose2&, const Pose2&);
  double max_rate;
  StepTally tally{};
  std::optional<io::StampedPose> last{};

  void add(const Pose2& odom, double stamp, std::size_t line) {
    if (last) {
      const double d = step(last->pose, odom);
      const double dt = stamp - last->stamp;
      if (d > max_rate * std::max(dt, kMinJumpTime)) tally.add(d, dt, line);
    }
    last = io::StampedPose{stamp, odom};
  }
};

/// Heading jumps in the odometry records the pairing used, the ODOM messages and the scans'
/// own odometry fields, each stream on its own and with headings as logged: wrapped, a
/// heading glitch of 1e6 rad looks like any turn.
StepTally heading_jumps(const io::CarmenLog& log, const io::PairedScans& paired) {
  JumpCounter odom{&turn_between, kMaxTurnRate}, fields{&turn_between, kMaxTurnRate};
  for (const io::OdomRecord& r : log.odometry) {
    odom.add({r.pose.x, r.pose.y, r.logged_theta}, r.stamp, r.line);
  }
  for (const io::PairedScan& p : paired.scans) {
    const io::CarmenScan& s = log.scans[p.scan_index];
    if (p.source == io::OdomSource::kScanFields) {
      fields.add({s.odom_pose.x, s.odom_pose.y, s.logged_odom_theta}, s.stamp, s.line);
    }
  }
  odom.tally.merge(fields.tally);
  return odom.tally;
}

std::string g(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
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
  u.rotation_noise_factor = r.rotation_noise_factor;
  u.translation_noise_factor = r.translation_noise_factor;
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
    std::string why;
    if (!log.report.malformed_lines.empty()) {
      // Every scan may have been dropped as malformed: that, not the log's layout, is the news.
      const io::LineIssue& i = log.report.malformed_lines.front();
      why = "; " + std::to_string(log.report.malformed) +
            " malformed line(s) were dropped, the first " + job.log_name + ":" +
            std::to_string(i.line) + ": " + i.message_type + " " + i.field + ": " + i.message;
    }
    throw io::UsageError(job.log_name +
                         ": no laser scan with odometry (need ODOM messages or FLASER/"
                         "ROBOTLASER1 scans, which carry their odometry pose)" +
                         why);
  }

  Localizer loc(*job.map, job.config);
  ReplayResult out;
  out.start = start_filter(loc, job, first_stamp, out.warnings);
  if (hooks.on_start) hooks.on_start(out.start, usable);

  io::MetricsAccumulator acc;
  out.rows.reserve(usable);
  out.trajectory.reserve(usable);
  std::size_t done = 0, out_of_order = 0, unpaired = 0;
  JumpCounter jumps{&distance_between, kMaxSpeed};
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
    jumps.add(p.odom, s.stamp, s.line);
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
      acc.set_noise_factors(r.rotation_noise_factor, r.translation_noise_factor);
    } else {
      acc.add_skipped();
    }
    ++done;
    if (hooks.on_update) hooks.on_update(done, usable, r);
  }
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  out.metrics = acc.summarise(wall_s);
  out.metrics.complete = out.complete;
  if (paired.report.shared_stamps > 0) {
    out.warnings.push_back(
        job.log_name + ": " + std::to_string(paired.report.shared_stamps) +
        " scan(s) share their timestamp with other scans or with several ODOM messages (first "
        "on line " +
        std::to_string(paired.report.first_shared_line) +
        "), so time cannot order this log: " + std::to_string(paired.report.by_file_order) +
        " scan(s) were paired with the ODOM message before them in the file");
  }
  if (paired.report.odom_repeated_stamps > 0) {
    out.warnings.push_back(
        job.log_name + ": " + std::to_string(paired.report.odom_repeated_stamps) +
        " ODOM message(s) carry the same stamp as the one before (first on line " +
        std::to_string(paired.report.first_repeated_odom_line) +
        "): rounded stamps? Scans between them get the later one's odometry");
  }
  if (const StepTally& m = jumps.tally; m.count > 0) {
    out.warnings.push_back(
        job.log_name + ": " + std::to_string(m.count) + " odometry jump(s) faster than " +
        g(kMaxSpeed) + " m/s between consecutive scans (largest " + g(m.largest) + " m in " +
        g(m.largest_dt) + " s, at the scan on line " + std::to_string(m.largest_line) +
        "); the filter moves its particles by them and is likely lost there");
  }
  if (const StepTally t = heading_jumps(log, paired); t.count > 0) {
    out.warnings.push_back(
        job.log_name + ": " + std::to_string(t.count) + " odometry heading jump(s) faster than " +
        g(kMaxTurnRate) + " rad/s between consecutive odometry records (largest " + g(t.largest) +
        " rad in " + g(t.largest_dt) + " s, on line " + std::to_string(t.largest_line) +
        "); the filter turns its particles by them and is likely lost there");
  }
  const std::size_t all = out.metrics.updates + out.metrics.skipped_updates;
  if (all >= 10 && out.metrics.updates * 10 < all) {
    std::size_t not_moved = 0, no_beams = 0;
    for (const UpdateRow& u : out.rows) {
      not_moved += u.skipped == SkipReason::kNotMoved ? 1 : 0;
      no_beams += u.skipped == SkipReason::kNoValidBeams ? 1 : 0;
    }
    out.warnings.push_back("the filter measured only " + std::to_string(out.metrics.updates) +
                           " of " + std::to_string(all) + " scans (" + std::to_string(not_moved) +
                           " gated: the odometry moved less than gating.d_min / theta_min; " +
                           std::to_string(no_beams) +
                           " without a valid reading: check likelihood.beam.max_range and the "
                           "ranges), so the trajectory is mostly dead reckoning");
  } else if (out.metrics.updates >= 10 && out.metrics.fit_mean < kLowFit) {
    out.warnings.push_back(
        "the scans hardly matched the map: mean fit " + g(out.metrics.fit_mean) + " over " +
        std::to_string(out.metrics.updates) +
        " updates (the fraction of beams ending near a mapped wall; 0.9 and more when "
        "tracking on the right map), so the estimate means little. Check the map (the right "
        "one? resolution, origin, mode, negate) and the start pose");
  } else if (out.metrics.updates >= kConvergenceUpdates && out.metrics.converged_fraction == 0.0) {
    out.warnings.push_back("the filter never converged in " + std::to_string(out.metrics.updates) +
                           " updates, so the estimate is a guess. Check the map (negate?) and "
                           "the start pose");
  }
  if (out_of_order > 0) {
    out.warnings.push_back(job.log_name + ": skipped " + std::to_string(out_of_order) +
                           " scan(s) stamped before the previous one");
  }
  if (unpaired > 0) {
    out.warnings.push_back(job.log_name + ": skipped " + std::to_string(unpaired) +
                           " scan(s) without odometry");
  }

  // Figures over nothing would read as a perfect 0: say so and leave them out instead.
  if (job.truth && !out.trajectory.empty()) {
    io::AteResult ate = io::evaluate_ate(out.trajectory, *job.truth);
    if (ate.matched == 0) {
      out.warnings.push_back("the ground truth matched none of the " +
                             std::to_string(out.trajectory.size()) +
                             " estimated poses in time (a different log, or another clock?); "
                             "no accuracy figures");
    } else {
      if (const std::string w = io::ate_match_warning(ate); !w.empty())
        out.warnings.push_back(job.log_name + " against the ground truth: " + w);
      out.ate = std::move(ate);
      out.metrics.accuracy = io::accuracy_metrics(*out.ate);
      count_false_convergence(out.rows, *out.ate, *out.metrics.accuracy);
    }
  }
  if (job.relations && !out.trajectory.empty()) {
    io::RelationOptions ro;
    ro.time_offset = job.relations_time_offset;
    const io::RelationResult rel = io::evaluate_relations(out.trajectory, *job.relations, ro);
    if (rel.matched == 0) {
      char offset[64];
      std::snprintf(offset, sizeof offset, "%.3f", io::kIntelRelationsTimeOffset);
      out.warnings.push_back("none of the " + std::to_string(rel.relations) +
                             " relations matched the estimate's stamps (does the log need a "
                             "time offset? intel: " +
                             offset + " s); no relations figures");
    } else {
      out.metrics.relations = io::relations_metrics(rel);
    }
  }
  out.metrics.warnings = out.warnings;
  const ParticlesView pv = loc.particles();
  out.particles.reserve(pv.size());
  for (std::size_t i = 0; i < pv.size(); ++i) out.particles.push_back(pv.global_pose(i));
  out.weights.assign(pv.weight.begin(), pv.weight.end());
  return out;
}

}  // namespace pgmcl::replay
