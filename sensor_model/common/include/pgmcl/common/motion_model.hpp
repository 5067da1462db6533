#pragma once
/// Odometry motion models, Probabilistic Robotics (Thrun, Burgard, Fox), Table 5.6
/// (sample_motion_model_odometry) and its omnidirectional variant.
///
/// Alphas are in *variance form*, as in Table 5.6:
///   var(rot1)  = a1 * rot1^2  + a2 * trans^2
///   var(trans) = a3 * trans^2 + a4 * (rot1^2 + rot2^2)
///   var(rot2)  = a1 * rot2^2  + a2 * trans^2
/// Units: a1 [rad^2/rad^2], a2 [rad^2/m^2], a3 [m^2/m^2], a4 [m^2/rad^2], a5 [m^2/m^2].
///
/// The omnidirectional model (same alphas; after nav2_amcl's omni model, in variance form)
/// splits the translation along and across the direction of travel, rot = rot1 + rot2:
///   var(along)  = a3 * trans^2 + a4 * rot^2
///   var(across) = a5 * trans^2 + a4 * rot^2
///   var(rot)    = a1 * rot^2   + a2 * trans^2
/// and applies the noisy increment by SE(2) composition in the particle's frame.

#include <cstddef>

#include "pgmcl/common/random.hpp"
#include "pgmcl/common/se2.hpp"

namespace pgmcl {

enum class MotionModelKind : unsigned char { kDifferentialDrive, kOmnidirectional };

struct MotionNoise {
  double a1 = 0.005;   ///< rotation noise from rotation (variance form)
  double a2 = 0.0005;  ///< rotation noise from translation
  double a3 = 0.005;   ///< translation noise from translation
  double a4 = 0.0005;  ///< translation noise from rotation
  double a5 = 0.0005;  ///< omnidirectional only: strafe noise from translation
};

/// The odometry increment decomposed as in Table 5.6.
struct OdometryIncrement {
  double rot1 = 0.0;       ///< radians
  double trans = 0.0;      ///< metres, >= 0
  double rot2 = 0.0;       ///< radians
  bool backwards = false;  ///< motion opposite to the heading (rot1 flipped by pi)
};

/// Decomposes odom_prev -> odom_now. Pure rotations (trans below 1e-6 m) give rot1 = 0
/// and rot2 = the whole rotation, so no spurious atan2 of a zero vector. Backward motion
/// (the translation points behind the robot) is decomposed with rot1 measured from the
/// reversed heading, |rot1| <= pi/2, and `backwards` set so trans is applied as negative
/// motion, as in nav2's "reverse" handling: a reversing robot is not rotate-pi, drive,
/// rotate-pi (which would inflate the rotation noise by a1 * pi^2).
[[nodiscard]] OdometryIncrement decompose_odometry(const Pose2& odom_prev,
                                                   const Pose2& odom_now) noexcept;

/// What the rotation noise of `inc` grows with: rot1^2 + rot2^2 as the differential-drive
/// draw scales them (on steps shorter than 5 cm rot1, set by pose jitter, is counted as part
/// of rot2), or the omnidirectional rotation squared. The variance form's a1 and a4 multiply it.
[[nodiscard]] double rotation_moment(MotionModelKind kind, const OdometryIncrement& inc) noexcept;

/// Samples a new pose for one particle: Table 5.6 for differential drive, or the
/// omnidirectional model (independent noise on forward/strafe translation and rotation).
/// `pose` is in any fixed frame (the filter uses the map-local frame); theta is wrapped.
[[nodiscard]] Pose2 sample_motion(MotionModelKind kind, const MotionNoise& noise,
                                  const Pose2& odom_prev, const Pose2& odom_now, const Pose2& pose,
                                  Rng& rng) noexcept;

/// The same draw from an increment decomposed once per update: the filter calls
/// decompose_odometry() once and this per particle, so no atan2/hypot per particle.
/// Zero motion (rot1 = trans = rot2 = 0) has zero variance in every term, so the pose is
/// returned unchanged and no random numbers are consumed.
[[nodiscard]] Pose2 sample_motion(MotionModelKind kind, const MotionNoise& noise,
                                  const OdometryIncrement& inc, const Pose2& pose,
                                  Rng& rng) noexcept;

/// Perturbs a true odometry increment (true_prev -> true_now) the way wheel odometry
/// would: returns a noisy increment (in the robot frame at true_prev) drawn from the same
/// model. Used by the simulator and `pgmcl perturb` to make noisy odometry from ground truth.
[[nodiscard]] Pose2 sample_noisy_increment(MotionModelKind kind, const MotionNoise& noise,
                                           const Pose2& true_prev, const Pose2& true_now,
                                           Rng& rng) noexcept;

}  // namespace pgmcl
