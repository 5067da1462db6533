// Embedding pgmcl: load a map, simulate a UTM-30LX driving a loop, localise, report.
// Built against the *installed* package (find_package(pgmcl)) by cmake/test.sh.
// Usage: pgmcl_consumer DATA_DIR   (DATA_DIR = the repository's data/ folder)
#include <cmath>
#include <cstdio>
#include <exception>
#include <pgmcl/map_io/map_io.hpp>
#include <pgmcl/mcl/localizer.hpp>
#include <pgmcl/sims/ray_caster.hpp>
#include <pgmcl/sims/sensor_profile.hpp>
#include <string>
#include <vector>

int main(int argc, char** argv) try {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s DATA_DIR\n", argv[0]);
    return 2;
  }
  const auto grid = pgmcl::maps::load_map(std::string(argv[1]) + "/maps/willow/willow-full.yaml");
  const auto sensor = pgmcl::sims::utm30lx();  // Dekan et al., Table 1
  const pgmcl::sims::RayCaster caster(grid);

  pgmcl::LocalizerConfig cfg;  // documented defaults
  cfg.seed = 7;
  cfg.filter.recovery.enabled = false;  // pure tracking from a known start
  pgmcl::Localizer localizer(grid, cfg);

  // A free corridor of the Willow Garage office (row 94, x 12.6..21.6 m); drive 8 m along +x.
  pgmcl::Pose2 truth{13.0, 9.45, 0.0};
  localizer.set_pose({truth.x + 0.1, truth.y - 0.1, 0.05},
                     Eigen::Vector3d(0.04, 0.04, 0.01).asDiagonal());
  double sq_err = 0.0;
  int updates = 0;
  for (int step = 0; step <= 40; ++step) {
    std::vector<float> ranges(static_cast<std::size_t>(sensor.beam_count));
    caster.cast_scan(truth, sensor.fan(), ranges);
    const auto scan = sensor.make_scan(ranges);
    const auto result = localizer.update(truth, scan, 0.25 * step);  // odometry = truth here
    if (result.measured()) {
      const double e = std::hypot(result.estimate.x - truth.x, result.estimate.y - truth.y);
      sq_err += e * e;
      ++updates;
    }
    truth = truth.compose({0.2, 0.0, 0.0});
  }
  const double rmse = updates ? std::sqrt(sq_err / updates) : INFINITY;
  std::printf("pgmcl consumer: %d updates, position RMSE %.3f m\n", updates, rmse);
  return rmse < 0.15 ? 0 : 1;
} catch (const std::exception& e) {
  std::fprintf(stderr, "pgmcl consumer: error: %s\n", e.what());
  return 1;
}
