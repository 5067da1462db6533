/// pgmcl perturb-map: a degraded copy of a ROS map, the map side of the robustness
/// benchmark (the scans stay real; the map is wrong in a controlled, seeded way).
///
/// In this order, each optional (map_perturbation.hpp):
///  1. --erase FRACTION,BLOCK_M: sparse structure, the occupied cells of a random FRACTION
///     of the BLOCK_M-sized blocks that hold walls are set free;
///  2. --thicken CELLS: walls dilated by CELLS cells (into known cells only);
///  3. --blur SIGMA_CELLS: a Gaussian blur of the occupancy probability over the known cells.
/// --thicken 1 --blur 1 turns a 1-cell wall into a fuzzy 2-3 cell wall, much like a
/// hand-made map. A result that is still only -1/0/100 is written as a trinary map (.pgm);
/// anything else in `mode: scale` (.png, unknown cells transparent) so the intermediate
/// probabilities survive; cells above occupied_thresh (0.65) still load as obstacles (100).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "app_util.hpp"
#include "cli_errors.hpp"
#include "commands.hpp"
#include "map_perturbation.hpp"
#include "output_files.hpp"
#include "perturb_random.hpp"
#include "pgmcl/io/values.hpp"
#include "pgmcl/map_io/map_io.hpp"

