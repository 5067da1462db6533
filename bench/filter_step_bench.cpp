/// Full filter step latency through the public API, Localizer::update: motion (Table 5.6)
/// + measurement (beam selection, preparation, scoring, normalisation) + estimate
/// (mean, covariance, clustering) + resampling, for each table kind, particles x beams.
///
/// The robot drives a closed circle (radius 0.45 m, 32 poses) in a room of a 50 m office;
/// scans are 1081-beam 270 deg casts from the true pose, and the filter picks `beams` of
/// them (BeamSelectionMode::kMaxBeams), as a subsampling deployment would. Gating and KLD
/// are off and resample_threshold = 1, so every step runs every stage with a fixed
/// particle count: the worst-case step. The counters split the time per stage
/// (UpdateResult::timings, steady_clock inside update()).
///
/// Threads: OMP_NUM_THREADS (passed as LocalizerConfig::threads).
/// Own flags: --out=DIR (DIR/filter_step_t<T>.csv), --particles=, --beams=, --kinds=, --size=50,
/// --hypotheses=on|off (HypothesesConfig::enabled; default on, the engine's default).

#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "bench_common.hpp"
#include "bench_report.hpp"
#include "pgmcl/mcl/localizer.hpp"

namespace pb = pgmcl::bench;
using pgmcl::maps::TableKind;

namespace {

constexpr int kLoopPoses = 32;

struct World {
  pb::OfficeSpec spec;
  pgmcl::maps::OccupancyGrid grid;
  std::vector<std::uint32_t> free_cells;
  std::vector<pgmcl::Pose2> poses;      // closed loop, map frame (origin at 0)
  std::vector<pgmcl::LaserScan> scans;  // 1081 beams per pose
  std::map<int, std::shared_ptr<const pgmcl::maps::LikelihoodField>> fields;
};

World& world(int size_m) {
  return pb::world_of_size<World>(size_m, [](World& w) {
    w.grid = pb::make_office(w.spec);
    w.free_cells = pgmcl::free_cell_indices(w.grid);
    const pgmcl::sims::RayCaster caster(w.grid);
    pb::circle_drive(caster, pb::room_centre(w.spec, 0, 0), kLoopPoses, w.poses, w.scans);
  });
}

std::shared_ptr<const pgmcl::maps::LikelihoodField> field(World& w, TableKind kind) {
  auto& f = w.fields[static_cast<int>(kind)];
  if (!f) f = pb::make_table(w.grid, kind);
  return f;
}

bool g_hypotheses = true;

void step(benchmark::State& state, TableKind kind, int size_m, std::size_t n, std::size_t beams) {
  World& w = world(size_m);
  pgmcl::LocalizerConfig cfg;
  cfg.hypotheses.enabled = g_hypotheses;
  cfg.filter.particles = n;
  cfg.filter.global_particles = n;
  cfg.filter.kld.enabled = false;
  cfg.filter.resample_threshold = 1.0;
  cfg.gating.enabled = false;
  cfg.likelihood.selection = {pgmcl::BeamSelectionMode::kMaxBeams, 1, beams};
  cfg.threads = pb::omp_threads();
  pgmcl::Localizer loc(field(w, kind), w.free_cells, cfg);
  const Eigen::Matrix3d cov = Eigen::Vector3d(0.01, 0.01, 0.003).asDiagonal();  // m^2, rad^2
  loc.set_pose(w.poses[0], cov);
  // One untimed step: the first update after set_pose has no odometry to move by.
  (void)loc.update(w.poses[0], w.scans[0], 0.0);
  double stamp = 0.1;
  std::size_t k = 1;
  pgmcl::UpdateTimings sum{};
  double beams_used = 0, particles = 0, resampled = 0;
  for (auto _ : state) {
    const pgmcl::UpdateResult r = loc.update(w.poses[k], w.scans[k], stamp);
    sum.motion_ms += r.timings.motion_ms;
    sum.measurement_ms += r.timings.measurement_ms;
    sum.hypotheses_ms += r.timings.hypotheses_ms;
    sum.free_space_ms += r.timings.free_space_ms;
    sum.resample_ms += r.timings.resample_ms;
    sum.estimate_ms += r.timings.estimate_ms;
    beams_used += static_cast<double>(r.beams_used);
    particles += static_cast<double>(r.particles);
    resampled += r.resampled ? 1.0 : 0.0;
    stamp += 0.1;
    k = (k + 1) % w.poses.size();
  }
  const double it = static_cast<double>(state.iterations());
  state.counters["motion_ms"] = sum.motion_ms / it;
  state.counters["measure_ms"] = sum.measurement_ms / it;
  state.counters["hypotheses_ms"] = sum.hypotheses_ms / it;  // of measure_ms
  state.counters["free_space_ms"] = sum.free_space_ms / it;  // of measure_ms
  state.counters["resample_ms"] = sum.resample_ms / it;
  state.counters["estimate_ms"] = sum.estimate_ms / it;
  state.counters["beams_used"] = beams_used / it;
  state.counters["particles"] = particles / it;
  state.counters["resampled"] = resampled / it;
  state.counters["beam_evals"] = benchmark::Counter(beams_used / it * static_cast<double>(n),
                                                    benchmark::Counter::kIsIterationInvariantRate);
  state.counters["threads"] = cfg.threads;
}

}  // namespace

int main(int argc, char** argv) {
  std::string out, particles = "1000,5000,20000", beams = "60,270,1081",
                   kinds = "isotropic,oriented,offset", size = "50", hypotheses = "on";
  if (!pb::init_benchmark(argc, argv,
                          {{"out", &out},
                           {"particles", &particles},
                           {"beams", &beams},
                           {"kinds", &kinds},
                           {"size", &size},
                           {"hypotheses", &hypotheses}}))
    return 2;
  g_hypotheses = hypotheses != "off";
  const int size_m = std::stoi(size);
  for (const auto& k : pb::split_list(kinds)) {
    const TableKind kind = pgmcl::maps::table_kind_from_string(k);
    for (const auto& n : pb::split_list(particles))
      for (const auto& b : pb::split_list(beams)) {
        const std::string name = "filter_step/" + k + "/map:" + size + "m/n:" + n + "/beams:" + b;
        benchmark::RegisterBenchmark(name.c_str(), step, kind, size_m, std::stoul(n), std::stoul(b))
            ->UseRealTime()
            ->Unit(benchmark::kMillisecond);
      }
  }
  const auto runs = pb::run_benchmarks();
  const int t = pb::omp_threads();
  std::printf(
      "\nFilter step (OMP threads = %d), ms per update: total = motion + measure + "
      "estimate + resample (+ bookkeeping)\n",
      t);
  for (const auto& r : runs) {
    const auto c = [&](const char* k) { return r.counters.at(k).value; };
    std::printf("  %-44s %8.3f = %7.3f + %7.3f + %7.3f + %7.3f\n", r.run_name.function_name.c_str(),
                pb::seconds_per_iteration(r) * 1e3, c("motion_ms"), c("measure_ms"),
                c("estimate_ms"), c("resample_ms"));
  }
  return pb::finish_csv(out, "filter_step", runs, t);
}
