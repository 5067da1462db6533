/// pgmcl_sweep: run time against error for one dataset. Loads (or simulates) the dataset
/// once, builds each table kind once, then runs the tracking filter (Localizer, started at
/// the true first pose) over the whole dataset for every configuration:
///  - grid study: particles x beams x table kind, with the default skip switches (gating,
///    selective resampling, beam subsampling) on and KLD off, so "particles" is the count;
///  - switch study (--switches): from a baseline with every skip switch on, each switch
///    turned off on its own (gating, selective resampling, KLD, beam subsampling), over
///    several filter seeds.
/// Times are steady_clock around Localizer::update(), one process, one thread by default.
/// Rows are appended to --csv (header written when the file is new); the grid rows carry a
/// Pareto flag (no other row of the dataset is both faster and more accurate).
///
///   pgmcl_sweep --name intel --map intel.yaml --log intel-corrected.log.gz --perturb 1
///               --particles 500,2000,5000 --beams 30,60,120 --csv sweep.csv [--switches]
///   pgmcl_sweep --name sim-office --sim 50 ...
///   pgmcl_sweep --name office --scenario configs/scenarios/office.yaml [--duration 60] ...

#include <CLI/CLI.hpp>
#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "../bench_common.hpp"
#include "../macro_common.hpp"
#include "pgmcl/mcl/localizer.hpp"
#include "sweep_data.hpp"

namespace pb = pgmcl::bench;
using pgmcl::maps::TableKind;

