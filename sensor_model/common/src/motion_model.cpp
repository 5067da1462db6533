#include "pgmcl/common/motion_model.hpp"

#include <cmath>
#include <numbers>

namespace pgmcl {
namespace {

/// Below this the translation direction is numerical noise: treat as a pure rotation.
constexpr double kMinTranslation = 1e-6;  // metres

/// Below this translation rot1 = atan2(dy, dx) is set by pose jitter, not motion, yet Table
/// 5.6 scales the noise with rot1^2; the noise is computed as if the turn happened in rot2,
/// fading back to Table 5.6 at this length (nav2_amcl does the same below 1 cm; why 5 cm:
/// configs/experiments/README.md, "Why the defaults").
constexpr double kBearingTranslation = 0.05;  // metres

/// Standard deviation from a variance-form sum; the sum of non-negative terms is >= 0
/// unless an alpha is negative, which we read as zero noise rather than NaN.
[[nodiscard]] inline double sigma_of(double variance) noexcept {
  return variance > 0.0 ? std::sqrt(variance) : 0.0;
}

/// The rotations the noise scales with (kBearingTranslation): Table 5.6's own for t >= 5 cm.
struct NoiseRotations {
  double r1, r2;
};
[[nodiscard]] NoiseRotations noise_rotations(const OdometryIncrement& inc) noexcept {
  const double r1 =
      inc.trans < kBearingTranslation ? inc.rot1 * (inc.trans / kBearingTranslation) : inc.rot1;
  return {r1, inc.rot2 + (inc.rot1 - r1)};
}

/// Probabilistic Robotics, Table 5.6, lines 5-10.
[[nodiscard]] Pose2 sample_diff_drive(const MotionNoise& n, const OdometryIncrement& inc,
                                      const Pose2& pose, Rng& rng) noexcept {
  const double r1 = inc.rot1, t = inc.trans, r2 = inc.rot2;
  const auto [r1_n, r2_n] = noise_rotations(inc);
  const double r1_sq = r1_n * r1_n, t_sq = t * t, r2_sq = r2_n * r2_n;
  // Fixed draw order (rot1, trans, rot2) keeps a seed's stream reproducible.
  const double r1_hat = r1 + rng.normal(sigma_of(n.a1 * r1_sq + n.a2 * t_sq));
  const double t_hat = t + rng.normal(sigma_of(n.a3 * t_sq + n.a4 * (r1_sq + r2_sq)));
  const double r2_hat = r2 + rng.normal(sigma_of(n.a1 * r2_sq + n.a2 * t_sq));
  const double signed_t = inc.backwards ? -t_hat : t_hat;
  const double heading = pose.theta + r1_hat;
  return {pose.x + signed_t * std::cos(heading), pose.y + signed_t * std::sin(heading),
          wrap_angle(pose.theta + r1_hat + r2_hat)};
}

/// Omnidirectional variant (see the header): noise along and across the direction of
/// travel, then the noisy increment composed onto the particle.
[[nodiscard]] Pose2 sample_omni(const MotionNoise& n, const OdometryIncrement& inc,
                                const Pose2& pose, Rng& rng) noexcept {
  const double t = inc.trans;
  const double rot = wrap_angle(inc.rot1 + inc.rot2);
  const double t_sq = t * t, rot_sq = rot * rot;
  const double along = t + rng.normal(sigma_of(n.a3 * t_sq + n.a4 * rot_sq));
  const double across = rng.normal(sigma_of(n.a5 * t_sq + n.a4 * rot_sq));
  const double rot_hat = rot + rng.normal(sigma_of(n.a1 * rot_sq + n.a2 * t_sq));
  // Direction of travel in the robot frame at the start of the step.
  const double dir = inc.backwards ? inc.rot1 + std::numbers::pi : inc.rot1;
  const double c = std::cos(dir), s = std::sin(dir);
  return pose.compose({c * along - s * across, s * along + c * across, rot_hat});
}

}  // namespace

double rotation_moment(MotionModelKind kind, const OdometryIncrement& inc) noexcept {
  if (kind == MotionModelKind::kOmnidirectional) {
    const double rot = wrap_angle(inc.rot1 + inc.rot2);
    return rot * rot;
  }
  const auto [r1, r2] = noise_rotations(inc);
  return r1 * r1 + r2 * r2;
}

OdometryIncrement decompose_odometry(const Pose2& odom_prev, const Pose2& odom_now) noexcept {
  // Working in the frame of odom_prev makes rot1 = atan2(dy, dx) of the local increment,
  // the same as Table 5.6's atan2(y' - y, x' - x) - theta but without a world-frame wrap.
  const Pose2 d = odom_prev.between(odom_now);
  OdometryIncrement inc;
  const double trans = std::hypot(d.x, d.y);
  if (trans < kMinTranslation) {
    inc.rot2 = wrap_angle(d.theta);  // pure rotation; the sub-micrometre shift is dropped
    return inc;
  }
  double rot1 = std::atan2(d.y, d.x);
  if (std::abs(rot1) > 0.5 * std::numbers::pi) {
    inc.backwards = true;
    rot1 = wrap_angle(rot1 + std::numbers::pi);
  }
  inc.rot1 = rot1;
  inc.trans = trans;
  inc.rot2 = wrap_angle(d.theta - rot1);
  return inc;
}

Pose2 sample_motion(MotionModelKind kind, const MotionNoise& noise, const OdometryIncrement& inc,
                    const Pose2& pose, Rng& rng) noexcept {
  return kind == MotionModelKind::kOmnidirectional ? sample_omni(noise, inc, pose, rng)
                                                   : sample_diff_drive(noise, inc, pose, rng);
}

Pose2 sample_motion(MotionModelKind kind, const MotionNoise& noise, const Pose2& odom_prev,
                    const Pose2& odom_now, const Pose2& pose, Rng& rng) noexcept {
  return sample_motion(kind, noise, decompose_odometry(odom_prev, odom_now), pose, rng);
}

Pose2 sample_noisy_increment(MotionModelKind kind, const MotionNoise& noise, const Pose2& true_prev,
                             const Pose2& true_now, Rng& rng) noexcept {
  // Sampling from the identity pose yields the noisy increment in true_prev's frame.
  return sample_motion(kind, noise, true_prev, true_now, Pose2{}, rng);
}

}  // namespace pgmcl
