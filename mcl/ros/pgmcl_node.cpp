// pgmcl_node: a ROS 1 drop-in for amcl. Only the ROS plumbing lives here (built as C++17,
// see ros1_bridge.hpp): topics, services, transforms and parameters. Everything else is
// NodeCore over the middleware-neutral adapter (pgmcl::nav).
#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/PoseArray.h>
#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <nav_msgs/GetMap.h>
#include <nav_msgs/OccupancyGrid.h>
#include <ros/ros.h>
#include <sensor_msgs/LaserScan.h>
#include <std_srvs/Empty.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>

#include <cmath>
#include <condition_variable>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "node_core.hpp"
#include "pgmcl/rosbag_io/ros1_messages.hpp"
#include "waiting_scans.hpp"

namespace pgmcl::ros1 {
namespace {

geometry_msgs::Quaternion yaw_quaternion(double yaw) {
  geometry_msgs::Quaternion q;
  q.z = std::sin(yaw / 2);
  q.w = std::cos(yaw / 2);
  return q;
}
geometry_msgs::Pose to_pose(const Planar& p) {
  geometry_msgs::Pose out;
  out.position.x = p.x;
  out.position.y = p.y;
  out.orientation = yaw_quaternion(p.theta);
  return out;
}
std::string strip_slash(std::string frame) {
  if (!frame.empty() && frame.front() == '/') frame.erase(0, 1);
  return frame;
}

/// The node's private parameters as the core reads them.
std::optional<ParamValue> private_param(const ros::NodeHandle& pnh, const std::string& name) {
  XmlRpc::XmlRpcValue v;
  if (!pnh.getParam(name, v)) return std::nullopt;
  switch (v.getType()) {
    case XmlRpc::XmlRpcValue::TypeBoolean:
      return ParamValue(static_cast<bool>(v));
    case XmlRpc::XmlRpcValue::TypeInt:
      return ParamValue(static_cast<std::int64_t>(static_cast<int>(v)));
    case XmlRpc::XmlRpcValue::TypeDouble:
      return ParamValue(static_cast<double>(v));
    case XmlRpc::XmlRpcValue::TypeString:
      return ParamValue(static_cast<std::string>(v));
    default:
      throw std::runtime_error("parameter ~" + name +
                               ": expected a boolean, number or string, not a list or map");
  }
}

/// Private parameter names relative to the node ("pgmcl/filter/kld/epsilon").
std::vector<std::string> private_names(const ros::NodeHandle& pnh) {
  std::vector<std::string> all, out;
  ros::param::getParamNames(all);
  const std::string prefix = pnh.getNamespace() + "/";
  for (const std::string& n : all)
    if (n.rfind(prefix, 0) == 0) out.push_back(n.substr(prefix.size()));
  return out;
}

/// Stores the last pose as private parameters on its own thread. Each value is one
/// round trip to the master (a new connection to a Python server); in the scan callback a
/// slow master would hold up localisation, and a bag played fast asks for many of them.
/// Only the newest pose waiting is stored.
class PoseParamWriter {
 public:
  explicit PoseParamWriter(ros::NodeHandle pnh)
      : pnh_(std::move(pnh)), thread_([this] { run(); }) {}
  ~PoseParamWriter() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_one();
    thread_.join();
  }
  PoseParamWriter(const PoseParamWriter&) = delete;
  PoseParamWriter& operator=(const PoseParamWriter&) = delete;

  void store(std::vector<std::pair<std::string, double>> values) {
    if (values.empty()) return;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      pending_ = std::move(values);
    }
    wake_.notify_one();
  }

 private:
  void run() {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      wake_.wait(lock, [this] { return stop_ || !pending_.empty(); });
      if (stop_) return;
      const std::vector<std::pair<std::string, double>> values = std::move(pending_);
      pending_.clear();
      lock.unlock();
      for (const auto& [key, value] : values) pnh_.setParam(key, value);
      lock.lock();
    }
  }

  ros::NodeHandle pnh_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::vector<std::pair<std::string, double>> pending_;
  bool stop_ = false;
  std::thread thread_;  // last: starts once the members it uses exist
};

