#include "pgmcl/io/evaluation.hpp"

#include <cmath>
#include <numbers>

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
  for (const StampedPose& e : est) {
    const auto t = truth_at(ref, e.stamp + opt.time_offset, opt);
    if (!t) continue;
    const PoseError pe{e.stamp, std::hypot(e.pose.x - t->x, e.pose.y - t->y),
                       std::abs(wrap_angle(e.pose.theta - t->theta)) * kRadToDeg};
    res.errors.push_back(pe);
    trans.push_back(pe.translation);
    rot.push_back(pe.rotation_deg);
  }
  res.matched = res.errors.size();
  res.unmatched = res.estimated - res.matched;
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
  }
  return res;
}

}  // namespace pgmcl::io
