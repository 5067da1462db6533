// read_node_settings(): amcl's parameter names, then pgmcl/... from the config schema.
#include "pgmcl/nav/parameters.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <set>
#include <utility>

#include "pgmcl/mcl/config_schema.hpp"

namespace pgmcl::nav {
namespace {

namespace schema = pgmcl::config_schema;

constexpr const char* kPgmclPrefix = "pgmcl/";

std::string format_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

const char* type_name(const ParamValue& v) {
  constexpr const char* kNames[] = {"a boolean", "an integer", "a real number", "a string"};
  return kNames[v.index()];
}

double as_number(const std::string& name, const ParamValue& v) {
  if (const auto* d = std::get_if<double>(&v)) return *d;
  if (const auto* i = std::get_if<std::int64_t>(&v)) return static_cast<double>(*i);
  throw ParameterError(name, std::string("expected a number, got ") + type_name(v));
}

std::int64_t as_integer(const std::string& name, const ParamValue& v) {
  if (const auto* i = std::get_if<std::int64_t>(&v)) return *i;
  if (const auto* d = std::get_if<double>(&v)) {
    // 500.0 for an integer parameter is fine; 500.5 is not.
    if (std::isfinite(*d) && std::trunc(*d) == *d && std::abs(*d) < 9.0e15)
      return static_cast<std::int64_t>(*d);
    throw ParameterError(name, "expected an integer, got " + format_number(*d));
  }
  throw ParameterError(name, std::string("expected an integer, got ") + type_name(v));
}

bool as_bool(const std::string& name, const ParamValue& v) {
  if (const auto* b = std::get_if<bool>(&v)) return *b;
  throw ParameterError(name, std::string("expected true or false, got ") + type_name(v));
}

std::string as_string(const std::string& name, const ParamValue& v) {
  if (const auto* s = std::get_if<std::string>(&v)) return *s;
  throw ParameterError(name, std::string("expected a string, got ") + type_name(v));
}

/// A value for a schema field and the parameter that gave it.
struct Source {
  std::string name;
  ParamValue value;
};
using FieldSource = std::function<std::optional<Source>(const std::string& dotted)>;

/// Walks config_schema.hpp and sets each field its source has a value for, checking type
/// and allowed values against the schema; errors name the parameter. Cross-field rules
/// are left to LocalizerConfig::validate() at the end.
class ApplyVisitor {
 public:
  explicit ApplyVisitor(FieldSource source) : source_(std::move(source)) {}

  template <class Body>
  void section(const char* name, Body&& body) {
    path_ += std::string(name) + ".";
    body();
    path_.resize(path_.size() - std::string(name).size() - 1);
  }
  void number(const schema::Field& f, double& v, const schema::Bounds& b) {
    if (const auto s = find(f)) {
      const double d = as_number(s->name, s->value);
      if (!b.contains(d))
        throw ParameterError(s->name, "must be " + b.text() + " (got " + format_number(d) + ")");
      v = d;
    }
  }
  template <class T>
  void integer(const schema::Field& f, T& v, const schema::IntRange& r) {
    if (const auto s = find(f)) {
      const std::int64_t i = as_integer(s->name, s->value);
      if (std::cmp_less(i, r.lo) || std::cmp_greater(i, r.hi))
        throw ParameterError(s->name, "must be " + r.text() + " (got " + std::to_string(i) + ")");
      v = static_cast<T>(i);
    }
  }
  void flag(const schema::Field& f, bool& v) {
    if (const auto s = find(f)) v = as_bool(s->name, s->value);
  }
  template <class E, std::size_t N>
  void choice(const schema::Field& f, E& v, const std::array<schema::EnumName<E>, N>& names) {
    const auto s = find(f);
    if (!s) return;
    const std::string text = as_string(s->name, s->value);
    std::string known;
    for (const auto& n : names) {
      if (text == n.name) {
        v = n.value;
        return;
      }
      known += (known.empty() ? "" : ", ") + std::string(n.name);
    }
    throw ParameterError(s->name, "'" + text + "' is not one of " + known);
  }
  void rule(const char*, bool, const char*) const noexcept {}

  [[nodiscard]] const std::vector<std::string>& fields() const noexcept { return fields_; }

