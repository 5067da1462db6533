/// pgmcl map: occupancy grid mapping with known poses from a corrected CARMEN log.
/// The sensor pose of each scan is the logged laser pose (FLASER `x y theta`, ROBOTLASER1
/// `laser_pose_*`), which equals the robot pose for logs without a laser offset PARAM.

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "app_util.hpp"
#include "cli_errors.hpp"
#include "commands.hpp"
#include "interrupt.hpp"
#include "output_files.hpp"
#include "pgmcl/io/carmen.hpp"
#include "pgmcl/io/values.hpp"
#include "pgmcl/map_io/map_io.hpp"
#include "pgmcl/maps/occupancy_mapping.hpp"
#include "run_checks.hpp"

namespace pgmcl::app {
namespace {

struct MapOptions {
  std::string log;
  std::string out;
  std::string image;
  double max_range = 0.0;
  maps::OccupancyMappingConfig mapping{};
  bool quiet = false;
  bool strict = false;
};

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

int run_map(const MapOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  char buf[320];
  if (o.mapping.resolution > maps::kMaxResolution) {
    std::snprintf(buf, sizeof buf, "--resolution: must be at most %g m per cell, got %g",
                  maps::kMaxResolution, o.mapping.resolution);
    throw io::UsageError(buf);
  }
  // Every output is known before the log is read: the YAML and its image, which must not be
  // one file (`--out map.pgm` would otherwise write the YAML over its own image).
  namespace fs = std::filesystem;
  const std::string image_name =
      o.image.empty() ? fs::path(o.out).stem().string() + ".pgm" : o.image;
  if (!ends_with(image_name, ".pgm") && !ends_with(image_name, ".pgm.gz") &&
      !ends_with(image_name, ".png")) {
    throw io::UsageError("--image: " + image_name + ": use a .pgm, .pgm.gz or .png name");
  }
  const std::string image_path = fs::path(image_name).is_absolute()
                                     ? image_name
                                     : (fs::path(o.out).parent_path() / image_name).string();
  if (same_file(o.out, image_path)) {
    throw io::UsageError("--out: the map YAML " + o.out + " and its image " + image_path +
                         " would be one file; give the YAML a .yaml name");
  }
  OutputFiles files;
  files.input(o.log, "--log");
  const std::string yaml_tmp = files.add(o.out, "--out");
  const std::string image_tmp = files.add(image_path, o.image.empty() ? "--out" : "--image");

  io::CarmenReadOptions ro;
  ro.front_range_max = o.max_range;
  ro.rear_range_max = o.max_range;
  const io::CarmenLog log = read_log(o.log, ro, o.strict);

  std::vector<maps::RangeScanView> views;
  views.reserve(log.scans.size());
  for (const io::CarmenScan& s : log.scans) {
    if (!s.has_poses) continue;
    maps::RangeScanView v;
    v.sensor_pose = s.laser_pose;
    v.angle_min = s.scan.angle_min;
    v.angle_increment = s.scan.angle_increment;
    v.range_min = s.scan.range_min;
    v.no_return_range = s.scan.range_max;
    v.ranges = s.scan.ranges;
    views.push_back(v);
  }
  if (views.empty()) {
    throw io::UsageError(o.log +
                         ": no laser scans with poses (FLASER, RLASER or ROBOTLASER1) "
                         "to build a map from");
  }
  const maps::MapBounds bounds = maps::compute_map_bounds(views, o.mapping);
  const double w = std::round((bounds.max_x - bounds.min_x) / o.mapping.resolution);
  const double h = std::round((bounds.max_y - bounds.min_y) / o.mapping.resolution);
  if (!(w * h <= static_cast<double>(maps::kMaxCells))) {
    // The mapper holds a float of log-odds per cell, the grid one byte more.
    std::snprintf(buf, sizeof buf,
                  "--resolution %g m: the map of %s would be %.0f x %.0f cells (%.3g GB while "
                  "mapping), more than the %llu cells a map may hold; use a coarser resolution",
                  o.mapping.resolution, o.log.c_str(), w, h, w * h * 5.0 / 1e9,
                  static_cast<unsigned long long>(maps::kMaxCells));
    throw io::UsageError(buf);
  }
  // A map localize refuses must not be written: check it against localize's defaults.
  const LocalizerConfig localize_defaults{};
  if (o.mapping.resolution > coarsest_usable_resolution(localize_defaults)) {
    char cells[240];
    std::snprintf(cells, sizeof cells,
                  "would be %.0f x %.0f cells, too coarse for localize (a beam of "
                  "likelihood.beam.max_range = %g m must span %g cells: at most %g m per "
                  "cell); nothing was written",
                  w, h, localize_defaults.likelihood.beam.max_range, kMinCellsPerBeam,
                  coarsest_usable_resolution(localize_defaults));
    std::snprintf(buf, sizeof buf, "--resolution %g m: the map of ", o.mapping.resolution);
    throw io::UsageError(buf + o.log + " " + cells);
  }
  maps::OccupancyMapper mapper(bounds, o.mapping);
  for (const auto& v : views) {
    check_interrupt();
    mapper.integrate(v);
  }
  const maps::OccupancyGrid grid = mapper.to_grid();

  std::size_t occ = 0, fre = 0;
  for (const auto c : grid.cells()) {
    occ += c == maps::kOccupied;
    fre += c == maps::kFree;
  }
  if (occ == 0) {
    throw std::runtime_error(o.log +
                             ": the map has no occupied cell (every beam read 'no "
                             "return' or was filtered out); localize would refuse it, "
                             "so nothing was written");
  }
  for (const std::string& w : check_map_for_localisation(grid, o.out, localize_defaults)) {
    std::fprintf(stderr, "pgmcl: warning: %s\n", w.c_str());
  }
  maps::save_map_image(grid, image_tmp, maps::MapMode::kTrinary);
  write_text_file(yaml_tmp, maps::map_yaml_text(grid, image_name, maps::MapMode::kTrinary, o.out));
  files.commit();
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!o.quiet) {
    std::printf(
        "map: %zu scans -> %d x %d cells at %.3f m, origin (%.3f, %.3f); "
        "%.1f%% free, %.1f%% occupied; no-return range %.2f m; wrote %s in %s\n",
        views.size(), grid.width(), grid.height(), grid.resolution(), grid.origin().x,
        grid.origin().y, 100.0 * fre / grid.size(), 100.0 * occ / grid.size(),
        views.front().no_return_range, o.out.c_str(), format_seconds(secs).c_str());
  }
  return 0;
}

void add_map_options(CLI::App& sub, MapOptions& o) {
  sub.description("Build an occupancy map from a log with known (corrected) poses");
  add_input_file(sub, "--log", o.log, "Corrected CARMEN log (.gz ok)", log_file())->required();
  sub.add_option("--out", o.out, "Output map YAML (the image is written next to it)")->required();
  sub.add_option("--image", o.image,
                 "Image file name next to the YAML (.pgm, .pgm.gz or .png; default <stem>.pgm)");
  auto& m = o.mapping;
  sub.add_option("--resolution", m.resolution, "Metres per cell (or with a unit: 5cm, 50mm)")
      ->capture_default_str()
      ->transform(length_in("m"))
      ->check(positive())
      ->type_name("M");
  sub.add_option("--margin", m.margin, "Metres of border around the data")
      ->capture_default_str()
      ->check(non_negative());
  sub.add_option("--max-range", o.max_range,
                 "Readings at or beyond this (metres) mean 'no return'; 0 = the log's "
                 "PARAM or its largest reading")
      ->capture_default_str()
      ->check(non_negative());
  sub.add_option("--clear-range", m.no_return_clear_range,
                 "Metres of free space cleared along a 'no return' beam")
      ->capture_default_str()
      ->check(non_negative());
  sub.add_option("--max-hit-range", m.max_hit_range,
                 "Longer returns are treated as 'no return' (metres)")
      ->check(positive());
  add_strict_flag(sub, o.strict);
  sub.add_flag("--quiet", o.quiet, "No summary line");
}

}  // namespace

Command add_map_command(CLI::App& app) {
  return make_command<MapOptions>(app, "map", add_map_options, run_map);
}

}  // namespace pgmcl::app
