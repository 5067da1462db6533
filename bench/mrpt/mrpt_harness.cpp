/// pgmcl_mrpt_harness: MRPT 2.5's CMonteCarloLocalization2D + CParticleFilter (SIR,
/// standard proposal, systematic resampling, ESS threshold 0.5, fixed particle count) run
/// on exactly the data pgmcl_sweep uses: the same map (converted cell by cell), the same
/// scans (beam angles set from the scan, not from carmen2rawlog's PARAM guess), the same
/// stamps and the same (perturbed) odometry, via the same loader and options
/// (sweep_data.hpp, macro_common.hpp). It writes the trajectory-level figures the
/// pf-localization app cannot: time per update and ATE against the truth.
///
/// Matching choices (pitfalls of MRPT's own conversion tools):
///  - beam layout: MRPT spreads N beams over `aperture` symmetrically about the sensor's x
///    axis; the SICK layout of even beam counts is not symmetric (-90..+89 deg), so the
///    aperture is (N-1) * step and the sensor yaw is turned by the half-step offset;
///  - map: built with setSize() on the grid's exact bounds; any snapping MRPT applies is
///    measured and added to every pose fed in and taken out;
///  - motion: the Gaussian model with the standard deviations of the Table 5.6 alphas
///    pgmcl uses (a1..a4 = sqrt of pgmcl's, SI units), minimum noise 1 cm / 0.5 deg;
///  - likelihood: the likelihood field (Thrun), LF_decimation chosen so that the number of
///    beams matches pgmcl's, LF_stdHit `--std-hit`, and powFactor = min(1, 20 / beams): the
///    same tempering pgmcl applies (LikelihoodConfig::effective_beams = 20).
///
///   pgmcl_mrpt_harness --name intel --map intel.yaml --log intel-corrected.log.gz \
///                      --perturb 1 --particles 1000 --beams 90 [--csv out.csv]

#include <mrpt/bayes/CParticleFilter.h>
#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt/slam/CMonteCarloLocalization2D.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "../macro_common.hpp"
#include "../sweep/sweep_data.hpp"
#include "pgmcl/common/random.hpp"
#include "pgmcl/mcl/beam_selection.hpp"
#include "pgmcl/mcl/localizer_config.hpp"

namespace pb = pgmcl::bench;

