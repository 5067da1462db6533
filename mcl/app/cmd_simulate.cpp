/// pgmcl simulate: simulate a scenario into a CARMEN log (and its ground truth).

#include <memory>
#include <string>

#include "app_util.hpp"
#include "commands.hpp"

namespace pgmcl::app {
namespace {

struct SimulateOptions {
  std::string scenario;
  std::string out;
  std::string truth;
};

int run_simulate(const SimulateOptions&) {
  not_available("simulate", "waiting for the simulator's Scenario and its YAML adapter");
}

}  // namespace

Command add_simulate_command(CLI::App& app) {
  auto o = std::make_shared<SimulateOptions>();
  CLI::App* sub = app.add_subcommand("simulate", "Simulate a scenario into a CARMEN log");
  sub->add_option("scenario", o->scenario, "Scenario YAML")->required()->check(CLI::ExistingFile);
  sub->add_option("--out", o->out, "Output CARMEN log")->required();
  sub->add_option("--truth", o->truth, "Also write the true trajectory (TUM)");
  return {sub, [o] { return run_simulate(*o); }};
}

}  // namespace pgmcl::app
