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
  CLI::Option* time_offset_opt = nullptr;
  CLI::Option* truth_offset_opt = nullptr;
  std::string out;
  io::AteOptions ate{};
};

/// What lock-on and convergence mean, in one line each, for the figures of the table.
void print_definitions(const io::AccuracyMetrics& a, const io::AteOptions& opt) {
  if (a.lock_on_s) {
    std::printf(
        "eval: locked on (within %.3g m from then on) at %.1f s, after %.1f m of travel; "
        "from then on ATE RMSE %.3f m (the whole run: %.3f m)\n",
        opt.lost_translation, *a.lock_on_s, a.lock_on_travel_m, a.post_lock_ate_rmse_m,
        a.ate_rmse_m);
  } else {
    std::printf("eval: more than %.3g m off at the end: never locked on for good\n",
                opt.lost_translation);
  }
  if (a.converged_after_s) {
    std::printf(
        "eval: converged_after_s %.1f: from then on every error is within %.3g m and "
        "%.3g deg (--converged-m, --converged-deg); one late excursion moves it\n",
        *a.converged_after_s, opt.converged_translation, opt.converged_rotation_deg);
  }
}

int run_eval(EvalOptions o) {
  // --time-offset is the relations' offset when there are relations (the intel log's
  // relations are in another clock), else it shifts the estimate against the truth.
  if (o.time_offset_opt->count() > 0 && o.relations.empty() && o.truth_offset_opt->count() == 0)
    o.ate.time_offset = o.time_offset;
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
  if (ate.matched == 0) {
    throw std::runtime_error(o.estimate + ": no estimate pose matched the ground truth " + o.truth +
                             " in time (do the clocks differ? --truth-offset S shifts the "
                             "estimate's stamps, --tolerance S widens the match)");
  }
  if (const std::string w = io::ate_match_warning(ate, o.ate); !w.empty()) {
    std::fprintf(stderr,
                 "pgmcl: warning: %s: %s; if the clocks differ, --truth-offset S shifts the "
                 "estimate's stamps, --tolerance S widens the match\n",
                 o.estimate.c_str(), w.c_str());
  }
  if (const std::string w = io::truth_coverage_warning(ate); !w.empty()) {
    std::fprintf(stderr, "pgmcl: warning: %s: %s\n", o.estimate.c_str(), w.c_str());
  }
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
  print_definitions(*m.accuracy, o.ate);
  std::printf("%s", io::metrics_table(m, false).c_str());
  if (!o.out.empty()) {
    write_text_file(out_tmp, io::metrics_yaml(m, false));
    files.commit();
  }
  return 0;
}

void add_eval_options(CLI::App& sub, EvalOptions& o) {
  sub.description("Evaluate an estimated trajectory");
  add_input_file(sub, "--estimate", o.estimate, "Estimated trajectory (TUM)",
                 trajectory_file(false))
      ->required();
  add_input_file(sub, "--truth", o.truth, "Ground truth: TUM file or a corrected CARMEN log",
                 trajectory_file(true))
      ->required();
  add_input_file(sub, "--relations", o.relations, "Benchmark relations file", relations_file());
  o.time_offset_opt =
      sub.add_option("--time-offset", o.time_offset,
                     "Seconds added to the estimate's stamps: to match the relations with "
                     "--relations, else to match the truth");
  o.truth_offset_opt = sub.add_option("--truth-offset", o.ate.time_offset,
                                      "Seconds added to the estimate's stamps to match the "
                                      "truth (with --relations too)");
  sub.add_option("--tolerance", o.ate.tolerance,
                 "Seconds: a truth pose this close in time matches where the truth cannot be "
                 "interpolated (gaps over 1 s, its ends)")
      ->capture_default_str()
      ->check(non_negative());
  sub.add_option("--converged-m", o.ate.converged_translation,
                 "Converged once the position error stays below this (metres)")
      ->capture_default_str()
      ->check(positive());
  sub.add_option("--converged-deg", o.ate.converged_rotation_deg,
                 "... and the heading error below this (degrees)")
      ->capture_default_str()
      ->check(positive());
  sub.add_option("--out", o.out, "Write the figures as YAML here");
}

}  // namespace

Command add_eval_command(CLI::App& app) {
  return make_command<EvalOptions>(app, "eval", add_eval_options, run_eval);
}

}  // namespace pgmcl::app
