#pragma once
/// A simulation scenario as a plain struct, and the in-memory log it produces.
/// No file I/O here: mcl/io parses scenarios from YAML and writes logs (CARMEN, TUM).

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "pgmcl/common/laser_scan.hpp"
#include "pgmcl/common/se2.hpp"
#include "pgmcl/maps/occupancy_grid.hpp"
#include "pgmcl/sims/beam_noise.hpp"
#include "pgmcl/sims/obstacles.hpp"
#include "pgmcl/sims/ray_caster.hpp"
#include "pgmcl/sims/robot.hpp"
#include "pgmcl/sims/sensor_profile.hpp"
#include "pgmcl/sims/surfaces.hpp"

namespace pgmcl::sims {

enum class MotionMode : unsigned char {
  kWaypoints,   ///< follow Scenario::waypoints
  kRandomWalk,  ///< Scenario::random_walk
  kStationary,  ///< stand still at the start pose (repeatability experiments)
};

/// Kidnapping: at `time` the true pose jumps to `pose`; odometry does not see it.
struct KidnapEvent {
  double time = 0.0;  ///< seconds
  Pose2 pose{};       ///< global frame
};

struct Scenario {
  // Sensor.
  SensorProfile sensor = utm30lx();
  Pose2 sensor_mount{};    ///< laser pose in the robot base frame
  double scan_rate = 0.0;  ///< Hz; 0 = sensor.scan_rate
  BeamNoise noise{};
  RayCastOptions raycast{};  ///< unknown cells pass beams through by default
  // World (the map itself is passed to simulate()).
  SurfaceLayout surfaces{};
  std::vector<DiscObstacle> discs;  ///< unmapped, moving
  std::vector<BoxObstacle> boxes;   ///< unmapped, moving
  // Robot.
  Pose2 start{};  ///< global frame
  MotionMode motion = MotionMode::kWaypoints;
  WaypointPlan waypoints{};
  RandomWalkPlan random_walk{};
  DiffDriveLimits limits{};
  double control_rate = 20.0;  ///< Hz: controller updates; the command is held in between
  OdometrySettings odometry{};
  std::vector<KidnapEvent> kidnaps;  ///< any order
  // Run.
  double duration = 10.0;  ///< seconds; scans at t = k / scan_rate for t <= duration
  std::uint64_t seed = 1;

  [[nodiscard]] double effective_scan_rate() const noexcept {
    return scan_rate > 0.0 ? scan_rate : sensor.scan_rate;
  }
  /// Checks every field against `grid` (start and kidnap poses inside the grid; admissible
  /// for a random walk) and throws std::invalid_argument naming the field.
  void validate(const maps::OccupancyGrid& grid) const;
};

/// One scan with its poses.
struct SimulationRecord {
  double stamp = 0.0;  ///< seconds
  Pose2 odometry{};    ///< odometry pose of the robot base (drifts; blind to kidnapping)
  Pose2 truth{};       ///< true pose of the robot base, global frame
  LaserScan scan;      ///< scan.sensor_pose = Scenario::sensor_mount
};

struct SimulationLog {
  std::vector<SimulationRecord> records;  ///< time-ordered
  std::vector<double> kidnap_times;       ///< seconds, sorted, those within the run
};

/// Samples of the true motion at the scan times (no sensing), for tests and tools.
struct MotionSample {
  double stamp = 0.0;
  Pose2 truth{};
  /// The same motion without teleports: odometry is derived from its increments.
  Pose2 kinematic{};
};

/// Runs the robot: controller at control_rate, exact arcs between events, kidnaps applied.
[[nodiscard]] std::vector<MotionSample> simulate_motion(const Scenario& scenario,
                                                        const maps::OccupancyGrid& grid);

/// Odometry poses for `motion`: per interval, sample_noisy_increment with the stream
/// Rng::for_block(seed, index, 1), then apply_systematic_error.
[[nodiscard]] std::vector<Pose2> simulate_odometry(const Scenario& scenario,
                                                   const std::vector<MotionSample>& motion);

/// One noisy scan of `scene` from the laser at `sensor` (global pose), beams in order from
/// one stream. `ranges.size()` must equal profile.beam_count (throws otherwise).
void render_scan(const Scene& scene, const SensorProfile& profile, const Pose2& sensor,
                 const BeamNoise& noise, Rng& rng, std::span<float> ranges);

/// The whole run. Deterministic for a seed: scan k draws from Rng::for_block(seed, k, 0),
/// so the OpenMP loop over scans gives the same log for any thread count. `threads`: OpenMP
/// threads for that loop, 0 = OpenMP's default (a setting, not a global: the caller's other
/// parallel regions keep theirs).
/// Throws std::invalid_argument for invalid scenarios (see Scenario::validate).
[[nodiscard]] SimulationLog simulate(const Scenario& scenario, const maps::OccupancyGrid& grid,
                                     int threads = 0);

}  // namespace pgmcl::sims
