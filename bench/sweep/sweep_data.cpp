#include "sweep_data.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "../bench_common.hpp"
#include "pgmcl/common/random.hpp"
#include "pgmcl/config/scenario_yaml.hpp"
#include "pgmcl/io/carmen.hpp"
#include "pgmcl/map_io/map_io.hpp"
#include "pgmcl/sims/scenario.hpp"

namespace pgmcl::bench {
namespace {

std::vector<const io::CarmenScan*> front_scans(const io::CarmenLog& log) {
  std::vector<const io::CarmenScan*> out;
  for (const auto& s : log.scans)
    if (s.message == io::LaserMessage::kFlaser && s.has_poses) out.push_back(&s);
  return out;
}

void append_simulation(Dataset& d, const sims::SimulationLog& log) {
  for (const auto& r : log.records) {
    d.scans.push_back(r.scan);
    d.odometry.push_back(r.odometry);
    d.truth.push_back(r.truth);
    d.stamps.push_back(r.stamp);
  }
  if (d.scans.empty()) throw std::runtime_error(d.name + ": the simulation produced no scans");
  d.log_beams = d.scans.front().ranges.size();
}

}  // namespace

std::vector<Pose2> perturb_odometry(const std::vector<Pose2>& truth, const MotionNoise& noise,
                                    std::uint64_t seed) {
  std::vector<Pose2> odom(truth.size());
  if (truth.empty()) return odom;
  odom[0] = truth[0];
  for (std::size_t k = 1; k < truth.size(); ++k) {
    Rng rng = Rng::for_block(seed, k, 1);
    const Pose2 inc = sample_noisy_increment(MotionModelKind::kDifferentialDrive, noise,
                                             truth[k - 1], truth[k], rng);
    odom[k] = odom[k - 1].compose(inc);
  }
  return odom;
}

Dataset load_log_dataset(const std::string& name, const LogSource& src) {
  Dataset d;
  d.name = name;
  d.grid = maps::load_map(src.map_yaml);
  const io::CarmenLog log = io::read_carmen(src.log);
  const io::CarmenLog truth_log =
      src.truth_log == src.log ? io::CarmenLog{} : io::read_carmen(src.truth_log);
  const auto scans = front_scans(log);
  const auto truth_scans = front_scans(src.truth_log == src.log ? log : truth_log);
  if (scans.empty()) throw std::runtime_error(src.log + ": no FLASER scans with poses");
  if (scans.size() != truth_scans.size())
    throw std::runtime_error(src.log + " has " + std::to_string(scans.size()) +
                             " FLASER scans but " + src.truth_log + " has " +
                             std::to_string(truth_scans.size()));
  std::size_t n = scans.size();
  if (src.max_scans > 0) n = std::min(n, src.max_scans);
  double last = -1e300;
  for (std::size_t k = 0; k < n; ++k) {
    const io::CarmenScan& s = *scans[k];
    const io::CarmenScan& t = *truth_scans[k];
    // The pair of csail logs holds the same scans in the same order; their stamps agree.
    if (std::abs(s.stamp - t.stamp) > 0.5)
      throw std::runtime_error("scan " + std::to_string(k) + ": stamp " +
                               std::to_string(s.stamp) + " in " + src.log + " but " +
                               std::to_string(t.stamp) + " in " + src.truth_log);
    d.scans.push_back(s.scan);
    d.odometry.push_back(s.odom_pose);
    // Robot pose = laser pose composed with the inverse mounting (io::scan_truth's rule).
    d.truth.push_back(t.laser_pose.compose(t.scan.sensor_pose.inverse()));
    last = std::max(last, s.stamp);
    d.stamps.push_back(last);
  }
  d.log_beams = d.scans.front().ranges.size();
  if (src.perturb) d.odometry = perturb_odometry(d.truth, src.odom_noise, src.perturb_seed);
  return d;
}

Dataset simulate_dataset(const std::string& name, const SimSource& src) {
  OfficeSpec spec;
  spec.width_m = spec.height_m = src.size_m;
  spec.seed = src.seed + 100;
  Dataset d;
  d.name = name;
  d.grid = make_office(spec);

  sims::Scenario sc;
  sc.sensor = sims::utm30lx();
  sc.scan_rate = src.scan_rate;
  sc.start = room_centre(spec, 0, 0);
  sc.motion = sims::MotionMode::kRandomWalk;
  sc.random_walk.clearance = 0.3;
  sc.limits = {0.6, 1.0};
  sc.odometry.wheel_radius_bias = 0.01;
  sc.odometry.yaw_drift_per_metre = 0.005;
  sc.duration = src.duration_s;
  sc.seed = src.seed;
  Rng rng(src.seed + 7);
  const double pitch = room_pitch(spec);
  const int rooms = std::max(1, static_cast<int>((src.size_m - 2 * spec.margin) / pitch));
  for (int k = 0; k < src.people; ++k) {
    // A person walks a 2 m square loop near the centre of a room next to the start.
    const Pose2 c = room_centre(spec, k % std::min(rooms, 2), (k / 2) % std::min(rooms, 2));
    sims::DiscObstacle p;
    p.radius = 0.25;
    const double ox = c.x + rng.uniform(-1.0, 1.0), oy = c.y + rng.uniform(-1.0, 1.0);
    p.path.waypoints = {{ox - 1, oy - 1}, {ox + 1, oy - 1}, {ox + 1, oy + 1}, {ox - 1, oy + 1}};
    p.path.speed = 0.6;
    p.path.start_offset = rng.uniform(0.0, 8.0);
    sc.discs.push_back(p);
  }
  append_simulation(d, sims::simulate(sc, d.grid));
  return d;
}

Dataset scenario_dataset(const std::string& name, const std::string& yaml_path, double duration_s) {
  Dataset d;
  d.name = name;
  io::ScenarioFile file = io::read_scenario_file(yaml_path, d.grid);
  if (duration_s > 0) file.scenario.duration = duration_s;
  append_simulation(d, sims::simulate(file.scenario, d.grid));
  return d;
}

}  // namespace pgmcl::bench
