#pragma once
/// What the macro benchmarks pgmcl_sweep and pgmcl_mrpt_harness share, so that both read
/// exactly the same data and report it the same way: the log dataset's command-line
/// options, Table 5.6 alphas from the command line, the update-time summary, and the
/// append-only CSV they write rows to.

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "pgmcl/common/motion_model.hpp"
#include "sweep/sweep_data.hpp"

namespace pgmcl::bench {

/// "A1,A2,A3,A4" (Probabilistic Robotics, Table 5.6, variance form) into `noise`; false,
/// with `noise` unchanged, unless the text holds four numbers.
[[nodiscard]] inline bool parse_alphas(const std::string& text, MotionNoise& noise) {
  MotionNoise n = noise;
  if (std::sscanf(text.c_str(), "%lf,%lf,%lf,%lf", &n.a1, &n.a2, &n.a3, &n.a4) != 4) return false;
  noise = n;
  return true;
}

/// The options that pick a log dataset (load_log_dataset): --map, --log, --truth,
/// --perturb, --odom-noise, --max-scans.
struct LogOptions {
  LogSource src;
  std::uint64_t perturb_seed = 0;  ///< 0 = the log's own odometry
  std::string odom_noise;          ///< "A1,A2,A3,A4" of the --perturb odometry; "" = default

  /// `required`: --map and --log must be given (pgmcl_sweep may simulate instead).
  void add_to(CLI::App& app, bool required) {
    auto* map = app.add_option("--map", src.map_yaml, "Map YAML")->check(CLI::ExistingFile);
    auto* log = app.add_option("--log", src.log, "CARMEN log with scans and odometry")
                    ->check(CLI::ExistingFile);
    if (required) {
      map->required();
      log->required();
    }
    app.add_option("--truth", src.truth_log, "Corrected CARMEN log (truth); default: --log")
        ->check(CLI::ExistingFile);
    app.add_option("--perturb", perturb_seed,
                   "Replace the log's odometry by noisy odometry from the truth with this seed");
    app.add_option("--odom-noise", odom_noise,
                   "A1,A2,A3,A4 for --perturb (Table 5.6 variance form)");
    app.add_option("--max-scans", src.max_scans, "Use only the first N scans (0 = all)");
  }

  /// The source after parsing (truth defaults to the log); nullopt, with a message naming
  /// `program`, on a malformed --odom-noise.
  [[nodiscard]] std::optional<LogSource> source(const char* program) const {
    LogSource s = src;
    if (s.truth_log.empty()) s.truth_log = s.log;
    if (perturb_seed != 0) {
      s.perturb = true;
      s.perturb_seed = perturb_seed;
    }
    if (!odom_noise.empty() && !parse_alphas(odom_noise, s.odom_noise)) {
      std::fprintf(stderr, "%s: --odom-noise needs A1,A2,A3,A4\n", program);
      return std::nullopt;
    }
    return s;
  }
};

struct TimeSummary {
  double mean = 0.0;  ///< same unit as the samples
  double p95 = 0.0;   ///< nearest-rank 95th percentile
};

/// Mean and 95th percentile of update times; zeros for no samples.
[[nodiscard]] inline TimeSummary summarize_times(std::vector<double> samples) {
  TimeSummary t;
  if (samples.empty()) return t;
  double sum = 0;
  for (double v : samples) sum += v;
  t.mean = sum / static_cast<double>(samples.size());
  std::sort(samples.begin(), samples.end());
  const auto rank = static_cast<std::size_t>(std::ceil(0.95 * static_cast<double>(samples.size())));
  t.p95 = samples[std::max<std::size_t>(rank, 1) - 1];
  return t;
}

/// Opens `path` for appending rows, writing `header` (one line, no newline) first when the
/// file is new or empty. nullptr, with a message naming `program`, when it cannot be opened.
[[nodiscard]] inline std::FILE* open_csv_for_append(const std::string& path, const char* header,
                                                    const char* program) {
  const bool fresh = !std::filesystem::exists(path) || std::filesystem::file_size(path) == 0;
  if (!fresh) {  // rows under another program version's columns would be misread
    std::ifstream in(path);
    std::string first;
    std::getline(in, first);
    if (first != header) {
      std::fprintf(stderr, "%s: %s has other columns than this version writes; use a new file\n",
                   program, path.c_str());
      return nullptr;
    }
  }
  std::FILE* f = std::fopen(path.c_str(), "a");
  if (!f) {
    std::fprintf(stderr, "%s: cannot write %s\n", program, path.c_str());
    return nullptr;
  }
  if (fresh) std::fprintf(f, "%s\n", header);
  return f;
}

}  // namespace pgmcl::bench
