#pragma once
/// The `pgmcl` subcommands. Each add_*_command registers its CLI11 subcommand (options and
/// help) on `app` and returns what to run when the user selects it; the options live in the
/// returned closure. Failures are reported by throwing (main prints "pgmcl: error: ...").

#include <CLI/CLI.hpp>
#include <functional>
#include <memory>
#include <string>

namespace pgmcl::app {

struct Command {
  CLI::App* sub = nullptr;
  std::function<int()> run;
};

/// Registers subcommand `name` whose options fill one `Options` struct: `declare(sub, options)`
/// adds them (and the subcommand's description), and the returned command calls
/// `run(options)`. The struct lives in the closure, so the pointers CLI11 keeps into it stay
/// valid for as long as the command.
template <class Options, class Declare, class Run>
Command make_command(CLI::App& app, const std::string& name, Declare declare, Run run) {
  auto options = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(name);
  declare(*sub, *options);
  return {sub, [options, run] { return run(*options); }};
}

Command add_localize_command(CLI::App& app);
Command add_run_command(CLI::App& app);
Command add_simulate_command(CLI::App& app);
Command add_map_command(CLI::App& app);
Command add_perturb_command(CLI::App& app);
Command add_perturb_map_command(CLI::App& app);
Command add_eval_command(CLI::App& app);
Command add_kernel_command(CLI::App& app);
Command add_calibrate_command(CLI::App& app);
Command add_config_command(CLI::App& app);
Command add_convert_command(CLI::App& app);

}  // namespace pgmcl::app
