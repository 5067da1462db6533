#pragma once
/// Datasets of the macro sweep: a map, scans with the odometry pose at each scan, and the
/// ground-truth pose at each scan (same index). Either a CARMEN log (real scans; odometry
/// from the log or synthesised from the truth with Table 5.6 noise, as `pgmcl perturb`
/// does), a scenario file of configs/scenarios/ or a simulated run on a synthetic office
/// (both through sims::simulate).

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "pgmcl/common/laser_scan.hpp"
#include "pgmcl/common/motion_model.hpp"
#include "pgmcl/common/se2.hpp"
#include "pgmcl/maps/occupancy_grid.hpp"

namespace pgmcl::bench {

struct Dataset {
  std::string name;
  maps::OccupancyGrid grid;
  std::vector<LaserScan> scans;
  std::vector<Pose2> odometry;  ///< robot odometry pose at each scan
  std::vector<Pose2> truth;     ///< true robot pose at each scan (global frame)
  std::vector<double> stamps;   ///< seconds, non-decreasing
  std::size_t log_beams = 0;    ///< readings per scan
};

struct LogSource {
  std::string map_yaml;   ///< ROS map (e.g. from `pgmcl map` on the corrected log)
  std::string log;        ///< scans and odometry (FLASER odom_* fields)
  std::string truth_log;  ///< corrected log: FLASER poses are the truth (same scan order)
  bool perturb = false;   ///< synthesise odometry from the truth instead of the log's
  std::uint64_t perturb_seed = 1;
  MotionNoise odom_noise{};   ///< Table 5.6 alphas of the synthetic odometry
  std::size_t max_scans = 0;  ///< 0 = all
};

/// Throws std::runtime_error when the logs disagree (scan count, stamps) or are empty.
[[nodiscard]] Dataset load_log_dataset(const std::string& name, const LogSource& src);

/// Odometry with Table 5.6 noise along `truth`: odom[0] = truth[0], then each true
/// increment is replaced by sample_noisy_increment(...) drawn from Rng::for_block(seed, k, 1).
[[nodiscard]] std::vector<Pose2> perturb_odometry(const std::vector<Pose2>& truth,
                                                  const MotionNoise& noise, std::uint64_t seed);

struct SimSource {
  double size_m = 50.0;       ///< square office side, metres
  double duration_s = 120.0;  ///< seconds of random walk
  double scan_rate = 5.0;     ///< Hz
  int people = 4;             ///< unmapped moving discs
  std::uint64_t seed = 1;
};

/// A UTM-30LX random walk through a synthetic office with people and biased odometry.
[[nodiscard]] Dataset simulate_dataset(const std::string& name, const SimSource& src);

/// The run a scenario YAML describes (its map, sensor, robot, people, odometry model;
/// what `pgmcl simulate` writes). duration_s > 0 replaces the file's duration: a robot whose
/// waypoints do not loop then stands at its goal for the rest of the run. Throws
/// io::ScenarioError / io::IoError for a bad file.
[[nodiscard]] Dataset scenario_dataset(const std::string& name, const std::string& yaml_path,
                                       double duration_s = 0.0);

}  // namespace pgmcl::bench
