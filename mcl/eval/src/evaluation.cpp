#include "pgmcl/eval/evaluation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <span>

namespace pgmcl::io {
namespace {

std::optional<Pose2> truth_at(const Trajectory& truth, double stamp, const AteOptions& opt) {
  if (opt.association == Association::kInterpolate) {
    if (const auto p = interpolate_at(truth, stamp, opt.max_gap)) return p;
  }
  if (const auto i = nearest_index(truth, stamp, opt.tolerance)) return truth[*i].pose;
  return std::nullopt;
}

}  // namespace

AteResult evaluate_ate(const Trajectory& estimate, const Trajectory& truth, const AteOptions& opt) {
  Trajectory est = estimate;
  Trajectory ref = truth;
  sort_by_stamp(est);
  sort_by_stamp(ref);
  AteResult res;
  res.estimated = est.size();
  constexpr double kRadToDeg = 180.0 / std::numbers::pi;
  std::vector<double> trans, rot;
  std::vector<Pose2> matched_truth;
  for (const StampedPose& e : est) {
    const auto t = truth_at(ref, e.stamp + opt.time_offset, opt);
    if (!t) continue;
    matched_truth.push_back(*t);
    const PoseError pe{e.stamp, std::hypot(e.pose.x - t->x, e.pose.y - t->y),
                       std::abs(wrap_angle(e.pose.theta - t->theta)) * kRadToDeg};
    res.errors.push_back(pe);
    trans.push_back(pe.translation);
    rot.push_back(pe.rotation_deg);
  }
  res.matched = res.errors.size();
  res.unmatched = res.estimated - res.matched;
  if (!ref.empty()) {
    res.truth_from = ref.front().stamp;
    res.truth_to = ref.back().stamp;
  }
  if (!res.errors.empty()) {
    // Nearest-pose matching may reach past the truth's ends by the tolerance: clamp.
    res.covered_from =
        std::clamp(res.errors.front().stamp + opt.time_offset, res.truth_from, res.truth_to);
    res.covered_to =
        std::clamp(res.errors.back().stamp + opt.time_offset, res.truth_from, res.truth_to);
    const double span = res.truth_to - res.truth_from;
    res.truth_covered_fraction = span > 0.0 ? (res.covered_to - res.covered_from) / span : 1.0;
  }
  res.translation = error_stats(trans);
  res.heading = error_stats(rot);

  if (!res.errors.empty()) {
    // Scan backwards for the last pose outside the thresholds.
    std::size_t first_good = res.errors.size();
    while (first_good > 0) {
      const PoseError& pe = res.errors[first_good - 1];
      if (pe.translation > opt.converged_translation ||
          pe.rotation_deg > opt.converged_rotation_deg) {
        break;
      }
      --first_good;
    }
    if (first_good < res.errors.size()) {
      res.converged_after_s =
          first_good == 0 ? 0.0 : res.errors[first_good].stamp - est.front().stamp;
    }
    std::size_t lock = res.errors.size();
    while (lock > 0 && res.errors[lock - 1].translation <= opt.lost_translation) --lock;
    if (lock < res.errors.size()) {
      res.lock_on_s = lock == 0 ? 0.0 : res.errors[lock].stamp - est.front().stamp;
      for (std::size_t i = 1; i <= lock; ++i)
        res.lock_on_travel_m += std::hypot(matched_truth[i].x - matched_truth[i - 1].x,
                                           matched_truth[i].y - matched_truth[i - 1].y);
      res.post_lock_translation = error_stats(std::span<const double>(trans).subspan(lock));
      res.post_lock_heading = error_stats(std::span<const double>(rot).subspan(lock));
    }
  }
  return res;
}

std::string ate_match_warning(const AteResult& ate, const AteOptions& opt) {
  if (ate.matched >= ate.estimated) return {};
  char buf[400];
  const char* how = opt.association == Association::kInterpolate
                        ? "interpolated between truth poses at most %.3g s apart, else the "
                          "nearest within %.3g s"
                        : "the nearest within %.3g s";
  char rule[200];
  if (opt.association == Association::kInterpolate) {
    std::snprintf(rule, sizeof rule, how, opt.max_gap, opt.tolerance);
  } else {
    std::snprintf(rule, sizeof rule, how, opt.tolerance);
  }
  std::snprintf(buf, sizeof buf,
                "only %zu of %zu estimate poses (%.0f %%) have a ground-truth pose (%s); the "
                "figures cover only those",
                ate.matched, ate.estimated,
                ate.estimated
                    ? 100.0 * static_cast<double>(ate.matched) / static_cast<double>(ate.estimated)
                    : 0.0,
                rule);
  return buf;
}

std::string truth_coverage_warning(const AteResult& ate) {
  // Two recordings of one run rarely start and stop on the same sample.
  constexpr double kWholeTruth = 0.95;
  if (ate.matched == 0 || ate.truth_covered_fraction >= kWholeTruth) return {};
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "the matched estimate poses cover only %.0f %% of the ground truth's time span "
                "(%.3f to %.3f s of %.3f to %.3f s); the figures score only that part of the run",
                100.0 * ate.truth_covered_fraction, ate.covered_from, ate.covered_to,
                ate.truth_from, ate.truth_to);
  return buf;
}

}  // namespace pgmcl::io
