#include "pgmcl/eval/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <utility>

#include "pgmcl/io/errors.hpp"

namespace pgmcl::io {
namespace {

std::string num(double v) {
  if (std::isnan(v)) return ".nan";
  if (std::isinf(v)) return v > 0 ? ".inf" : "-.inf";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

/// A double-quoted YAML scalar: any text, including ": " and "#", reads back as itself.
std::string yaml_quoted(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", static_cast<unsigned char>(c));
      out += buf;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string text_of(const MetricEntry& e) {
  switch (e.kind) {
    case MetricEntry::Kind::kCount:
      return std::to_string(e.count);
    case MetricEntry::Kind::kNull:
      return "null";
    case MetricEntry::Kind::kFlag:
      return e.count != 0 ? "true" : "false";
    case MetricEntry::Kind::kReal:
      break;
  }
  return num(e.real);
}

/// Rows of (key, value text) shared by the YAML and the table.
std::vector<std::pair<std::string, std::string>> rows(const RunMetrics& m, bool run_figures) {
  std::vector<std::pair<std::string, std::string>> r;
  for (const MetricEntry& e : metrics_entries(m, run_figures)) r.emplace_back(e.key, text_of(e));
  return r;
}

MetricEntry count(const char* key, std::size_t v) {
  return {MetricEntry::Kind::kCount, key, v, 0.0};
}
MetricEntry real(const char* key, double v) {
  return {MetricEntry::Kind::kReal, key, 0, v};
}
MetricEntry flag(const char* key, bool v) {
  return {MetricEntry::Kind::kFlag, key, v ? 1u : 0u, 0.0};
}
MetricEntry maybe(const char* key, const std::optional<double>& v) {
  return v ? real(key, *v) : MetricEntry{MetricEntry::Kind::kNull, key, 0, 0.0};
}

}  // namespace

std::vector<MetricEntry> metrics_entries(const RunMetrics& m, bool run_figures) {
  std::vector<MetricEntry> r;
  if (run_figures) {
    r = {
        count("updates", m.updates),
        count("skipped_updates", m.skipped_updates),
        real("update_ms_mean", m.update_ms_mean),
        real("update_ms_p95", m.update_ms_p95),
        real("update_ms_median", m.update_ms_median),
        real("update_ms_max", m.update_ms_max),
        real("wall_s", m.wall_s),
        real("particles_mean", m.particles_mean),
        count("particles_min", m.particles_min),
        count("particles_max", m.particles_max),
        real("beams_used_mean", m.beams_used_mean),
        real("fit_mean", m.fit_mean),
        real("converged_fraction", m.converged_fraction),
        real("rotation_noise_factor", m.rotation_noise_factor),
        real("translation_noise_factor", m.translation_noise_factor),
        flag("complete", m.complete),
        count("warning_count", m.warnings.size()),
    };
  }
  if (m.accuracy) {
    const AccuracyMetrics& a = *m.accuracy;
    r.push_back(real("ate_rmse_m", a.ate_rmse_m));
    r.push_back(real("ate_max_m", a.ate_max_m));
    r.push_back(real("heading_rmse_deg", a.heading_rmse_deg));
    r.push_back(maybe("converged_after_s", a.converged_after_s));
    r.push_back(count("truth_matched", a.matched));
    r.push_back(real("truth_matched_fraction", a.matched_fraction));
    r.push_back(real("truth_covered_fraction", a.truth_covered_fraction));
    r.push_back(maybe("lock_on_s", a.lock_on_s));
    r.push_back(real("lock_on_travel_m", a.lock_on_travel_m));
    r.push_back(real("post_lock_ate_rmse_m", a.post_lock_ate_rmse_m));
    r.push_back(real("post_lock_ate_max_m", a.post_lock_ate_max_m));
    r.push_back(real("post_lock_heading_rmse_deg", a.post_lock_heading_rmse_deg));
    if (run_figures) {
      r.push_back(count("false_converged", a.false_converged));
      r.push_back(count("false_converged_run", a.false_converged_run));
    }
  }
  if (m.relations) {
    r.push_back(real("relations_trans_m", m.relations->trans_m));
    r.push_back(real("relations_rot_deg", m.relations->rot_deg));
    r.push_back(real("relations_trans_std_m", m.relations->trans_std_m));
    r.push_back(real("relations_rot_std_deg", m.relations->rot_std_deg));
    r.push_back(count("relations_used", m.relations->used));
  }
  return r;
}

AccuracyMetrics accuracy_metrics(const AteResult& ate) {
  AccuracyMetrics a;
  a.ate_rmse_m = ate.translation.rms;
  a.ate_max_m = ate.translation.max;
  a.heading_rmse_deg = ate.heading.rms;
  a.converged_after_s = ate.converged_after_s;
  a.matched = ate.matched;
  a.matched_fraction =
      ate.estimated ? static_cast<double>(ate.matched) / static_cast<double>(ate.estimated) : 0.0;
  a.truth_covered_fraction = ate.truth_covered_fraction;
  a.lock_on_s = ate.lock_on_s;
  a.lock_on_travel_m = ate.lock_on_travel_m;
  a.post_lock_ate_rmse_m = ate.post_lock_translation.rms;
  a.post_lock_ate_max_m = ate.post_lock_translation.max;
  a.post_lock_heading_rmse_deg = ate.post_lock_heading.rms;
  return a;
}

RelationsMetrics relations_metrics(const RelationResult& rel) {
  return {rel.translation.mean, rel.rotation.mean, rel.matched, rel.translation.stddev,
          rel.rotation.stddev};
}

void MetricsAccumulator::add_update(double update_ms, std::size_t particles, std::size_t beams_used,
                                    double fit, bool converged) {
  particles_min_ = update_ms_.empty() ? particles : std::min(particles_min_, particles);
  particles_max_ = std::max(particles_max_, particles);
  update_ms_.push_back(update_ms);
  particles_sum_ += static_cast<double>(particles);
  beams_sum_ += static_cast<double>(beams_used);
  fit_sum_ += fit;
  converged_ += converged ? 1 : 0;
}

RunMetrics MetricsAccumulator::summarise(double wall_s) const {
  RunMetrics m;
  m.updates = update_ms_.size();
  m.skipped_updates = skipped_;
  m.wall_s = wall_s;
  m.rotation_noise_factor = rotation_noise_factor_;
  m.translation_noise_factor = translation_noise_factor_;
  if (!update_ms_.empty()) {
    const double n = static_cast<double>(update_ms_.size());
    double sum = 0.0;
    for (const double v : update_ms_) sum += v;
    m.update_ms_mean = sum / n;
    m.update_ms_p95 = percentile(update_ms_, 95.0);
    m.update_ms_median = percentile(update_ms_, 50.0);
    m.update_ms_max = *std::max_element(update_ms_.begin(), update_ms_.end());
    m.particles_mean = particles_sum_ / n;
    m.particles_min = particles_min_;
    m.particles_max = particles_max_;
    m.beams_used_mean = beams_sum_ / n;
    m.fit_mean = fit_sum_ / n;
    m.converged_fraction = static_cast<double>(converged_) / n;
  }
  return m;
}

double percentile(std::vector<double> values, double p) {
  if (values.empty()) return 0.0;
  p = std::clamp(p, 0.0, 100.0);
  // Nearest rank: the smallest value with at least p % of the data at or below it.
  const auto n = values.size();
  auto rank = static_cast<std::size_t>(std::ceil(p / 100.0 * static_cast<double>(n)));
  rank = std::clamp<std::size_t>(rank, 1, n);
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(rank - 1),
                   values.end());
  return values[rank - 1];
}

std::string metrics_yaml(const RunMetrics& m, bool run_figures) {
  std::string out = "# pgmcl run metrics\n";
  for (const auto& [key, value] : rows(m, run_figures)) out += key + ": " + value + "\n";
  if (run_figures && !m.warnings.empty()) {
    out += "warnings:\n";
    for (const std::string& w : m.warnings) out += "  - " + yaml_quoted(w) + "\n";
  }
  return out;
}

void write_metrics_yaml(const std::string& path, const RunMetrics& m, bool run_figures) {
  std::ofstream f(path);
  if (!f) throw IoError(path + ": cannot create file");
  f << metrics_yaml(m, run_figures);
  f.close();
  if (!f) throw IoError(path + ": write failed");
}

std::string metrics_table(const RunMetrics& m, bool run_figures) {
  std::size_t w = 0;
  const auto r = rows(m, run_figures);
  for (const auto& row : r) w = std::max(w, row.first.size());
  std::string out;
  for (const auto& [key, value] : r) {
    out += "  " + key + std::string(w - key.size() + 2, ' ') + value + "\n";
  }
  return out;
}

}  // namespace pgmcl::io
