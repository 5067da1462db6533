/// pgmcl: the command-line front end. Every failure ends as one "pgmcl: error: ..." line on
/// stderr and a non-zero exit code (2 usage, 1 input/runtime, 130/143 stopped by
/// SIGINT/SIGTERM: cli_errors.hpp, interrupt.hpp).

#include <CLI/CLI.hpp>
#include <iostream>
#include <string>
#include <vector>

#include "cli_errors.hpp"
#include "commands.hpp"
#include "interrupt.hpp"
#include "pgmcl/io/values.hpp"

int main(int argc, char** argv) {
  pgmcl::app::install_interrupt_handlers();
  CLI::App app{
      "pgmcl: Monte Carlo localisation with the planar Gaussian beam model "
      "(Dekan et al.)",
      "pgmcl"};
  app.set_version_flag("--version", PGMCL_VERSION);
  app.require_subcommand(1);
  app.fallthrough(false);
  const std::vector<pgmcl::app::Command> commands = {
      pgmcl::app::add_localize_command(app),  pgmcl::app::add_run_command(app),
      pgmcl::app::add_simulate_command(app),  pgmcl::app::add_map_command(app),
      pgmcl::app::add_perturb_command(app),   pgmcl::app::add_perturb_map_command(app),
      pgmcl::app::add_eval_command(app),      pgmcl::app::add_kernel_command(app),
      pgmcl::app::add_calibrate_command(app), pgmcl::app::add_config_command(app),
      pgmcl::app::add_convert_command(app),
  };
  return pgmcl::app::run_reporting_errors(
      [&]() -> int {
        try {
          app.parse(argc, argv);
        } catch (const CLI::CallForHelp& e) {
          return app.exit(e);
        } catch (const CLI::CallForAllHelp& e) {
          return app.exit(e);
        } catch (const CLI::CallForVersion& e) {
          return app.exit(e);
        } catch (const CLI::ParseError& e) {
          // CLI11 reports an unknown command as "A subcommand is required"; name it instead.
          bool known = false;
          for (const auto& c : commands) known = known || (argc > 1 && c.sub->check_name(argv[1]));
          if (argc > 1 && argv[1][0] != '-' && !known) {
            std::string names;
            for (const auto& c : commands) names += (names.empty() ? "" : ", ") + c.sub->get_name();
            std::cerr << "pgmcl: error: unknown command '" << argv[1] << "' (commands: " << names
                      << ")\n";
            return pgmcl::app::kExitUsage;
          }
          std::cerr << "pgmcl: error: " << e.what() << "\n"
                    << "Run 'pgmcl --help' or 'pgmcl <command> --help' for usage.\n";
          return pgmcl::app::kExitUsage;
        }
        for (const auto& c : commands) {
          if (!c.sub->parsed()) continue;
          const int code = c.run();
          // A command that finished although the user asked it to stop still reports it.
          if (code == pgmcl::app::kExitOk && pgmcl::app::interrupted() &&
              !pgmcl::app::interrupt_handled()) {
            std::cerr << "pgmcl: interrupted by "
                      << pgmcl::app::signal_name(pgmcl::app::interrupt_signal()) << "\n";
            return pgmcl::app::interrupted_exit_code();
          }
          return code;
        }
        return pgmcl::app::kExitUsage;  // unreachable: require_subcommand(1)
      },
      std::cerr);
}
