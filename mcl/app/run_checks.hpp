#pragma once
/// The checks `localize` and `run` make before the filter starts, so a map or start the
/// filter cannot use is refused up front with the field at fault, not found after the run
/// as a "pose is not finite" or as a trajectory 20 m off.

#include <string>
#include <vector>

#include "pgmcl/maps/occupancy_grid.hpp"
#include "pgmcl/mcl/localizer_config.hpp"
#include "pgmcl/replay/replay.hpp"

namespace pgmcl::app {

/// A beam must span this many cells for its endpoint to say anything about the map.
constexpr double kMinCellsPerBeam = 4.0;

/// Refuses (maps::MapError naming `map_name` and the field) a map the filter cannot match
/// scans against: no occupied cell, cells so coarse that a beam of
/// likelihood.beam.max_range spans fewer than 4 of them, or a likelihood kernel too wide
/// for the table (naming the config field that makes it so). Returns a warning for a map
/// with more occupied than free cells (an inverted image: `negate`).
[[nodiscard]] std::vector<std::string> check_map_for_localisation(const maps::OccupancyGrid& map,
                                                                  const std::string& map_name,
                                                                  const LocalizerConfig& config);

/// The coarsest map resolution (metres per cell) the filter can match scans against with
/// `config`: a beam of likelihood.beam.max_range must span kMinCellsPerBeam cells.
[[nodiscard]] double coarsest_usable_resolution(const LocalizerConfig& config);

/// Refuses (io::UsageError naming `what`, "--init" or "FILE: init") a start pose outside the
/// map or standard deviations past the map's size (a start that wide is --global) or 2π;
/// returns warnings for a start in an occupied or unknown cell.
[[nodiscard]] std::vector<std::string> check_initial_belief(const replay::InitialBelief& b,
                                                            const maps::OccupancyGrid& map,
                                                            const std::string& what);

/// Whether the theta of a start pose looks like degrees typed as radians (|theta| > 2π);
/// the warning text, or "" when it does not.
[[nodiscard]] std::string heading_warning(double theta, const std::string& what);

}  // namespace pgmcl::app