class PgmclNode {
 public:
  PgmclNode(ros::NodeHandle nh, ros::NodeHandle pnh)
      : nh_(nh),
        pnh_(pnh),
        core_([&](const std::string& n) { return private_param(pnh, n); }, private_names(pnh),
              [](LogLevel level, const std::string& m) {
                if (level == LogLevel::kWarn)
                  ROS_WARN("pgmcl: %s", m.c_str());
                else
                  ROS_INFO("pgmcl: %s", m.c_str());
              }),
        opt_(core_.options()),
        listener_(buffer_),
        waiting_scans_(nh_, buffer_, opt_.odom_frame_id, opt_.base_frame_id, 100,
                       [this](const auto& scan, const auto& odom) { on_scan(scan, odom); }),
        pose_params_(pnh) {
    pose_pub_ = nh_.advertise<geometry_msgs::PoseWithCovarianceStamped>("amcl_pose", 100, true);
    cloud_pub_ = nh_.advertise<geometry_msgs::PoseArray>("particlecloud", 2, true);
    diag_pub_ = nh_.advertise<diagnostic_msgs::DiagnosticArray>("/diagnostics", 2);
    if (!opt_.map_file.empty()) {
      core_.load_map_file();
    } else if (opt_.use_map_topic) {
      map_sub_ = nh_.subscribe("map", 1, &PgmclNode::on_map, this);
      ROS_INFO("pgmcl: waiting for a map on %s", map_sub_.getTopic().c_str());
    } else {
      request_map();
    }
    if (core_.has_map()) publish_cloud(true);  // where the filter starts
    scan_sub_ = nh_.subscribe("scan", 100, &WaitingScans::add, &waiting_scans_);
    initial_sub_ = nh_.subscribe("initialpose", 2, &PgmclNode::on_initial_pose, this);
    global_srv_ = nh_.advertiseService("global_localization", &PgmclNode::on_global, this);
    nomotion_srv_ = nh_.advertiseService("request_nomotion_update", &PgmclNode::on_nomotion, this);
  }

 private:
  void request_map() {
    // amcl's use_map_topic = false: the static_map service (Debian has no map_server;
    // ~map_file reads a map file instead).
    ROS_INFO("pgmcl: requesting the map from the static_map service");
    nav_msgs::GetMap srv;
    while (ros::ok() && !ros::service::call("static_map", srv)) {
      ROS_WARN_THROTTLE(5.0,
                        "pgmcl: static_map is not available yet (set ~map_file or "
                        "~use_map_topic to take the map elsewhere)");
      ros::Duration(0.5).sleep();
    }
    if (ros::ok()) on_map(boost::make_shared<const nav_msgs::OccupancyGrid>(srv.response.map));
  }

  void on_map(const nav_msgs::OccupancyGridConstPtr& msg) {
    if (opt_.first_map_only && core_.has_map()) return;
    Grid g{static_cast<int>(msg->info.width), static_cast<int>(msg->info.height),
           msg->info.resolution, from_msg(msg->info.origin), msg->data};
    try {
      core_.set_map(g, strip_slash(msg->header.frame_id));
    } catch (const std::exception& e) {
      ROS_ERROR("pgmcl: map refused: %s", e.what());
      return;
    }
    ROS_INFO("pgmcl: map %u x %u cells of %.3f m", msg->info.width, msg->info.height,
             msg->info.resolution);
    publish_cloud(true);
  }

  std::optional<Rigid> lookup(const std::string& target, const std::string& source,
                              const ros::Time& t, double timeout) {
    try {
      return from_msg(buffer_.lookupTransform(target, source, t, ros::Duration(timeout)).transform);
    } catch (const tf2::TransformException& e) {
      ROS_DEBUG("pgmcl: %s", e.what());
      return std::nullopt;
    }
  }

