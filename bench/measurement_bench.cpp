/// Measurement-update throughput (beam evaluations per second) of the engine's real code
/// path, MeasurementModel::prepare + score_serial / score_parallel (what
/// Localizer::measurement_update calls), for each table kind, against a yardstick: a bare
/// "transform + bounds check + one byte gather + add" loop over a byte table of the same
/// size with the very same particles and beam endpoints, run right before the engine
/// configurations it is compared with. After the runs a summary prints, per configuration,
/// engine rate / yardstick rate (the ratio survives a noisy machine far better than the
/// absolute rates) and the log-log scaling exponents of update time against particles and
/// beams, and writes both as CSV.
///
/// Threads: OMP_NUM_THREADS (1 -> score_serial, as the Localizer does with threads = 1).
/// Own flags (besides --benchmark_*):
///   --out=DIR         write DIR/measurement_t<T>.csv and DIR/scaling_t<T>.csv
///   --sizes=10,50,200 map sides in metres (5 cm cells)
///   --particles=1000,5000,20000   --beams=60,270,1081
///   --kinds=isotropic,oriented,offset   --patterns=tracking,global

#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "bench_common.hpp"
#include "bench_report.hpp"
#include "pgmcl/maps/likelihood_field.hpp"
#include "pgmcl/mcl/beam_selection.hpp"
#include "pgmcl/mcl/localizer_config.hpp"
#include "pgmcl/mcl/measurement_model.hpp"
#include "pgmcl/sims/ray_caster.hpp"

namespace pb = pgmcl::bench;
using pgmcl::maps::TableKind;

namespace {

struct Config {
  bool yardstick = false;
  TableKind kind = TableKind::kIsotropic;
  int size_m = 50;
  std::size_t particles = 1000;
  int beams = 270;
  bool global = false;  // particle pattern: false = tracking cloud, true = uniform
};

std::string pattern_name(bool global) {
  return global ? "global" : "tracking";
}

std::string name_of(const Config& c) {
  std::string n =
      c.yardstick ? "yardstick" : std::string("engine/") + pgmcl::maps::to_string(c.kind);
  return n + "/map:" + std::to_string(c.size_m) + "m/n:" + std::to_string(c.particles) +
         "/beams:" + std::to_string(c.beams) + "/" + pattern_name(c.global);
}

// Maps, tables and scans are built once per process and shared by all benchmarks.
struct World {
  pb::OfficeSpec spec;
  pgmcl::maps::OccupancyGrid grid;
  std::unique_ptr<pgmcl::sims::RayCaster> caster;
  std::map<int, std::shared_ptr<const pgmcl::maps::LikelihoodField>> fields;  // by kind
  std::map<int, pgmcl::LaserScan> scans;                                      // by beams
  std::map<std::pair<std::size_t, bool>, pgmcl::ParticleSet> clouds;
};

World& world(int size_m) {
  return pb::world_of_size<World>(size_m, [](World& w) {
    w.grid = pb::make_office(w.spec);
    w.caster = std::make_unique<pgmcl::sims::RayCaster>(w.grid);
  });
}

const pgmcl::maps::LikelihoodField& field(World& w, TableKind kind) {
  auto& f = w.fields[static_cast<int>(kind)];
  if (!f) f = pb::make_table(w.grid, kind);
  return *f;
}

const pgmcl::LaserScan& scan(World& w, int beams) {
  auto it = w.scans.find(beams);
  if (it == w.scans.end())
    it = w.scans.emplace(beams, pb::cast_scan(*w.caster, pb::room_centre(w.spec, 0, 0), beams))
             .first;
  return it->second;
}

const pgmcl::ParticleSet& cloud(World& w, std::size_t n, bool global) {
  auto it = w.clouds.find({n, global});
  if (it == w.clouds.end()) {
    auto p =
        global ? pb::global_cloud(w.grid, n) : pb::tracking_cloud(pb::room_centre(w.spec, 0, 0), n);
    it = w.clouds.emplace(std::make_pair(n, global), std::move(p)).first;
  }
  return it->second;
}

// The bare loop the engine is judged against (bench/README.md): per particle one rotation, per beam
// a transform, an unsigned bounds check, one byte gather and an add.
[[gnu::noinline]] void yardstick_loop(const std::uint8_t* table, int width, int height,
                                      const float* ex, const float* ey, std::size_t m,
                                      const float* x, const float* y, const float* th,
                                      std::size_t n, float inv_res, std::uint32_t* out) {
  const auto ln = static_cast<std::ptrdiff_t>(n);
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t i = 0; i < ln; ++i) {
    const float px = x[i] * inv_res, py = y[i] * inv_res;
    const float c = std::cos(th[i]), s = std::sin(th[i]);
    std::uint32_t sum = 0;
    for (std::size_t j = 0; j < m; ++j) {
      const int col = static_cast<int>(px + (c * ex[j] - s * ey[j]) + 1024.0f) - 1024;
      const int row = static_cast<int>(py + (s * ex[j] + c * ey[j]) + 1024.0f) - 1024;
      const bool in = static_cast<unsigned>(col) < static_cast<unsigned>(width) &&
                      static_cast<unsigned>(row) < static_cast<unsigned>(height);
      sum += in ? table[static_cast<std::size_t>(row) * static_cast<std::size_t>(width) +
                        static_cast<std::size_t>(col)]
                : 255u;
    }
    out[i] = sum;
  }
}