namespace {

struct RunConfig {
  std::string study = "grid";  // "grid" or "switch:<name>:<on|off>"
  TableKind kind = TableKind::kIsotropic;
  std::size_t particles = 2000;
  std::size_t beams = 60;  // beam subsampling target (kMaxBeams)
  bool gating = true;
  bool selective = true;  // selective resampling (N_eff threshold 0.5) vs every update
  bool kld = false;
  bool subsample = true;   // kMaxBeams(beams) vs every valid beam
  bool recovery = true;    // augmented-MCL random injection (not a skip switch; --recovery)
  bool hypotheses = true;  // competing hypotheses (--hypotheses)
  std::uint64_t seed = 1;
};

struct RunResult {
  std::size_t scans = 0, updates = 0;
  double ms_per_scan = 0, update_ms_mean = 0, update_ms_p95 = 0;
  double hypotheses_ms_mean = 0;  // of update_ms_mean
  double free_space_ms_mean = 0;  // of update_ms_mean
  double particles_mean = 0, beams_used_mean = 0;
  double ate_rmse = 0, ate_max = 0, heading_rmse_deg = 0;
  bool pareto = false;
};

pgmcl::LocalizerConfig make_config(const RunConfig& c, int threads,
                                   const pgmcl::MotionNoise& motion) {
  pgmcl::LocalizerConfig cfg;
  cfg.motion.noise = motion;
  cfg.filter.recovery.enabled = c.recovery;
  cfg.hypotheses.enabled = c.hypotheses;
  cfg.filter.particles = c.particles;
  cfg.filter.global_particles = c.particles;
  cfg.filter.kld.enabled = c.kld;
  cfg.filter.kld.max_particles = std::max<std::size_t>(c.particles, cfg.filter.kld.min_particles);
  cfg.filter.resample_threshold = c.selective ? 0.5 : 1.0;
  cfg.gating.enabled = c.gating;
  cfg.likelihood.selection =
      c.subsample ? pgmcl::BeamSelection{pgmcl::BeamSelectionMode::kMaxBeams, 1, c.beams}
                  : pgmcl::BeamSelection{pgmcl::BeamSelectionMode::kAll, 1, 1};
  cfg.time_backwards = pgmcl::TimeBackwardsPolicy::kReset;
  cfg.threads = threads;
  cfg.seed = c.seed;
  return cfg;
}

RunResult run_one(const pb::Dataset& d, std::shared_ptr<const pgmcl::maps::LikelihoodField> field,
                  const std::vector<std::uint32_t>& free_cells, const RunConfig& c, int threads,
                  const pgmcl::MotionNoise& motion) {
  const pgmcl::LocalizerConfig cfg = make_config(c, threads, motion);
  pgmcl::Localizer loc(std::move(field), free_cells, cfg);
  // Tracking: start at the true first pose with a small spread (metres^2, rad^2).
  const Eigen::Matrix3d cov = Eigen::Vector3d(0.01, 0.01, 0.0025).asDiagonal();
  loc.set_pose(d.truth.front(), cov);
  RunResult r;
  std::vector<double> update_ms;
  double total_ms = 0, hypotheses_ms = 0, free_space_ms = 0, sq = 0, sq_h = 0, particles = 0,
         beams = 0;
  for (std::size_t k = 0; k < d.scans.size(); ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    const pgmcl::UpdateResult u = loc.update(d.odometry[k], d.scans[k], d.stamps[k]);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    total_ms += ms;
    if (u.measured()) {
      update_ms.push_back(ms);
      hypotheses_ms += u.timings.hypotheses_ms;
      free_space_ms += u.timings.free_space_ms;
      particles += static_cast<double>(u.particles);
      beams += static_cast<double>(u.beams_used);
    }
    const double e = std::hypot(u.estimate.x - d.truth[k].x, u.estimate.y - d.truth[k].y);
    const double eh = pgmcl::wrap_angle(u.estimate.theta - d.truth[k].theta);
    sq += e * e;
    sq_h += eh * eh;
    r.ate_max = std::max(r.ate_max, e);
  }
  const auto n = static_cast<double>(d.scans.size());
  r.scans = d.scans.size();
  r.updates = update_ms.size();
  r.ms_per_scan = total_ms / n;
  r.ate_rmse = std::sqrt(sq / n);
  r.heading_rmse_deg = std::sqrt(sq_h / n) * 180.0 / std::numbers::pi;
  if (!update_ms.empty()) {
    const pb::TimeSummary t = pb::summarize_times(update_ms);
    r.update_ms_mean = t.mean;
    r.update_ms_p95 = t.p95;
    r.hypotheses_ms_mean = hypotheses_ms / static_cast<double>(update_ms.size());
    r.free_space_ms_mean = free_space_ms / static_cast<double>(update_ms.size());
    r.particles_mean = particles / static_cast<double>(update_ms.size());
    r.beams_used_mean = beams / static_cast<double>(update_ms.size());
  }
  return r;
}

std::vector<std::size_t> parse_sizes(const std::string& s) {
  std::vector<std::size_t> out;
  std::size_t b = 0;
  while (b < s.size()) {
    const std::size_t e = s.find(',', b);
    out.push_back(std::stoul(s.substr(b, e == std::string::npos ? std::string::npos : e - b)));
    if (e == std::string::npos) break;
    b = e + 1;
  }
  return out;
}

const char* on_off(bool b) {
  return b ? "1" : "0";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"pgmcl_sweep: run time against localisation error for one dataset"};
  std::string name = "dataset", csv_path = "sweep.csv", sim_size, scenario;
  double scenario_duration = 0.0;
  pb::LogOptions log_options;
  pb::SimSource sim;
  std::string particles_s = "500,2000,5000", beams_s = "30,60,120",
              kinds_s = "isotropic,oriented,offset";
  bool switches = false;
  std::size_t switch_seeds = 3, switch_particles = 2000, switch_beams = 60;
  int threads = 1;
  bool recovery = pgmcl::RecoveryConfig{}.enabled;
  bool hypotheses = pgmcl::HypothesesConfig{}.enabled;
  std::string motion_s;
  app.add_option("--name", name, "Dataset label in the CSV")->required();
  log_options.add_to(app, /*required=*/false);
  app.add_option("--sim", sim_size,
                 "Simulate a random walk in a synthetic office of this side (m)");
  app.add_option("--sim-duration", sim.duration_s, "Seconds of simulated driving");
  app.add_option("--scenario", scenario, "Simulate this scenario YAML (configs/scenarios/)")
      ->check(CLI::ExistingFile);
  app.add_option("--duration", scenario_duration,
                 "Scenario: seconds instead of the file's (a non-looping robot then waits "
                 "at its goal)");
  app.add_option("--particles", particles_s, "Grid: particle counts");
  app.add_option("--beams", beams_s, "Grid: beams per update (kMaxBeams)");
  app.add_option("--kinds", kinds_s, "Grid: table kinds");
  app.add_flag("--switches", switches, "Also run the skip-switch study");
  app.add_option("--switch-seeds", switch_seeds, "Filter seeds per switch-study configuration");
  app.add_option("--switch-particles", switch_particles, "Switch study: particles");
  app.add_option("--switch-beams", switch_beams, "Switch study: beams when subsampling");
  app.add_option("--threads", threads, "Localizer threads");
  app.add_option("--motion-noise", motion_s,
                 "Filter's motion model A1,A2,A3,A4 (Table 5.6 variance form; default: library's)");
  app.add_option("--recovery", recovery,
                 "Augmented-MCL random injection (filter.recovery.enabled; default: library's)");
  app.add_option("--hypotheses", hypotheses,
                 "Competing hypotheses (hypotheses.enabled; default: library's)");
  app.add_option("--csv", csv_path, "Append rows here");
  CLI11_PARSE(app, argc, argv);
  pgmcl::MotionNoise motion = pgmcl::LocalizerConfig{}.motion.noise;
  if (!motion_s.empty() && !pb::parse_alphas(motion_s, motion)) {
    std::fprintf(stderr, "pgmcl_sweep: --motion-noise needs A1,A2,A3,A4\n");
    return 2;
  }

