/// pgmcl localize: run the filter over a log against a map.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "app_util.hpp"
#include "commands.hpp"

namespace pgmcl::app {
namespace {

struct LocalizeOptions {
  std::string map;
  std::string log;
  std::string config;
  std::vector<std::string> sets;
  std::string init;
  bool global = false;
  std::string truth;
  std::string relations;
  double time_offset = 0.0;
  int threads = 1;
  std::uint64_t seed = 42;
  std::string out = "pgmcl-out";
  bool quiet = false;
};

int run_localize(const LocalizeOptions&) {
  not_available("localize", "waiting for pgmcl::Localizer and the YAML config adapter");
}

}  // namespace

Command add_localize_command(CLI::App& app) {
  auto o = std::make_shared<LocalizeOptions>();
  CLI::App* sub = app.add_subcommand("localize", "Localise a logged robot on a map");
  sub->add_option("--map", o->map, "Map YAML (ROS map_server)")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--log", o->log, "CARMEN log (.log, .clf, optionally .gz)")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--config", o->config, "Filter configuration YAML")->check(CLI::ExistingFile);
  sub->add_option("--set", o->sets, "Override a config key, e.g. filter.particles=2000")
      ->take_all();
  auto* init =
      sub->add_option("--init", o->init, "Initial pose X,Y,THETA[,SX,SY,STH] (metres, radians)");
  auto* global = sub->add_flag("--global", o->global, "Start with global localisation");
  init->excludes(global);
  sub->add_option("--truth", o->truth, "Ground truth: TUM file or a corrected CARMEN log")
      ->check(CLI::ExistingFile);
  auto* rel = sub->add_option("--relations", o->relations, "Benchmark relations file")
                  ->check(CLI::ExistingFile);
  sub->add_option("--time-offset", o->time_offset,
                  "Seconds added to log stamps to match the relations")
      ->needs(rel);
  sub->add_option("--threads", o->threads, "OpenMP threads (0 = OpenMP default)")
      ->check(non_negative());
  sub->add_option("--seed", o->seed, "Random seed");
  sub->add_option("--out", o->out, "Output directory")->capture_default_str();
  sub->add_flag("--quiet", o->quiet, "No progress output");
  return {sub, [o] { return run_localize(*o); }};
}

}  // namespace pgmcl::app
