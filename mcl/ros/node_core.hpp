#pragma once
// pgmcl_node's core: everything but the ROS plumbing, over nav::NavLocalizer. This header
// is included by the ROS side (C++17, see ros1_bridge.hpp) and implemented in C++20, so it
// holds plain standard types only.

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "pgmcl/rosbag_io/ros1_bridge.hpp"

namespace pgmcl::ros1 {

using ParamValue = std::variant<bool, std::int64_t, double, std::string>;
using ParamLookup = std::function<std::optional<ParamValue>(const std::string& name)>;

struct Planar {
  double x = 0.0, y = 0.0, theta = 0.0;
};

/// The node's settings besides the filter (nav::NodeSettings).
struct NodeOptions {
  std::string global_frame_id, odom_frame_id, base_frame_id;
  bool tf_broadcast = true;
  bool use_map_topic = false;
  bool first_map_only = false;
  std::string map_file;
  double gui_publish_rate = -1.0;
};

/// A nav_msgs/OccupancyGrid's contents.
struct Grid {
  int width = 0, height = 0;
  double resolution = 0.0;
  Rigid origin;
  std::vector<std::int8_t> cells;
};

struct ScanResult {
  bool filtered = false, rejected = false, pose_ready = false, transform_ready = false;
  std::string error;
};

struct PoseOut {
  Planar pose;
  std::array<double, 36> covariance{};
  double stamp = 0.0;
  double fit = 0.0;
  bool converged = false;
  double alternative_evidence = 0.0;
};

struct TransformOut {
  Planar map_T_odom;
  double stamp = 0.0;
};

struct Particle {
  Planar pose;
  double weight = 0.0;
};

struct DiagnosticsOut {
  bool ok = true;       ///< false: not converged or scans refused
  std::string message;  ///< one line
  std::vector<std::pair<std::string, std::string>> values;
};

enum class LogLevel { kInfo, kWarn };
using Logger = std::function<void(LogLevel, const std::string&)>;

class NodeCore {
 public:
  /// Reads ~config (pgmcl's filter YAML, if set) and the parameters (nav/parameters.hpp);
  /// logs the notes. Throws std::runtime_error naming the parameter or file.
  NodeCore(const ParamLookup& get, const std::vector<std::string>& names, Logger log);
  ~NodeCore();
  NodeCore(const NodeCore&) = delete;
  NodeCore& operator=(const NodeCore&) = delete;

  [[nodiscard]] const NodeOptions& options() const noexcept;

  /// ~map_file (a map_server YAML), in the global frame. Throws std::runtime_error.
  void load_map_file();
  /// A map message. The first map starts the filter (the initial pose parameters, else
  /// the pose in ~pose_file, else global localisation); a later map in the same frame keeps the
  /// particles, one in another frame restarts. Throws std::runtime_error.
  void set_map(const Grid& grid, const std::string& frame_id);
  [[nodiscard]] bool has_map() const noexcept;

  ScanResult process_scan(const Scan& scan, const Rigid& base_T_laser, const Rigid& odom_T_base);
  /// Throws std::runtime_error for a non-finite pose or a covariance that is not PSD.
  void set_initial_pose(const Rigid& pose, const std::array<double, 36>& covariance,
                        const std::optional<Rigid>& odom_T_base_at_pose);
  void global_localize();
  void request_nomotion_update();

  [[nodiscard]] PoseOut pose() const;
  [[nodiscard]] std::optional<TransformOut> map_to_odom() const;
  void particles(std::vector<Particle>& out) const;
  [[nodiscard]] DiagnosticsOut diagnostics() const;
  /// amcl's initial_pose_* / initial_cov_* values to store as parameters now (also written
  /// to ~pose_file when set), or empty when it is not time yet.
  [[nodiscard]] std::vector<std::pair<std::string, double>> pose_to_store(double now);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pgmcl::ros1