  pb::Dataset d;
  const auto t_load = std::chrono::steady_clock::now();
  try {
    if (!scenario.empty()) {
      d = pb::scenario_dataset(name, scenario, scenario_duration);
    } else if (!sim_size.empty()) {
      sim.size_m = std::stod(sim_size);
      d = pb::simulate_dataset(name, sim);
    } else {
      if (log_options.src.map_yaml.empty() || log_options.src.log.empty()) {
        std::fprintf(stderr, "pgmcl_sweep: need --map and --log (or --scenario or --sim)\n");
        return 2;
      }
      const std::optional<pb::LogSource> src = log_options.source("pgmcl_sweep");
      if (!src) return 2;
      d = pb::load_log_dataset(name, *src);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "pgmcl_sweep: %s: %s\n", name.c_str(), e.what());
    return 1;
  }
  // Dead reckoning from the true start: the error the filter has to remove.
  double odo_sq = 0;
  for (std::size_t k = 0; k < d.scans.size(); ++k) {
    const pgmcl::Pose2 p = d.truth.front().compose(d.odometry.front().between(d.odometry[k]));
    odo_sq += std::pow(std::hypot(p.x - d.truth[k].x, p.y - d.truth[k].y), 2);
  }
  std::printf(
      "%s: %zu scans x %zu beams, map %d x %d at %.3f m, odometry-only ATE %.3f m "
      "(loaded in %.1f s)\n",
      name.c_str(), d.scans.size(), d.log_beams, d.grid.width(), d.grid.height(),
      d.grid.resolution(), std::sqrt(odo_sq / static_cast<double>(d.scans.size())),
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t_load).count());
  std::fflush(stdout);

  const std::vector<std::uint32_t> free_cells = pgmcl::free_cell_indices(d.grid);
  std::map<int, std::shared_ptr<const pgmcl::maps::LikelihoodField>> fields;
  const auto field = [&](TableKind k) {
    auto& f = fields[static_cast<int>(k)];
    if (!f) {
      f = pb::make_table(d.grid, k);
      std::printf("  table %-10s built in %.2f s (%.0f MB)\n", pgmcl::maps::to_string(k),
                  f->stats().build_seconds, static_cast<double>(f->stats().bytes) / 1e6);
    }
    return f;
  };

  std::vector<std::pair<RunConfig, RunResult>> rows;
  const auto run = [&](const RunConfig& c) {
    const RunResult r = run_one(d, field(c.kind), free_cells, c, threads, motion);
    std::printf(
        "  %-24s %-10s n=%-6zu beams=%-5s g%s s%s k%s r%s seed %llu: %7.3f ms/scan "
        "(%zu updates, %.3f ms each, hypotheses %.3f, free space %.3f)  ATE %.3f m (max %.2f)\n",
        c.study.c_str(), pgmcl::maps::to_string(c.kind), c.particles,
        c.subsample ? std::to_string(c.beams).c_str() : "all", on_off(c.gating),
        on_off(c.selective), on_off(c.kld), on_off(c.recovery),
        static_cast<unsigned long long>(c.seed), r.ms_per_scan, r.updates, r.update_ms_mean,
        r.hypotheses_ms_mean, r.free_space_ms_mean, r.ate_rmse, r.ate_max);
    std::fflush(stdout);
    rows.emplace_back(c, r);
  };

  std::vector<TableKind> kinds;
  {
    std::size_t b = 0;
    while (b < kinds_s.size()) {
      const std::size_t e = kinds_s.find(',', b);
      kinds.push_back(pgmcl::maps::table_kind_from_string(
          kinds_s.substr(b, e == std::string::npos ? std::string::npos : e - b)));
      if (e == std::string::npos) break;
      b = e + 1;
    }
  }
  for (const TableKind k : kinds)
    for (const std::size_t n : parse_sizes(particles_s))
      for (const std::size_t b : parse_sizes(beams_s)) {
        RunConfig c;
        c.kind = k;
        c.particles = n;
        c.beams = b;
        c.recovery = recovery;
        c.hypotheses = hypotheses;
        run(c);
      }

  if (switches) {
    // Baseline: every skip switch on. Then each one off on its own.
    struct Variant {
      const char* name;
      void (*off)(RunConfig&);
    };
    const Variant variants[] = {
        {"baseline", [](RunConfig&) {}},
        {"gating", [](RunConfig& c) { c.gating = false; }},
        {"selective_resampling", [](RunConfig& c) { c.selective = false; }},
        {"kld", [](RunConfig& c) { c.kld = false; }},
        {"beam_subsampling", [](RunConfig& c) { c.subsample = false; }},
        // Not a skip switch: the random injection flipped against the baseline's setting.
        {"recovery_flipped", [](RunConfig& c) { c.recovery = !c.recovery; }},
    };
    for (const Variant& v : variants)
      for (std::uint64_t s = 1; s <= switch_seeds; ++s) {
        RunConfig c;
        c.study = std::string("switch:") + v.name;
        c.particles = switch_particles;
        c.beams = switch_beams;
        c.kld = true;
        c.recovery = recovery;
        c.hypotheses = hypotheses;
        c.seed = s;
        v.off(c);
        run(c);
      }
  }

  // Pareto flags over the grid rows of this dataset.
  for (auto& [c, r] : rows) {
    if (c.study != "grid") continue;
    r.pareto = true;
    for (const auto& [c2, r2] : rows) {
      if (c2.study != "grid" || &r2 == &r) continue;
      if (r2.ms_per_scan <= r.ms_per_scan && r2.ate_rmse <= r.ate_rmse &&
          (r2.ms_per_scan < r.ms_per_scan || r2.ate_rmse < r.ate_rmse)) {
        r.pareto = false;
        break;
      }
    }
  }

  std::FILE* f = pb::open_csv_for_append(
      csv_path,
      "dataset,study,kind,particles,beams,gating,selective,kld,subsample,seed,threads,"
      "scans,updates,ms_per_scan,update_ms_mean,update_ms_p95,particles_mean,"
      "beams_used_mean,ate_rmse_m,ate_max_m,heading_rmse_deg,pareto,recovery,"
      "hypotheses_ms_mean,free_space_ms_mean",
      "pgmcl_sweep");
  if (!f) return 1;
  for (const auto& [c, r] : rows)
    std::fprintf(f,
                 "%s,%s,%s,%zu,%zu,%s,%s,%s,%s,%llu,%d,%zu,%zu,%.4f,%.4f,%.4f,%.1f,%.1f,%.5f,%.4f,%"
                 ".3f,%d,%d,%.4f,%.4f\n",
                 name.c_str(), c.study.c_str(), pgmcl::maps::to_string(c.kind), c.particles,
                 c.beams, on_off(c.gating), on_off(c.selective), on_off(c.kld), on_off(c.subsample),
                 static_cast<unsigned long long>(c.seed), threads, r.scans, r.updates,
                 r.ms_per_scan, r.update_ms_mean, r.update_ms_p95, r.particles_mean,
                 r.beams_used_mean, r.ate_rmse, r.ate_max, r.heading_rmse_deg, r.pareto ? 1 : 0,
                 c.recovery ? 1 : 0, r.hypotheses_ms_mean, r.free_space_ms_mean);
  std::fclose(f);

  if (switches) {
    // One row per switch: mean over seeds, against the baseline.
    std::map<std::string, std::pair<double, double>> mean;  // study -> (ms/scan, ATE)
    std::map<std::string, int> count;
    for (const auto& [c, r] : rows) {
      if (c.study == "grid") continue;
      mean[c.study].first += r.ms_per_scan;
      mean[c.study].second += r.ate_rmse;
      ++count[c.study];
    }
    for (auto& [k, v] : mean) {
      v.first /= count[k];
      v.second /= count[k];
    }
    const auto base = mean["switch:baseline"];
    std::printf(
        "\n%s skip switches (baseline: all on, %zu particles, %zu beams, KLD on; mean "
        "of %zu seeds):\n  %-22s %12s %12s %12s %12s\n",
        name.c_str(), switch_particles, switch_beams, switch_seeds, "switch", "ms/scan off",
        "time saved", "ATE off (m)", "ATE change");
    for (const auto& [k, v] : mean) {
      if (k == "switch:baseline") continue;
      std::printf("  %-22s %12.3f %11.0f%% %12.4f %+12.4f\n", k.substr(7).c_str(), v.first,
                  100.0 * (v.first - base.first) / v.first, v.second, base.second - v.second);
    }
    std::printf(
        "  (time saved = (off - on) / off; ATE change = ATE(on) - ATE(off), metres: positive = the "
        "skip costs accuracy)\n");
  }
  return 0;
}
