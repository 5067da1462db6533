#pragma once
// Online inflation of the motion noise (MotionAdaptationConfig): how far the odometry's
// increments miss the filter's own estimates, in units of the noise the model predicts.

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "pgmcl/common/motion_model.hpp"
#include "pgmcl/common/se2.hpp"
#include "pgmcl/mcl/localizer_config.hpp"

namespace pgmcl::detail {

/// `noise` for the composite increment `inc` of several odometry readings whose own
/// increments' rotation_moment()s sum to `moment`: widened so that the heading variance (and
/// the translation variance's rotation term) is the readings' sum. A moment no larger than
/// the composite's own returns `noise` unchanged.
[[nodiscard]] MotionNoise spanning_readings(MotionModelKind kind, const MotionNoise& noise,
                                            const OdometryIncrement& inc, double moment) noexcept;

class MotionNoiseAdaptation {
 public:
  explicit MotionNoiseAdaptation(const MotionConfig& motion);

  /// One step between two converged estimates (global frame, with their covariances) over
  /// which the odometry moved by `odom_delta` (robot frame), over readings whose rotation
  /// moments sum to `moment` (spanning_readings()).
  void observe(const Pose2& odom_delta, double moment, const Pose2& est_prev,
               const Eigen::Matrix3d& cov_prev, const Pose2& est_now,
               const Eigen::Matrix3d& cov_now);

  /// The configured noise with its rotation terms (a1, a2) and translation terms (a3, a4,
  /// a5) multiplied by the current factors.
  [[nodiscard]] MotionNoise noise() const noexcept;
  /// Standard deviation of the odometry's heading error over `odom_delta` (robot frame),
  /// readings of rotation moment `moment`, under noise(), radians.
  [[nodiscard]] double heading_sigma(const Pose2& odom_delta, double moment) const noexcept;
  [[nodiscard]] double rotation_factor() const noexcept { return rotation_factor_; }
  [[nodiscard]] double translation_factor() const noexcept { return translation_factor_; }

 private:
  struct Window {
    std::vector<double> ratios;  // ring buffer of squared residual / predicted variance
    std::size_t next = 0, count = 0;
    void push(double v) noexcept;
    [[nodiscard]] double factor(std::vector<double>& scratch, double margin,
                                double max_factor) const;
  };

  MotionConfig cfg_{};
  Window rotation_, translation_;
  std::vector<double> scratch_;
  double rotation_factor_ = 1.0, translation_factor_ = 1.0;
};

}  // namespace pgmcl::detail