void run_config(benchmark::State& state, const Config& c) {
  World& w = world(c.size_m);
  // The yardstick reads the isotropic table (one byte per cell, same width x height).
  const auto& f = field(w, c.yardstick ? TableKind::kIsotropic : c.kind);
  const pgmcl::LaserScan& s = scan(w, c.beams);
  const pgmcl::ParticleSet& p = cloud(w, c.particles, c.global);
  auto shared = w.fields[static_cast<int>(c.yardstick ? TableKind::kIsotropic : c.kind)];
  pgmcl::MeasurementModel model(shared);
  std::vector<std::uint32_t> valid, selected;
  pgmcl::valid_beam_indices(s, f.model().params().max_range, valid);
  pgmcl::select_beams(valid, {pgmcl::BeamSelectionMode::kAll, 1, 1}, selected);
  model.prepare(s, selected);
  const std::size_t m = model.beams().size();
  std::vector<std::uint32_t> sum(p.size());
  const int threads = pb::omp_threads();
  const float inv_res = static_cast<float>(1.0 / f.resolution());
  const auto iso = c.yardstick ? f.isotropic() : pgmcl::maps::IsotropicView{};

  for (auto _ : state) {
    if (c.yardstick) {
      yardstick_loop(iso.q, iso.width, iso.height, model.beams().ex.data(), model.beams().ey.data(),
                     m, p.x.data(), p.y.data(), p.theta.data(), p.size(), inv_res, sum.data());
    } else {
      model.prepare(s, selected);
      if (threads == 1)
        model.score_serial(p.x, p.y, p.theta, sum);
      else
        model.score_parallel(p.x, p.y, p.theta, sum, 0);
    }
    benchmark::DoNotOptimize(sum.data());
    benchmark::ClobberMemory();
  }
  state.counters["beam_evals"] = benchmark::Counter(static_cast<double>(m * p.size()),
                                                    benchmark::Counter::kIsIterationInvariantRate);
  state.counters["beams_used"] = static_cast<double>(m);
  state.counters["threads"] = threads;
}

struct Result {
  double seconds = 0.0;  // per update, mean over repetitions
  double evals = 0.0;    // beam evaluations per second
  double beams_used = 0.0;
  int reps = 0;
};

