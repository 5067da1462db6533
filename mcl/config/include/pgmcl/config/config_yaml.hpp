#pragma once
/// Filter configuration files: YAML <-> pgmcl::LocalizerConfig (the adapter at the edge;
/// the engine only sees the plain struct).
///
/// The YAML mirrors the structs field for field, as described once in
/// pgmcl/mcl/config_schema.hpp (configs/reference.md lists every key with its default,
/// unit and allowed values). Every key is optional; an absent key keeps the value already in
/// the struct. Enumerations are written as names.
///
/// Errors throw ConfigError, what() = "file:line: key: problem": YAML syntax, wrong types,
/// unknown keys (typos are never ignored; the nearest known key is suggested), bad enum
/// names, and LocalizerConfig::validate() failures, reported at the line of the key they
/// concern.

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

/// The reference table of every key (default, unit, allowed values, meaning) as Markdown,
/// generated from config_schema.hpp; configs/reference.md is its output.
[[nodiscard]] std::string localizer_config_reference();

/// Parses "key=value" pairs and applies them in order (see apply_localizer_override).
void apply_localizer_overrides(const std::vector<std::string>& assignments, LocalizerConfig& cfg);

}  // namespace pgmcl::io
