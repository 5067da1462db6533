#pragma once
/// A localisation node's parameters, middleware-neutral: amcl's names where they mean the
/// same thing, and every LocalizerConfig field under pgmcl/ (walked from the one schema,
/// pgmcl/mcl/config_schema.hpp: "pgmcl/filter/kld/epsilon"). The node only supplies a
/// lookup of its private parameters; the table of names, meanings and differences from
/// amcl is mcl/ros/README.md.

#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "pgmcl/mcl/localizer_config.hpp"
#include "pgmcl/nav/nav_localizer.hpp"
#include "pgmcl/nav/stored_pose.hpp"

namespace pgmcl::nav {

using ParamValue = std::variant<bool, std::int64_t, double, std::string>;
/// The value of a private parameter by its name relative to the node ("min_particles",
/// "pgmcl/filter/kld/epsilon"), or nullopt when it is not set.
using ParamLookup = std::function<std::optional<ParamValue>(const std::string& name)>;

/// A parameter with a wrong type or value; what() = "parameter ~<name>: <problem>".
class ParameterError : public std::invalid_argument {
 public:
  ParameterError(std::string name, std::string problem);
  [[nodiscard]] const std::string& name() const noexcept { return name_; }
  [[nodiscard]] const std::string& problem() const noexcept { return problem_; }

 private:
  std::string name_;
  std::string problem_;
};

/// Everything a node reads at start besides the map and ~config (which the node parses).
struct NodeSettings {
  NavConfig nav{};
  std::string global_frame_id = "map";
  std::string odom_frame_id = "odom";
  std::string base_frame_id = "base_link";
  bool tf_broadcast = true;
  bool use_map_topic = false;
  bool first_map_only = false;
  /// initial_pose_x/y/a (any of them set) with initial_cov_xx/yy/aa (amcl's defaults
  /// 0.25, 0.25, (pi/12)² where unset); nullopt: start with global localisation.
  std::optional<StoredPose> initial_pose;
  double save_pose_rate = 0.5;     ///< Hz; <= 0: never (NavConfig::save_pose_period)
  double gui_publish_rate = -1.0;  ///< Hz of the particle cloud; <= 0: every update
  std::string map_file;            ///< ~map_file: a map_server YAML, instead of a topic
  std::string pose_file;           ///< ~pose_file: also store the last pose there
  /// amcl parameters that were set but mean something else here or nothing: one line
  /// each, for the node to log.
  std::vector<std::string> notes;
};

/// Reads amcl's names, then pgmcl/..., over `base` (the defaults, or what ~config gave).
/// `names`: every parameter set in the node's namespace (relative names), used to refuse
/// pgmcl/ names the schema does not know (empty: no such check). The result is validated.
/// Throws ParameterError naming the parameter.
[[nodiscard]] NodeSettings read_node_settings(const ParamLookup& get, const LocalizerConfig& base,
                                              const std::vector<std::string>& names = {});

/// Every pgmcl/... parameter, in the schema's order.
[[nodiscard]] std::vector<std::string> pgmcl_parameter_names();

}  // namespace pgmcl::nav