std::vector<int> parse_ints(const std::string& s) {
  std::vector<int> out;
  for (const auto& p : pb::split_list(s)) out.push_back(std::stoi(p));
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  std::string out, sizes = "10,50,200", particles = "1000,5000,20000", beams = "60,270,1081",
                   kinds = "isotropic,oriented,offset", patterns = "tracking,global";
  if (!pb::init_benchmark(argc, argv,
                          {{"out", &out},
                           {"sizes", &sizes},
                           {"particles", &particles},
                           {"beams", &beams},
                           {"kinds", &kinds},
                           {"patterns", &patterns}}))
    return 2;

  std::vector<TableKind> kind_list;
  for (const auto& k : pb::split_list(kinds))
    kind_list.push_back(pgmcl::maps::table_kind_from_string(k));
  std::vector<bool> pattern_list;
  for (const auto& p : pb::split_list(patterns)) pattern_list.push_back(p == "global");

  std::vector<Config> configs;  // registration (= run) order
  for (const bool global : pattern_list) {
    for (const int size : parse_ints(sizes)) {
      for (const int n : parse_ints(particles)) {
        // The global pattern is the cache-hostile case; one particle/beam setting suffices.
        for (const int b : parse_ints(beams)) {
          if (global && (n != 5000 || b != 270)) continue;
          Config base{false, TableKind::kIsotropic, size, static_cast<std::size_t>(n), b, global};
          Config y = base;
          y.yardstick = true;
          configs.push_back(y);
          benchmark::RegisterBenchmark(name_of(y).c_str(), run_config, y)
              ->UseRealTime()
              ->Unit(benchmark::kMicrosecond);
          for (const TableKind k : kind_list) {
            Config e = base;
            e.kind = k;
            configs.push_back(e);
            benchmark::RegisterBenchmark(name_of(e).c_str(), run_config, e)
                ->UseRealTime()
                ->Unit(benchmark::kMicrosecond);
          }
        }
      }
    }
  }

  const auto runs = pb::run_benchmarks();

  // ---- Summary: ratios and scaling exponents. ----
  std::map<std::string, Result> res;
  for (const auto& r : runs) {
    Result& x = res[r.run_name.function_name];
    x.seconds += pb::seconds_per_iteration(r);
    x.evals += r.counters.count("beam_evals") ? r.counters.at("beam_evals").value : 0.0;
    x.beams_used = r.counters.count("beams_used") ? r.counters.at("beams_used").value : 0.0;
    ++x.reps;
  }
  for (auto& [_, x] : res) {
    x.seconds /= x.reps;
    x.evals /= x.reps;
  }
  const int threads = pb::omp_threads();
  std::FILE* csv = nullptr;
  std::FILE* scsv = nullptr;
  if (!out.empty()) {
    std::filesystem::create_directories(out);
    const std::string t = std::to_string(threads);
    csv = std::fopen((out + "/measurement_t" + t + ".csv").c_str(), "w");
    scsv = std::fopen((out + "/scaling_t" + t + ".csv").c_str(), "w");
    if (!csv || !scsv) {
      std::fprintf(stderr, "measurement_bench: cannot write to %s\n", out.c_str());
      return 1;
    }
    std::fprintf(csv,
                 "kind,pattern,map_m,particles,beams,beams_used,threads,update_us,"
                 "beam_evals_per_s,yardstick_evals_per_s,ratio\n");
    std::fprintf(scsv, "kind,pattern,map_m,vary,fixed,exponent,points\n");
  }

  std::printf(
      "\nSummary (OMP threads = %d): engine beam evaluations/s as a fraction of the "
      "yardstick's\n",
      threads);
  std::printf("%-10s %-8s %6s %7s %6s %5s %11s %10s %6s\n", "kind", "pattern", "map_m", "n",
              "beams", "used", "update_us", "evals/s", "ratio");
  std::map<std::string, std::vector<double>> ratios_by_kind;
  for (const Config& c : configs) {
    const std::string name = name_of(c);
    if (!res.count(name)) continue;
    const Result& e = res.at(name);
    const char* kn = c.yardstick ? "yardstick" : pgmcl::maps::to_string(c.kind);
    Config yc = c;
    yc.yardstick = true;
    const auto yit = res.find(name_of(yc));
    const double yard = yit != res.end() ? yit->second.evals : 0.0;
    const double ratio = yard > 0 ? e.evals / yard : 0.0;
    if (c.yardstick) std::printf("\n");
    std::printf("%-10s %-8s %6d %7zu %6d %5.0f %11.1f %10.3g %6.3f\n", kn,
                pattern_name(c.global).c_str(), c.size_m, c.particles, c.beams, e.beams_used,
                e.seconds * 1e6, e.evals, ratio);
    if (c.yardstick) continue;
    if (ratio > 0) ratios_by_kind[std::string(kn) + "/" + pattern_name(c.global)].push_back(ratio);
    if (csv)
      std::fprintf(csv, "%s,%s,%d,%zu,%d,%.0f,%d,%.3f,%.6g,%.6g,%.4f\n", kn,
                   pattern_name(c.global).c_str(), c.size_m, c.particles, c.beams, e.beams_used,
                   threads, e.seconds * 1e6, e.evals, yard, ratio);
  }
  std::printf("\nGeometric mean of the ratio per kind:\n");
  for (const auto& [k, v] : ratios_by_kind) {
    double l = 0;
    for (double r : v) l += std::log(r);
    std::printf("  %-20s %.3f  (%zu configurations)\n", k.c_str(), std::exp(l / v.size()),
                v.size());
  }

  // Scaling exponents: log(update time) vs log(particles) at each beam count, and vs
  // log(beams used) at each particle count (tracking pattern; 1.0 = linear).
  std::printf("\nScaling exponents of update time (log-log least squares; 1 = linear):\n");
  std::printf("%-10s %6s  %-28s %-28s\n", "kind", "map_m", "vs particles (at beams ...)",
              "vs beams (at particles ...)");
  // One cell of the table: the exponent against particles (at `fixed` beams) or against
  // beams used (at `fixed` particles), also written to the scaling CSV.
  const auto exponent = [&](TableKind k, int size, bool vs_particles, int fixed) {
    std::vector<double> xs, ys;
    for (const int v : parse_ints(vs_particles ? particles : beams)) {
      const int n = vs_particles ? v : fixed, bm = vs_particles ? fixed : v;
      const auto it = res.find(name_of({false, k, size, static_cast<std::size_t>(n), bm, false}));
      if (it == res.end()) continue;
      xs.push_back(vs_particles ? n : it->second.beams_used);
      ys.push_back(it->second.seconds);
    }
    const double e = pb::loglog_slope(xs, ys);
    if (scsv && xs.size() >= 2)
      std::fprintf(scsv, "%s,tracking,%d,%s,%s=%d,%.4f,%zu\n", pgmcl::maps::to_string(k), size,
                   vs_particles ? "particles" : "beams", vs_particles ? "beams" : "particles",
                   fixed, e, xs.size());
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.2f@%d ", e, fixed);
    return std::string(buf);
  };
  for (const TableKind k : kind_list) {
    for (const int size : parse_ints(sizes)) {
      std::string a, b;
      for (const int bm : parse_ints(beams)) a += exponent(k, size, true, bm);
      for (const int n : parse_ints(particles)) b += exponent(k, size, false, n);
      std::printf("%-10s %6d  %-28s %-28s\n", pgmcl::maps::to_string(k), size, a.c_str(),
                  b.c_str());
    }
  }
  if (csv) std::fclose(csv);
  if (scsv) std::fclose(scsv);
  return 0;
}
