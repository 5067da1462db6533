/// pgmcl eval: accuracy of an estimated trajectory against ground truth.

#include <memory>
#include <string>

#include "app_util.hpp"
#include "commands.hpp"

namespace pgmcl::app {
namespace {

struct EvalOptions {
  std::string estimate;
  std::string truth;
  std::string relations;
  double time_offset = 0.0;
  std::string out;
};

int run_eval(const EvalOptions&) {
  not_available("eval", "waiting for the TUM reader and ATE");
}

}  // namespace

Command add_eval_command(CLI::App& app) {
  auto o = std::make_shared<EvalOptions>();
  CLI::App* sub = app.add_subcommand("eval", "Evaluate an estimated trajectory");
  sub->add_option("--estimate", o->estimate, "Estimated trajectory (TUM)")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--truth", o->truth, "Ground truth (TUM)")->required()->check(CLI::ExistingFile);
  auto* rel = sub->add_option("--relations", o->relations, "Benchmark relations file")
                  ->check(CLI::ExistingFile);
  sub->add_option("--time-offset", o->time_offset,
                  "Seconds added to the estimate's stamps to match the relations")
      ->needs(rel);
  sub->add_option("--out", o->out, "Write the figures as YAML here");
  return {sub, [o] { return run_eval(*o); }};
}

}  // namespace pgmcl::app
