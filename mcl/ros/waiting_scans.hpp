#pragma once
// Scans waiting for the odometry at their stamps (ROS side, C++17). This replaces
// tf2_ros::MessageFilter: in Debian's tf2_ros 0.7.6 the filter loses a scan whose transform
// arrives on the listener's thread while the scan is being queued (ros/geometry2#538): it
// then waits until a hundred newer scans push it out, never processed.

#include <geometry_msgs/TransformStamped.h>
#include <ros/ros.h>
#include <sensor_msgs/LaserScan.h>
#include <tf2/exceptions.h>
#include <tf2_ros/buffer.h>

#include <cstddef>
#include <deque>
#include <functional>
#include <string>
#include <utility>

namespace pgmcl::ros1 {

/// Holds scans in arrival order until odom_T_base at the stamp is in the buffer, and hands
/// each on with it. Everything runs on the node's callback queue (the retry is a wall timer,
/// so a paused /clock does not hold it up); the buffer is filled on the listener's thread.
class WaitingScans {
 public:
  using Ready = std::function<void(const sensor_msgs::LaserScanConstPtr& scan,
                                   const geometry_msgs::Transform& odom_T_base)>;

  /// `capacity` as amcl's message filter queue: beyond it the oldest waiting scan is dropped.
  WaitingScans(ros::NodeHandle& nh, const tf2_ros::Buffer& buffer, std::string odom_frame,
               std::string base_frame, std::size_t capacity, Ready ready)
      : buffer_(buffer),
        odom_frame_(std::move(odom_frame)),
        base_frame_(std::move(base_frame)),
        capacity_(capacity),
        ready_(std::move(ready)),
        retry_(nh.createWallTimer(
            ros::WallDuration(kRetrySeconds), [this](const ros::WallTimerEvent&) { release(); },
            false, false)) {}

  void add(const sensor_msgs::LaserScanConstPtr& scan) {
    // A scan stamped well before those waiting: the clock went back (a looped bag), and
    // their odometry will not come before the new scans'.
    const double jumped = scan->header.stamp.toSec() + kClockJumpSeconds;
    while (!waiting_.empty() && waiting_.back()->header.stamp.toSec() > jumped) {
      waiting_.pop_back();
      drop("the clock went back; a scan waiting for odometry is dropped");
    }
    if (waiting_.size() >= capacity_) {
      waiting_.pop_front();
      drop("more than " + std::to_string(capacity_) +
           " scans wait for odometry; the oldest is dropped");
    }
    waiting_.push_back(scan);
    release();
  }

  WaitingScans(const WaitingScans&) = delete;  // the timer calls back into this object
  WaitingScans& operator=(const WaitingScans&) = delete;

  /// Scans that never got their odometry (dropped from a full queue, older than the buffer
  /// holds, or waiting when the clock went back), for the diagnostics.
  [[nodiscard]] std::size_t dropped() const noexcept { return dropped_; }

 private:
  static constexpr double kRetrySeconds = 0.01;
  // Scans of several lasers may arrive a little out of order; a clock that went back
  // differs by more.
  static constexpr double kClockJumpSeconds = 1.0;

  void release() {
    while (!waiting_.empty()) {
      const sensor_msgs::LaserScanConstPtr scan = waiting_.front();
      const ros::Time stamp = scan->header.stamp;
      try {
        const geometry_msgs::TransformStamped odom =
            buffer_.lookupTransform(odom_frame_, base_frame_, stamp);
        waiting_.pop_front();
        ready_(scan, odom.transform);
        continue;
      } catch (const tf2::TransformException&) {
      }
      if (!odometry_after(stamp)) break;  // not there yet: the retry comes back for it
      // Odometry newer than the scan but none at its stamp: older than the buffer holds.
      waiting_.pop_front();
      drop("no odometry " + odom_frame_ + " -> " + base_frame_ +
           " at a scan's stamp (older than the buffer holds); scan dropped");
    }
    if (waiting_.empty())
      retry_.stop();
    else
      retry_.start();
  }

  [[nodiscard]] bool odometry_after(const ros::Time& stamp) const {
    try {
      return buffer_.lookupTransform(odom_frame_, base_frame_, ros::Time(0)).header.stamp > stamp;
    } catch (const tf2::TransformException&) {
      return false;  // the frames are not connected yet
    }
  }

  void drop(const std::string& why) {
    ++dropped_;
    ROS_WARN_THROTTLE(5.0, "pgmcl: %s", why.c_str());
  }

  const tf2_ros::Buffer& buffer_;
  const std::string odom_frame_, base_frame_;
  const std::size_t capacity_;
  Ready ready_;
  ros::WallTimer retry_;
  std::deque<sensor_msgs::LaserScanConstPtr> waiting_;
  std::size_t dropped_ = 0;
};

}  // namespace pgmcl::ros1
