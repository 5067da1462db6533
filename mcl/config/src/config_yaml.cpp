#include "pgmcl/config/config_yaml.hpp"

#include <map>
#include <sstream>
#include <stdexcept>

#include "config_yaml_detail.hpp"
#include "pgmcl/io/values.hpp"
#include "yaml_reader.hpp"

namespace pgmcl::io {
namespace {

using detail::YamlMap;

/// Reads leaves and remembers the line of each dotted key, so a validate() failure can be
/// reported where the offending value was written.
class Reader {
 public:
  explicit Reader(std::map<std::string, std::size_t>& lines) : lines_(&lines) {}

  void number(YamlMap& m, const char* key, double& v) { note(m, key, m.number(key, v)); }
  void flag(YamlMap& m, const char* key, bool& v) { note(m, key, m.boolean(key, v)); }
  void count(YamlMap& m, const char* key, std::size_t& v) {
    std::uint64_t u = v;
    if (m.uint64(key, u)) {
      v = static_cast<std::size_t>(u);
      note(m, key, true);
    }
  }
  void integer(YamlMap& m, const char* key, int& v, long long lo, long long hi) {
    note(m, key, m.integer(key, v, lo, hi));
  }
  void seed(YamlMap& m, const char* key, std::uint64_t& v) { note(m, key, m.uint64(key, v)); }
  /// An enumeration written as a name; `parse` throws std::invalid_argument for others.
  template <class E, class Parse>
  void name(YamlMap& m, const char* key, E& v, Parse parse, const char* choices) {
    std::string text;
    if (!m.text(key, text)) return;
    try {
      v = parse(text);
    } catch (const std::invalid_argument&) {
      m.fail(key, "expected one of " + std::string(choices) + ", got \"" + text + "\"");
    }
    note(m, key, true);
  }

