/// pgmcl calibrate: Dekan et al.'s experiments in reverse -- estimate the beam model's
/// sigmas from repeated readings (sims/calibration.hpp), recorded or simulated.
///   calibrate range: along-beam sigma (Sec. 4, Table 2) from repeated readings of one beam
///     of a stationary scanner: --log (split into --experiments consecutive chunks, each
///     with its own mean) or --simulate (a flat surface of --material at --distance).
///   calibrate edge: across-beam sigma (Table 3, Table 4, Eq. (5)) from the jitter of the
///     boundary beam at an object edge: --log (boundary searched from --first-beam with
///     --split-range) or --simulate (an edge at --distance).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "app_util.hpp"
#include "cli_errors.hpp"
#include "commands.hpp"
#include "pgmcl/io/values.hpp"
#include "pgmcl/sims/calibration.hpp"

namespace pgmcl::app {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

struct RangeOptions {
  std::string log;
  std::size_t beam = 0;
  int experiments = 1;  ///< --log's default; --simulate's is sim.experiments unless given
  CLI::Option* experiments_opt = nullptr;
  bool simulate = false;
  sims::FlatSurfaceExperiment sim{};
  double incidence_deg = 0.0;
};

struct EdgeOptions {
  std::string log;
  std::size_t first_beam = 0;
  double split_range = 0.0;
  double distance = 1.5;
  double edge_fraction = 0.5;
  bool simulate = false;
  sims::EdgeShiftExperiment sim{};
};

struct CalibrateOptions {
  CLI::App* range_cmd = nullptr;
  CLI::App* edge_cmd = nullptr;
  RangeOptions range;
  EdgeOptions edge;
};

/// How far the robot moved during a log, from its odometry and the scans' poses: metres and
/// radians away from where it started.
struct Motion {
  double metres = 0.0;
  double radians = 0.0;
};

Motion log_motion(const io::CarmenLog& log) {
  Motion m;
  std::vector<Pose2> odom, laser;
  for (const auto& r : log.odometry) odom.push_back(r.pose);
  for (const auto& s : log.scans) {
    if (!s.has_poses) continue;
    odom.push_back(s.odom_pose);
    laser.push_back(s.laser_pose);
  }
  for (const auto* track : {&odom, &laser}) {
    if (track->empty()) continue;
    const Pose2& a = track->front();
    for (const Pose2& p : *track) {
      m.metres = std::max(m.metres, std::hypot(p.x - a.x, p.y - a.y));
      m.radians = std::max(m.radians, std::abs(wrap_angle(p.theta - a.theta)));
    }
  }
  return m;
}

/// Pooled lag-1 autocorrelation of the readings around each experiment's own mean: ~0 for
/// sensor noise, near 1 when the range drifts (the robot or the scene moving).
double lag1_autocorrelation(const std::vector<std::vector<double>>& experiments) {
  double num = 0.0, den = 0.0;
  for (const auto& e : experiments) {
    if (e.size() < 2) continue;
    double mean = 0.0;
    for (const double v : e) mean += v;
    mean /= static_cast<double>(e.size());
    for (std::size_t i = 0; i < e.size(); ++i) {
      den += (e[i] - mean) * (e[i] - mean);
      if (i + 1 < e.size()) num += (e[i] - mean) * (e[i + 1] - mean);
    }
  }
  return den > 0.0 ? num / den : 0.0;
}

/// Scans of a log as ranges; the angular step of the first one; how far the robot moved.
std::vector<std::vector<float>> log_ranges(const std::string& path, double* step, double* rmin,
                                           double* rmax, Motion* motion = nullptr) {
  const io::CarmenLog log = read_log(path, {}, false);
  if (motion) *motion = log_motion(log);
  if (log.scans.empty()) throw std::runtime_error(path + ": no laser scans");
  std::vector<std::vector<float>> scans;
  scans.reserve(log.scans.size());
  for (const auto& s : log.scans) scans.push_back(s.scan.ranges);
  *step = log.scans.front().scan.angle_increment;
  *rmin = log.scans.front().scan.range_min;
  *rmax = log.scans.front().scan.range_max;
  return scans;
}

int run_range(const RangeOptions& o) {
  std::vector<std::vector<double>> experiments;
  std::string what;
  if (o.simulate) {
    sims::FlatSurfaceExperiment x = o.sim;
    x.incidence = o.incidence_deg * kDeg;
    if (o.experiments_opt->count() > 0) x.experiments = o.experiments;
    experiments = sims::simulate_flat_surface(x);
    char buf[256];
    std::snprintf(buf, sizeof buf, "simulated %s at %.2f m, incidence %.1f deg", x.material.c_str(),
                  x.distance, o.incidence_deg);
    what = buf;
    for (const auto& m : x.materials) {
      if (m.name == x.material) {
        std::snprintf(buf, sizeof buf, " (model sigma %.4f mm)", m.sigma.sigma(x.incidence) * 1e3);
        what += buf;
      }
    }
  } else {
    double step = 0, rmin = 0, rmax = 0;
    Motion motion;
    const auto scans = log_ranges(o.log, &step, &rmin, &rmax, &motion);
    if (motion.metres > 0.01 || motion.radians > 0.5 * kDeg) {
      std::fprintf(stderr,
                   "pgmcl: warning: %s: the robot moved %.3f m and %.1f deg during the log; "
                   "calibrate range wants a stationary scanner, so sigma_x below measures the "
                   "motion as much as the sensor\n",
                   o.log.c_str(), motion.metres, motion.radians / kDeg);
    }
    const std::vector<double> r = sims::beam_readings(scans, o.beam, rmin, rmax);
    const auto k = static_cast<std::size_t>(o.experiments);
    if (r.size() < 2 * k) {
      throw io::UsageError(o.log + ": beam " + std::to_string(o.beam) + " has " +
                           std::to_string(r.size()) + " valid readings, too few for " +
                           std::to_string(k) + " experiment(s)");
    }
    for (std::size_t e = 0; e < k; ++e) {
      const std::size_t a = e * r.size() / k, b = (e + 1) * r.size() / k;
      experiments.emplace_back(r.begin() + static_cast<std::ptrdiff_t>(a),
                               r.begin() + static_cast<std::ptrdiff_t>(b));
    }
    what = o.log + ", beam " + std::to_string(o.beam);
  }
  const sims::RangeSigmaEstimate est = sims::estimate_range_sigma(experiments);
  // Sensor noise is white and millimetres wide; a drifting range is the scene moving.
  const double rho = lag1_autocorrelation(experiments);
  if (!o.simulate && (rho > 0.5 || est.sigma > 0.1)) {
    std::fprintf(stderr,
                 "pgmcl: warning: %s: the readings are not a static scene's (lag-1 "
                 "autocorrelation %.2f, sigma %.1f mm; sensor noise gives about 0 and a few "
                 "mm): the scanner or what it sees moved, so this sigma is not the sensor's\n",
                 o.log.c_str(), rho, est.sigma * 1e3);
  }
  std::printf("calibrate range: %s\n", what.c_str());
  std::printf("  readings         %zu in %zu experiment(s), %zu degrees of freedom\n", est.readings,
              est.experiments, est.dof);
  std::printf("  mean range       %.4f m\n", est.mean);
  std::printf("  sigma_x          %.4f mm  (standard error %.4f mm)\n", est.sigma * 1e3,
              est.standard_error * 1e3);
  std::printf("  lag-1 autocorr.  %.3f (static scene: about 0)\n", rho);
  return 0;
}

int run_edge(const EdgeOptions& o) {
  std::vector<std::vector<long>> runs;
  double edge = 0.0, step = 0.0, distance = o.distance, fraction = o.edge_fraction;
  std::string what;
  if (o.simulate) {
    sims::EdgeShiftExperiment x = o.sim;
    x.distance = o.distance;
    x.edge_fraction = o.edge_fraction;
    const sims::EdgeShiftData d = sims::simulate_edge_shift(x);
    runs = d.boundaries;
    edge = d.edge;
    step = x.sensor.angle_increment;
    char buf[160];
    std::snprintf(buf, sizeof buf, "simulated edge at %.2f m, %.2f of a step past a beam",
                  x.distance, x.edge_fraction);
    what = buf;
  } else {
    double rmin = 0, rmax = 0;
    const auto scans = log_ranges(o.log, &step, &rmin, &rmax);
    if (!(o.split_range > 0.0)) throw io::UsageError("--split-range: required with --log, > 0");
    std::vector<long> b;
    b.reserve(scans.size());
    for (const auto& s : scans) {
      b.push_back(sims::boundary_beam(s, o.first_beam, static_cast<float>(o.split_range)));
    }
    // The edge lies `edge_fraction` of a step past the most frequent boundary beam.
    std::vector<long> sorted = b;
    std::sort(sorted.begin(), sorted.end());
    long mode = sorted.front();
    std::size_t best = 0;
    for (std::size_t i = 0; i < sorted.size();) {
      std::size_t j = i;
      while (j < sorted.size() && sorted[j] == sorted[i]) ++j;
      if (j - i > best) best = j - i, mode = sorted[i];
      i = j;
    }
    edge = static_cast<double>(mode) + fraction;
    runs.push_back(std::move(b));
    what = o.log + ", boundary from beam " + std::to_string(o.first_beam);
  }
  std::size_t changes = 0, pairs = 0;
  std::vector<long> all;
  std::printf("calibrate edge: %s\n", what.c_str());
  std::printf("  run  scans  boundary changes (Dekan et al., Table 3)\n");
  for (std::size_t r = 0; r < runs.size(); ++r) {
    const std::size_t c = sims::count_boundary_changes(runs[r]);
    std::printf("  %3zu  %5zu  %zu\n", r + 1, runs[r].size(), c);
    changes += c;
    pairs += runs[r].empty() ? 0 : runs[r].size() - 1;
    all.insert(all.end(), runs[r].begin(), runs[r].end());
  }
  if (pairs == 0) throw std::runtime_error("calibrate edge: need at least two scans");
  const double from_changes = sims::sigma_beams_from_changes(changes, pairs, fraction);
  const double mle = sims::sigma_beams_mle(all, edge);
  const sims::AcrossBeamEstimate a = sims::across_beam_estimate(mle, step, distance);
  std::printf("  sigma (beam steps)  %.4f from the change rate, %.4f maximum likelihood\n",
              from_changes, mle);
  std::printf("  y (Eq. 5)           %.4f mm at %.2f m, step %.4f deg\n", a.y * 1e3, distance,
              step / kDeg);
  std::printf("  sigma_y = y / 3     %.4f mm\n", a.sigma_y * 1e3);
  return 0;
}

int run_calibrate(const CalibrateOptions& o) {
  if (o.range_cmd->parsed()) {
    if (!o.range.simulate && o.range.log.empty()) {
      throw io::UsageError("calibrate range: give --log LOG or --simulate");
    }
    return run_range(o.range);
  }
  if (!o.edge.simulate && o.edge.log.empty()) {
    throw io::UsageError("calibrate edge: give --log LOG or --simulate");
  }
  return run_edge(o.edge);
}

void add_calibrate_options(CLI::App& sub, CalibrateOptions& o) {
  sub.description("Estimate the beam model's sigmas (Dekan et al. Sec. 4)");
  sub.require_subcommand(1);

  RangeOptions& r = o.range;
  o.range_cmd = sub.add_subcommand("range", "Along-beam sigma from repeated readings");
  auto* rlog =
      add_input_file(*o.range_cmd, "--log", r.log, "Log of a stationary scanner", log_file());
  o.range_cmd->add_option("--beam", r.beam, "Beam index (with --log)")->capture_default_str();
  r.experiments_opt =
      o.range_cmd
          ->add_option("--experiments", r.experiments,
                       "Experiments: the log split into this many (default 1), or this many "
                       "simulated (default 20)")
          ->check(CLI::Range(1, 100000));
  auto* rsim = o.range_cmd->add_flag("--simulate", r.simulate, "Simulate the experiment");
  rsim->excludes(rlog);
  o.range_cmd->add_option("--material", r.sim.material, "Table 2 surface (simulation)")
      ->capture_default_str();
  o.range_cmd->add_option("--distance", r.sim.distance, "Metres (simulation)")
      ->capture_default_str()
      ->check(positive());
  o.range_cmd->add_option("--incidence", r.incidence_deg, "Degrees (simulation)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 89.0));
  o.range_cmd->add_option("--readings", r.sim.readings, "Per experiment (simulation)")
      ->capture_default_str()
      ->check(CLI::Range(2, 10000000));
  add_seed_option(*o.range_cmd, r.sim.seed, "Random seed (simulation)");

  EdgeOptions& e = o.edge;
  o.edge_cmd = sub.add_subcommand("edge", "Across-beam sigma from edge-boundary jitter");
  auto* elog = add_input_file(*o.edge_cmd, "--log", e.log, "Log of a stationary scanner at an edge",
                              log_file());
  o.edge_cmd->add_option("--first-beam", e.first_beam, "A beam on the object (with --log)");
  o.edge_cmd->add_option("--split-range", e.split_range,
                         "Metres: shorter readings are on the object (with --log)");
  o.edge_cmd->add_option("--distance", e.distance, "Metres to the edge (Eq. 5)")
      ->capture_default_str()
      ->check(positive());
  o.edge_cmd
      ->add_option("--edge-fraction", e.edge_fraction,
                   "Edge position past the last sure beam, in steps [0, 1)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 0.999));
  auto* esim = o.edge_cmd->add_flag("--simulate", e.simulate, "Simulate the experiment");
  esim->excludes(elog);
  o.edge_cmd->add_option("--runs", e.sim.runs, "Runs (simulation)")->capture_default_str();
  o.edge_cmd->add_option("--scans", e.sim.scans, "Scans per run (simulation)")
      ->capture_default_str();
  add_seed_option(*o.edge_cmd, e.sim.seed, "Random seed (simulation)");
}

}  // namespace

Command add_calibrate_command(CLI::App& app) {
  return make_command<CalibrateOptions>(app, "calibrate", add_calibrate_options, run_calibrate);
}

}  // namespace pgmcl::app
