#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "pgmcl/sims/scenario.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace pgmcl::sims {

void render_scan(const Scene& scene, const SensorProfile& profile, const Pose2& sensor,
                 const BeamNoise& noise, Rng& rng, std::span<float> ranges) {
  if (ranges.size() != static_cast<std::size_t>(profile.beam_count)) {
    throw std::invalid_argument("render_scan: " + std::to_string(ranges.size()) + " ranges for " +
                                std::to_string(profile.beam_count) + " beams");
  }
  const Pose2 local = scene.caster().origin().between(sensor);
  const auto x = static_cast<float>(local.x);
  const auto y = static_cast<float>(local.y);
  const RangeLimits limits{static_cast<float>(profile.range_min),
                           static_cast<float>(profile.range_max)};
  for (int i = 0; i < profile.beam_count; ++i) {
    const double a = local.theta + profile.beam_angle(i);
    ranges[static_cast<std::size_t>(i)] =
        render_beam(scene, x, y, static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)),
                    limits, noise, rng);
  }
}

SimulationLog simulate(const Scenario& sc, const maps::OccupancyGrid& grid, int threads) {
  const std::vector<MotionSample> motion = simulate_motion(sc, grid);  // validates
  const std::vector<Pose2> odom = simulate_odometry(sc, motion);
  const RayCaster caster(grid, sc.raycast);
  const SurfaceField surfaces(sc.surfaces, grid);

  SimulationLog log;
  for (const auto& k : sc.kidnaps) {
    if (k.time <= sc.duration) log.kidnap_times.push_back(k.time);
  }
  std::sort(log.kidnap_times.begin(), log.kidnap_times.end());
  log.records.resize(motion.size());
  const auto n = static_cast<std::ptrdiff_t>(motion.size());
  // Scans are independent given the motion: one RNG stream per scan keeps the result
  // independent of the thread count. Nothing in the loop throws (names were validated).
#ifdef _OPENMP
  const int team = threads > 0 ? threads : omp_get_max_threads();
#pragma omp parallel for schedule(dynamic, 4) num_threads(team)
#else
  (void)threads;
#endif
  for (std::ptrdiff_t k = 0; k < n; ++k) {
    const auto i = static_cast<std::size_t>(k);
    const MotionSample& m = motion[i];
    Scene scene(caster, surfaces);
    scene.set_obstacles(sc.discs, sc.boxes, m.stamp);
    Rng rng = Rng::for_block(sc.seed, i, 0);
    SimulationRecord& rec = log.records[i];
    rec.stamp = m.stamp;
    rec.truth = m.truth;
    rec.odometry = odom[i];
    rec.scan = sc.sensor.make_scan(sc.sensor_mount);
    render_scan(scene, sc.sensor, m.truth.compose(sc.sensor_mount), sc.noise, rng, rec.scan.ranges);
  }
  return log;
}

}  // namespace pgmcl::sims
