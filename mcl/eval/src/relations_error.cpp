#include "pgmcl/eval/relations_error.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <utility>

namespace pgmcl::io {
namespace {

/// The estimate's pose at relation time `t` (estimate clock = t - offset), and how far in
/// time the pose used is from it (0 when interpolated).
std::optional<std::pair<Pose2, double>> pose_at(const Trajectory& est, double t,
                                                const RelationOptions& opt) {
  const double local = t - opt.time_offset;
  if (opt.interpolate) {
    if (const auto p = interpolate_at(est, local, opt.max_gap)) return std::pair{*p, 0.0};
  }
  const auto i = nearest_index(est, local, opt.tolerance);
  if (!i) return std::nullopt;
  return std::pair{est[*i].pose, std::abs(est[*i].stamp - local)};
}

}  // namespace

RelationResult evaluate_relations(const Trajectory& estimate,
                                  const std::vector<Relation>& relations,
                                  const RelationOptions& opt) {
  Trajectory est = estimate;
  sort_by_stamp(est);
  RelationResult res;
  res.relations = relations.size();
  std::vector<double> trans, trans_sq, rot, rot_sq;
  constexpr double kRadToDeg = 180.0 / std::numbers::pi;
  for (const Relation& r : relations) {
    if (std::abs(r.t2 - r.t1) <= opt.tolerance) {
      ++res.degenerate;
      continue;
    }
    const auto a = pose_at(est, r.t1, opt);
    const auto b = pose_at(est, r.t2, opt);
    if (!a || !b) continue;
    res.max_time_error = std::max({res.max_time_error, a->second, b->second});
    // Kümmerle et al. 2009: error of relation (i, j) is delta_ij (-) delta*_ij, with
    // a (-) b = b^-1 (+) a, i.e. the estimated relative pose seen from the reference one.
    const Pose2 delta_est = a->first.between(b->first);
    const Pose2 e = r.delta.inverse().compose(delta_est);
    const double t = std::hypot(e.x, e.y);
    const double d = std::abs(wrap_angle(e.theta)) * kRadToDeg;
    res.errors.push_back({r.t1, r.t2, t, d});
    trans.push_back(t);
    trans_sq.push_back(t * t);
    rot.push_back(d);
    rot_sq.push_back(d * d);
  }
  res.matched = res.errors.size();
  res.unmatched = res.relations - res.matched - res.degenerate;
  res.translation = error_stats(trans);
  res.translation_sq = error_stats(trans_sq);
  res.rotation = error_stats(rot);
  res.rotation_sq = error_stats(rot_sq);
  return res;
}

}  // namespace pgmcl::io
