#pragma once
/// What to say about a filter key that does not exist: the pgmcl key for an AMCL
/// (nav2_amcl / ROS 1 amcl) parameter name, or why there is none, and the full path of a
/// pgmcl key written at the wrong level ("particles" at the top is filter.particles).
/// The readers of config_yaml.hpp add these to their "unknown key" errors; the AMCL table
/// is also the one in configs/README.md (`pgmcl config --amcl` prints it, a test checks
/// the copy).

#include <span>
#include <string>
#include <vector>

namespace pgmcl::io {

/// One AMCL parameter and where it went in pgmcl.
struct AmclParameter {
  const char* amcl;   ///< nav2_amcl / ROS 1 amcl name
  const char* pgmcl;  ///< pgmcl key(s) or option; "" when there is no equivalent
  const char* note;   ///< the difference, or why there is no equivalent
};

/// Every AMCL parameter pgmcl has an answer for, in AMCL's documentation order.
[[nodiscard]] std::span<const AmclParameter> amcl_parameters() noexcept;

/// The AMCL table as Markdown (`| AMCL | pgmcl | notes |`).
[[nodiscard]] std::string amcl_parameter_table();

/// Every filter key, dotted ("filter.kld.max_particles"), in the schema's order.
[[nodiscard]] std::vector<std::string> localizer_config_keys();

/// For an unknown filter key (`field` dotted from the config's root, e.g.
/// "filter.max_particles"): "AMCL's max_particles is pgmcl's filter.kld.max_particles (...)"
/// for an AMCL name, "pgmcl's key is filter.particles" for a pgmcl key at the wrong level,
/// else "". `prefix` goes before the pgmcl keys named ("filter." in an experiment file).
[[nodiscard]] std::string localizer_key_hint(const std::string& field,
                                             const std::string& prefix = "");

/// The candidate nearest `key` in edit distance (insertions, deletions, substitutions and
/// swaps of neighbours, the typos people make in keys) when within a third of the key's
/// length (at least one edit), else "": the "did you mean" of every unknown key.
[[nodiscard]] std::string nearest_key(const std::string& key,
                                      const std::vector<std::string>& candidates);

}  // namespace pgmcl::io
