#pragma once
/// The frame every bench/*_bench.cpp main() shares: its own --name=value flags taken out
/// before Google Benchmark parses the rest, a console reporter that also keeps the runs,
/// and a CSV writer for them (with --out=DIR every binary writes its figures).

#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <initializer_list>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace pgmcl::bench {

/// Removes `--name=value` from argv (before benchmark::Initialize sees it); returns whether
/// it was present.
inline bool take_flag(int& argc, char** argv, const std::string& name, std::string& value) {
  const std::string prefix = "--" + name + "=";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a.rfind(prefix, 0) == 0) {
      value = a.substr(prefix.size());
      for (int j = i; j + 1 < argc; ++j) argv[j] = argv[j + 1];
      --argc;
      return true;
    }
  }
  return false;
}

/// Takes each of `flags` (`--name=value`; an absent one keeps the string's default) out of
/// argv, then initialises Google Benchmark with the rest. False when an argument is left
/// that neither knows (main then exits with 2).
inline bool init_benchmark(int& argc, char** argv,
                           std::initializer_list<std::pair<const char*, std::string*>> flags) {
  for (const auto& [name, value] : flags) take_flag(argc, argv, name, *value);
  benchmark::Initialize(&argc, argv);
  return !benchmark::ReportUnrecognizedArguments(argc, argv);
}

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

/// Runs every registered benchmark (console table on stdout) and returns the runs.
inline std::vector<benchmark::BenchmarkReporter::Run> run_benchmarks() {
  CollectingReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  return std::move(reporter.kept);
}

/// With --out=DIR (`out` not empty) writes the runs to DIR/<stem>_t<threads>.csv. Returns
/// main's exit code: 1, with a message, when the file cannot be written.
inline int finish_csv(const std::string& out, const std::string& stem,
                      const std::vector<benchmark::BenchmarkReporter::Run>& runs, int omp_threads) {
  if (out.empty() || write_runs_csv(out + "/" + stem + "_t" + std::to_string(omp_threads) + ".csv",
                                    runs, omp_threads))
    return 0;
  std::fprintf(stderr, "%s_bench: cannot write to %s\n", stem.c_str(), out.c_str());
  return 1;
}

}  // namespace pgmcl::bench