  void on_scan(const sensor_msgs::LaserScanConstPtr& msg,
               const geometry_msgs::Transform& odom_T_base) {
    if (!core_.has_map()) return;
    const std::string frame = strip_slash(msg->header.frame_id);
    auto mount = mounts_.find(frame);
    if (mount == mounts_.end()) {
      std::optional<Rigid> t = lookup(opt_.base_frame_id, frame, msg->header.stamp, 0.0);
      if (!t) t = lookup(opt_.base_frame_id, frame, ros::Time(0), 0.0);
      if (!t) {
        ++scans_without_mount_;
        ROS_WARN_THROTTLE(5.0, "pgmcl: no transform %s -> %s yet; scan skipped",
                          opt_.base_frame_id.c_str(), frame.c_str());
        return;
      }
      mount = mounts_.emplace(frame, *t).first;
    }
    scan_.stamp = msg->header.stamp.toSec();
    scan_.angle_min = msg->angle_min;
    scan_.angle_increment = msg->angle_increment;
    scan_.range_min = msg->range_min;
    scan_.range_max = msg->range_max;
    scan_.ranges = msg->ranges;
    const ScanResult r = core_.process_scan(scan_, mount->second, from_msg(odom_T_base));
    if (r.rejected) ROS_WARN_THROTTLE(5.0, "pgmcl: scan refused: %s", r.error.c_str());
    if (r.transform_ready && opt_.tf_broadcast) publish_transform();
    if (r.pose_ready) {
      publish_pose();
      publish_cloud(false);
      publish_diagnostics(msg->header.stamp);
      pose_params_.store(core_.pose_to_store(ros::Time::now().toSec()));
    }
  }

  void publish_transform() {
    const std::optional<TransformOut> t = core_.map_to_odom();
    if (!t) return;
    geometry_msgs::TransformStamped tf;
    tf.header.stamp = ros::Time(t->stamp);
    tf.header.frame_id = opt_.global_frame_id;
    tf.child_frame_id = opt_.odom_frame_id;
    tf.transform.translation.x = t->map_T_odom.x;
    tf.transform.translation.y = t->map_T_odom.y;
    tf.transform.rotation = yaw_quaternion(t->map_T_odom.theta);
    broadcaster_.sendTransform(tf);
  }

  void publish_pose() {
    const PoseOut p = core_.pose();
    geometry_msgs::PoseWithCovarianceStamped msg;
    msg.header.stamp = ros::Time(p.stamp);
    msg.header.frame_id = opt_.global_frame_id;
    msg.pose.pose = to_pose(p.pose);
    for (std::size_t i = 0; i < 36; ++i) msg.pose.covariance[i] = p.covariance[i];
    pose_pub_.publish(msg);
  }

  void publish_cloud(bool now) {
    const ros::Time t = ros::Time::now();
    if (!now && opt_.gui_publish_rate > 0.0 && !last_cloud_.isZero() && t >= last_cloud_ &&
        (t - last_cloud_).toSec() < 1.0 / opt_.gui_publish_rate)
      return;
    last_cloud_ = t;
    core_.particles(cloud_);
    geometry_msgs::PoseArray msg;
    msg.header.stamp = t;
    msg.header.frame_id = opt_.global_frame_id;
    msg.poses.reserve(cloud_.size());
    for (const Particle& p : cloud_) msg.poses.push_back(to_pose(p.pose));
    cloud_pub_.publish(msg);
  }

