#pragma once
/// Simulator output (sims::SimulationLog) as files: a CARMEN log a filter can replay and
/// the ground truth as a TUM trajectory (for `evo_ape tum truth.tum estimate.tum`).

#include <string>

#include "pgmcl/io/carmen.hpp"
#include "pgmcl/io/trajectory.hpp"
#include "pgmcl/sims/scenario.hpp"

namespace pgmcl::io {

/// One CARMEN record set per scan, all stamped with the scan time: ODOM (the drifting
/// odometry pose, with tv/rv from the odometry increment to the previous scan), the scan
/// (FLASER when its angles are the SICK layout and the laser faces forward on the x axis,
/// i.e. <= 180 deg scans from sims::carmen_sick; ROBOTLASER1 otherwise, e.g. the 270 deg
/// UTM-30LX, logging start angle, resolution, range_max and the laser pose), and TRUEPOS
/// (true pose + odometry pose). For FLASER the PARAMs robot_front_laser_max and
/// robot_frontlaser_offset are set so read_carmen() restores range_max and the mounting.
[[nodiscard]] CarmenLog to_carmen_log(const sims::SimulationLog& log,
                                      const std::string& host = "pgmcl");

/// True robot-base poses at the scan times.
[[nodiscard]] Trajectory sim_truth_trajectory(const sims::SimulationLog& log);
/// Odometry poses at the scan times (what a filter would be given).
[[nodiscard]] Trajectory sim_odometry_trajectory(const sims::SimulationLog& log);

/// write_carmen(path, to_carmen_log(log)) (gzip if the path ends in ".gz"). Throws IoError.
void write_sim_carmen(const std::string& path, const sims::SimulationLog& log);
/// write_tum(path, sim_truth_trajectory(log)). Throws IoError.
void write_sim_truth_tum(const std::string& path, const sims::SimulationLog& log);

}  // namespace pgmcl::io
