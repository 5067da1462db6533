/// pgmcl eval: accuracy of an estimated trajectory against ground truth (ATE without
/// alignment: both are in the map frame) and, optionally, the SLAM benchmark relations
/// (Kümmerle et al. 2009).

#include <cstdio>
#include <memory>
#include <string>

#include "app_util.hpp"
#include "commands.hpp"
#include "output_files.hpp"
#include "pgmcl/eval/evaluation.hpp"
#include "pgmcl/eval/metrics.hpp"
#include "pgmcl/eval/relations_error.hpp"
#include "pgmcl/io/relations.hpp"
#include "pgmcl/io/tum.hpp"

namespace pgmcl::app {
namespace {

struct EvalOptions {
  std::string estimate;
  std::string truth;
  std::string relations;
  double time_offset = 0.0;
  std::string out;
  io::AteOptions ate{};
};

int run_eval(const EvalOptions& o) {
  OutputFiles files;
  files.input(o.estimate, "--estimate");
  files.input(o.truth, "--truth");
  files.input(o.relations, "--relations");
  const std::string out_tmp = o.out.empty() ? std::string() : files.add(o.out, "--out");
  const io::Trajectory est = io::read_tum(o.estimate);
  const io::Trajectory truth = load_truth(o.truth);
  io::RunMetrics m;
  const io::AteResult ate = io::evaluate_ate(est, truth, o.ate);
  m.accuracy = io::accuracy_metrics(ate);
  std::printf("eval: %zu estimate poses, %zu matched to %zu truth poses\n", ate.estimated,
              ate.matched, truth.size());
  if (!o.relations.empty()) {
    io::RelationOptions ro;
    ro.time_offset = o.time_offset;
    const io::RelationResult rel = io::evaluate_relations(est, io::read_relations(o.relations), ro);
    m.relations = io::relations_metrics(rel);
    std::printf("eval: %zu of %zu relations matched\n", rel.matched, rel.relations);
    if (rel.matched == 0 && rel.relations > 0) {
      std::fprintf(stderr,
                   "pgmcl: warning: %s: no relation matched the estimate's stamps; does it "
                   "need --time-offset (intel: %.3f)?\n",
                   o.relations.c_str(), io::kIntelRelationsTimeOffset);
    }
  }
  std::printf("%s", io::metrics_table(m, false).c_str());
  if (ate.matched == 0) {
    throw std::runtime_error(o.estimate + ": no estimate pose matched the ground truth " + o.truth +
                             " in time");
  }
  if (!o.out.empty()) {
    write_text_file(out_tmp, io::metrics_yaml(m, false));
    files.commit();
  }
  return 0;
}

}  // namespace

Command add_eval_command(CLI::App& app) {
  auto o = std::make_shared<EvalOptions>();
  CLI::App* sub = app.add_subcommand("eval", "Evaluate an estimated trajectory");
  sub->add_option("--estimate", o->estimate, "Estimated trajectory (TUM)")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--truth", o->truth, "Ground truth: TUM file or a corrected CARMEN log")
      ->required()
      ->check(CLI::ExistingFile);
  auto* rel = sub->add_option("--relations", o->relations, "Benchmark relations file")
                  ->check(CLI::ExistingFile);
  sub->add_option("--time-offset", o->time_offset,
                  "Seconds added to the estimate's stamps to match the relations")
      ->needs(rel);
  sub->add_option("--converged-m", o->ate.converged_translation,
                  "Converged once the position error stays below this (metres)")
      ->capture_default_str()
      ->check(positive());
  sub->add_option("--converged-deg", o->ate.converged_rotation_deg,
                  "... and the heading error below this (degrees)")
      ->capture_default_str()
      ->check(positive());
  sub->add_option("--out", o->out, "Write the figures as YAML here");
  return {sub, [o] { return run_eval(*o); }};
}

}  // namespace pgmcl::app
