#pragma once
// A logged case for the replay tests: a map, a CARMEN log and its truth, and a job that
// starts the filter on the truth at the first scan.
#include <string>
#include <utility>

#include "pgmcl/io/carmen.hpp"
#include "pgmcl/io/trajectory.hpp"
#include "pgmcl/maps/occupancy_grid.hpp"
#include "pgmcl/replay/replay.hpp"

namespace pgmcl::replay::test {

struct Case {
  maps::OccupancyGrid map;
  io::CarmenLog log;
  io::Trajectory truth;
};

// `c` must outlive the job (it points to the map and the log).
inline ReplayJob job_from_truth(const Case& c, std::string name) {
  ReplayJob job;
  job.map = &c.map;
  job.log = &c.log;
  job.log_name = std::move(name);
  job.truth = c.truth;
  job.init.kind = InitialBelief::Kind::kTruth;
  return job;
}

}  // namespace pgmcl::replay::test
