/// pgmcl simulate: simulate a scenario (configs/scenarios/*.yaml) into a CARMEN log a filter
/// can replay, and optionally its ground truth as TUM.

#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <string>

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
  bool quiet = false;
};

int run_simulate(const SimulateOptions& o) {
  OutputFiles files;
  files.input(o.scenario, "scenario");
  const std::string out_tmp = files.add(o.out, "--out");
  const std::string truth_tmp = o.truth.empty() ? std::string() : files.add(o.truth, "--truth");
  maps::OccupancyGrid map;
  const io::ScenarioFile sf = io::read_scenario_file(o.scenario, map);
  files.input(sf.map_path, "the scenario's map");
  files.input(map_image_path(sf.map_path), "the scenario's map image");
  const sims::SimulationLog log = sims::simulate(sf.scenario, map);
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
        "kidnap(s); final odometry error %.3f m, %.2f deg (odometry frame); wrote %s%s%s\n",
        sf.name.c_str(), log.records.size(), log.records.front().scan.ranges.size(),
        log.records.back().stamp - log.records.front().stamp, travelled, log.kidnap_times.size(),
        std::hypot(err.x, err.y), std::abs(err.theta) * 180.0 / std::numbers::pi, o.out.c_str(),
        o.truth.empty() ? "" : " and ", o.truth.c_str());
  }
  return 0;
}

}  // namespace

Command add_simulate_command(CLI::App& app) {
  auto o = std::make_shared<SimulateOptions>();
  CLI::App* sub = app.add_subcommand("simulate", "Simulate a scenario into a CARMEN log");
  sub->add_option("scenario", o->scenario, "Scenario YAML (configs/scenarios/)")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--out", o->out, "Output CARMEN log (.gz ok)")->required();
  sub->add_option("--truth", o->truth, "Also write the true trajectory (TUM)");
  sub->add_flag("--quiet", o->quiet, "No summary line");
  return {sub, [o] { return run_simulate(*o); }};
}

}  // namespace pgmcl::app
