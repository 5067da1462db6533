#pragma once
/// What to read from a ROS 1 bag, shared by `localize --bag` and `convert`: the options and
/// the read into the in-memory log (pgmcl::rosbag_io, when built with PGMCL_WITH_ROS).

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "pgmcl/io/carmen.hpp"

namespace pgmcl::app {

struct BagInput {
  std::string scan_topic = "/scan";
  std::string odom_topic;  ///< empty: odometry from /tf
  std::string odom_frame = "odom";
  std::string base_frame = "base_link";
};

/// --scan-topic, --odom-topic, --odom-frame, --base-frame on `sub`; each needs `needs`
/// when that is not null.
void add_bag_input_options(CLI::App& sub, BagInput& in, CLI::Option* needs);

/// Throws std::runtime_error: `what` needs ROS 1, which this pgmcl was built without.
[[noreturn]] void throw_without_ros(const std::string& what);

/// True for "*.bag".
[[nodiscard]] bool is_bag_path(const std::string& path);

/// The bag at `path` as a log; scans outside the odometry's time span are reported as one
/// warning on stderr (also appended to `warnings` when given). Throws what
/// rosbag_io::read_bag throws, or std::runtime_error when pgmcl was built without ROS 1
/// (`what` names the command).
[[nodiscard]] io::CarmenLog read_bag_input(const std::string& path, const BagInput& in,
                                           const std::string& what,
                                           std::vector<std::string>* warnings = nullptr);

}  // namespace pgmcl::app
