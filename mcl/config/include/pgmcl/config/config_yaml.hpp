#pragma once
/// Filter configuration files: YAML <-> pgmcl::LocalizerConfig (the adapter at the edge;
/// the engine only sees the plain struct).
///
/// The YAML mirrors the structs field for field (localizer_config.hpp documents defaults
/// and units: metres, radians, seconds). Every key is optional; an absent key keeps the
/// value already in the struct. Enumerations are written as names:
///
///   motion:      { kind: differential_drive | omnidirectional,
///                  noise: { a1, a2, a3, a4, a5 } }
///   likelihood:  { beam: { sigma_along, sigma_across, model_mismatch, add_discretisation,
///                          w_hit, w_rand, max_range },
///                  table: { kind: isotropic | oriented | offset, orientation_bins,
///                           reach_sigmas, isotropy_tolerance, max_table_bytes },
///                  effective_beams, tempering, min_ess_ratio,
///                  selection: { mode: all | stride | max_beams, stride, max_beams },
///                  expected_beams }
///   filter:      { particles, global_particles, resample_threshold,
///                  kld: { enabled, min_particles, max_particles, epsilon, delta, bin_xy,
///                         bin_theta },
///                  recovery: { enabled, alpha_slow, alpha_fast, threshold,
///                             probation, probation_weight } }
///   gating:      { enabled, d_min, theta_min }
///   estimate:    { cluster_xy, cluster_theta, converged_weight, converged_xy_std,
///                  converged_theta_std }
///   time_backwards: throw | reset
///   threads: 1
///   seed: 42
///
/// Errors throw ConfigError, what() = "file:line: key: problem": YAML syntax, wrong types,
/// unknown keys (typos are never ignored), bad enum names, and LocalizerConfig::validate()
/// failures, reported at the line of the key they concern.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "pgmcl/io/errors.hpp"
#include "pgmcl/mcl/localizer_config.hpp"

namespace pgmcl::io {

class ConfigError : public FormatError {
 public:
  using FormatError::FormatError;
};

/// Reads the filter YAML at `path` over `cfg` (absent keys keep cfg's values), then
/// validates the result. Throws ConfigError, or IoError if the file is unreadable.
void read_localizer_config(const std::string& path, LocalizerConfig& cfg);

/// Same from YAML text; `source` names it in messages.
void parse_localizer_config(std::string_view text, const std::string& source, LocalizerConfig& cfg);

/// One `--set key=value` override with a dotted key ("filter.kld.max_particles=5000"); the
/// value is read as YAML ("true", "0.05", "oriented"). Validates the result. Throws
/// ConfigError with file "--set key=value" and line 0 for unknown keys and bad values.
void apply_localizer_override(const std::string& key, const std::string& value,
                              LocalizerConfig& cfg);

/// Every field of `cfg` as YAML in the layout above (parse_localizer_config reads it back
/// to an identical struct). Written next to each run's results.
[[nodiscard]] std::string localizer_config_yaml(const LocalizerConfig& cfg);

/// Parses "key=value" pairs and applies them in order (see apply_localizer_override).
void apply_localizer_overrides(const std::vector<std::string>& assignments, LocalizerConfig& cfg);

}  // namespace pgmcl::io