int main(int argc, char** argv) {
  CLI::App app{"pgmcl_mrpt_harness: MRPT's MCL on pgmcl_sweep's data"};
  std::string name = "dataset", csv_path;
  pb::LogOptions log_options;
  std::size_t particles = 1000, beams = 90;
  double std_hit = 0.1, max_corrs = 0.3;
  std::uint64_t seed = 1;
  app.add_option("--name", name, "Dataset label")->required();
  log_options.add_to(app, /*required=*/true);
  app.add_option("--particles", particles, "Particle count (fixed)");
  app.add_option("--beams", beams, "Beams per update (LF_decimation = readings / beams)");
  app.add_option("--std-hit", std_hit, "LF_stdHit, metres");
  app.add_option("--max-corrs", max_corrs, "LF_maxCorrsDistance, metres");
  app.add_option("--seed", seed, "Random seed (MRPT's global generator)");
  app.add_option("--csv", csv_path, "Append a row here");
  std::string motion_s;
  app.add_option("--motion-noise", motion_s,
                 "A1,A2,A3,A4 as pgmcl_sweep's (Table 5.6 variance form), mapped to MRPT's "
                 "Gaussian model");
  CLI11_PARSE(app, argc, argv);
  const std::optional<pb::LogSource> src = log_options.source("pgmcl_mrpt_harness");
  if (!src) return 2;
  const pb::Dataset d = pb::load_log_dataset(name, *src);
  const pgmcl::maps::OccupancyGrid& g = d.grid;
  if (std::abs(g.origin().theta) > 1e-12) {
    std::fprintf(stderr, "pgmcl_mrpt_harness: rotated map origins are not supported\n");
    return 2;
  }

  // ---- Map: one MRPT cell per pgmcl cell. MRPT cells hold p(free). ----
  auto map = mrpt::maps::COccupancyGridMap2D::Create();
  const double res = g.resolution();
  map->setSize(static_cast<float>(g.origin().x), static_cast<float>(g.origin().x + g.width() * res),
               static_cast<float>(g.origin().y),
               static_cast<float>(g.origin().y + g.height() * res), static_cast<float>(res), 0.5f);
  // Offset of MRPT's grid corner from ours (setSize snaps bounds to the resolution).
  const double shift_x = map->getXMin() - g.origin().x, shift_y = map->getYMin() - g.origin().y;
  for (int r = 0; r < g.height(); ++r)
    for (int c = 0; c < g.width(); ++c)
      map->setCell(c, r, g.occupied(c, r) ? 0.0f : (g.free(c, r) ? 1.0f : 0.5f));
  const std::size_t readings = d.log_beams;
  const auto decimation = static_cast<std::uint32_t>(
      std::max<std::size_t>(1, readings / std::max<std::size_t>(1, beams)));
  auto& lo = map->likelihoodOptions;
  lo.likelihoodMethod = mrpt::maps::COccupancyGridMap2D::lmLikelihoodField_Thrun;
  lo.LF_stdHit = static_cast<float>(std_hit);
  lo.LF_maxCorrsDistance = static_cast<float>(max_corrs);
  lo.LF_decimation = decimation;
  lo.LF_maxRange = static_cast<float>(pgmcl::LocalizerConfig{}.likelihood.beam.max_range);
  lo.enableLikelihoodCache = true;
  // A pose in pgmcl's frame -> MRPT's frame (and back with the opposite sign).
  const auto to_mrpt = [&](const pgmcl::Pose2& p) {
    return mrpt::math::TPose2D(p.x - shift_x, p.y - shift_y, p.theta);
  };

  // ---- Filter. ----
  mrpt::random::getRandomGenerator().randomize(static_cast<uint32_t>(seed));
  mrpt::slam::CMonteCarloLocalization2D pdf(particles);
  pdf.options.metricMap = map;
  mrpt::bayes::CParticleFilter pf;
  pf.m_options.PF_algorithm = mrpt::bayes::CParticleFilter::pfStandardProposal;
  pf.m_options.resamplingMethod = mrpt::bayes::CParticleFilter::prSystematic;
  pf.m_options.adaptiveSampleSize = false;
  pf.m_options.BETA = 0.5;
  const double used_beams = static_cast<double>((readings + decimation - 1) / decimation);
  pf.m_options.powFactor = std::min(1.0, 20.0 / used_beams);

  // Start as pgmcl_sweep does: around the true first pose, N(0, 0.1 m) and N(0, 0.05 rad).
  pdf.resetDeterministic(to_mrpt(d.truth.front()), particles);
  pgmcl::Rng rng(seed);
  for (auto& p : pdf.m_particles) {
    p.d.x += rng.normal(0.1);
    p.d.y += rng.normal(0.1);
    p.d.phi = pgmcl::wrap_angle(p.d.phi + rng.normal(0.05));
    p.log_w = 0;
  }

  mrpt::obs::CActionRobotMovement2D::TMotionModelOptions mm;
  mm.modelSelection = mrpt::obs::CActionRobotMovement2D::mmGaussian;
  pgmcl::MotionNoise n = pgmcl::LocalizerConfig{}.motion.noise;
  if (!motion_s.empty() && !pb::parse_alphas(motion_s, n)) {
    std::fprintf(stderr, "pgmcl_mrpt_harness: --motion-noise needs A1,A2,A3,A4\n");
    return 2;
  }
  mm.gaussianModel = {std::sqrt(n.a3),
                      std::sqrt(n.a4),
                      std::sqrt(n.a2),
                      std::sqrt(n.a1),
                      0.01,
                      0.5 * std::numbers::pi / 180.0};

  std::vector<double> update_ms;
  double sq = 0, ate_max = 0;
  for (std::size_t k = 0; k < d.scans.size(); ++k) {
    const pgmcl::LaserScan& s = d.scans[k];
    auto obs = mrpt::obs::CObservation2DRangeScan::Create();
    const std::size_t m = s.ranges.size();
    obs->resizeScan(m);
    obs->rightToLeft = true;
    obs->aperture = static_cast<float>(s.angle_increment * static_cast<double>(m - 1));
    obs->maxRange = static_cast<float>(s.range_max);
    for (std::size_t i = 0; i < m; ++i) {
      obs->setScanRange(i, s.ranges[i]);
      obs->setScanRangeValidity(
          i, pgmcl::valid_range(s.ranges[i], s.range_min, s.range_max, lo.LF_maxRange));
    }
    // MRPT's first beam is at -aperture / 2; turn the sensor so it lands on angle_min.
    const double yaw_offset = s.angle_min + 0.5 * obs->aperture;
    obs->sensorPose = mrpt::poses::CPose3D(s.sensor_pose.x, s.sensor_pose.y, 0.0,
                                           s.sensor_pose.theta + yaw_offset, 0.0, 0.0);
    obs->timestamp = mrpt::Clock::fromDouble(d.stamps[k]);
    mrpt::obs::CSensoryFrame sf;
    sf.insert(obs);

    mrpt::obs::CActionCollection acts;
    const pgmcl::Pose2 inc = k == 0 ? pgmcl::Pose2{} : d.odometry[k - 1].between(d.odometry[k]);
    mrpt::obs::CActionRobotMovement2D act;
    act.computeFromOdometry(mrpt::poses::CPose2D(inc.x, inc.y, inc.theta), mm);
    act.timestamp = obs->timestamp;
    acts.insert(act);

    const auto t0 = std::chrono::steady_clock::now();
    pf.executeOn(pdf, &acts, &sf);
    update_ms.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    const mrpt::poses::CPose2D mean = pdf.getMeanVal();
    const double e =
        std::hypot(mean.x() + shift_x - d.truth[k].x, mean.y() + shift_y - d.truth[k].y);
    sq += e * e;
    ate_max = std::max(ate_max, e);
  }
  const pb::TimeSummary times = pb::summarize_times(update_ms);
  const double mean_ms = times.mean, p95 = times.p95;
  const double ate = std::sqrt(sq / static_cast<double>(d.scans.size()));
  std::printf(
      "mrpt %s: %zu particles, %.0f beams (decimation %u), %zu updates: %.3f ms/update "
      "(p95 %.3f), ATE %.3f m (max %.2f); map shift (%.4f, %.4f) m\n",
      name.c_str(), particles, used_beams, decimation, update_ms.size(), mean_ms, p95, ate, ate_max,
      shift_x, shift_y);
  if (!csv_path.empty()) {
    std::FILE* f = pb::open_csv_for_append(
        csv_path,
        "dataset,engine,particles,beams_used,updates,update_ms_mean,update_ms_p95,"
        "ate_rmse_m,ate_max_m",
        "pgmcl_mrpt_harness");
    if (!f) return 1;
    std::fprintf(f, "%s,mrpt,%zu,%.0f,%zu,%.4f,%.4f,%.5f,%.4f\n", name.c_str(), particles,
                 used_beams, update_ms.size(), mean_ms, p95, ate, ate_max);
    std::fclose(f);
  }
  return 0;
}
