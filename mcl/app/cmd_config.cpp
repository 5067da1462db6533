/// pgmcl config: the filter configuration after --config and --set, as the YAML every run
/// writes next to its results, or (--reference) every key with its default, unit and
/// allowed values as Markdown (configs/reference.md), or (--amcl) the AMCL parameter names
/// and their pgmcl keys (the table in configs/README.md).

#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "app_util.hpp"
#include "commands.hpp"
#include "pgmcl/config/config_yaml.hpp"
#include "pgmcl/config/key_hints.hpp"

namespace pgmcl::app {
namespace {

struct ConfigOptions {
  std::string config;
  std::vector<std::string> sets;
  bool reference = false;
  bool amcl = false;
};

int run_config(const ConfigOptions& o) {
  if (o.amcl) {
    std::cout << io::amcl_parameter_table();
    return 0;
  }
  if (o.reference) {
    std::cout << io::localizer_config_reference();
    return 0;
  }
  LocalizerConfig cfg;
  if (!o.config.empty()) io::read_localizer_config(o.config, cfg);
  io::apply_localizer_overrides(o.sets, cfg);
  std::cout << io::localizer_config_yaml(cfg);
  return 0;
}

void add_config_options(CLI::App& sub, ConfigOptions& o) {
  sub.description("Print the filter configuration after --config and --set, or the key reference");
  const FilterOptions filter = add_filter_options(sub, o.config, o.sets);
  auto* ref = sub.add_flag("--reference", o.reference,
                           "Print every key with its default, unit and allowed values (Markdown)");
  ref->excludes(filter.config)->excludes(filter.sets);
  sub.add_flag("--amcl", o.amcl,
               "Print the table of AMCL (nav2_amcl, ROS 1 amcl) parameters and their pgmcl keys")
      ->excludes(ref)
      ->excludes(filter.config)
      ->excludes(filter.sets);
}

}  // namespace

Command add_config_command(CLI::App& app) {
  return make_command<ConfigOptions>(app, "config", add_config_options, run_config);
}

}  // namespace pgmcl::app
