/// pgmcl run: one experiment file = map + data (a log, or a scenario to simulate) + filter.

#include <memory>
#include <string>
#include <vector>

#include "app_util.hpp"
#include "commands.hpp"

namespace pgmcl::app {
namespace {

struct RunOptions {
  std::string experiment;
  std::string out;
  std::vector<std::string> sets;
};

int run_run(const RunOptions&) {
  not_available("run", "waiting for pgmcl::Localizer and the experiment YAML adapter");
}

}  // namespace

Command add_run_command(CLI::App& app) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* sub = app.add_subcommand("run", "Run an experiment file (map + data + filter)");
  sub->add_option("experiment", o->experiment, "Experiment YAML")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--out", o->out, "Output directory (default: from the experiment)");
  sub->add_option("--set", o->sets, "Override an experiment key, e.g. filter.particles=2000")
      ->take_all();
  return {sub, [o] { return run_run(*o); }};
}

}  // namespace pgmcl::app
