/// pgmcl convert: a CARMEN log as a ROS 1 bag (/scan, /tf, /tf_static, /odom), or a bag as
/// a CARMEN log. The direction follows the file names: one side must end in ".bag". The
/// output is written beside its target and renamed into place at the end (OutputFiles).

#include <cstdio>
#include <memory>
#include <string>

#include "app_util.hpp"
#include "bag_input.hpp"
#include "commands.hpp"
#include "output_files.hpp"
#include "pgmcl/io/carmen_writer.hpp"
#include "pgmcl/io/values.hpp"
#ifdef PGMCL_HAVE_ROS
#include "pgmcl/rosbag_io/rosbag_io.hpp"
#endif

namespace pgmcl::app {
namespace {

struct ConvertOptions {
  std::string in;
  std::string out;
  BagInput bag;
  std::string laser_frame = "laser";
  double time_offset = 0.0;
  bool strict = false;
};

int run_convert(const ConvertOptions& o) {
#ifdef PGMCL_HAVE_ROS
  const bool bag_in = is_bag_path(o.in), bag_out = is_bag_path(o.out);
  const bool to_bag = !bag_in && bag_out && io::is_carmen_path(o.in);
  const bool to_log = bag_in && !bag_out && io::is_carmen_path(o.out);
  if (!to_bag && !to_log)
    throw io::UsageError(
        "convert: one of --log and --out must be a ROS bag (.bag), the other a "
        "CARMEN log (.log or .clf, optionally .gz)");
  OutputFiles files;
  files.input(o.in, "--log");
  const std::string out_tmp = files.add(o.out, "--out");
  if (to_bag) {
    const io::CarmenLog log = read_log(o.in, {}, o.strict);
    rosbag_io::BagWriteOptions w;
    w.scan_topic = o.bag.scan_topic;
    w.odom_topic = o.bag.odom_topic.empty() ? "/odom" : o.bag.odom_topic;
    w.odom_frame = o.bag.odom_frame;
    w.base_frame = o.bag.base_frame;
    w.laser_frame = o.laser_frame;
    w.time_offset = o.time_offset;
    const rosbag_io::BagWriteReport r = rosbag_io::write_bag(log, out_tmp, w);
    files.commit();
    std::printf("convert: wrote %zu scans to %s (%s, /tf %s -> %s, /tf_static %s -> %s, %s)",
                r.scans, o.out.c_str(), w.scan_topic.c_str(), w.odom_frame.c_str(),
                w.base_frame.c_str(), w.base_frame.c_str(), w.laser_frame.c_str(),
                w.odom_topic.c_str());
    if (r.without_odometry > 0) std::printf("; left out %zu without odometry", r.without_odometry);
    if (r.out_of_order > 0)
      std::printf("; left out %zu stamped before the previous scan", r.out_of_order);
    std::printf("\n");
    return 0;
  }
  const io::CarmenLog log = read_bag_input(o.in, o.bag, "convert");
  io::write_carmen(out_tmp, log);
  files.commit();
  std::printf("convert: wrote %zu scans and %zu odometry poses to %s\n", log.scans.size(),
              log.odometry.size(), o.out.c_str());
  return 0;
#else
  (void)o;
  throw_without_ros("convert");
#endif
}

void add_convert_options(CLI::App& sub, ConvertOptions& o) {
  sub.description("Write a CARMEN log as a ROS 1 bag (/scan, /tf, /tf_static, /odom), or back");
  sub.add_option("--log", o.in, "Input: a CARMEN log (.log, .clf, optionally .gz) or a .bag")
      ->required()
      ->check(CLI::ExistingFile);
  sub.add_option("--out", o.out, "Output: a .bag, or a CARMEN log for a bag input")->required();
  add_bag_input_options(sub, o.bag, nullptr);
  sub.add_option("--laser-frame", o.laser_frame, "Laser frame (written bags)")
      ->capture_default_str();
  sub.add_option("--time-offset", o.time_offset,
                 "Seconds added to every stamp of a written bag (ROS time must be > 0)");
  add_strict_flag(sub, o.strict);
}

}  // namespace

Command add_convert_command(CLI::App& app) {
  return make_command<ConvertOptions>(app, "convert", add_convert_options, run_convert);
}

}  // namespace pgmcl::app
