#pragma once
// Test-only closed-loop driver: feeds a Localizer synthetic scans along a ground-truth
// path with noisy odometry and measures the error of its estimate against the truth.

#include <algorithm>
#include <cmath>
#include <vector>

#include "drive_path.hpp"
#include "pgmcl/mcl/localizer.hpp"
#include "synthetic_world.hpp"

namespace pgmcl::test {

struct LoopErrors {
  std::size_t updates = 0;                                     // steps fed
  std::size_t measured = 0;                                    // steps with a measurement update
  double rmse_xy = 0.0;                                        // metres, over the scored steps
  double max_xy = 0.0;                                         // metres
  double max_theta = 0.0;                                      // radians
  double final_xy = 0.0;                                       // metres, last step
  double final_theta = 0.0;                                    // radians, last step
  std::size_t first_converged = static_cast<std::size_t>(-1);  // step index, or -1
  std::size_t last_particles = 0;
  std::size_t min_particles = static_cast<std::size_t>(-1);
  std::vector<double> err_xy;  // per step
};

using testkit::theta_error;
using testkit::xy_error;

// Runs steps [begin, end) of `truth` (map-local). Errors are accumulated from step
// `score_from` on (to leave time for global convergence). Global truth = origin ∘ local.
inline LoopErrors run_loop(Localizer& loc, const World& world, const std::vector<Pose2>& truth,
                           const std::vector<Pose2>& odom, const ScanSpec& spec,
                           std::uint64_t noise_seed, std::size_t begin, std::size_t end,
                           std::size_t score_from = 0, double t0 = 0.0) {
  LoopErrors e;
  Rng noise(noise_seed);
  testkit::ErrorScore score;
  const Pose2& origin = world.grid.origin();
  for (std::size_t k = begin; k < end; ++k) {
    const double stamp = t0 + 0.1 * static_cast<double>(k);
    const LaserScan scan = world.scan(truth[k], spec, &noise, stamp);
    const UpdateResult r = loc.update(odom[k], scan, stamp);
    ++e.updates;
    if (r.measured) ++e.measured;
    if (r.converged && e.first_converged == static_cast<std::size_t>(-1)) e.first_converged = k;
    e.last_particles = r.particles;
    e.min_particles = std::min(e.min_particles, r.particles);
    const Pose2 gt = origin.compose(truth[k]);
    const double dxy = xy_error(r.estimate, gt), dth = theta_error(r.estimate, gt);
    e.err_xy.push_back(dxy);
    e.final_xy = dxy;
    e.final_theta = dth;
    if (k >= score_from) score.add(dxy, dth);
  }
  e.rmse_xy = score.rmse_xy();
  e.max_xy = score.max_xy;
  e.max_theta = score.max_theta;
  return e;
}

}  // namespace pgmcl::test
