#include "pgmcl/config/key_hints.hpp"

#include <algorithm>
#include <array>
#include <string_view>

#include "pgmcl/mcl/config_schema.hpp"

namespace pgmcl::io {
namespace {

namespace schema = pgmcl::config_schema;

// nav2_amcl's parameters (docs.nav2.org, "AMCL"), ROS 1 amcl's where they differ; ROS 1's
// odom_ and laser_ prefixes (odom_alpha1, laser_z_hit) are looked up without them.
constexpr AmclParameter kAmcl[] = {
    {"alpha1", "motion.noise.a1",
     "rotation noise from rotation; Probabilistic Robotics Table 5.6 in variance form, as "
     "nav2's differential model (ROS 1: odom_alpha1, model diff-corrected)"},
    {"alpha2", "motion.noise.a2", "rotation noise from translation"},
    {"alpha3", "motion.noise.a3", "translation noise from translation"},
    {"alpha4", "motion.noise.a4", "translation noise from rotation"},
    {"alpha5", "motion.noise.a5", "omnidirectional only (motion.kind: omnidirectional)"},
    {"robot_model_type", "motion.kind",
     "differential_drive or omnidirectional (nav2's DifferentialMotionModel / "
     "OmniMotionModel; ROS 1 odom_model_type)"},
    {"odom_model_type", "motion.kind", "ROS 1's name of robot_model_type"},
    {"min_particles", "filter.kld.min_particles", "KLD-sampling's lower bound"},
    {"max_particles", "filter.kld.max_particles",
     "KLD-sampling's upper bound; filter.particles is the count after a pose is set "
     "(--init) and the fixed count with filter.kld.enabled false, filter.global_particles "
     "the count of a global start"},
    {"pf_err", "filter.kld.epsilon", "KLD bound (ROS 1: kld_err)"},
    {"kld_err", "filter.kld.epsilon", "KLD bound"},
    {"pf_z", "filter.kld.delta",
     "AMCL uses the number itself as the normal quantile z (0.99); pgmcl takes the "
     "probability delta with z = quantile(1 - delta): AMCL's 0.99 is delta 0.161 (ROS 1: "
     "kld_z)"},
    {"kld_z", "filter.kld.delta", "see pf_z"},
    {"laser_model_type", "likelihood.table.kind",
     "likelihood_field is closest to isotropic (pgmcl's default); pgmcl's model is Dekan et "
     "al.'s planar Gaussian (oriented, offset keep its two sigmas); there is no beam model "
     "and no likelihood_field_prob beam skipping"},
    {"z_hit", "likelihood.beam.w_hit", "weight of the Gaussian term; w_hit + w_rand must be 1"},
    {"z_rand", "likelihood.beam.w_rand", "weight of the uniform floor over max_range"},
    {"z_short", "", "beam model only; pgmcl has no beam model (no ray casting per particle)"},
    {"z_max", "",
     "beam model only; readings at or beyond the scan's range_max or past "
     "likelihood.beam.max_range are skipped, not scored"},
    {"lambda_short", "", "beam model only"},
    {"sigma_hit", "likelihood.beam.sigma_along, likelihood.beam.sigma_across",
     "the Gaussian's sigma along and across the beam (the isotropic table uses sigma_along); "
     "pgmcl adds likelihood.beam.model_mismatch and the cell's res/sqrt(12) in quadrature: set "
     "model_mismatch 0 and add_discretisation false for AMCL's sigma as is"},
    {"laser_likelihood_max_dist", "likelihood.table.reach_sigmas",
     "in sigmas, not metres: AMCL's 2.0 m with sigma 0.2 m is 10"},
    {"laser_max_range", "likelihood.beam.max_range", "longer readings are skipped"},
    {"laser_min_range", "",
     "readings below the scan's own range_min (LaserScan::range_min; CARMEN logs 0.1 m) are "
     "skipped; no filter key"},
    {"max_beams", "likelihood.selection.max_beams",
     "with likelihood.selection.mode max_beams (evenly spread), pgmcl's default (ROS 1: "
     "laser_max_beams)"},
    {"update_min_d", "gating.d_min", "metres"},
    {"update_min_a", "gating.theta_min", "radians"},
    {"resample_interval", "",
     "pgmcl resamples when the effective sample size drops below filter.resample_threshold x "
     "N (selective resampling), not every k updates"},
    {"recovery_alpha_slow", "filter.recovery.alpha_slow",
     "augmented MCL; AMCL's default 0 turns recovery off, pgmcl's filter.recovery.enabled is "
     "true by default"},
    {"recovery_alpha_fast", "filter.recovery.alpha_fast", "see recovery_alpha_slow"},
    {"initial_pose", "--init X,Y,THETA,SX,SY,STH",
     "SX, SY, STH are standard deviations (m, m, rad), not AMCL's covariances "
     "(initial_cov_xx = SX^2); the map's origin yaw is honoured, not ignored"},
};

/// Collects dotted keys (leaves and sections) in the schema's order.
class KeyCollector {
 public:
  template <class Body>
  void section(const char* name, Body&& body) {
    path_.push_back(name);
    sections_.push_back(key(""));
    sections_.back().pop_back();  // no trailing dot
    body();
    path_.pop_back();
  }
  void number(const schema::Field& f, double, const schema::Bounds&) { leaf(f); }
  void flag(const schema::Field& f, bool) { leaf(f); }
  template <class T>
  void integer(const schema::Field& f, T, const schema::IntRange&) {
    leaf(f);
  }
  template <class E, std::size_t N>
  void choice(const schema::Field& f, E, const std::array<schema::EnumName<E>, N>&) {
    leaf(f);
  }
  void rule(const char*, bool, const char*) const {}

