#include "run_checks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "pgmcl/io/values.hpp"
#include "pgmcl/map_io/map_io.hpp"
#include "pgmcl/sensor_model/sigma_models.hpp"

namespace pgmcl::app {
namespace {

/// LikelihoodField's stamp limit (maps/src/likelihood_field.cpp, kMaxStampReach): the
/// engine refuses a wider kernel with a message about cells; here it gets its cause.
constexpr double kMaxKernelReachCells = 1000.0;

std::string g(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

/// "x in [a, b] m, y in [c, d] m": the bounding box of the grid in the map frame.
std::string extent_text(const maps::OccupancyGrid& m) {
  double lo_x = INFINITY, hi_x = -INFINITY, lo_y = INFINITY, hi_y = -INFINITY;
  const double w = m.width() * m.resolution(), h = m.height() * m.resolution();
  for (const auto& [cx, cy] : {std::pair{0.0, 0.0}, {w, 0.0}, {0.0, h}, {w, h}}) {
    double gx = 0.0, gy = 0.0;
    m.origin().transform_point(cx, cy, gx, gy);
    lo_x = std::min(lo_x, gx);
    hi_x = std::max(hi_x, gx);
    lo_y = std::min(lo_y, gy);
    hi_y = std::max(hi_y, gy);
  }
  return "x in [" + g(lo_x) + ", " + g(hi_x) + "] m, y in [" + g(lo_y) + ", " + g(hi_y) + "] m";
}

}  // namespace

double coarsest_usable_resolution(const LocalizerConfig& config) {
  return config.likelihood.beam.max_range / kMinCellsPerBeam;
}

std::vector<std::string> check_map_for_localisation(const maps::OccupancyGrid& map,
                                                    const std::string& map_name,
                                                    const LocalizerConfig& config) {
  std::size_t occupied = 0, free = 0;
  for (const std::int8_t v : map.cells()) {
    occupied += v >= map.occupied_threshold() ? 1 : 0;
    free += v >= 0 && v < map.occupied_threshold() ? 1 : 0;
  }
  if (occupied == 0) {
    throw maps::MapError(
        map_name, 0, "image",
        "no occupied cell among its " + std::to_string(map.width()) + " x " +
            std::to_string(map.height()) + " cells (" + std::to_string(free) + " free, " +
            std::to_string(map.size() - free) +
            " unknown): nothing for the scans to match. Check `mode` (raw reads grey levels "
            "0..100 as occupancy, so a trinary image's black walls read as free), `negate` and "
            "`occupied_thresh`");
  }
  const double res = map.resolution();
  const auto& beam = config.likelihood.beam;
  if (res > coarsest_usable_resolution(config)) {
    throw maps::MapError(map_name, 0, "resolution",
                         g(res) + " m per cell: a beam of likelihood.beam.max_range = " +
                             g(beam.max_range) + " m spans fewer than " + g(kMinCellsPerBeam) +
                             " cells, so the scans have nothing to match (wrong resolution?)");
  }
  const double cell = beam.add_discretisation ? res : 0.0;
  const double sigma =
      std::max(sensor_model::effective_sigma(beam.sigma_along, cell, beam.model_mismatch),
               sensor_model::effective_sigma(beam.sigma_across, cell, beam.model_mismatch));
  const double reach_sigmas = config.likelihood.table.reach_sigmas;
  const double reach = reach_sigmas * sigma / res;
  if (!(reach <= kMaxKernelReachCells)) {
    // Name the term of sigma² = sigma_x² + model_mismatch² + res²/12 that dominates.
    std::string culprit = "likelihood.beam.sigma_along = " + g(beam.sigma_along) + " m";
    double largest = beam.sigma_along;
    if (beam.sigma_across > largest) {
      largest = beam.sigma_across;
      culprit = "likelihood.beam.sigma_across = " + g(beam.sigma_across) + " m";
    }
    if (beam.model_mismatch > largest) {
      culprit = "likelihood.beam.model_mismatch = " + g(beam.model_mismatch) + " m";
    }
    throw io::UsageError(
        "the likelihood kernel would reach " + g(std::ceil(reach)) + " cells (limit " +
        g(kMaxKernelReachCells) + "): likelihood.table.reach_sigmas = " + g(reach_sigmas) +
        " times an effective sigma of " + g(sigma) + " m, mostly " + culprit + ", on " + map_name +
        " at " + g(res) + " m per cell; lower " + culprit.substr(0, culprit.find(' ')) +
        " or reach_sigmas, or use a coarser map");
  }
  std::vector<std::string> warnings;
  if (occupied > free) {
    warnings.push_back(map_name + ": more occupied (" + std::to_string(occupied) + ") than free (" +
                       std::to_string(free) +
                       ") cells; a map of a building is mostly free space: is `negate` right?");
  }
  return warnings;
}

std::string heading_warning(double theta, const std::string& what) {
  if (!(std::abs(theta) > 2.0 * std::numbers::pi)) return "";
  return what + ": heading " + g(theta) +
         " rad is beyond ±2π; headings are radians (did you mean " + g(theta) +
         " degrees = " + g(theta * std::numbers::pi / 180.0) + " rad?)";
}

std::vector<std::string> check_initial_belief(const replay::InitialBelief& b,
                                              const maps::OccupancyGrid& map,
                                              const std::string& what) {
  std::vector<std::string> warnings;
  if (b.kind != replay::InitialBelief::Kind::kPose &&
      b.kind != replay::InitialBelief::Kind::kTruth) {
    return warnings;
  }
  const double span = std::hypot(map.width(), map.height()) * map.resolution();
  const double sy = b.sigma_y >= 0.0 ? b.sigma_y : b.sigma_xy;
  for (const auto& [name, v] : {std::pair{"SX", b.sigma_xy}, std::pair{"SY", sy}}) {
    if (!(v > 0.0 && v <= span)) {
      throw io::UsageError(what + ": " + name + " = " + g(v) +
                           " m is wider than the map (diagonal " + g(span) +
                           " m); a start that uncertain is global localisation (--global / "
                           "init: global)");
    }
  }
  if (!(b.sigma_theta > 0.0 && b.sigma_theta <= 2.0 * std::numbers::pi)) {
    throw io::UsageError(what + ": STH = " + g(b.sigma_theta) +
                         " rad must be in (0, 2π]; a wider heading spread is a uniform heading");
  }
  if (b.kind != replay::InitialBelief::Kind::kPose) return warnings;
  const Pose2& p = b.pose;
  double col = 0.0, row = 0.0;
  map.global_to_cell(p.x, p.y, col, row);
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !(col >= 0.0 && col < map.width()) ||
      !(row >= 0.0 && row < map.height())) {
    throw io::UsageError(what + ": the start (" + g(p.x) + ", " + g(p.y) +
                         ") lies outside the map, which covers " + extent_text(map));
  }
  const std::int8_t v = map.at(static_cast<int>(col), static_cast<int>(row));
  if (v >= map.occupied_threshold()) {
    warnings.push_back(what + ": the start (" + g(p.x) + ", " + g(p.y) +
                       ") is in an occupied cell of the map: a robot cannot stand in a wall "
                       "(wrong frame or swapped x, y?)");
  } else if (v < 0) {
    warnings.push_back(what + ": the start (" + g(p.x) + ", " + g(p.y) +
                       ") is in an unknown cell of the map");
  }
  return warnings;
}

}  // namespace pgmcl::app
