#pragma once
/// Console reporter that also keeps the runs, and a CSV writer for them: every benchmark
/// binary prints Google Benchmark's console table and, with --out=DIR, writes its figures.

#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace pgmcl::bench {

class CollectingReporter : public benchmark::ConsoleReporter {
 public:
  /// Colours only on a terminal (the library's own reporter decides that from the
  /// --benchmark_color flag, which a custom reporter cannot read).
  CollectingReporter() : ConsoleReporter(isatty(fileno(stdout)) ? OO_ColorTabular : OO_Tabular) {}
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const auto& r : runs)
      if (r.run_type == Run::RT_Iteration && !r.error_occurred) kept.push_back(r);
  }
  std::vector<Run> kept;
};

/// Seconds per iteration (real time) of a run.
inline double seconds_per_iteration(const benchmark::BenchmarkReporter::Run& r) {
  return r.GetAdjustedRealTime() / benchmark::GetTimeUnitMultiplier(r.time_unit);
}

/// One row per run: name, threads (OMP), iterations, seconds per iteration, then every
/// counter seen in any run (rates already divided by time). Returns false on I/O failure.
inline bool write_runs_csv(const std::string& path,
                           const std::vector<benchmark::BenchmarkReporter::Run>& runs,
                           int omp_threads) {
  const std::filesystem::path p(path);
  if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) return false;
  std::set<std::string> names;
  for (const auto& r : runs)
    for (const auto& [k, _] : r.counters) names.insert(k);
  std::fprintf(f, "name,omp_threads,iterations,seconds_per_iteration");
  for (const auto& k : names) std::fprintf(f, ",%s", k.c_str());
  std::fprintf(f, "\n");
  for (const auto& r : runs) {
    std::fprintf(f, "%s,%d,%lld,%.9g", r.run_name.function_name.c_str(), omp_threads,
                 static_cast<long long>(r.iterations), seconds_per_iteration(r));
    for (const auto& k : names) {
      const auto it = r.counters.find(k);
      if (it != r.counters.end())
        std::fprintf(f, ",%.6g", it->second.value);
      else
        std::fprintf(f, ",");
    }
    std::fprintf(f, "\n");
  }
  return std::fclose(f) == 0;
}

}  // namespace pgmcl::bench
