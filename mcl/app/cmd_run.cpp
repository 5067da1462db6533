/// pgmcl run: one experiment file = map + data (a log, or a scenario to simulate) + filter
/// (schema: mcl/io/include/pgmcl/config/experiment_yaml.hpp). A simulated log and its truth
/// are kept in the output directory (sim.log.gz, truth.tum) so the run can be replayed.

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "app_util.hpp"
#include "cli_errors.hpp"
#include "commands.hpp"
#include "interrupt.hpp"
#include "localize_pipeline.hpp"
#include "pgmcl/config/experiment_yaml.hpp"
#include "pgmcl/config/scenario_yaml.hpp"
#include "pgmcl/io/relations.hpp"
#include "pgmcl/io/sim_log_io.hpp"
#include "pgmcl/io/tum.hpp"
#include "pgmcl/io/values.hpp"
#include "pgmcl/map_io/map_io.hpp"
#include "pgmcl/sims/scenario.hpp"

namespace pgmcl::app {
namespace {

struct RunOptions {
  std::string experiment;
  std::string out;
  std::vector<std::string> sets;
  int threads = 1;
  std::uint64_t seed = 42;
  CLI::Option* threads_opt = nullptr;
  CLI::Option* seed_opt = nullptr;
  bool quiet = false;
};

/// The simulated moving obstacles over the run, for overlay.png.
std::vector<ObstacleDrawing> obstacle_drawings(const sims::Scenario& sc,
                                               const sims::SimulationLog& sim) {
  std::vector<ObstacleDrawing> out;
  const double t0 = sim.records.front().stamp, t1 = sim.records.back().stamp;
  auto path = [&](const sims::ObstaclePath& p, double yaw) {
    std::vector<Pose2> pts;
    for (double t = t0; t <= t1 + 1e-9; t += 0.1) {
      const sims::Point2 q = p.position_at(t);
      pts.push_back({q.x, q.y, yaw});
    }
    return pts;
  };
  for (const sims::DiscObstacle& d : sc.discs) out.push_back({path(d.path, 0.0), d.radius, 0, 0});
  for (const sims::BoxObstacle& b : sc.boxes)
    out.push_back({path(b.path, b.yaw), 0.0, b.half_length, b.half_width});
  return out;
}

InitialBelief to_belief(const io::Experiment& e, bool have_truth) {
  const io::ExperimentInit& init = e.init;
  InitialBelief b;
  switch (init.kind) {
    case io::ExperimentInit::Kind::kDefault:
      b.kind = have_truth ? InitialBelief::Kind::kTruth : InitialBelief::Kind::kGlobal;
      break;
    case io::ExperimentInit::Kind::kGlobal:
      b.kind = InitialBelief::Kind::kGlobal;
      break;
    case io::ExperimentInit::Kind::kTruth:
      if (!have_truth) {
        throw io::UsageError(e.path +
                             ": init: 'truth' needs ground truth (data.truth or "
                             "data.scenario)");
      }
      b.kind = InitialBelief::Kind::kTruth;
      break;
    case io::ExperimentInit::Kind::kPose:
      b.kind = InitialBelief::Kind::kPose;
      b.pose = init.pose;
      break;
  }
  b.sigma_xy = init.sigma_x;
  b.sigma_y = init.sigma_y;
  b.sigma_theta = init.sigma_theta;
  return b;
}

int run_run(const RunOptions& o) {
  // Precedence as in localize: the file < --set (in order) < --threads / --seed.
  std::vector<std::string> sets = o.sets;
  if (!o.out.empty()) sets.push_back("out=" + o.out);
  if (o.threads_opt->count() > 0) sets.push_back("threads=" + std::to_string(o.threads));
  if (o.seed_opt->count() > 0) sets.push_back("seed=" + std::to_string(o.seed));
  const io::Experiment e = io::read_experiment(o.experiment, sets);
  for (const std::string& n : e.notes) std::fprintf(stderr, "pgmcl: note: %s\n", n.c_str());

  OutputFiles files;
  files.input(o.experiment, "experiment");
  files.input(e.scenario, "data.scenario");
  files.input(e.log, "data.log");
  files.input(e.truth, "data.truth");
  files.input(e.relations, "data.relations");
  if (!e.map.empty()) {
    files.input(e.map, "map");
    files.input(map_image_path(e.map), "map's image");
  }
  const LocalizeOutputs outputs = register_localize_outputs(files, e.out, "out");
  std::string sim_log, sim_truth;
  if (!e.scenario.empty()) {
    sim_log = files.add((std::filesystem::path(e.out) / "sim.log.gz").string(), "out");
    sim_truth = files.add((std::filesystem::path(e.out) / "truth.tum").string(), "out");
  }

  LocalizeJob job;
  job.config = e.filter;
  job.title = e.name;
  job.quiet = o.quiet;
  job.init = to_belief(e, !e.scenario.empty() || !e.truth.empty());
  maps::OccupancyGrid map, world;
  std::string scenario_map;
  io::CarmenLog log;
  if (!e.scenario.empty()) {
    const io::ScenarioFile sf = io::read_scenario_file(e.scenario, world);
    scenario_map = sf.map_path;
    files.input(sf.map_path, "the scenario's map");
    files.input(map_image_path(sf.map_path), "the scenario's map image");
    const sims::SimulationLog sim = sims::simulate(sf.scenario, world, e.filter.threads);
    check_interrupt();
    if (sim.records.empty())
      throw std::runtime_error(e.scenario + ": simulation produced no scans");
    io::write_sim_carmen(sim_log, sim);
    io::write_sim_truth_tum(sim_truth, sim);
    log = io::to_carmen_log(sim);
    job.log_name = e.scenario + " (simulated)";
    job.truth = io::sim_truth_trajectory(sim);
    job.obstacles = obstacle_drawings(sf.scenario, sim);
    job.events = sim.kidnap_times;
    if (!o.quiet) {
      std::fprintf(stderr, "run: %s: simulated %zu scans from %s\n", e.name.c_str(),
                   sim.records.size(), e.scenario.c_str());
    }
  } else {
    log = read_log(e.log, {}, false, &job.warnings);
    job.log_name = e.log;
  }
  if (!e.truth.empty()) job.truth = load_truth(e.truth);
  const std::string map_name = e.map.empty() ? e.scenario : e.map;
  if (!e.map.empty()) {
    maps::MapLoadReport report;
    map = maps::load_map(e.map, &report);
    for (const auto& w : report.warnings) warn(job, w);
    job.map = &map;
    job.map_name = e.map;
  } else {
    job.map_name = scenario_map;
    job.map = &world;
  }
  job.log = &log;
  if (!e.relations.empty()) {
    job.relations = io::read_relations(e.relations);
    job.relations_time_offset = e.time_offset;
  }
  check_job(job, map_name, e.path + ": init");
  const io::RunMetrics m = run_localization(job, outputs, files);
  std::printf("%s: %s\n", e.name.c_str(), summary_line(m, e.out, job.config).c_str());
  return finish_exit_code(m, e.out);
}

void add_run_options(CLI::App& sub, RunOptions& o) {
  sub.description("Run an experiment file (map + data + filter)");
  add_input_file(sub, "experiment", o.experiment, "Experiment YAML", experiment_file())->required();
  sub.add_option("--out", o.out, "Output directory (default: the experiment's `out`)");
  sub.add_option("--set", o.sets,
                 "Override a key: a filter key as in localize (filter.particles=500), or name, "
                 "map, out, init (x,y,theta[,sx,sy,stheta] or YAML), data.*")
      ->take_all();
  o.threads_opt = add_threads_option(sub, o.threads, "OpenMP threads (0 = OpenMP default)");
  o.seed_opt = add_seed_option(sub, o.seed, "Random seed of the filter");
  sub.add_flag("--quiet", o.quiet, "No progress output");
}

}  // namespace

Command add_run_command(CLI::App& app) {
  return make_command<RunOptions>(app, "run", add_run_options, run_run);
}

}  // namespace pgmcl::app
