#pragma once
// A logged case for the replay tests: a map, a CARMEN log and its truth, and a job that
// starts the filter on the truth at the first scan.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <string>
#include <utility>

#include "pgmcl/io/carmen.hpp"
#include "pgmcl/io/trajectory.hpp"
#include "pgmcl/io/tum.hpp"
#include "pgmcl/map_io/map_io.hpp"
#include "pgmcl/maps/occupancy_grid.hpp"
#include "pgmcl/replay/replay.hpp"

namespace pgmcl::replay::test {

struct Case {
  maps::OccupancyGrid map;
  io::CarmenLog log;
  io::Trajectory truth;
};

// The bundled map at `map` and the log `stem`.log.gz with its truth `stem`.tum.gz.
inline Case load_case(const std::string& map, const std::string& stem) {
  return {maps::load_map(map), io::read_carmen(stem + ".log.gz"), io::read_tum(stem + ".tum.gz")};
}

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

// The longest run of `r`'s updates in a row more than `metres` off `c`'s truth.
inline std::size_t longest_run_off(const Case& c, const ReplayResult& r, double metres) {
  std::size_t run = 0, longest = 0;
  for (const io::StampedPose& p : r.trajectory) {
    const std::optional<Pose2> t = io::interpolate_at(c.truth, p.stamp);
    const bool off = t && std::hypot(p.pose.x - t->x, p.pose.y - t->y) > metres;
    run = off ? run + 1 : 0;
    longest = std::max(longest, run);
  }
  return longest;
}

}  // namespace pgmcl::replay::test
