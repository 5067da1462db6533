/// Throughput of the other per-step primitives:
///  - ray casting (sims::RayCaster::cast_scan, exact Amanatides & Woo traversal), rays/s,
///    1081-beam 270 deg scans from the room centres of 10 / 50 / 200 m offices;
///  - systematic resampling + the SoA gather of x, y, theta (what Localizer::resample
///    does), particles/s;
///  - KLD-sampling's sizing loop (Fox 2003, Table 1) as Localizer::kld_sample_count runs
///    it: cumulative weights, draws by binary search, KldBinner::insert and
///    kld_required_particles, drawn particles/s.
///
/// Threads: OMP_NUM_THREADS (ray casting is OpenMP-parallel over beams; resampling and KLD
/// are serial). Own flags: --out=DIR (DIR/primitives_t<T>.csv).

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "bench_common.hpp"
#include "bench_report.hpp"
#include "pgmcl/mcl/kld_sampling.hpp"
#include "pgmcl/mcl/resampling.hpp"
#include "pgmcl/sims/ray_caster.hpp"

namespace pb = pgmcl::bench;

namespace {

struct CastWorld {
  pb::OfficeSpec spec;
  std::unique_ptr<pgmcl::sims::RayCaster> caster;
  std::vector<pgmcl::Pose2> poses;
};

CastWorld& cast_world(int size_m) {
  return pb::world_of_size<CastWorld>(size_m, [size_m](CastWorld& w) {
    const auto grid = pb::make_office(w.spec);
    w.caster = std::make_unique<pgmcl::sims::RayCaster>(grid);
    const int rooms =
        std::max(1, static_cast<int>((size_m - 2 * w.spec.margin) / pb::room_pitch(w.spec)));
    for (int i = 0; i < std::min(rooms, 4); ++i)
      for (int j = 0; j < std::min(rooms, 4); ++j)
        w.poses.push_back(pb::room_centre(w.spec, i, j, 0.1 * (i + 4 * j)));
  });
}

void raycast(benchmark::State& state, int size_m) {
  CastWorld& w = cast_world(size_m);
  const pgmcl::sims::BeamFan fan{-0.75 * std::numbers::pi, 1.5 * std::numbers::pi / 1080, 1081,
                                 30.0};
  std::vector<float> ranges(1081);
  std::size_t k = 0;
  double sum = 0;
  for (auto _ : state) {
    w.caster->cast_scan(w.poses[k], fan, ranges);
    sum += ranges[540];
    k = (k + 1) % w.poses.size();
  }
  benchmark::DoNotOptimize(sum);
  state.counters["rays"] = benchmark::Counter(1081, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["threads"] = pb::omp_threads();
}

// Weights of a tracking cloud after a measurement: Gaussian in the distance to the centre.
std::vector<double> tracking_weights(const pgmcl::ParticleSet& p, double sigma) {
  std::vector<double> w(p.size());
  double s = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double dx = p.x[i] - 10.0, dy = p.y[i] - 10.0;
    s += w[i] = std::exp(-(dx * dx + dy * dy) / (2 * sigma * sigma));
  }
  for (double& x : w) x /= s;
  return w;
}

void resample(benchmark::State& state, std::size_t n) {
  const pgmcl::ParticleSet p = pb::tracking_cloud({10.0, 10.0, 0.0}, n);
  const std::vector<double> w = tracking_weights(p, 0.15);
  std::vector<std::uint32_t> idx;
  std::vector<float> x(n), y(n), th(n);
  pgmcl::Rng rng(5);
  for (auto _ : state) {
    pgmcl::systematic_resample(w, n, rng, idx);
    pgmcl::gather<float>(p.x, idx, x);
    pgmcl::gather<float>(p.y, idx, y);
    pgmcl::gather<float>(p.theta, idx, th);
    benchmark::DoNotOptimize(x.data());
    benchmark::DoNotOptimize(y.data());
    benchmark::DoNotOptimize(th.data());
  }
  state.counters["particles"] =
      benchmark::Counter(static_cast<double>(n), benchmark::Counter::kIsIterationInvariantRate);
}

// KLD sizing loop as in Localizer::kld_sample_count (Fox 2003, Table 1), on the library's
// primitives, with the default KldConfig (0.2 m x 0.2 m x 10 deg bins, epsilon 0.05,
// delta 0.01, 300..20000 particles).
void kld(benchmark::State& state, std::size_t n, double spread) {
  const pgmcl::ParticleSet p = pb::tracking_cloud({10.0, 10.0, 0.0}, n, spread, spread / 2);
  const std::vector<double> w = tracking_weights(p, spread);
  pgmcl::KldBinner binner(0.2, 0.2, 10.0 * std::numbers::pi / 180.0);
  binner.reserve(20000);
  const double z = pgmcl::normal_quantile(1.0 - 0.01);
  std::vector<double> cum(n);
  pgmcl::Rng rng(9);
  double drawn_total = 0, bins_total = 0;
  for (auto _ : state) {
    double acc = 0.0;
    for (std::size_t i = 0; i < n; ++i) cum[i] = (acc += w[i]);
    binner.clear();
    std::size_t drawn = 0, bound = 300;
    while (drawn < 20000 && (drawn < bound || drawn < 300)) {
      const double u = rng.uniform() * acc;
      const auto it = std::upper_bound(cum.begin(), cum.end(), u);
      const std::size_t i =
          std::min<std::size_t>(static_cast<std::size_t>(it - cum.begin()), n - 1);
      if (binner.insert(p.x[i], p.y[i], p.theta[i]))
        bound = pgmcl::kld_required_particles(binner.occupied(), 0.05, z);
      ++drawn;
    }
    drawn_total += static_cast<double>(drawn);
    bins_total += static_cast<double>(binner.occupied());
  }
  const double it = static_cast<double>(state.iterations());
  state.counters["drawn"] =
      benchmark::Counter(drawn_total / it, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["kld_n"] = drawn_total / it;
  state.counters["bins"] = bins_total / it;
}

}  // namespace

int main(int argc, char** argv) {
  std::string out;
  if (!pb::init_benchmark(argc, argv, {{"out", &out}})) return 2;
  for (const int s : {10, 50, 200})
    benchmark::RegisterBenchmark(("raycast/1081beams/map:" + std::to_string(s) + "m").c_str(),
                                 raycast, s)
        ->UseRealTime()
        ->Unit(benchmark::kMicrosecond);
  for (const std::size_t n : {1000, 5000, 20000, 100000})
    benchmark::RegisterBenchmark(("resample_systematic+gather/n:" + std::to_string(n)).c_str(),
                                 resample, n)
        ->UseRealTime()
        ->Unit(benchmark::kMicrosecond);
  for (const std::size_t n : {1000, 5000, 20000})
    for (const double spread : {0.1, 0.5, 2.0}) {
      char name[96];
      std::snprintf(name, sizeof name, "kld_sizing/n:%zu/spread:%.1fm", n, spread);
      benchmark::RegisterBenchmark(name, kld, n, spread)
          ->UseRealTime()
          ->Unit(benchmark::kMicrosecond);
    }
  return pb::finish_csv(out, "primitives", pb::run_benchmarks(), pb::omp_threads());
}
