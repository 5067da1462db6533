// The simulated set-ups of Dekan et al.'s experiments, built from the simulator's own
// beam model (render_beam), so the estimators in calibration.cpp are tested end to end.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "pgmcl/sims/calibration.hpp"

namespace pgmcl::sims {

namespace {

// A small free grid around the sensor: the surfaces are analytic boxes (exactly flat, exact
// normals), and beams leave the grid after a few cells.
constexpr double kGridSize = 1.0;  // metres
constexpr float kSensor = 0.5F;    // sensor at the grid centre (map-local)
constexpr double kThickness = 0.05;
// The edge object is a 1 mm sheet: beams passing just beside its front edge travel
// obliquely to it (by their angle to the edge direction) and would otherwise clip its side
// face within the thickness, moving the effective edge outwards by thickness * tan(angle).
constexpr double kSheet = 0.001;

maps::OccupancyGrid free_grid() {
  constexpr int kCells = 20;
  return {kCells, kCells, kGridSize / kCells, {}, maps::kFree};
}

/// A box whose face, perpendicular to direction `a`, spans lateral offsets [lat0, lat1]
/// (along the left normal of `a`) at `depth` metres from the sensor.
BoxShape face_box(double a, double depth, double lat0, double lat1, std::uint8_t material,
                  double thickness = kThickness) {
  const double ux = std::cos(a), uy = std::sin(a), nx = -uy, ny = ux;
  const double along = depth + 0.5 * thickness, lat = 0.5 * (lat0 + lat1);
  return {static_cast<float>(kSensor + along * ux + lat * nx),
          static_cast<float>(kSensor + along * uy + lat * ny),
          static_cast<float>(ux),
          static_cast<float>(uy),
          static_cast<float>(0.5 * thickness),
          static_cast<float>(0.5 * (lat1 - lat0)),
          material};
}

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

}  // namespace

std::vector<std::vector<double>> simulate_flat_surface(const FlatSurfaceExperiment& x) {
  require(x.incidence >= 0.0 && x.incidence < std::numbers::pi / 2,
          "FlatSurfaceExperiment.incidence must lie in [0, pi/2) rad");
  require(x.distance > 0.0 && x.distance <= 25.0, "FlatSurfaceExperiment.distance: (0, 25] m");
  require(x.experiments >= 1 && x.readings >= 1,
          "FlatSurfaceExperiment: experiments and readings must be >= 1");
  x.noise.validate();
  const auto grid = free_grid();
  const RayCaster caster(grid);
  SurfaceLayout layout;
  layout.materials = x.materials;
  layout.default_material = x.materials.empty() ? std::string() : x.materials.front().name;
  const SurfaceField field(layout, grid);
  Scene scene(caster, field);
  // The beam runs along +x; the surface normal is tilted by the incidence angle.
  const std::uint8_t m = field.index_of(x.material, "FlatSurfaceExperiment.material");
  const double normal = std::numbers::pi - x.incidence;  // outward normal direction
  const double inward = normal + std::numbers::pi;
  // Build the face around the point (distance, 0) relative to the sensor.
  BoxShape wall = face_box(inward, 0.0, -1.0, 1.0, m);
  wall.cx += static_cast<float>(x.distance);
  scene.add(wall);

  const RangeLimits limits{0.01F, 30.0F};
  std::vector<std::vector<double>> out(static_cast<std::size_t>(x.experiments));
  for (int e = 0; e < x.experiments; ++e) {
    Rng rng = Rng::for_block(x.seed, static_cast<std::uint64_t>(e), 3);
    auto& v = out[static_cast<std::size_t>(e)];
    v.reserve(static_cast<std::size_t>(x.readings));
    for (int i = 0; i < x.readings; ++i) {
      v.push_back(render_beam(scene, kSensor, kSensor, 1.0F, 0.0F, limits, x.noise, rng));
    }
  }
  return out;
}

EdgeShiftData simulate_edge_shift(const EdgeShiftExperiment& x) {
  require(x.distance > 0.0 && x.distance <= 25.0, "EdgeShiftExperiment.distance: (0, 25] m");
  require(x.edge_fraction >= 0.0 && x.edge_fraction < 1.0,
          "EdgeShiftExperiment.edge_fraction must lie in [0, 1)");
  require(x.background_gap > 0.0 && x.distance + x.background_gap < x.sensor.range_max,
          "EdgeShiftExperiment.background_gap must be > 0 and the background within range");
  require(x.runs >= 1 && x.scans >= 2, "EdgeShiftExperiment: runs >= 1 and scans >= 2");
  x.sensor.validate();
  x.noise.validate();
  const double step = x.sensor.angle_increment;
  const double sigma_beams =
      x.noise.across_beam ? x.noise.sigma_y / (x.distance * std::sin(step)) : 0.0;
  const int k = x.sensor.beam_count / 2;
  const int half = static_cast<int>(std::ceil(8.0 * sigma_beams)) + 4;
  require(k - half >= 0 && k + half < x.sensor.beam_count,
          "EdgeShiftExperiment: the sensor has too few beams for the edge window");

  const auto grid = free_grid();
  const RayCaster caster(grid);
  const SurfaceField field(SurfaceLayout{}, grid);
  Scene scene(caster, field);
  // Sensor facing +x: beam i at angle_min + i * step. The edge direction lies
  // edge_fraction steps past beam k; the object covers the lower angles (lateral offsets
  // below 0 along the edge direction's left normal).
  const double edge_angle = x.sensor.beam_angle(k) + x.edge_fraction * step;
  const double reach = (half + 2) * step;
  scene.add(face_box(edge_angle, x.distance, -(reach * x.distance + 0.1), 0.0, 0, kSheet));
  const double far = x.distance + x.background_gap;
  scene.add(face_box(edge_angle, far, -(reach * far + 0.5), reach * far + 0.5, 0));

  EdgeShiftData data;
  data.window = static_cast<std::size_t>(2 * half + 1);
  data.edge = half + x.edge_fraction;
  data.split_range = static_cast<float>(x.distance + 0.5 * x.background_gap);
  const RangeLimits limits{static_cast<float>(x.sensor.range_min),
                           static_cast<float>(x.sensor.range_max)};
  std::vector<float> ranges(data.window);
  data.boundaries.assign(static_cast<std::size_t>(x.runs), {});
  for (int r = 0; r < x.runs; ++r) {
    auto& run = data.boundaries[static_cast<std::size_t>(r)];
    run.reserve(static_cast<std::size_t>(x.scans));
    for (int s = 0; s < x.scans; ++s) {
      Rng rng = Rng::for_block(x.seed, static_cast<std::uint64_t>(r) * x.scans + s, 4);
      for (std::size_t w = 0; w < data.window; ++w) {
        const double a = x.sensor.beam_angle(k - half + static_cast<int>(w));
        ranges[w] = render_beam(scene, kSensor, kSensor, static_cast<float>(std::cos(a)),
                                static_cast<float>(std::sin(a)), limits, x.noise, rng);
      }
      run.push_back(boundary_beam(ranges, 0, data.split_range));
    }
  }
  return data;
}

}  // namespace pgmcl::sims
