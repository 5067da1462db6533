/// pgmcl run: one experiment file = map + data (a log, or a scenario to simulate) + filter
/// (schema: mcl/io/include/pgmcl/config/experiment_yaml.hpp). A simulated log and its truth
/// are kept in the output directory (sim.log.gz, truth.tum) so the run can be replayed.

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
  bool quiet = false;
};

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
  std::vector<std::string> sets = o.sets;
  if (!o.out.empty()) sets.push_back("out=" + o.out);
  const io::Experiment e = io::read_experiment(o.experiment, sets);

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
  io::CarmenLog log;
  if (!e.scenario.empty()) {
    const io::ScenarioFile sf = io::read_scenario_file(e.scenario, world);
    files.input(sf.map_path, "the scenario's map");
    files.input(map_image_path(sf.map_path), "the scenario's map image");
    const sims::SimulationLog sim = sims::simulate(sf.scenario, world);
    check_interrupt();
    if (sim.records.empty())
      throw std::runtime_error(e.scenario + ": simulation produced no scans");
    io::write_sim_carmen(sim_log, sim);
    io::write_sim_truth_tum(sim_truth, sim);
    log = io::to_carmen_log(sim);
    job.log_name = e.scenario + " (simulated)";
    job.truth = io::sim_truth_trajectory(sim);
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
  } else {
    job.map = &world;
  }
  job.log = &log;
  if (!e.relations.empty()) {
    job.relations = io::read_relations(e.relations);
    job.relations_time_offset = e.time_offset;
  }
  check_job(job, map_name, e.path + ": init");
  const io::RunMetrics m = run_localization(job, outputs, files);
  std::printf("%s: %s\n", e.name.c_str(), summary_line(m, e.out).c_str());
  return finish_exit_code(m, e.out);
}

}  // namespace

Command add_run_command(CLI::App& app) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* sub = app.add_subcommand("run", "Run an experiment file (map + data + filter)");
  sub->add_option("experiment", o->experiment, "Experiment YAML")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--out", o->out, "Output directory (default: the experiment's `out`)");
  sub->add_option("--set", o->sets,
                  "Override an experiment key: filter.<key>=v, name, map, out, init, data.*")
      ->take_all();
  sub->add_flag("--quiet", o->quiet, "No progress output");
  return {sub, [o] { return run_run(*o); }};
}

}  // namespace pgmcl::app
