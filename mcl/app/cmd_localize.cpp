/// pgmcl localize: run the filter over a log (CARMEN, or a ROS 1 bag with --bag) against a
/// map. A bag is read into the same in-memory log (pgmcl::rosbag_io) and replayed by the
/// same loop (pgmcl::replay).
///
/// Configuration precedence: struct defaults < --config file < --set overrides (in order)
/// < --threads / --seed. Start: --init pose, --global, or (neither) the ground truth at the
/// first scan when --truth is given, else global localisation.

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "app_util.hpp"
#include "bag_input.hpp"
#include "commands.hpp"
#include "localize_pipeline.hpp"
#include "pgmcl/config/config_yaml.hpp"
#include "pgmcl/io/relations.hpp"
#include "pgmcl/io/values.hpp"
#include "pgmcl/map_io/map_io.hpp"

namespace pgmcl::app {
namespace {

struct LocalizeOptions {
  std::string map;
  std::string log;
  std::string bag;
  BagInput bag_input;
  std::string config;
  std::vector<std::string> sets;
  std::string init;
  CLI::Option* init_opt = nullptr;
  bool global = false;
  std::string truth;
  std::string relations;
  double time_offset = 0.0;
  int threads = 1;
  std::uint64_t seed = 42;
  CLI::Option* threads_opt = nullptr;
  CLI::Option* seed_opt = nullptr;
  std::string out = "pgmcl-out";
  bool strict = false;
  bool quiet = false;
};

int run_localize(const LocalizeOptions& o) {
  LocalizeJob job;
  if (!o.config.empty()) io::read_localizer_config(o.config, job.config);
  io::apply_localizer_overrides(o.sets, job.config);
  if (o.threads_opt->count() > 0) job.config.threads = o.threads;
  if (o.seed_opt->count() > 0) job.config.seed = o.seed;
  // --init "" is a mistake, not a request for global localisation.
  if (o.init_opt->count() > 0) job.init = parse_init(o.init);
  if (o.log.empty() == o.bag.empty())
    throw io::UsageError("localize: give the scans with --log (CARMEN) or --bag (ROS 1)");
  const std::string& source = o.bag.empty() ? o.log : o.bag;

  // Every output and input is known before any work: an unwritable --out or an output that
  // would overwrite an input fails now, not after the run.
  OutputFiles files;
  files.input(o.map, "--map");
  files.input(map_image_path(o.map), "--map's image");
  files.input(o.log, "--log");
  files.input(o.bag, "--bag");
  files.input(o.config, "--config");
  files.input(o.truth, "--truth");
  files.input(o.relations, "--relations");
  const LocalizeOutputs outputs = register_localize_outputs(files, o.out, "--out");

  maps::MapLoadReport report;
  const maps::OccupancyGrid map = maps::load_map(o.map, &report);
  for (const auto& w : report.warnings) warn(job, w);
  const io::CarmenLog log =
      o.bag.empty() ? read_log(o.log, {}, o.strict, &job.warnings)
                    : read_bag_input(o.bag, o.bag_input, "localize --bag", &job.warnings);

  job.map = &map;
  job.log = &log;
  job.log_name = source;
  if (!o.truth.empty()) job.truth = load_truth(o.truth);
  if (!o.relations.empty()) {
    job.relations = io::read_relations(o.relations);
    job.relations_time_offset = o.time_offset;
  }
  if (o.init_opt->count() == 0 && !o.global && job.truth) {
    job.init.kind = InitialBelief::Kind::kTruth;
  }
  check_job(job, o.map, "--init");
  job.map_name = o.map;
  job.title = run_title(o.out, source);
  job.quiet = o.quiet;
  const io::RunMetrics m = run_localization(job, outputs, files);
  std::printf("%s\n", summary_line(m, o.out, job.config).c_str());
  return finish_exit_code(m, o.out);
}

void add_localize_options(CLI::App& sub, LocalizeOptions& o) {
  sub.description("Localise a logged robot on a map");
  add_input_file(sub, "--map", o.map, "Map YAML (ROS map_server)", map_file())->required();
  auto* log =
      add_input_file(sub, "--log", o.log, "CARMEN log (.log, .clf, optionally .gz)", log_file());
  auto* bag = sub.add_option("--bag", o.bag, "ROS 1 bag (instead of --log)")
                  ->check(CLI::ExistingFile)
                  ->excludes(log);
  add_bag_input_options(sub, o.bag_input, bag);
  add_filter_options(sub, o.config, o.sets);
  o.init_opt =
      sub.add_option("--init", o.init, "Initial pose X,Y,THETA[,SX,SY,STH] (metres, radians)");
  auto* global = sub.add_flag("--global", o.global, "Start with global localisation");
  o.init_opt->excludes(global);
  add_input_file(sub, "--truth", o.truth, "Ground truth: TUM file or a corrected CARMEN log",
                 trajectory_file(true));
  auto* rel =
      add_input_file(sub, "--relations", o.relations, "Benchmark relations file", relations_file());
  sub.add_option("--time-offset", o.time_offset,
                 "Seconds added to log stamps to match the relations")
      ->needs(rel);
  o.threads_opt = add_threads_option(sub, o.threads, "OpenMP threads (0 = OpenMP default)");
  o.seed_opt = add_seed_option(sub, o.seed, "Random seed");
  sub.add_option("--out", o.out, "Output directory")->capture_default_str();
  add_strict_flag(sub, o.strict);
  sub.add_flag("--quiet", o.quiet, "No progress output");
}

}  // namespace

Command add_localize_command(CLI::App& app) {
  return make_command<LocalizeOptions>(app, "localize", add_localize_options, run_localize);
}

}  // namespace pgmcl::app
