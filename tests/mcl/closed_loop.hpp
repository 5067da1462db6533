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
  double last_rotation_noise_factor = 1.0;  // UpdateResult's, last step
  std::vector<double> err_xy;               // per step
};

using testkit::theta_error;
using testkit::xy_error;

// Which steps of the path run_loop() feeds, and how.
struct LoopSteps {
  std::uint64_t noise_seed = 1;  // seeds the scans' range noise
  std::size_t begin = 0;         // first step fed
  std::size_t end = 0;           // one past the last step fed
  std::size_t score_from = 0;    // first step whose error counts (time to converge)
  double t0 = 0.0;               // stamp of step 0, seconds (steps are 0.1 s apart)
};

// Runs steps [steps.begin, steps.end) of `truth` (map-local). Global truth = origin ∘ local.
inline LoopErrors run_loop(Localizer& loc, const World& world, const std::vector<Pose2>& truth,
                           const std::vector<Pose2>& odom, const ScanSpec& spec,
                           const LoopSteps& steps) {
  LoopErrors e;
  Rng noise(steps.noise_seed);
  testkit::ErrorScore score;
  const Pose2& origin = world.grid.origin();
  for (std::size_t k = steps.begin; k < steps.end; ++k) {
    const double stamp = steps.t0 + 0.1 * static_cast<double>(k);
    const LaserScan scan = world.scan(truth[k], spec, &noise);
    const UpdateResult r = loc.update(odom[k], scan, stamp);
    ++e.updates;
    if (r.measured()) ++e.measured;
    if (r.converged && e.first_converged == static_cast<std::size_t>(-1)) e.first_converged = k;
    e.last_particles = r.particles;
    e.min_particles = std::min(e.min_particles, r.particles);
    e.last_rotation_noise_factor = r.rotation_noise_factor;
    const Pose2 gt = origin.compose(truth[k]);
    const double dxy = xy_error(r.estimate, gt), dth = theta_error(r.estimate, gt);
    e.err_xy.push_back(dxy);
    e.final_xy = dxy;
    e.final_theta = dth;
    if (k >= steps.score_from) score.add(dxy, dth);
  }
  e.rmse_xy = score.rmse_xy();
  e.max_xy = score.max_xy;
  e.max_theta = score.max_theta;
  return e;
}

}  // namespace pgmcl::test