  void publish_diagnostics(const ros::Time& stamp) {
    const DiagnosticsOut d = core_.diagnostics();
    diagnostic_msgs::DiagnosticArray arr;
    arr.header.stamp = stamp;
    diagnostic_msgs::DiagnosticStatus s;
    s.name = ros::this_node::getName() + ": localisation";
    s.level =
        d.ok ? diagnostic_msgs::DiagnosticStatus::OK : diagnostic_msgs::DiagnosticStatus::WARN;
    s.message = d.message;
    const auto add = [&s](const std::string& key, const std::string& value) {
      diagnostic_msgs::KeyValue kv;
      kv.key = key;
      kv.value = value;
      s.values.push_back(kv);
    };
    for (const auto& [k, v] : d.values) add(k, v);
    add("dropped without odometry", std::to_string(waiting_scans_.dropped()));
    add("skipped without laser mount", std::to_string(scans_without_mount_));
    arr.status.push_back(s);
    diag_pub_.publish(arr);
  }

  void on_initial_pose(const geometry_msgs::PoseWithCovarianceStampedConstPtr& msg) {
    if (!core_.has_map()) {
      ROS_WARN("pgmcl: initial pose ignored: no map yet");
      return;
    }
    const std::string frame = strip_slash(msg->header.frame_id);
    if (frame != opt_.global_frame_id) {
      ROS_WARN("pgmcl: initial pose ignored: frame '%s', expected the global frame '%s'",
               frame.c_str(), opt_.global_frame_id.c_str());
      return;
    }
    // The odometry at the pose's stamp lets the adapter move it to the filter's time.
    std::optional<Rigid> odom;
    if (!msg->header.stamp.isZero()) {
      odom = lookup(opt_.odom_frame_id, opt_.base_frame_id, msg->header.stamp, 0.5);
      if (!odom)
        ROS_WARN("pgmcl: no odometry at the initial pose's stamp; taking it as the pose now");
    }
    std::array<double, 36> cov{};
    for (std::size_t i = 0; i < 36; ++i) cov[i] = msg->pose.covariance[i];
    try {
      core_.set_initial_pose(from_msg(msg->pose.pose), cov, odom);
    } catch (const std::exception& e) {
      ROS_WARN("pgmcl: initial pose refused: %s", e.what());
      return;
    }
    ROS_INFO("pgmcl: initial pose (%.3f, %.3f)", msg->pose.pose.position.x,
             msg->pose.pose.position.y);
    publish_cloud(true);
  }

  bool on_global(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
    if (!core_.has_map()) return false;
    core_.global_localize();
    ROS_INFO("pgmcl: global localisation");
    publish_cloud(true);
    return true;
  }

  bool on_nomotion(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
    if (!core_.has_map()) return false;
    core_.request_nomotion_update();
    return true;
  }

  ros::NodeHandle nh_, pnh_;
  NodeCore core_;
  NodeOptions opt_;
  tf2_ros::Buffer buffer_;
  tf2_ros::TransformListener listener_;
  tf2_ros::TransformBroadcaster broadcaster_;
  WaitingScans waiting_scans_;
  ros::Subscriber scan_sub_, map_sub_, initial_sub_;
  ros::Publisher pose_pub_, cloud_pub_, diag_pub_;
  ros::ServiceServer global_srv_, nomotion_srv_;
  PoseParamWriter pose_params_;
  std::map<std::string, Rigid> mounts_;  // base_T_laser per scan frame
  std::size_t scans_without_mount_ = 0;
  Scan scan_;
  std::vector<Particle> cloud_;
  ros::Time last_cloud_;
};

}  // namespace
}  // namespace pgmcl::ros1

int main(int argc, char** argv) {
  ros::init(argc, argv, "pgmcl_node");
  // Held outside the try: when the last NodeHandle goes, ROS (and its logging) shuts down,
  // and the error below would not be printed.
  const ros::NodeHandle nh, pnh("~");
  try {
    pgmcl::ros1::PgmclNode node(nh, pnh);
    ros::spin();
  } catch (const std::exception& e) {
    ROS_FATAL("pgmcl: %s", e.what());
    return 1;
  }
  return 0;
}
