/// pgmcl calibrate: fit filter parameters against simulated or logged data.

#include <memory>
#include <string>
#include <vector>

#include "app_util.hpp"
#include "commands.hpp"

namespace pgmcl::app {
namespace {

struct CalibrateOptions {
  std::vector<std::string> args;
};

int run_calibrate(const CalibrateOptions&) {
  not_available("calibrate", "waiting for the simulator's Scenario and the Localizer");
}

}  // namespace

Command add_calibrate_command(CLI::App& app) {
  auto o = std::make_shared<CalibrateOptions>();
  CLI::App* sub = app.add_subcommand("calibrate", "Calibrate filter parameters (not yet)");
  sub->allow_extras();
  return {sub, [o] { return run_calibrate(*o); }};
}

}  // namespace pgmcl::app
