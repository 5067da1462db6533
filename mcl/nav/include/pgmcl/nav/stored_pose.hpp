#pragma once
/// Pose persistence, as amcl does it: the last pose and the diagonal of its covariance
/// under amcl's parameter names (initial_pose_x/y/a, initial_cov_xx/yy/aa), so a restarted
/// node starts where the robot was. A node stores them as parameters; these functions
/// also keep them in a small file that survives the parameter server (a YAML subset that
/// `rosparam load` reads too).

#include <Eigen/Core>
#include <optional>
#include <string>
#include <string_view>

#include "pgmcl/common/se2.hpp"

namespace pgmcl::nav {

struct StoredPose {
  Pose2 pose{};         ///< global (map) frame
  double cov_xx = 0.0;  ///< m²
  double cov_yy = 0.0;  ///< m²
  double cov_aa = 0.0;  ///< rad²

  /// The diagonal of `covariance` (x, y, theta), clamped at 0 against round-off.
  [[nodiscard]] static StoredPose of(const Pose2& pose, const Eigen::Matrix3d& covariance) noexcept;
  [[nodiscard]] Eigen::Matrix3d covariance() const noexcept;
  /// All six numbers finite and the variances >= 0.
  [[nodiscard]] bool valid() const noexcept;
};

/// The six amcl keys, one "key: value" line each, numbers in shortest round-trip form.
[[nodiscard]] std::string format_stored_pose(const StoredPose& p);
/// Reads what format_stored_pose writes ('#' comments and blank lines allowed, keys in any
/// order). Throws std::invalid_argument "source:line: key: problem" for a malformed line,
/// an unknown, repeated or missing key, a non-finite number or a negative variance.
[[nodiscard]] StoredPose parse_stored_pose(std::string_view text, const std::string& source);

/// Writes the file atomically (a temporary beside it, then rename), so a crash leaves the
/// old pose or the new one. Throws std::runtime_error naming the file on failure.
void save_stored_pose(const std::string& path, const StoredPose& p);
/// The pose in `path`, or nullopt when the file does not exist. Throws as
/// parse_stored_pose, or std::runtime_error when it exists but cannot be read.
[[nodiscard]] std::optional<StoredPose> load_stored_pose(const std::string& path);

}  // namespace pgmcl::nav