 private:
  void note(const YamlMap& m, const char* key, bool present) {
    if (present) (*lines_)[m.field(key)] = m.line(key);
  }
  std::map<std::string, std::size_t>* lines_;
};

MotionModelKind motion_kind(const std::string& s) {
  if (s == "differential_drive" || s == "diff_drive") return MotionModelKind::kDifferentialDrive;
  if (s == "omnidirectional" || s == "omni") return MotionModelKind::kOmnidirectional;
  throw std::invalid_argument(s);
}
const char* motion_kind_name(MotionModelKind k) {
  return k == MotionModelKind::kOmnidirectional ? "omnidirectional" : "differential_drive";
}

BeamSelectionMode selection_mode(const std::string& s) {
  if (s == "all") return BeamSelectionMode::kAll;
  if (s == "stride") return BeamSelectionMode::kStride;
  if (s == "max_beams") return BeamSelectionMode::kMaxBeams;
  throw std::invalid_argument(s);
}
const char* selection_mode_name(BeamSelectionMode m) {
  switch (m) {
    case BeamSelectionMode::kAll:
      return "all";
    case BeamSelectionMode::kStride:
      return "stride";
    case BeamSelectionMode::kMaxBeams:
      break;
  }
  return "max_beams";
}

TimeBackwardsPolicy time_policy(const std::string& s) {
  if (s == "throw") return TimeBackwardsPolicy::kThrow;
  if (s == "reset") return TimeBackwardsPolicy::kReset;
  throw std::invalid_argument(s);
}

void read_all(YamlMap& root, Reader& r, LocalizerConfig& c) {
  {
    YamlMap m = root.child("motion");
    r.name(m, "kind", c.motion.kind, motion_kind, "differential_drive, omnidirectional");
    YamlMap n = m.child("noise");
    r.number(n, "a1", c.motion.noise.a1);
    r.number(n, "a2", c.motion.noise.a2);
    r.number(n, "a3", c.motion.noise.a3);
    r.number(n, "a4", c.motion.noise.a4);
    r.number(n, "a5", c.motion.noise.a5);
    n.finish();
    m.finish();
  }
  {
    LikelihoodConfig& l = c.likelihood;
    YamlMap m = root.child("likelihood");
    YamlMap b = m.child("beam");
    r.number(b, "sigma_along", l.beam.sigma_along);
    r.number(b, "sigma_across", l.beam.sigma_across);
    r.number(b, "model_mismatch", l.beam.model_mismatch);
    r.flag(b, "add_discretisation", l.beam.add_discretisation);
    r.number(b, "w_hit", l.beam.w_hit);
    r.number(b, "w_rand", l.beam.w_rand);
    r.number(b, "max_range", l.beam.max_range);
    b.finish();
    YamlMap t = m.child("table");
    r.name(t, "kind", l.table.kind, maps::table_kind_from_string, "isotropic, oriented, offset");
    r.integer(t, "orientation_bins", l.table.orientation_bins, 1, 1024);
    r.number(t, "reach_sigmas", l.table.reach_sigmas);
    r.number(t, "isotropy_tolerance", l.table.isotropy_tolerance);
    r.count(t, "max_table_bytes", l.table.max_table_bytes);
    t.finish();
    r.number(m, "effective_beams", l.effective_beams);
    r.number(m, "tempering", l.tempering);
    r.number(m, "min_ess_ratio", l.min_ess_ratio);
    YamlMap s = m.child("selection");
    r.name(s, "mode", l.selection.mode, selection_mode, "all, stride, max_beams");
    r.count(s, "stride", l.selection.stride);
    r.count(s, "max_beams", l.selection.max_beams);
    s.finish();
    r.count(m, "expected_beams", l.expected_beams);
    m.finish();
  }
  {
    FilterConfig& f = c.filter;
    YamlMap m = root.child("filter");
    r.count(m, "particles", f.particles);
    r.count(m, "global_particles", f.global_particles);
    r.number(m, "resample_threshold", f.resample_threshold);
    YamlMap k = m.child("kld");
    r.flag(k, "enabled", f.kld.enabled);
    r.count(k, "min_particles", f.kld.min_particles);
    r.count(k, "max_particles", f.kld.max_particles);
    r.number(k, "epsilon", f.kld.epsilon);
    r.number(k, "delta", f.kld.delta);
    r.number(k, "bin_xy", f.kld.bin_xy);
    r.number(k, "bin_theta", f.kld.bin_theta);
    k.finish();
    YamlMap rec = m.child("recovery");
    r.flag(rec, "enabled", f.recovery.enabled);
    r.number(rec, "alpha_slow", f.recovery.alpha_slow);
    r.number(rec, "alpha_fast", f.recovery.alpha_fast);
    r.count(rec, "probation", f.recovery.probation);
    r.number(rec, "probation_weight", f.recovery.probation_weight);
    rec.finish();
    m.finish();
  }
  {
    YamlMap m = root.child("gating");
    r.flag(m, "enabled", c.gating.enabled);
    r.number(m, "d_min", c.gating.d_min);
    r.number(m, "theta_min", c.gating.theta_min);
    m.finish();
  }
  {
    EstimateConfig& e = c.estimate;
    YamlMap m = root.child("estimate");
    r.number(m, "cluster_xy", e.cluster_xy);
    r.number(m, "cluster_theta", e.cluster_theta);
    r.number(m, "converged_weight", e.converged_weight);
    r.number(m, "converged_xy_std", e.converged_xy_std);
    r.number(m, "converged_theta_std", e.converged_theta_std);
    m.finish();
  }
  {
    HypothesesConfig& h = c.hypotheses;
    YamlMap m = root.child("hypotheses");
    r.flag(m, "enabled", h.enabled);
    YamlMap s = m.child("search");
    r.number(s, "leaf_size", h.search.leaf_size);
    r.integer(s, "root_levels", h.search.root_levels, 1, 12);
    r.count(s, "max_beams", h.search.max_beams);
    r.number(s, "min_angle_step", h.search.min_angle_step);
    r.number(s, "max_angle_step", h.search.max_angle_step);
    s.finish();
    r.count(m, "global_candidates", h.global_candidates);
    r.number(m, "global_seed_fraction", h.global_seed_fraction);
    r.number(m, "candidate_margin", h.candidate_margin);
    r.count(m, "global_budget", h.global_budget);
    r.count(m, "max_competitors", h.max_competitors);
    r.number(m, "switch_evidence", h.switch_evidence);
    r.number(m, "drop_evidence", h.drop_evidence);
    r.number(m, "switch_seed_fraction", h.switch_seed_fraction);
    r.number(m, "rival_view", h.rival_view);
    r.number(m, "rescue_fit_ratio", h.rescue_fit_ratio);
    r.number(m, "rescue_xy", h.rescue_xy);
    r.number(m, "rescue_theta", h.rescue_theta);
    r.count(m, "rescue_budget", h.rescue_budget);
    r.number(m, "sweep_share", h.sweep_share);
    r.number(m, "separation_xy", h.separation_xy);
    r.number(m, "separation_theta", h.separation_theta);
    m.finish();
  }
  r.name(root, "time_backwards", c.time_backwards, time_policy, "throw, reset");
  r.integer(root, "threads", c.threads, 0, 4096);
  r.seed(root, "seed", c.seed);
  root.finish();
}

/// LocalizerConfig::validate() says "LocalizerConfig: <field> <problem>"; report it at the
/// line of <field> (or of the closest enclosing key that was written).
[[noreturn]] void rethrow_validation(const std::invalid_argument& e, const std::string& file,
                                     const std::string& path,
                                     const std::map<std::string, std::size_t>& lines,
                                     std::size_t root_line) {
  std::string msg = e.what();
  const std::string prefix = "LocalizerConfig: ";
  if (msg.rfind(prefix, 0) == 0) msg = msg.substr(prefix.size());
  const std::size_t sp = msg.find(' ');
  std::string field = msg.substr(0, sp);
  const std::string problem = sp == std::string::npos ? "invalid" : msg.substr(sp + 1);
  const std::string full = path.empty() ? field : path + "." + field;
  std::size_t line = root_line;
  for (std::string key = full; !key.empty();) {
    const auto it = lines.find(key);
    if (it != lines.end()) {
      line = it->second;
      break;
    }
    const std::size_t dot = key.rfind('.');
    key = dot == std::string::npos ? std::string() : key.substr(0, dot);
  }
  throw ConfigError(file, line, full, problem);
}

}  // namespace

namespace detail {

void read_localizer_node(const std::string& file, const YAML::Node& node, const std::string& path,
                         LocalizerConfig& cfg) {
  std::map<std::string, std::size_t> lines;
  Reader reader(lines);
  LocalizerConfig c = cfg;
  std::size_t root_line = 0;
  try {
    YamlMap root(file, node, path);
    root_line = root.line();
    read_all(root, reader, c);
  } catch (const ConfigError&) {
    throw;
  } catch (const FormatError& e) {
    throw ConfigError(e.file(), e.line(), e.field(), e.message());
  }
  try {
    c.validate();
  } catch (const std::invalid_argument& e) {
    rethrow_validation(e, file, path, lines, root_line);
  }
  cfg = c;
}

}  // namespace detail

void read_localizer_config(const std::string& path, LocalizerConfig& cfg) {
  YAML::Node node;
  try {
    node = detail::load_yaml_file(path);
  } catch (const FormatError& e) {
    throw ConfigError(e.file(), e.line(), e.field(), e.message());
  }
  detail::read_localizer_node(path, node, "", cfg);
}

void parse_localizer_config(std::string_view text, const std::string& source,
                            LocalizerConfig& cfg) {
  YAML::Node node;
  try {
    node = YAML::Load(std::string(text));
  } catch (const YAML::Exception& e) {
    const std::size_t line = e.mark.is_null() ? 0 : static_cast<std::size_t>(e.mark.line) + 1;
    throw ConfigError(source, line, "yaml", "not valid YAML: " + e.msg);
  }
  detail::read_localizer_node(source, node, "", cfg);
}

void apply_localizer_override(const std::string& key, const std::string& value,
                              LocalizerConfig& cfg) {
  const std::string source = "--set " + key + "=" + value;
  YAML::Node leaf;
  try {
    leaf = YAML::Load(value);
  } catch (const YAML::Exception& e) {
    throw ConfigError(source, 0, key, "value is not valid YAML: " + e.msg);
  }
  // Build {a: {b: {c: value}}} from "a.b.c".
  std::vector<std::string> parts;
  std::stringstream ss(key);
  for (std::string part; std::getline(ss, part, '.');) {
    if (part.empty()) throw ConfigError(source, 0, key, "empty component in the dotted key");
    parts.push_back(part);
  }
  if (parts.empty()) throw ConfigError(source, 0, key, "empty key");
  YAML::Node node = leaf;
  for (auto it = parts.rbegin(); it != parts.rend(); ++it) {
    YAML::Node parent(YAML::NodeType::Map);
    parent[*it] = node;
    node = parent;
  }
  try {
    detail::read_localizer_node(source, node, "", cfg);
  } catch (const ConfigError& e) {  // the value's own line 1 would point nowhere
    throw ConfigError(source, 0, e.field(), e.message());
  }
}

void apply_localizer_overrides(const std::vector<std::string>& assignments, LocalizerConfig& cfg) {
  for (const std::string& a : assignments) {
    const auto [key, value] = parse_key_value(a, "--set");
    apply_localizer_override(key, value, cfg);
  }
}

std::string localizer_config_yaml(const LocalizerConfig& c) {
  YAML::Emitter out;
  out.SetDoublePrecision(17);
  out << YAML::Comment("pgmcl LocalizerConfig (units: metres, radians)");
  out << YAML::BeginMap;
  out << YAML::Key << "motion" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "kind" << YAML::Value << motion_kind_name(c.motion.kind);
  out << YAML::Key << "noise" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "a1" << YAML::Value << c.motion.noise.a1;
  out << YAML::Key << "a2" << YAML::Value << c.motion.noise.a2;
  out << YAML::Key << "a3" << YAML::Value << c.motion.noise.a3;
  out << YAML::Key << "a4" << YAML::Value << c.motion.noise.a4;
  out << YAML::Key << "a5" << YAML::Value << c.motion.noise.a5;
  out << YAML::EndMap << YAML::EndMap;

  const LikelihoodConfig& l = c.likelihood;
  out << YAML::Key << "likelihood" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "beam" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "sigma_along" << YAML::Value << l.beam.sigma_along;
  out << YAML::Key << "sigma_across" << YAML::Value << l.beam.sigma_across;
  out << YAML::Key << "model_mismatch" << YAML::Value << l.beam.model_mismatch;
  out << YAML::Key << "add_discretisation" << YAML::Value << l.beam.add_discretisation;
  out << YAML::Key << "w_hit" << YAML::Value << l.beam.w_hit;
  out << YAML::Key << "w_rand" << YAML::Value << l.beam.w_rand;
  out << YAML::Key << "max_range" << YAML::Value << l.beam.max_range;
  out << YAML::EndMap;
  out << YAML::Key << "table" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "kind" << YAML::Value << maps::to_string(l.table.kind);
  out << YAML::Key << "orientation_bins" << YAML::Value << l.table.orientation_bins;
  out << YAML::Key << "reach_sigmas" << YAML::Value << l.table.reach_sigmas;
  out << YAML::Key << "isotropy_tolerance" << YAML::Value << l.table.isotropy_tolerance;
  out << YAML::Key << "max_table_bytes" << YAML::Value
      << static_cast<unsigned long long>(l.table.max_table_bytes);
  out << YAML::EndMap;
  out << YAML::Key << "effective_beams" << YAML::Value << l.effective_beams;
  out << YAML::Key << "tempering" << YAML::Value << l.tempering;
  out << YAML::Key << "min_ess_ratio" << YAML::Value << l.min_ess_ratio;
  out << YAML::Key << "selection" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "mode" << YAML::Value << selection_mode_name(l.selection.mode);
  out << YAML::Key << "stride" << YAML::Value
      << static_cast<unsigned long long>(l.selection.stride);
  out << YAML::Key << "max_beams" << YAML::Value
      << static_cast<unsigned long long>(l.selection.max_beams);
  out << YAML::EndMap;
  out << YAML::Key << "expected_beams" << YAML::Value
      << static_cast<unsigned long long>(l.expected_beams);
  out << YAML::EndMap;

  const FilterConfig& f = c.filter;
  out << YAML::Key << "filter" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "particles" << YAML::Value << static_cast<unsigned long long>(f.particles);
  out << YAML::Key << "global_particles" << YAML::Value
      << static_cast<unsigned long long>(f.global_particles);
  out << YAML::Key << "resample_threshold" << YAML::Value << f.resample_threshold;
  out << YAML::Key << "kld" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "enabled" << YAML::Value << f.kld.enabled;
  out << YAML::Key << "min_particles" << YAML::Value
      << static_cast<unsigned long long>(f.kld.min_particles);
  out << YAML::Key << "max_particles" << YAML::Value
      << static_cast<unsigned long long>(f.kld.max_particles);
  out << YAML::Key << "epsilon" << YAML::Value << f.kld.epsilon;
  out << YAML::Key << "delta" << YAML::Value << f.kld.delta;
  out << YAML::Key << "bin_xy" << YAML::Value << f.kld.bin_xy;
  out << YAML::Key << "bin_theta" << YAML::Value << f.kld.bin_theta;
  out << YAML::EndMap;
  out << YAML::Key << "recovery" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "enabled" << YAML::Value << f.recovery.enabled;
  out << YAML::Key << "alpha_slow" << YAML::Value << f.recovery.alpha_slow;
  out << YAML::Key << "alpha_fast" << YAML::Value << f.recovery.alpha_fast;
  out << YAML::Key << "probation" << YAML::Value << f.recovery.probation;
  out << YAML::Key << "probation_weight" << YAML::Value << f.recovery.probation_weight;
  out << YAML::EndMap << YAML::EndMap;

  out << YAML::Key << "gating" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "enabled" << YAML::Value << c.gating.enabled;
  out << YAML::Key << "d_min" << YAML::Value << c.gating.d_min;
  out << YAML::Key << "theta_min" << YAML::Value << c.gating.theta_min;
  out << YAML::EndMap;

  const EstimateConfig& e = c.estimate;
  out << YAML::Key << "estimate" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "cluster_xy" << YAML::Value << e.cluster_xy;
  out << YAML::Key << "cluster_theta" << YAML::Value << e.cluster_theta;
  out << YAML::Key << "converged_weight" << YAML::Value << e.converged_weight;
  out << YAML::Key << "converged_xy_std" << YAML::Value << e.converged_xy_std;
  out << YAML::Key << "converged_theta_std" << YAML::Value << e.converged_theta_std;
  out << YAML::EndMap;

  const HypothesesConfig& h = c.hypotheses;
  out << YAML::Key << "hypotheses" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "enabled" << YAML::Value << h.enabled;
  out << YAML::Key << "search" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "leaf_size" << YAML::Value << h.search.leaf_size;
  out << YAML::Key << "root_levels" << YAML::Value << h.search.root_levels;
  out << YAML::Key << "max_beams" << YAML::Value
      << static_cast<unsigned long long>(h.search.max_beams);
  out << YAML::Key << "min_angle_step" << YAML::Value << h.search.min_angle_step;
  out << YAML::Key << "max_angle_step" << YAML::Value << h.search.max_angle_step;
  out << YAML::EndMap;
  out << YAML::Key << "global_candidates" << YAML::Value
      << static_cast<unsigned long long>(h.global_candidates);
  out << YAML::Key << "global_seed_fraction" << YAML::Value << h.global_seed_fraction;
  out << YAML::Key << "candidate_margin" << YAML::Value << h.candidate_margin;
  out << YAML::Key << "global_budget" << YAML::Value
      << static_cast<unsigned long long>(h.global_budget);
  out << YAML::Key << "max_competitors" << YAML::Value
      << static_cast<unsigned long long>(h.max_competitors);
  out << YAML::Key << "switch_evidence" << YAML::Value << h.switch_evidence;
  out << YAML::Key << "drop_evidence" << YAML::Value << h.drop_evidence;
  out << YAML::Key << "switch_seed_fraction" << YAML::Value << h.switch_seed_fraction;
  out << YAML::Key << "rival_view" << YAML::Value << h.rival_view;
  out << YAML::Key << "rescue_fit_ratio" << YAML::Value << h.rescue_fit_ratio;
  out << YAML::Key << "rescue_xy" << YAML::Value << h.rescue_xy;
  out << YAML::Key << "rescue_theta" << YAML::Value << h.rescue_theta;
  out << YAML::Key << "rescue_budget" << YAML::Value
      << static_cast<unsigned long long>(h.rescue_budget);
  out << YAML::Key << "sweep_share" << YAML::Value << h.sweep_share;
  out << YAML::Key << "separation_xy" << YAML::Value << h.separation_xy;
  out << YAML::Key << "separation_theta" << YAML::Value << h.separation_theta;
  out << YAML::EndMap;

  out << YAML::Key << "time_backwards" << YAML::Value
      << (c.time_backwards == TimeBackwardsPolicy::kReset ? "reset" : "throw");
  out << YAML::Key << "threads" << YAML::Value << c.threads;
  out << YAML::Key << "seed" << YAML::Value << static_cast<unsigned long long>(c.seed);
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace pgmcl::io
