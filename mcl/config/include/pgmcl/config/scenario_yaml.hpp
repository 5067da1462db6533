#pragma once
/// Scenario files: YAML -> sims::Scenario, the simulator's plain struct (the adapter at the
/// edge; sims itself does no file I/O). Example files live in configs/scenarios/.
///
/// Every key is optional except `map`; an absent key keeps the struct's documented default
/// (sims/scenario.hpp and the headers it includes). Units: metres, seconds, radians, Hz.
/// Poses are [x, y, theta], points [x, y], all in the map's global frame. Paths (map,
/// surfaces.labels) are relative to the scenario file's folder.
///
///   name: text                       description: text
///   map: file.yaml                   # map_server YAML (maps::load_map)
///   seed: 1                          duration: 10.0        # s
///   scan_rate: 0.0                   # Hz, 0 = the sensor's own
///   control_rate: 20.0               # Hz
///   sensor:   { profile: hokuyo_utm30lx, mount: [x, y, theta],
///               angle_min, angle_increment, beam_count, range_min, range_max,
///               scan_rate, scan_time }           # fields override the named profile
///   noise:    { preset: default | none,          # base before the fields below
///               along_beam, range_growth, across_beam, sigma_y, quantum,
///               dropouts: {enabled, rate}, short_returns: {enabled, rate, lambda},
///               specular: {enabled, rate, min_incidence} }
///   raycast:  { unknown: pass_through | block | absorb }
///   surfaces: { default: average,
///               materials: [ {name, sigma_normal, sigma_45, grazing_limit, specular} ],
///                          # a known name (sims::default_materials) is modified in place,
///                          # a new one is appended (sigmas default to Table 2's means)
///               labels: image.pgm,           # pixel value = palette index, > 100 = none
///               regions: [ {material, min: [x, y], max: [x, y]} ] }
///   obstacles: { discs: [ {radius, material, path} ],
///                boxes: [ {half_length, half_width, yaw, material, path} ] }
///               # path: {waypoints: [[x, y], ...], speed, start_offset}
///   robot:    { start: [x, y, theta], motion: waypoints | random_walk | stationary,
///               limits: {max_v, max_omega},
///               waypoints: {points: [[x, y], ...], controller: pure_pursuit |
///                           turn_then_drive, lookahead, goal_tolerance, heading_tolerance,
///                           loop},
///               random_walk: {clearance, goal_tolerance, min_leg, max_leg, max_retries} }
///   odometry: { random_noise, model: differential_drive | omnidirectional,
///               alphas: {a1, a2, a3, a4, a5}, wheel_radius_bias, wheelbase_bias,
///               yaw_drift_per_metre, origin: [x, y, theta] }
///   kidnaps:  [ {time, pose: [x, y, theta]} ]
///   (no `filter:`: filter settings belong in an experiment or filter file; a scenario
///   that has one is an error, not silently ignored)
///
/// Errors: any problem throws ScenarioError ("file:line: key: problem"): syntax, wrong
/// types, unknown keys (typos are never ignored), out-of-range values, and the checks of
/// sims::Scenario::validate against the loaded map, reported at the key they concern.

#include <string>
#include <vector>

#include "pgmcl/io/errors.hpp"
#include "pgmcl/maps/occupancy_grid.hpp"
#include "pgmcl/sims/scenario.hpp"

namespace pgmcl::io {

/// A scenario file that cannot be used. file() is the scenario YAML (or, for problems
/// inside the map it names, still the scenario, with the map's message in message()),
/// field() the dotted key ("robot.waypoints.points[2]"), line() 1-based (0 if unknown).
class ScenarioError : public FormatError {
 public:
  using FormatError::FormatError;
};

/// Everything a scenario file holds besides the map's pixels.
struct ScenarioFile {
  std::string path;         ///< the scenario YAML as given
  std::string name;         ///< `name:`, default: the file's stem
  std::string description;  ///< `description:`, may be empty
  std::string map_path;     ///< the map YAML, resolved against the scenario's folder
  sims::Scenario scenario;  ///< validated against the map
};

/// Reads the scenario at `yaml_path`, loads its map into `map` and validates the scenario
/// against it. `sets` are "key=value" overrides of the file's keys ("duration=20",
/// "robot.start=[1, 2, 0]"), values read as YAML, applied before reading: a problem with an
/// overridden key is reported as "--set key=value: key: problem". Throws ScenarioError
/// (see above), UsageError for a malformed --set, io::IoError if the file is unreadable.
[[nodiscard]] ScenarioFile read_scenario_file(const std::string& yaml_path,
                                              maps::OccupancyGrid& map,
                                              const std::vector<std::string>& sets = {});

/// Convenience for tools: the scenario alone; the map goes to `map_out` when non-null.
[[nodiscard]] sims::Scenario load_scenario(const std::string& yaml_path,
                                           maps::OccupancyGrid* map_out = nullptr);

}  // namespace pgmcl::io
