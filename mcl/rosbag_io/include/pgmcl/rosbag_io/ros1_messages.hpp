#pragma once
/// geometry_msgs <-> the bridge's Rigid, for the translation units that include ROS 1
/// headers (C++17; ros1_bridge.hpp says why): the bag reader and writer, and pgmcl_node.

#include <geometry_msgs/Pose.h>
#include <geometry_msgs/Transform.h>

#include "pgmcl/rosbag_io/ros1_bridge.hpp"

namespace pgmcl::ros1 {

inline Rigid from_msg(const geometry_msgs::Transform& t) {
  return {t.translation.x, t.translation.y, t.translation.z, t.rotation.x,
          t.rotation.y,    t.rotation.z,    t.rotation.w};
}

inline Rigid from_msg(const geometry_msgs::Pose& p) {
  return {p.position.x,    p.position.y,    p.position.z,   p.orientation.x,
          p.orientation.y, p.orientation.z, p.orientation.w};
}

inline geometry_msgs::Transform to_transform_msg(const Rigid& r) {
  geometry_msgs::Transform t;
  t.translation.x = r.x;
  t.translation.y = r.y;
  t.translation.z = r.z;
  t.rotation.x = r.qx;
  t.rotation.y = r.qy;
  t.rotation.z = r.qz;
  t.rotation.w = r.qw;
  return t;
}

}  // namespace pgmcl::ros1
