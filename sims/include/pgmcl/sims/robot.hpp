#pragma once
/// The simulated robot: differential-drive kinematics, two waypoint controllers, a random
/// exploration walk that stays in free space, and odometry with random and systematic error.

#include <cstddef>
#include <optional>
#include <vector>

#include "pgmcl/common/motion_model.hpp"
#include "pgmcl/common/random.hpp"
#include "pgmcl/common/se2.hpp"
#include "pgmcl/maps/occupancy_grid.hpp"
#include "pgmcl/sims/obstacles.hpp"

namespace pgmcl::sims {

struct DiffDriveLimits {
  double max_v = 0.5;      ///< m/s, > 0
  double max_omega = 1.0;  ///< rad/s, > 0
};

struct VelocityCommand {
  double v = 0.0;      ///< m/s, forward
  double omega = 0.0;  ///< rad/s, counter-clockwise
};

/// Exact unicycle motion under a constant command for dt seconds (a circular arc, or a
/// straight line when omega = 0).
[[nodiscard]] Pose2 integrate_diff_drive(const Pose2& pose, const VelocityCommand& cmd,
                                         double dt) noexcept;

enum class Controller : unsigned char {
  kPurePursuit,    ///< steer towards a point `lookahead` metres ahead on the path
  kTurnThenDrive,  ///< rotate in place towards the next waypoint, then drive straight
};

/// Waypoint following. The path runs from the start pose through `waypoints` (global
/// frame); no collision checks are made: the path is the scenario author's responsibility.
struct WaypointPlan {
  std::vector<Point2> waypoints;
  Controller controller = Controller::kPurePursuit;
  double lookahead = 0.5;           ///< m, pure pursuit, > 0
  double goal_tolerance = 0.05;     ///< m, a waypoint counts as reached within this, > 0
  double heading_tolerance = 0.05;  ///< rad, turn-then-drive drives once aligned this well
  bool loop = false;                ///< after the last waypoint, continue with the first
};

/// Random exploration: straight legs to random reachable points, turn-then-drive.
struct RandomWalkPlan {
  /// m: every cell within this distance of the robot centre must be free (not occupied,
  /// not unknown), at every control step.
  double clearance = 0.2;
  double goal_tolerance = 0.05;  ///< m, a leg ends this close to its goal
  double min_leg = 0.5;          ///< m, shortest leg
  double max_leg = 3.0;          ///< m, longest leg
  int max_retries = 50;          ///< goal draws per control step before rotating in place instead
};

/// Pose checks against a grid: a pose is admissible when all cells within `clearance` of
/// it are inside the grid and free.
class FreeSpace {
 public:
  FreeSpace(const maps::OccupancyGrid& grid, double clearance);
  [[nodiscard]] bool admissible(double x, double y) const noexcept;
  /// Every point of the segment a-b (sampled at a quarter cell) is admissible.
  [[nodiscard]] bool segment_admissible(const Point2& a, const Point2& b) const noexcept;

 private:
  const maps::OccupancyGrid* grid_;
  double clearance_;
};

/// Drives along a WaypointPlan; keeps its progress between calls.
class WaypointFollower {
 public:
  WaypointFollower(WaypointPlan plan, const Pose2& start, DiffDriveLimits limits);
  [[nodiscard]] VelocityCommand command(const Pose2& pose, double dt);
  [[nodiscard]] bool finished() const noexcept { return finished_; }

 private:
  [[nodiscard]] VelocityCommand pure_pursuit(const Pose2& pose, double dt);
  [[nodiscard]] VelocityCommand turn_then_drive(const Pose2& pose, double dt);
  [[nodiscard]] const Point2& point(std::size_t i) const noexcept;  // 0 = start
  [[nodiscard]] std::size_t last_index() const noexcept;

  WaypointPlan plan_;
  Point2 start_;
  DiffDriveLimits limits_;
  std::size_t segment_ = 0;  // current segment: point(segment_) -> point(segment_ + 1)
  bool finished_ = false;
};

/// Random walk in free space, seeded through the caller's Rng.
class RandomWalker {
 public:
  RandomWalker(RandomWalkPlan plan, const maps::OccupancyGrid& grid, DiffDriveLimits limits);
  /// The command for the next dt seconds; never one that would leave admissible space.
  [[nodiscard]] VelocityCommand command(const Pose2& pose, double dt, Rng& rng);
  /// Forget the current goal (after a teleport).
  void reset() noexcept { goal_.reset(); }
  [[nodiscard]] const FreeSpace& free_space() const noexcept { return free_; }

 private:
  RandomWalkPlan plan_;
  FreeSpace free_;
  DiffDriveLimits limits_;
  std::optional<Point2> goal_;
};

/// Odometry: random error per Probabilistic Robotics Table 5.6 (variance-form alphas,
/// sample_noisy_increment), then systematic error of a miscalibrated differential drive.
struct OdometrySettings {
  bool random_noise = true;
  MotionModelKind kind = MotionModelKind::kDifferentialDrive;
  MotionNoise alphas{};
  /// Relative error of the assumed wheel radius: odometry distances are scaled by
  /// (1 + wheel_radius_bias), and rotations too (both come from wheel arc lengths).
  double wheel_radius_bias = 0.0;
  /// Relative error of the assumed wheelbase: odometry rotations are divided by
  /// (1 + wheelbase_bias).
  double wheelbase_bias = 0.0;
  /// rad per metre travelled: unequal left/right wheel radii curve the odometry path.
  double yaw_drift_per_metre = 0.0;
  /// Odometry pose at t = 0; default: the true start pose.
  std::optional<Pose2> origin;
};

/// The systematic part: maps a true (or randomly perturbed) increment, expressed in the
/// robot frame at its start, to what the miscalibrated odometry reports.
[[nodiscard]] Pose2 apply_systematic_error(const Pose2& increment,
                                           const OdometrySettings& s) noexcept;

}  // namespace pgmcl::sims
