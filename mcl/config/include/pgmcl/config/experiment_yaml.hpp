#pragma once
/// Experiment files for `pgmcl run`: map + data + filter in one YAML file.
///
///   name: intel-tracking          # default: the file's stem
///   map: maps/intel.yaml          # the filter's map; optional with data.scenario (the
///                                 # scenario's own map is then used)
///   data:                         # exactly one of log / scenario
///     log: logs/intel-raw.log.gz  # a CARMEN log to replay
///     truth: logs/truth.tum       # optional: TUM, or a corrected CARMEN log
///     relations: intel.relations  # optional: Kümmerle et al. relations
///     time_offset: 976052857.338  # seconds added to log stamps for the relations
///     scenario: sc/lab.yaml       # or: simulate this scenario first (its truth is used)
///   init: global                  # global | truth | [x, y, theta] |
///                                 # {pose: [x, y, theta], sigma: [sx, sy, stheta]}
///                                 # default: truth when there is one, else global
///   filter: {...}                 # a LocalizerConfig mapping (config_yaml.hpp), or the
///                                 # path of a filter YAML file
///   out: results/intel            # default: pgmcl-out/<name>
///
/// Relative paths are relative to the experiment file's folder (`out` too). Errors throw
/// ConfigError "file:line: key: problem" (unknown keys, wrong types, both or neither of
/// data.log and data.scenario, and the filter's own errors at their lines); an input path
/// that does not exist, or is the wrong kind of file (io::detect_file_kind), is an error
/// naming the key, the path as written and the folder it was resolved against.

#include <optional>
#include <string>
#include <vector>

#include "pgmcl/common/se2.hpp"
#include "pgmcl/config/config_yaml.hpp"
#include "pgmcl/mcl/localizer_config.hpp"

namespace pgmcl::io {

struct ExperimentInit {
  enum class Kind { kDefault, kGlobal, kTruth, kPose } kind = Kind::kDefault;
  Pose2 pose{};              ///< kPose
  double sigma_x = 0.25;     ///< metres
  double sigma_y = 0.25;     ///< metres
  double sigma_theta = 0.1;  ///< radians
};

struct Experiment {
  std::string path;  ///< the experiment file as given
  std::string name;
  std::string map;           ///< resolved path, empty if the scenario's map is used
  std::string log;           ///< resolved path (exclusive with scenario)
  std::string scenario;      ///< resolved path
  std::string truth;         ///< resolved path, may be empty
  std::string relations;     ///< resolved path, may be empty
  double time_offset = 0.0;  ///< seconds
  ExperimentInit init{};
  LocalizerConfig filter{};        ///< validated
  std::string out;                 ///< resolved output directory
  std::vector<std::string> notes;  ///< deprecated spellings used in `sets`, for the caller
};

/// Reads an experiment. `sets` are "key=value" overrides applied after the file: name, map,
/// out, init, data.log, data.scenario, data.truth, data.relations, data.time_offset replace
/// those values (paths relative to the current directory, as typed on a command line; init
/// also as "x,y,theta[,sx,sy,stheta]" like --init), and every other key is a filter key
/// with the same path as `pgmcl localize --set` ("filter.particles=500"); the old
/// "filter.filter.particles" still works and adds a line to Experiment::notes.
/// Then every input path must exist and be of its kind. Throws ConfigError (file errors,
/// missing inputs), UsageError (a bad --set, a missing input it named, a wrong kind of
/// file), IoError (unreadable file).
[[nodiscard]] Experiment read_experiment(const std::string& path,
                                         const std::vector<std::string>& sets = {});

}  // namespace pgmcl::io
