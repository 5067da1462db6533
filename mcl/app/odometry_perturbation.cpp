#include "odometry_perturbation.hpp"

#include <cmath>
#include <numbers>

#include "perturb_random.hpp"

namespace pgmcl::app {
namespace {

/// Systematic odometry error on one increment (robot frame at the previous pose): the
/// translation is scaled by (1 + scale) and the heading drifts by yaw_per_m per metre.
Pose2 apply_bias(const Pose2& inc, double scale, double yaw_per_m) {
  const double dist = std::hypot(inc.x, inc.y);
  return {inc.x * (1.0 + scale), inc.y * (1.0 + scale), wrap_angle(inc.theta + yaw_per_m * dist)};
}

double sigma_of(double variance) noexcept {
  return variance > 0.0 ? std::sqrt(variance) : 0.0;
}

}  // namespace

Pose2 sample_textbook_increment(const MotionNoise& n, const Pose2& true_prev, const Pose2& true_now,
                                Rng& rng) noexcept {
  const Pose2 d = true_prev.between(true_now);
  // Table 5.6, lines 2-4. In true_prev's frame atan2(y' - y, x' - x) - theta is atan2(dy, dx).
  const double rot1 = std::atan2(d.y, d.x);
  const double trans = std::hypot(d.x, d.y);
  const double rot2 = wrap_angle(d.theta - rot1);
  // Lines 5-7, variance form; the book subtracts the sample, drawn in this order.
  const double r1_sq = rot1 * rot1, t_sq = trans * trans, r2_sq = rot2 * rot2;
  const double rot1_hat = rot1 - rng.normal(sigma_of(n.a1 * r1_sq + n.a2 * t_sq));
  const double trans_hat = trans - rng.normal(sigma_of(n.a3 * t_sq + n.a4 * (r1_sq + r2_sq)));
  const double rot2_hat = rot2 - rng.normal(sigma_of(n.a1 * r2_sq + n.a2 * t_sq));
  // Lines 8-10 from the identity pose.
  return {trans_hat * std::cos(rot1_hat), trans_hat * std::sin(rot1_hat),
          wrap_angle(rot1_hat + rot2_hat)};
}

PerturbedOdometry perturb_odometry(const io::Trajectory& truth, const OdometryPerturbation& p,
                                   std::uint64_t seed) {
  PerturbedOdometry out;
  if (truth.empty()) return out;
  Rng rng(seed);
  Rng heading_rng = perturb_rng(seed, PerturbStream::kHeadingGlitch);
  Rng slip_rng = perturb_rng(seed, PerturbStream::kTranslationGlitch);
  io::Trajectory& odom = out.odometry;
  odom.resize(truth.size());
  odom[0] = truth[0];
  for (std::size_t i = 1; i < truth.size(); ++i) {
    const Pose2& prev = truth[i - 1].pose;
    const Pose2& now = truth[i].pose;
    Pose2 inc =
        p.model == OdometryModel::kTextbook
            ? sample_textbook_increment(p.noise, prev, now, rng)
            : sample_noisy_increment(MotionModelKind::kDifferentialDrive, p.noise, prev, now, rng);
    inc = apply_bias(inc, p.scale_bias, p.yaw_drift);
    // One decision draw per step from each stream, so a step's glitch does not depend on
    // whether earlier steps had one.
    if (heading_rng.uniform() < p.heading_glitch.rate) {
      const double magnitude = heading_rng.uniform(0.8, 1.0) * p.heading_glitch.size;
      const double g = heading_rng.uniform() < 0.5 ? -magnitude : magnitude;
      inc = Pose2{0.0, 0.0, g}.compose(inc);
      ++out.heading_glitches;
    }
    if (slip_rng.uniform() < p.translation_glitch.rate) {
      const double dir = slip_rng.uniform(-std::numbers::pi, std::numbers::pi);
      inc.x += p.translation_glitch.size * std::cos(dir);
      inc.y += p.translation_glitch.size * std::sin(dir);
      ++out.translation_glitches;
    }
    odom[i].stamp = truth[i].stamp;
    odom[i].pose = odom[i - 1].pose.compose(inc);
    out.travelled += std::hypot(now.x - prev.x, now.y - prev.y);
  }
  return out;
}

}  // namespace pgmcl::app