  std::vector<std::string> leaves;
  std::vector<std::string> sections_;

 private:
  [[nodiscard]] std::string key(const char* name) const {
    std::string k;
    for (const char* p : path_) k.append(p).append(".");
    return k + name;
  }
  void leaf(const schema::Field& f) { leaves.push_back(key(f.name)); }
  std::vector<const char*> path_;
};

KeyCollector collect() {
  KeyCollector c;
  const LocalizerConfig defaults;
  schema::describe_config(c, defaults);
  return c;
}

// Optimal string alignment distance: insertions, deletions, substitutions and swaps of
// neighbours each cost 1.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
    for (std::size_t j = 1; j <= b.size(); ++j) {
      d[i][j] = std::min(
          {d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

std::string_view last_component(std::string_view field) {
  const std::size_t dot = field.rfind('.');
  return dot == std::string_view::npos ? field : field.substr(dot + 1);
}

}  // namespace

std::span<const AmclParameter> amcl_parameters() noexcept {
  return kAmcl;
}

namespace {

const AmclParameter* find_amcl(std::string_view name) {
  for (const std::string_view prefix : {"", "odom_", "laser_"}) {
    if (name.substr(0, prefix.size()) != prefix) continue;
    const std::string_view rest = name.substr(prefix.size());
    for (const AmclParameter& p : kAmcl)
      if (rest == p.amcl) return &p;
  }
  return nullptr;
}

}  // namespace

std::string amcl_parameter_table() {
  std::string out = "| AMCL | pgmcl | notes |\n|---|---|---|\n";
  for (const AmclParameter& p : kAmcl) {
    out.append("| `").append(p.amcl).append("` | ");
    out.append(*p.pgmcl ? std::string("`") + p.pgmcl + "`" : std::string("—"));
    out.append(" | ").append(p.note).append(" |\n");
  }
  return out;
}

std::vector<std::string> localizer_config_keys() {
  return collect().leaves;
}

std::string localizer_key_hint(const std::string& field, const std::string& prefix) {
  const std::string_view name = last_component(field);
  if (name == "amcl" || name == "ros__parameters") {  // a whole ROS parameters file
    return "this looks like a ROS amcl parameters file (amcl: ros__parameters: ...); pgmcl's "
           "keys have other names and places: `pgmcl config --amcl` gives the pgmcl key of each "
           "AMCL parameter";
  }
  if (const AmclParameter* p = find_amcl(name)) {
    if (*p->pgmcl == '\0') return "AMCL's " + std::string(name) + " has no pgmcl key: " + p->note;
    std::string keys = p->pgmcl;
    if (keys.rfind("--", 0) != 0) {  // config keys, not an option: in the file's terms
      keys = prefix + keys;
      for (std::size_t at = keys.find(", "); at != std::string::npos; at = keys.find(", ", at + 2))
        keys.insert(at + 2, prefix);
    }
    return "AMCL's " + std::string(name) + " is pgmcl's " + keys + " (" + p->note + ")";
  }
  // A pgmcl key or section at the wrong level.
  const KeyCollector c = collect();
  std::string found;
  for (const auto* list : {&c.leaves, &c.sections_}) {
    for (const std::string& k : *list) {
      if (k == field || last_component(k) != name) continue;
      found += (found.empty() ? "" : " or ") + prefix + k;
    }
  }
  return found.empty() ? std::string() : "pgmcl's key is " + found;
}

std::string nearest_key(const std::string& key, const std::vector<std::string>& candidates) {
  // Within a third of the key's length: a suggestion, not a guess.
  const std::size_t limit = std::max<std::size_t>(1, key.size() / 3);
  std::string best;
  std::size_t best_distance = limit + 1;
  for (const std::string& known : candidates) {
    const std::size_t d = edit_distance(key, known);
    if (d < best_distance) {
      best = known;
      best_distance = d;
    }
  }
  return best;
}

}  // namespace pgmcl::io
