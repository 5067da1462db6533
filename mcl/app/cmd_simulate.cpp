/// pgmcl simulate: simulate a scenario (configs/scenarios/*.yaml) into a CARMEN log a filter
/// can replay, and optionally its ground truth as TUM. --set overrides scenario keys as
/// `run` and `localize` override filter keys; --seed is --set seed=S.

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "app_util.hpp"
#include "commands.hpp"
#include "interrupt.hpp"
#include "output_files.hpp"
#include "pgmcl/config/scenario_yaml.hpp"
#include "pgmcl/io/sim_log_io.hpp"
#include "pgmcl/sims/scenario.hpp"

namespace pgmcl::app {
namespace {

struct SimulateOptions {
  std::string scenario;
  std::string out;
  std::string truth;
  DeprecatedName truth_name;
  std::vector<std::string> sets;
  std::uint64_t seed = 0;
  CLI::Option* seed_opt = nullptr;
  int threads = 0;
  bool quiet = false;
};

int run_simulate(const SimulateOptions& o) {
  o.truth_name.note_if_used();
  std::vector<std::string> sets = o.sets;
  if (o.seed_opt->count() > 0) sets.push_back("seed=" + std::to_string(o.seed));
  OutputFiles files;
  files.input(o.scenario, "scenario");
  const std::string out_tmp = files.add(o.out, "--out");
  const std::string truth_tmp =
      o.truth.empty() ? std::string() : files.add(o.truth, o.truth_name.used());
  maps::OccupancyGrid map;
  const io::ScenarioFile sf = io::read_scenario_file(o.scenario, map, sets);
  files.input(sf.map_path, "the scenario's map");
  files.input(map_image_path(sf.map_path), "the scenario's map image");
  if (const std::string w = threads_warning(o.threads); !w.empty()) {
    std::fprintf(stderr, "pgmcl: warning: %s\n", w.c_str());
  }
  const sims::SimulationLog log = sims::simulate(sf.scenario, map, o.threads);
  check_interrupt();
  if (log.records.empty()) {
    throw std::runtime_error(o.scenario + ": the simulation produced no scans (duration " +
                             std::to_string(sf.scenario.duration) + " s)");
  }
  io::write_sim_carmen(out_tmp, log);
  if (!o.truth.empty()) io::write_sim_truth_tum(truth_tmp, log);
  files.commit();
  if (!o.quiet) {
    double travelled = 0.0;
    for (std::size_t i = 1; i < log.records.size(); ++i) {
      const Pose2 &a = log.records[i - 1].truth, &b = log.records[i].truth;
      travelled += std::hypot(b.x - a.x, b.y - a.y);
    }
    const Pose2 err = log.records.back().truth.between(log.records.back().odometry);
    std::printf(
        "simulate: %s: %zu scans of %zu beams over %.1f s, %.1f m travelled, %zu "
        "kidnap(s), seed %llu; final odometry error %.3f m, %.2f deg (odometry frame); wrote "
        "%s%s%s\n",
        sf.name.c_str(), log.records.size(), log.records.front().scan.ranges.size(),
        log.records.back().stamp - log.records.front().stamp, travelled, log.kidnap_times.size(),
        static_cast<unsigned long long>(sf.scenario.seed), std::hypot(err.x, err.y),
        std::abs(err.theta) * 180.0 / std::numbers::pi, o.out.c_str(),
        o.truth.empty() ? "" : " and ", o.truth.c_str());
  }
  return 0;
}

void add_simulate_options(CLI::App& sub, SimulateOptions& o) {
  sub.description("Simulate a scenario into a CARMEN log");
  add_input_file(sub, "scenario", o.scenario, "Scenario YAML (configs/scenarios/)", scenario_file())
      ->required();
  sub.add_option("--out", o.out, "Output CARMEN log (.gz ok)")->required();
  auto* truth = sub.add_option("--truth-out", o.truth, "Also write the true trajectory (TUM)")
                    ->type_name("FILE");
  o.truth_name = DeprecatedName(sub, truth, "--truth", o.truth);
  sub.add_option("--set", o.sets,
                 "Override a scenario key, e.g. duration=20 or robot.start=[1,2,0] (value read "
                 "as YAML)")
      ->take_all();
  o.seed_opt = add_seed_option(sub, o.seed, "Random seed (the scenario's seed: key)");
  add_threads_option(sub, o.threads,
                     "OpenMP threads (0 = OpenMP default); the log is the same for any count")
      ->capture_default_str();
  sub.add_flag("--quiet", o.quiet, "No summary line");
}

}  // namespace

Command add_simulate_command(CLI::App& app) {
  return make_command<SimulateOptions>(app, "simulate", add_simulate_options, run_simulate);
}

}  // namespace pgmcl::app
