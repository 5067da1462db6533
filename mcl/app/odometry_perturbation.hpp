#pragma once
/// `pgmcl perturb`'s odometry: a noisy odometry chain made from ground-truth increments.
///
/// Per step (from one kept scan's true pose to the next), in this order:
///  1. a noisy increment from the odometry model, in the robot frame at the step's start:
///     `pgmcl` = sample_noisy_increment (Probabilistic Robotics Table 5.6 with pgmcl's
///     backward-motion flip and small-translation bearing fade), or `textbook` = Table 5.6
///     taken literally (sample_textbook_increment);
///  2. the systematic bias: translation scaled by (1 + scale_bias), heading += yaw_drift per
///     metre of the increment's translation;
///  3. a heading glitch, with probability heading_glitch.rate: g of magnitude uniform in
///     [0.8, 1] * heading_glitch.size and random sign, applied at the start of the step,
///     inc = Pose2{0, 0, g} ∘ inc, so the translation direction is off by g too (what a
///     mis-sampled rot1 does in Table 5.6);
///  4. a translation glitch, with probability translation_glitch.rate: translation_glitch.size
///     metres added in a uniformly random direction (a wheel slip, a small kidnap);
/// then chained onto the previous odometry pose; the chain starts at the first true pose.
/// Step 1 draws from Rng(seed), steps 3 and 4 from their own streams (perturb_random.hpp).

#include <cstddef>
#include <cstdint>

#include "pgmcl/common/motion_model.hpp"
#include "pgmcl/common/random.hpp"
#include "pgmcl/common/se2.hpp"
#include "pgmcl/io/trajectory.hpp"

namespace pgmcl::app {

enum class OdometryModel : unsigned char {
  kPgmcl,     ///< sample_noisy_increment (mcl/src/motion_model.cpp)
  kTextbook,  ///< sample_textbook_increment
};

/// A random event per odometry step.
struct StepGlitch {
  double rate = 0.0;  ///< probability per step, in [0, 1]
  double size = 0.0;  ///< heading: largest magnitude, radians; translation: metres
};

struct OdometryPerturbation {
  MotionNoise noise{.a1 = 0.0, .a2 = 0.0, .a3 = 0.0, .a4 = 0.0, .a5 = 0.0};  ///< variance form
  OdometryModel model = OdometryModel::kPgmcl;
  double scale_bias = 0.0;  ///< translation reads (1 + scale_bias) times the truth; > -1
  double yaw_drift = 0.0;   ///< radians of heading error per metre of translation
  StepGlitch heading_glitch;
  StepGlitch translation_glitch;
};

/// The odometry chain and what went into it.
struct PerturbedOdometry {
  io::Trajectory odometry;  ///< one pose per truth pose, same stamps
  std::size_t heading_glitches = 0;
  std::size_t translation_glitches = 0;
  double travelled = 0.0;  ///< metres, sum of the true step lengths
};

/// Probabilistic Robotics, Table 5.6 (sample_motion_model_odometry) as printed, differential
/// drive, from the identity pose (so the result is the noisy increment in true_prev's frame):
/// rot1 = atan2(y' - y, x' - x) - theta (computed in true_prev's frame), trans, rot2 =
/// theta' - theta - rot1 (wrapped). No backward-motion flip and no small-translation fade: a
/// short backward move has rot1 ≈ ±pi and gets sqrt(a1) * pi of rot1 noise, and a robot
/// turning in place on a few millimetres of jitter gets a random-looking rot1. That is the
/// glitch naive odometry models produce, kept here on purpose.
[[nodiscard]] Pose2 sample_textbook_increment(const MotionNoise& noise, const Pose2& true_prev,
                                              const Pose2& true_now, Rng& rng) noexcept;

/// The chain for `truth` (at least one pose). Same inputs and seed, same chain.
[[nodiscard]] PerturbedOdometry perturb_odometry(const io::Trajectory& truth,
                                                 const OdometryPerturbation& p, std::uint64_t seed);

}  // namespace pgmcl::app
