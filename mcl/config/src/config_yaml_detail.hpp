#pragma once
/// Private: the LocalizerConfig reader on an already-parsed YAML node, so larger files
/// (experiments) can embed a filter section and keep their own line numbers.

#include <yaml-cpp/yaml.h>

#include <string>

#include "pgmcl/mcl/localizer_config.hpp"

namespace pgmcl::io::detail {

/// Reads `node` (a mapping, or null) over `cfg` and validates. `path` is the dotted key of
/// the node in its file ("" for a whole filter file, "filter" inside an experiment).
void read_localizer_node(const std::string& file, const YAML::Node& node, const std::string& path,
                         LocalizerConfig& cfg);

}  // namespace pgmcl::io::detail