namespace pgmcl::app {
namespace {

namespace fs = std::filesystem;

struct PerturbMapOptions {
  std::string map;
  std::string out;
  std::string blur;
  std::string thicken;
  std::string erase;
  std::uint64_t seed = 1;
  bool quiet = false;
};

struct PerturbMapSettings {
  double blur_sigma = 0.0;  ///< cells; 0: no blur
  int thicken = 0;          ///< cells
  bool erase = false;
  double erase_fraction = 0.0;
  double erase_block = 0.0;  ///< metres
};

PerturbMapSettings parse_settings(const PerturbMapOptions& o) {
  PerturbMapSettings s;
  if (!o.blur.empty()) {
    // The kernel spans 6 sigma; past 100 cells it is a typo and costs minutes and gigabytes.
    s.blur_sigma = parse_checked_list(o.blur, "--blur",
                                      {{.name = "SIGMA_CELLS", .lo = 0.0, .hi = 100.0}}, 1)[0];
  }
  if (!o.thicken.empty()) {
    // More than 1000 cells (50 m at 5 cm) is a typo, not a condition.
    const double c =
        parse_checked_list(o.thicken, "--thicken",
                           {{.name = "CELLS", .lo = 0.0, .hi = 1000.0, .integer = true}}, 1)[0];
    s.thicken = static_cast<int>(c);
  }
  if (!o.erase.empty()) {
    const auto v = parse_checked_list(o.erase, "--erase",
                                      {{.name = "FRACTION", .lo = 0.0, .hi = 1.0},
                                       {.name = "BLOCK_M", .lo = 0.0, .lo_open = true}},
                                      2);
    s.erase = true;
    s.erase_fraction = v[0];
    s.erase_block = v[1];
  }
  return s;
}

bool only_trinary(const maps::OccupancyGrid& g) {
  for (const std::int8_t v : g.cells()) {
    if (v != maps::kUnknown && v != maps::kFree && v != maps::kOccupied) return false;
  }
  return true;
}

int run_perturb_map(const PerturbMapOptions& o) {
  const PerturbMapSettings s = parse_settings(o);
  // The image's name depends on the result (.pgm or .png), so both are registered and the
  // one not written is dropped: no stale image of the other kind stays beside the YAML.
  OutputFiles files;
  files.input(o.map, "--map");
  files.input(map_image_path(o.map), "--map's image");
  const fs::path out_yaml(o.out);
  const std::string yaml_tmp = files.add(o.out, "--out");
  const std::string pgm_path =
      (out_yaml.parent_path() / (out_yaml.stem().string() + ".pgm")).string();
  const std::string png_path =
      (out_yaml.parent_path() / (out_yaml.stem().string() + ".png")).string();
  for (const std::string* image : {&pgm_path, &png_path}) {
    if (same_file(o.out, *image)) {
      throw io::UsageError("--out: the map YAML " + o.out + " and its image " + *image +
                           " would be one file; give the YAML a .yaml name");
    }
  }
  const std::string pgm_tmp = files.add(pgm_path, "--out (its image)");
  const std::string png_tmp = files.add(png_path, "--out (its image)");
  maps::MapLoadReport report;
  maps::OccupancyGrid grid = maps::load_map(o.map, &report);
  for (const auto& w : report.warnings) std::fprintf(stderr, "pgmcl: warning: %s\n", w.c_str());

  std::string summary;
  char buf[256];
  if (s.erase) {
    // A block wider than the map is the whole map (and keeps lround within range).
    const double cells = std::min(s.erase_block / grid.resolution(),
                                  static_cast<double>(std::max(grid.width(), grid.height())));
    const int block = static_cast<int>(std::lround(cells));
    if (block < 1) {
      std::snprintf(buf, sizeof buf, "%g m is less than half a cell (%g m)", s.erase_block,
                    grid.resolution());
      throw io::UsageError("--erase: BLOCK_M " + std::string(buf));
    }
    Rng rng = perturb_rng(o.seed, PerturbStream::kMapErase);
    const EraseResult e = erase_blocks(grid, block, s.erase_fraction, rng);
    std::snprintf(buf, sizeof buf, "erased %zu of %zu wall blocks (%d cells square, %zu cells); ",
                  e.blocks_erased, e.blocks_with_walls, block, e.cells_erased);
    summary += buf;
  }
  if (s.thicken > 0) {
    std::snprintf(buf, sizeof buf, "thickened by %d cell(s) (%zu cells); ", s.thicken,
                  thicken_walls(grid, s.thicken));
    summary += buf;
  }
  if (s.blur_sigma > 0.0) {
    blur_known_cells(grid, s.blur_sigma);
    std::snprintf(buf, sizeof buf, "blurred, sigma %g cells; ", s.blur_sigma);
    summary += buf;
  }

  if (std::none_of(grid.cells().begin(), grid.cells().end(),
                   [&grid](std::int8_t v) { return v >= grid.occupied_threshold(); })) {
    throw std::runtime_error("perturb-map: " + summary +
                             "the result has no occupied cell left, which localize refuses; "
                             "nothing written (erase less)");
  }
  const maps::MapMode mode = only_trinary(grid) ? maps::MapMode::kTrinary : maps::MapMode::kScale;
  const bool scale = mode == maps::MapMode::kScale;
  const std::string image_name = out_yaml.stem().string() + (scale ? ".png" : ".pgm");
  maps::save_map_image(grid, scale ? png_tmp : pgm_tmp, mode);
  files.drop(scale ? pgm_path : png_path);
  write_text_file(yaml_tmp, maps::map_yaml_text(grid, image_name, mode, o.out));
  files.commit();

  if (!o.quiet) {
    // What a map_server user gets: the written map as the loader reads it.
    const maps::OccupancyGrid back = maps::load_map(o.out);
    std::size_t obstacles = 0, between = 0;
    for (const std::int8_t v : back.cells()) {
      obstacles += v == maps::kOccupied ? 1 : 0;
      between += v > maps::kFree && v < maps::kOccupied ? 1 : 0;
    }
    std::printf(
        "perturb-map: %sreloads with %zu obstacle cells (100) and %zu in between; wrote %s "
        "(%s, %s)\n",
        summary.c_str(), obstacles, between, o.out.c_str(), image_name.c_str(),
        maps::to_string(mode));
  }
  return 0;
}

void add_perturb_map_options(CLI::App& sub, PerturbMapOptions& o) {
  sub.description("Make a degraded copy of a map (blurred, thickened or missing walls)");
  add_input_file(sub, "--map", o.map, "Input ROS map YAML", map_file())->required();
  sub.add_option("--out", o.out,
                 "Output map YAML; the image goes next to it (<stem>.pgm, or <stem>.png for "
                 "a scale map)")
      ->required();
  sub.add_option("--blur", o.blur,
                 "Gaussian blur of the occupancy probability over the known cells, sigma in "
                 "cells (written as a mode: scale map)")
      ->type_name("SIGMA_CELLS");
  sub.add_option("--thicken", o.thicken, "Dilate the walls by CELLS cells (before --blur)")
      ->type_name("CELLS");
  sub.add_option("--erase", o.erase,
                 "Tile the map into BLOCK_M x BLOCK_M blocks and free the occupied cells of a "
                 "random FRACTION of the blocks holding walls (before --thicken)")
      ->type_name("FRACTION,BLOCK_M");
  add_seed_option(sub, o.seed, "Random seed (--erase)")->capture_default_str();
  sub.add_flag("--quiet", o.quiet, "No summary line");
}

}  // namespace

Command add_perturb_map_command(CLI::App& app) {
  return make_command<PerturbMapOptions>(app, "perturb-map", add_perturb_map_options,
                                         run_perturb_map);
}

}  // namespace pgmcl::app
