#include "bag_input.hpp"

#include <cstdio>
#include <stdexcept>
#include <string>

#ifdef PGMCL_HAVE_ROS
#include "pgmcl/rosbag_io/rosbag_io.hpp"
#endif

namespace pgmcl::app {

void add_bag_input_options(CLI::App& sub, BagInput& in, CLI::Option* needs) {
  const auto need = [&](CLI::Option* o) { return needs != nullptr ? o->needs(needs) : o; };
  need(sub.add_option("--scan-topic", in.scan_topic, "Bag: sensor_msgs/LaserScan topic")
           ->capture_default_str());
  need(sub.add_option("--odom-topic", in.odom_topic,
                      "Bag: nav_msgs/Odometry topic (read: odometry from /tf unless given)"));
  need(sub.add_option("--odom-frame", in.odom_frame, "Bag: odometry frame")->capture_default_str());
  need(sub.add_option("--base-frame", in.base_frame, "Bag: robot base frame")
           ->capture_default_str());
}

void throw_without_ros(const std::string& what) {
  throw std::runtime_error(what +
                           ": this pgmcl was built without ROS 1 (PGMCL_WITH_ROS=OFF or the ROS "
                           "packages missing): bags need librosbag-storage-dev");
}

bool is_bag_path(const std::string& path) {
  return path.size() > 4 && path.compare(path.size() - 4, 4, ".bag") == 0;
}

io::CarmenLog read_bag_input(const std::string& path, const BagInput& in, const std::string& what,
                             std::vector<std::string>* warnings) {
#ifdef PGMCL_HAVE_ROS
  (void)what;  // only the build without ROS names the command
  rosbag_io::BagReadOptions opt;
  opt.scan_topic = in.scan_topic;
  opt.odom_topic = in.odom_topic;
  opt.odom_frame = in.odom_frame;
  opt.base_frame = in.base_frame;
  rosbag_io::BagReadReport report;
  io::CarmenLog log = rosbag_io::read_bag(path, opt, &report);
  if (report.outside_odometry > 0) {
    const std::string w = path + ": " + std::to_string(report.outside_odometry) +
                          " scan(s) outside the odometry's time span";
    std::fprintf(stderr, "pgmcl: warning: %s\n", w.c_str());
    if (warnings != nullptr) warnings->push_back(w);
  }
  for (const std::string& n : report.notes)
    std::fprintf(stderr, "pgmcl: %s: %s\n", path.c_str(), n.c_str());
  return log;
#else
  (void)path;
  (void)in;
  (void)warnings;
  throw_without_ros(what);
#endif
}

}  // namespace pgmcl::app
