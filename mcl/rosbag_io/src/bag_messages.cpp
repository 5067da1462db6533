// The only translation unit of pgmcl::rosbag_io that includes ROS 1 headers (built as
// C++17, see ros1_bridge.hpp): bag records <-> plain types.
#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/LaserScan.h>
#include <tf2_msgs/TFMessage.h>

#include <algorithm>
#include <boost/make_shared.hpp>
#include <map>
#include <stdexcept>

#include "pgmcl/rosbag_io/ros1_bridge.hpp"
#include "pgmcl/rosbag_io/ros1_messages.hpp"

namespace pgmcl::ros1 {
namespace {

geometry_msgs::TransformStamped stamped(const StampedTransform& t) {
  geometry_msgs::TransformStamped ts;
  ts.header.stamp = ros::Time(t.stamp);
  ts.header.frame_id = t.parent;
  ts.child_frame_id = t.child;
  ts.transform = to_transform_msg(t.transform);
  return ts;
}

void append_transforms(const tf2_msgs::TFMessage& m, std::vector<StampedTransform>& out) {
  for (const geometry_msgs::TransformStamped& t : m.transforms)
    out.push_back(
        {t.header.stamp.toSec(), t.header.frame_id, t.child_frame_id, from_msg(t.transform)});
}

template <class M>
boost::shared_ptr<M> instantiate(const rosbag::MessageInstance& m, const std::string& path) {
  if (m.getDataType() != ros::message_traits::datatype<M>())
    throw std::runtime_error(path + ": topic " + m.getTopic() + " holds " + m.getDataType() +
                             ", expected " + ros::message_traits::datatype<M>());
  return m.instantiate<M>();
}

}  // namespace

BagMessages read_bag_messages(const std::string& path, const std::string& scan_topic,
                              const std::string& odom_topic) {
  BagMessages out;
  try {
    rosbag::Bag bag(path, rosbag::bagmode::Read);
    rosbag::View view(bag);
    std::map<std::string, std::size_t> others;
    for (const rosbag::MessageInstance& m : view) {
      const std::string& topic = m.getTopic();
      if (topic == scan_topic) {
        const auto s = instantiate<sensor_msgs::LaserScan>(m, path);
        out.scans.push_back({s->header.stamp.toSec(), s->header.frame_id, s->angle_min,
                             s->angle_increment, s->range_min, s->range_max, s->ranges});
      } else if (topic == "/tf" || topic == "tf") {
        append_transforms(*instantiate<tf2_msgs::TFMessage>(m, path), out.transforms);
      } else if (topic == "/tf_static" || topic == "tf_static") {
        append_transforms(*instantiate<tf2_msgs::TFMessage>(m, path), out.static_transforms);
      } else if (!odom_topic.empty() && topic == odom_topic) {
        const auto o = instantiate<nav_msgs::Odometry>(m, path);
        out.odometry.push_back({o->header.stamp.toSec(), o->header.frame_id, o->child_frame_id,
                                from_msg(o->pose.pose)});
      } else {
        ++others[topic];
      }
    }
    out.other_topics.assign(others.begin(), others.end());
  } catch (const rosbag::BagException& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
  return out;
}

void write_bag_messages(const std::string& path, const BagMessages& m,
                        const std::string& scan_topic, const std::string& odom_topic) {
  try {
    rosbag::Bag bag(path, rosbag::bagmode::Write);
    bag.setCompression(rosbag::compression::LZ4);
    // rosbag play republishes a topic latched when its connection header says so.
    auto latched = boost::make_shared<ros::M_string>();
    // A connection header given to write() is taken as is: it needs the type fields too.
    (*latched)["latching"] = "1";
    (*latched)["callerid"] = "/pgmcl_convert";
    (*latched)["type"] = ros::message_traits::datatype<tf2_msgs::TFMessage>();
    (*latched)["md5sum"] = ros::message_traits::md5sum<tf2_msgs::TFMessage>();
    (*latched)["message_definition"] = ros::message_traits::definition<tf2_msgs::TFMessage>();
    if (!m.static_transforms.empty()) {  // one message, as a static broadcaster sends
      tf2_msgs::TFMessage msg;
      for (const StampedTransform& t : m.static_transforms) msg.transforms.push_back(stamped(t));
      bag.write("/tf_static", msg.transforms.front().header.stamp, msg, latched);
    }
    const auto write_tf = [&](const StampedTransform& t) {
      tf2_msgs::TFMessage msg;
      msg.transforms.push_back(stamped(t));
      bag.write("/tf", msg.transforms.front().header.stamp, msg);
    };
    const auto write_odom = [&](const OdometryPose& o) {
      nav_msgs::Odometry msg;
      msg.header.stamp = ros::Time(o.stamp);
      msg.header.frame_id = o.frame_id;
      msg.child_frame_id = o.child_frame_id;
      const geometry_msgs::Transform t = to_transform_msg(o.pose);
      msg.pose.pose.position.x = t.translation.x;
      msg.pose.pose.position.y = t.translation.y;
      msg.pose.pose.position.z = t.translation.z;
      msg.pose.pose.orientation = t.rotation;
      bag.write(odom_topic, msg.header.stamp, msg);
    };
    // Everything in time order; at equal stamps transforms and odometry before the scan.
    std::size_t it = 0, io = 0;
    const std::size_t n_odom = odom_topic.empty() ? 0 : m.odometry.size();
    for (const Scan& s : m.scans) {
      for (; it < m.transforms.size() && m.transforms[it].stamp <= s.stamp; ++it)
        write_tf(m.transforms[it]);
      for (; io < n_odom && m.odometry[io].stamp <= s.stamp; ++io) write_odom(m.odometry[io]);
      sensor_msgs::LaserScan msg;
      msg.header.stamp = ros::Time(s.stamp);
      msg.header.frame_id = s.frame_id;
      msg.angle_min = static_cast<float>(s.angle_min);
      msg.angle_increment = static_cast<float>(s.angle_increment);
      const double last = s.ranges.empty() ? 0.0 : static_cast<double>(s.ranges.size() - 1);
      msg.angle_max = static_cast<float>(s.angle_min + s.angle_increment * last);
      msg.range_min = static_cast<float>(s.range_min);
      msg.range_max = static_cast<float>(s.range_max);
      msg.ranges = s.ranges;
      bag.write(scan_topic, msg.header.stamp, msg);
    }
    for (; it < m.transforms.size(); ++it) write_tf(m.transforms[it]);
    for (; io < n_odom; ++io) write_odom(m.odometry[io]);
    bag.close();
  } catch (const rosbag::BagException& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
}

}  // namespace pgmcl::ros1