 private:
  std::optional<Source> find(const schema::Field& f) {
    fields_.push_back(path_ + f.name);
    return source_(fields_.back());
  }
  FieldSource source_;
  std::string path_;
  std::vector<std::string> fields_;  // every dotted field visited, in order
};

/// "filter.kld.epsilon" <-> "filter/kld/epsilon".
std::string replace_all(std::string s, char from, char to) {
  for (char& c : s)
    if (c == from) c = to;
  return s;
}
std::string slashes(const std::string& dotted) {
  return replace_all(dotted, '.', '/');
}

// Typed reads of one parameter.
std::optional<double> number_param(const ParamLookup& get, const std::string& name) {
  const auto v = get(name);
  return v ? std::optional<double>(as_number(name, *v)) : std::nullopt;
}
std::optional<bool> bool_param(const ParamLookup& get, const std::string& name) {
  const auto v = get(name);
  return v ? std::optional<bool>(as_bool(name, *v)) : std::nullopt;
}
std::optional<std::string> string_param(const ParamLookup& get, const std::string& name) {
  const auto v = get(name);
  return v ? std::optional<std::string>(as_string(name, *v)) : std::nullopt;
}

/// amcl strips a leading '/' from frame ids (tf2 refuses them).
std::string frame_param(const ParamLookup& get, const std::string& name, std::string fallback) {
  std::string id = string_param(get, name).value_or(std::move(fallback));
  if (!id.empty() && id.front() == '/') id.erase(0, 1);
  if (id.empty()) throw ParameterError(name, "must not be empty");
  return id;
}

/// amcl's parameters that have a pgmcl field of the same meaning, as schema sources.
std::map<std::string, Source> amcl_fields(const ParamLookup& get, NodeSettings& s) {
  std::map<std::string, Source> out;
  const auto direct = [&](const char* amcl, const char* dotted) {
    if (auto v = get(amcl)) out[dotted] = Source{amcl, *v};
  };
  direct("min_particles", "filter.kld.min_particles");
  direct("max_particles", "filter.kld.max_particles");
  direct("kld_err", "filter.kld.epsilon");
  if (const auto z = number_param(get, "kld_z")) {
    // amcl's kld_z is the normal quantile z itself; pgmcl keeps delta = 1 - Phi(z).
    const double delta = 0.5 * std::erfc(*z / std::numbers::sqrt2);
    if (!std::isfinite(*z) || !(delta > 0.0 && delta < 1.0))
      throw ParameterError("kld_z",
                           "must be a finite normal quantile (got " + format_number(*z) + ")");
    out["filter.kld.delta"] = Source{"kld_z", delta};
  }
  direct("update_min_d", "gating.d_min");
  direct("update_min_a", "gating.theta_min");
  const auto slow = number_param(get, "recovery_alpha_slow");
  const auto fast = number_param(get, "recovery_alpha_fast");
  if (slow || fast) {
    // amcl's defaults (0, 0) turn recovery off; pgmcl needs both rates to turn it on.
    if (slow.value_or(0.0) > 0.0 && fast.value_or(0.0) > 0.0) {
      out["filter.recovery.enabled"] = Source{"recovery_alpha_slow", true};
      out["filter.recovery.alpha_slow"] = Source{"recovery_alpha_slow", *slow};
      out["filter.recovery.alpha_fast"] = Source{"recovery_alpha_fast", *fast};
    } else {
      out["filter.recovery.enabled"] = Source{"recovery_alpha_slow", false};
    }
  }
  if (const auto v = get("laser_max_beams")) {
    out["likelihood.selection.mode"] = Source{"laser_max_beams", std::string("max_beams")};
    out["likelihood.selection.max_beams"] = Source{"laser_max_beams", *v};
  }
  if (const auto v = number_param(get, "laser_max_range"); v && *v > 0.0)
    out["likelihood.beam.max_range"] = Source{"laser_max_range", *v};
  if (const auto t = string_param(get, "laser_model_type")) {
    std::string kind;
    if (*t == "likelihood_field") {
      kind = "isotropic";
    } else if (*t == "likelihood_field_prob") {
      kind = "isotropic";
      s.notes.push_back(
          "laser_model_type likelihood_field_prob: read as likelihood_field (pgmcl "
          "has no beam skipping; its recovery and hypotheses handle clutter)");
    } else if (*t == "beam") {
      kind = "oriented";
      s.notes.push_back(
          "laser_model_type beam: pgmcl's oriented planar-Gaussian table, which "
          "knows the beam's direction, stands in for amcl's ray-cast beam model");
    } else {
      throw ParameterError("laser_model_type", "'" + *t +
                                                   "' is not one of likelihood_field, "
                                                   "likelihood_field_prob, beam");
    }
    out["likelihood.table.kind"] = Source{"laser_model_type", kind};
  }
  if (const auto t = string_param(get, "odom_model_type")) {
    std::string kind;
    if (*t == "diff" || *t == "diff-corrected") {
      kind = "differential_drive";
    } else if (*t == "omni" || *t == "omni-corrected") {
      kind = "omnidirectional";
    } else {
      throw ParameterError("odom_model_type",
                           "'" + *t + "' is not one of diff, diff-corrected, omni, omni-corrected");
    }
    if (*t == "diff" || *t == "omni")
      s.notes.push_back("odom_model_type " + *t + ": read as " + *t +
                        "-corrected (variance-form alphas, Probabilistic Robotics Table 5.6)");
    out["motion.kind"] = Source{"odom_model_type", kind};
  }
  const char* alphas[] = {"odom_alpha1", "odom_alpha2", "odom_alpha3", "odom_alpha4",
                          "odom_alpha5"};
  const char* fields[] = {"motion.noise.a1", "motion.noise.a2", "motion.noise.a3",
                          "motion.noise.a4", "motion.noise.a5"};
  for (int i = 0; i < 5; ++i) direct(alphas[i], fields[i]);
  return out;
}

/// amcl parameters with no pgmcl counterpart: accepted and reported, never silently.
void note_unsupported(const ParamLookup& get, NodeSettings& s) {
  if (const auto v = get("resample_interval"))
    s.notes.push_back(
        "resample_interval: ignored; pgmcl resamples when N_eff < "
        "filter.resample_threshold x N (~pgmcl/filter/resample_threshold)");
  for (const char* name :
       {"laser_z_hit", "laser_z_short", "laser_z_max", "laser_z_rand", "laser_sigma_hit",
        "laser_lambda_short", "laser_likelihood_max_dist", "do_beamskip", "beam_skip_distance",
        "beam_skip_threshold", "beam_skip_error_threshold", "selective_resampling",
        "restore_defaults"}) {
    if (get(name))
      s.notes.push_back(std::string(name) +
                        ": ignored; the sensor model is Dekan et al.'s planar Gaussian "
                        "(~pgmcl/likelihood/...)");
  }
}

void read_node_fields(const ParamLookup& get, NodeSettings& s) {
  s.global_frame_id = frame_param(get, "global_frame_id", s.global_frame_id);
  s.odom_frame_id = frame_param(get, "odom_frame_id", s.odom_frame_id);
  s.base_frame_id = frame_param(get, "base_frame_id", s.base_frame_id);
  s.tf_broadcast = bool_param(get, "tf_broadcast").value_or(s.tf_broadcast);
  s.use_map_topic = bool_param(get, "use_map_topic").value_or(s.use_map_topic);
  s.first_map_only = bool_param(get, "first_map_only").value_or(s.first_map_only);
  s.map_file = string_param(get, "map_file").value_or("");
  s.pose_file = string_param(get, "pose_file").value_or("");
  s.gui_publish_rate = number_param(get, "gui_publish_rate").value_or(s.gui_publish_rate);
  s.save_pose_rate = number_param(get, "save_pose_rate").value_or(s.save_pose_rate);
  if (std::isnan(s.save_pose_rate) || std::isnan(s.gui_publish_rate))
    throw ParameterError("save_pose_rate", "must be a number");
  s.nav.save_pose_period = s.save_pose_rate > 0.0 ? 1.0 / s.save_pose_rate : 0.0;

  NavConfig& n = s.nav;
  if (const auto v = number_param(get, "transform_tolerance")) {
    if (!(std::isfinite(*v) && *v >= 0.0))
      throw ParameterError("transform_tolerance", "must be finite and >= 0");
    n.transform_tolerance = *v;
  }
  n.ranges.min = number_param(get, "laser_min_range").value_or(n.ranges.min);
  n.ranges.max = number_param(get, "laser_max_range").value_or(n.ranges.max);
  if (const auto v = get("scan_stride")) {
    const std::int64_t k = as_integer("scan_stride", *v);
    if (k < 1) throw ParameterError("scan_stride", "must be >= 1");
    n.scan_stride = static_cast<std::size_t>(k);
  }

  const auto x = number_param(get, "initial_pose_x"), y = number_param(get, "initial_pose_y"),
             a = number_param(get, "initial_pose_a");
  if (x || y || a) {
    StoredPose p;
    p.pose = {x.value_or(0.0), y.value_or(0.0), wrap_angle(a.value_or(0.0))};
    p.cov_xx = number_param(get, "initial_cov_xx").value_or(0.5 * 0.5);
    p.cov_yy = number_param(get, "initial_cov_yy").value_or(0.5 * 0.5);
    p.cov_aa = number_param(get, "initial_cov_aa").value_or(std::pow(std::numbers::pi / 12, 2));
    if (!p.valid())
      throw ParameterError("initial_pose_x",
                           "the initial pose must be finite and initial_cov_xx/yy/aa >= 0");
    s.initial_pose = p;
  }
}

}  // namespace

ParameterError::ParameterError(std::string name, std::string problem)
    : std::invalid_argument("parameter ~" + name + ": " + problem),
      name_(std::move(name)),
      problem_(std::move(problem)) {}

NodeSettings read_node_settings(const ParamLookup& get, const LocalizerConfig& base,
                                const std::vector<std::string>& names) {
  NodeSettings s;
  s.nav.filter = base;
  read_node_fields(get, s);
  note_unsupported(get, s);
  std::map<std::string, std::string> set_by;  // dotted field -> parameter
  const std::map<std::string, Source> amcl = amcl_fields(get, s);
  ApplyVisitor from_amcl([&](const std::string& dotted) -> std::optional<Source> {
    const auto it = amcl.find(dotted);
    if (it == amcl.end()) return std::nullopt;
    set_by[dotted] = it->second.name;
    return it->second;
  });
  schema::describe_config(from_amcl, s.nav.filter);
  // amcl's max_particles also bounds the counts amcl would start with.
  if (amcl.contains("filter.kld.max_particles")) {
    FilterConfig& f = s.nav.filter.filter;
    f.particles = std::min(f.particles, f.kld.max_particles);
    f.global_particles = std::min(f.global_particles, f.kld.max_particles);
    // ... and its lower bound, when only max_particles is given and is below pgmcl's.
    if (!amcl.contains("filter.kld.min_particles"))
      f.kld.min_particles = std::min(f.kld.min_particles, f.kld.max_particles);
  }
  ApplyVisitor from_pgmcl([&](const std::string& dotted) -> std::optional<Source> {
    const std::string name = kPgmclPrefix + slashes(dotted);
    auto v = get(name);
    if (!v) return std::nullopt;
    set_by[dotted] = name;
    return Source{name, std::move(*v)};
  });
  schema::describe_config(from_pgmcl, s.nav.filter);

  const std::set<std::string> known(from_pgmcl.fields().begin(), from_pgmcl.fields().end());
  for (const std::string& n : names) {
    if (n.rfind(kPgmclPrefix, 0) != 0) continue;
    if (!known.contains(replace_all(n.substr(std::string(kPgmclPrefix).size()), '/', '.')))
      throw ParameterError(n,
                           "unknown pgmcl setting (every key: configs/reference.md, with '/' "
                           "for '.')");
  }
  try {
    s.nav.validate();
  } catch (const InvalidConfigField& e) {
    const auto it = set_by.find(e.field());
    throw ParameterError(it != set_by.end() ? it->second : kPgmclPrefix + slashes(e.field()),
                         e.problem());
  } catch (const std::invalid_argument& e) {
    throw ParameterError("laser_max_range", e.what());  // NavConfig's own checks: the ranges
  }
  return s;
}

std::vector<std::string> pgmcl_parameter_names() {
  LocalizerConfig cfg;
  ApplyVisitor v([](const std::string&) -> std::optional<Source> { return std::nullopt; });
  schema::describe_config(v, cfg);
  std::vector<std::string> out;
  for (const std::string& f : v.fields()) out.push_back(kPgmclPrefix + slashes(f));
  return out;
}

}  // namespace pgmcl::nav
