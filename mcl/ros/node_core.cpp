// pgmcl_node's core (C++20): parameters, maps, the adapter; no ROS headers here.
#include "node_core.hpp"

#include <cmath>
#include <stdexcept>

#include "pgmcl/config/config_yaml.hpp"
#include "pgmcl/map_io/map_io.hpp"
#include "pgmcl/nav/nav_localizer.hpp"
#include "pgmcl/nav/parameters.hpp"
#include "pgmcl/rosbag_io/rosbag_io.hpp"

namespace pgmcl::ros1 {
namespace {

Planar planar_of(const Pose2& p) {
  return {p.x, p.y, p.theta};
}

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

}  // namespace

struct NodeCore::Impl {
  nav::NodeSettings settings;
  NodeOptions options;
  Logger log;
  std::unique_ptr<nav::NavLocalizer> nav;
  std::string map_frame;
  std::vector<nav::WeightedPose> cloud;

  void start(const maps::OccupancyGrid& grid, const std::string& frame_id) {
    if (frame_id != settings.global_frame_id)
      log(LogLevel::kWarn, "the map's frame '" + frame_id + "' is not global_frame_id '" +
                               settings.global_frame_id + "'; poses are published in the latter");
    if (nav) {
      const bool same = frame_id == map_frame;
      nav->replace_map(grid, same);
      log(LogLevel::kInfo, same ? "new map in the same frame: particles kept"
                                : "new map in another frame: global localisation");
      map_frame = frame_id;
      return;
    }
    nav = std::make_unique<nav::NavLocalizer>(grid, settings.nav);
    map_frame = frame_id;
    // amcl's order: the initial_pose_* parameters (which the node also stores the last
    // pose in, so a restart without a new launch resumes), then the pose file.
    std::optional<nav::StoredPose> start = settings.initial_pose;
    std::string from = "initial_pose_x/y/a";
    if (!start && !settings.pose_file.empty()) {
      start = nav::load_stored_pose(settings.pose_file);
      from = "the last pose in " + settings.pose_file;
    }
    if (start) {
      nav->set_initial_pose(start->pose, start->covariance());
      log(LogLevel::kInfo, "starting at " + from + ": (" + number(start->pose.x) + ", " +
                               number(start->pose.y) + ", " + number(start->pose.theta) + ")");
    } else {
      log(LogLevel::kInfo, "no initial pose: global localisation");
    }
  }
};

NodeCore::NodeCore(const ParamLookup& get, const std::vector<std::string>& names, Logger log)
    : impl_(std::make_unique<Impl>()) {
  impl_->log = std::move(log);
  LocalizerConfig base;
  // A bag played in a loop or a restarted simulation sends time backwards: restart the
  // odometry chain instead of refusing every later scan.
  base.time_backwards = TimeBackwardsPolicy::kReset;
  const nav::ParamLookup lookup = [&](const std::string& n) { return get(n); };
  try {
    if (const auto c = get("config")) {
      const auto* path = std::get_if<std::string>(&*c);
      if (path == nullptr) throw nav::ParameterError("config", "expected a file name");
      io::read_localizer_config(*path, base);
    }
    impl_->settings = nav::read_node_settings(lookup, base, names);
  } catch (const std::exception& e) {
    throw std::runtime_error(e.what());
  }
  for (const std::string& n : impl_->settings.notes) impl_->log(LogLevel::kWarn, n);
  const nav::NodeSettings& s = impl_->settings;
  impl_->options = {s.global_frame_id, s.odom_frame_id,  s.base_frame_id, s.tf_broadcast,
                    s.use_map_topic,   s.first_map_only, s.map_file,      s.gui_publish_rate};
}

NodeCore::~NodeCore() = default;

const NodeOptions& NodeCore::options() const noexcept {
  return impl_->options;
}
bool NodeCore::has_map() const noexcept {
  return impl_->nav != nullptr;
}

void NodeCore::load_map_file() {
  try {
    maps::MapLoadReport report;
    const maps::OccupancyGrid grid = maps::load_map(impl_->settings.map_file, &report);
    for (const std::string& w : report.warnings) impl_->log(LogLevel::kWarn, w);
    impl_->log(LogLevel::kInfo,
               "map " + impl_->settings.map_file + ": " + std::to_string(grid.width()) + " x " +
                   std::to_string(grid.height()) + " cells of " + number(grid.resolution()) + " m");
    impl_->start(grid, impl_->settings.global_frame_id);
  } catch (const std::exception& e) {
    throw std::runtime_error(e.what());
  }
}

void NodeCore::set_map(const Grid& g, const std::string& frame_id) {
  try {
    maps::OccupancyGrid grid(g.width, g.height, g.resolution,
                             nav::planar(rosbag_io::to_isometry(g.origin)));
    if (g.cells.size() != grid.size())
      throw std::invalid_argument("map message: " + std::to_string(g.cells.size()) +
                                  " cells for a " + std::to_string(g.width) + " x " +
                                  std::to_string(g.height) + " grid");
    grid.cells() = g.cells;
    impl_->start(grid, frame_id);
  } catch (const std::exception& e) {
    throw std::runtime_error(e.what());
  }
}

ScanResult NodeCore::process_scan(const Scan& s, const Rigid& base_T_laser,
                                  const Rigid& odom_T_base) {
  const nav::ScanInput in{{s.angle_min, s.angle_increment, s.range_min, s.range_max, s.ranges},
                          rosbag_io::to_isometry(base_T_laser),
                          nav::planar(rosbag_io::to_isometry(odom_T_base)),
                          s.stamp};
  const nav::ScanOutcome o = impl_->nav->process_scan(in);
  return {o.filtered, o.rejected, o.pose_ready, o.transform_ready, o.error};
}

void NodeCore::set_initial_pose(const Rigid& pose, const std::array<double, 36>& covariance,
                                const std::optional<Rigid>& odom_T_base_at_pose) {
  std::optional<Pose2> at;
  if (odom_T_base_at_pose) at = nav::planar(rosbag_io::to_isometry(*odom_T_base_at_pose));
  try {
    impl_->nav->set_initial_pose(nav::planar(rosbag_io::to_isometry(pose)),
                                 nav::from_ros_covariance(covariance), at);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
}

void NodeCore::global_localize() {
  impl_->nav->global_localize();
}
void NodeCore::request_nomotion_update() {
  impl_->nav->request_nomotion_update();
}

PoseOut NodeCore::pose() const {
  const nav::PoseOutput p = impl_->nav->pose();
  return {planar_of(p.pose), p.ros_covariance, p.stamp, p.fit, p.converged, p.alternative_evidence};
}

std::optional<TransformOut> NodeCore::map_to_odom() const {
  const auto t = impl_->nav->map_to_odom();
  if (!t) return std::nullopt;
  return TransformOut{planar_of(t->map_T_odom), t->stamp};
}

void NodeCore::particles(std::vector<Particle>& out) const {
  impl_->nav->particles(impl_->cloud);
  out.resize(impl_->cloud.size());
  for (std::size_t i = 0; i < out.size(); ++i)
    out[i] = {planar_of(impl_->cloud[i].pose), impl_->cloud[i].weight};
}

DiagnosticsOut NodeCore::diagnostics() const {
  const nav::Diagnostics& d = impl_->nav->diagnostics();
  const nav::PoseOutput p = impl_->nav->pose();
  DiagnosticsOut out;
  out.ok = p.converged && d.rejected == 0;
  out.message = std::string(p.converged ? "converged" : "not converged") +
                (d.rejected > 0 ? ", " + std::to_string(d.rejected) + " scans refused" : "");
  const auto add = [&](const char* k, const std::string& v) { out.values.emplace_back(k, v); };
  add("scans", std::to_string(d.scans));
  add("filtered", std::to_string(d.filtered));
  add("measured", std::to_string(d.measured));
  add("not moved", std::to_string(d.not_moved));
  add("no valid beams", std::to_string(d.no_valid_beams));
  add("time resets", std::to_string(d.time_resets));
  add("stride skipped", std::to_string(d.stride_skipped));
  add("refused", std::to_string(d.rejected));
  add("last refusal", d.last_error);
  add("last skip", to_string(d.last_skip));
  add("update ms", number(d.update_ms));
  add("particles", std::to_string(d.particles));
  add("beams used", std::to_string(d.beams_used));
  add("beams invalid", std::to_string(d.beams_invalid));
  add("beams total", std::to_string(d.beams_total));
  add("n_eff", number(d.n_eff));
  add("fit", number(p.fit));
  add("converged", p.converged ? "true" : "false");
  add("alternative evidence", number(p.alternative_evidence));
  return out;
}

std::vector<std::pair<std::string, double>> NodeCore::pose_to_store(double now) {
  const auto p = impl_->nav->pose_to_store(now);
  if (!p) return {};
  if (!impl_->settings.pose_file.empty()) {
    try {
      nav::save_stored_pose(impl_->settings.pose_file, *p);
    } catch (const std::exception& e) {
      impl_->log(LogLevel::kWarn, e.what());
    }
  }
  return {{"initial_pose_x", p->pose.x},     {"initial_pose_y", p->pose.y},
          {"initial_pose_a", p->pose.theta}, {"initial_cov_xx", p->cov_xx},
          {"initial_cov_yy", p->cov_yy},     {"initial_cov_aa", p->cov_aa}};
}

}  // namespace pgmcl::ros1
