#include "pgmcl/io/sim_log_io.hpp"

#include "pgmcl/io/carmen_writer.hpp"
#include "pgmcl/io/tum.hpp"

namespace pgmcl::io {

CarmenLog to_carmen_log(const sims::SimulationLog& log, const std::string& host) {
  CarmenLog out;
  out.odometry.reserve(log.records.size());
  out.scans.reserve(log.records.size());
  out.truepos.reserve(log.records.size());
  bool params_set = false;
  for (std::size_t k = 0; k < log.records.size(); ++k) {
    const sims::SimulationRecord& r = log.records[k];
    OdomRecord odom;
    odom.pose = r.odometry;
    odom.stamp = r.stamp;
    odom.logger_stamp = r.stamp;
    odom.host = host;
    if (k > 0) {
      // Velocities over the last scan interval, in the robot frame (CARMEN's tv, rv).
      const sims::SimulationRecord& p = log.records[k - 1];
      const double dt = r.stamp - p.stamp;
      if (dt > 0.0) {
        const Pose2 inc = p.odometry.between(r.odometry);
        odom.tv = inc.x / dt;
        odom.rv = inc.theta / dt;
      }
    }
    out.odometry.push_back(std::move(odom));

    CarmenScan scan = make_scan_record(r.scan, r.stamp, r.odometry, host);
    if (scan.message == LaserMessage::kFlaser && !params_set) {
      set_front_laser_params(out.params, r.scan);
      params_set = true;
    }
    out.scans.push_back(std::move(scan));

    TruePosRecord truth;
    truth.true_pose = r.truth;
    truth.odom_pose = r.odometry;
    truth.stamp = r.stamp;
    truth.logger_stamp = r.stamp;
    truth.host = host;
    out.truepos.push_back(std::move(truth));
  }
  return out;
}

Trajectory sim_truth_trajectory(const sims::SimulationLog& log) {
  Trajectory t;
  t.reserve(log.records.size());
  for (const auto& r : log.records) t.push_back({r.stamp, r.truth});
  return t;
}

Trajectory sim_odometry_trajectory(const sims::SimulationLog& log) {
  Trajectory t;
  t.reserve(log.records.size());
  for (const auto& r : log.records) t.push_back({r.stamp, r.odometry});
  return t;
}

void write_sim_carmen(const std::string& path, const sims::SimulationLog& log) {
  write_carmen(path, to_carmen_log(log));
}

void write_sim_truth_tum(const std::string& path, const sims::SimulationLog& log) {
  write_tum(path, sim_truth_trajectory(log));
}

}  // namespace pgmcl::io
