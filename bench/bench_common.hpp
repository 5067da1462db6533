#pragma once
/// Shared fixtures of the micro-benchmarks: synthetic office maps, scans cast on them, and
/// particle clouds. Header-only because every bench/*_bench.cpp is its own executable.
///
/// The synthetic map is an office floor: a free interior inside a 1.5 m unknown margin,
/// a 10 cm outer wall, a square grid of rooms separated by 10 cm walls with one door per
/// wall segment, and a few boxes of clutter per room. Everything is deterministic for a
/// seed, so every run of a benchmark sees the same map, scan and particles.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <map>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "pgmcl/common/laser_scan.hpp"
#include "pgmcl/common/random.hpp"
#include "pgmcl/common/se2.hpp"
#include "pgmcl/maps/likelihood_field.hpp"
#include "pgmcl/maps/occupancy_grid.hpp"
#include "pgmcl/mcl/localizer_config.hpp"
#include "pgmcl/mcl/particles.hpp"
#include "pgmcl/sims/ray_caster.hpp"

namespace pgmcl::bench {

/// Threads the OpenMP runtime would use by default (OMP_NUM_THREADS), 1 without OpenMP.
inline int omp_threads() noexcept {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

struct OfficeSpec {
  double width_m = 50.0;     ///< metres, whole grid including the margin
  double height_m = 50.0;    ///< metres
  double resolution = 0.05;  ///< metres per cell
  double margin = 1.5;       ///< metres of unknown cells around the building
  double room = 8.0;         ///< metres, room pitch (shrunk to fit at least 2x2 rooms)
  double wall = 0.10;        ///< metres, wall thickness
  double door = 1.2;         ///< metres, door width
  int clutter_per_room = 6;  ///< boxes of 0.2..0.8 m per room
  std::uint64_t seed = 7;
};

/// Room pitch actually used for a spec.
inline double room_pitch(const OfficeSpec& s) {
  const double inner = std::min(s.width_m, s.height_m) - 2.0 * s.margin;
  return std::min(s.room, inner / 2.0);
}

inline maps::OccupancyGrid make_office(const OfficeSpec& s) {
  const int w = static_cast<int>(std::lround(s.width_m / s.resolution));
  const int h = static_cast<int>(std::lround(s.height_m / s.resolution));
  maps::OccupancyGrid g(w, h, s.resolution, {}, maps::kUnknown);
  const auto cell = [&](double m) { return static_cast<int>(std::floor(m / s.resolution)); };
  const int m0 = cell(s.margin);
  const int cx1 = w - m0, cy1 = h - m0;  // exclusive interior bounds
  for (int r = m0; r < cy1; ++r)
    for (int c = m0; c < cx1; ++c) g.set(c, r, maps::kFree);
  const auto fill = [&](int c0, int r0, int c1, int r1, std::int8_t v) {
    c0 = std::max(c0, 0);
    r0 = std::max(r0, 0);
    c1 = std::min(c1, w);
    r1 = std::min(r1, h);
    for (int r = r0; r < r1; ++r)
      for (int c = c0; c < c1; ++c) g.set(c, r, v);
  };
  const int t = std::max(1, cell(s.wall + 1e-9));
  // Outer wall.
  fill(m0, m0, cx1, m0 + t, maps::kOccupied);
  fill(m0, cy1 - t, cx1, cy1, maps::kOccupied);
  fill(m0, m0, m0 + t, cy1, maps::kOccupied);
  fill(cx1 - t, m0, cx1, cy1, maps::kOccupied);

  Rng rng(s.seed);
  const double pitch = room_pitch(s);
  const int pc = std::max(2, cell(pitch));
  const int door = std::max(2, cell(s.door));
  // Interior walls at every multiple of the pitch, one door per segment between crossings.
  for (int x = m0 + pc; x < cx1 - pc / 2; x += pc) {
    for (int y = m0; y < cy1; y += pc) {
      const int y1 = std::min(y + pc, cy1);
      fill(x, y, x + t, y1, maps::kOccupied);
      if (y1 - y > door + 2 * t) {
        const int d =
            y + t + static_cast<int>(rng.below(static_cast<std::uint64_t>(y1 - y - door - 2 * t)));
        fill(x, d, x + t, d + door, maps::kFree);
      }
    }
  }
  for (int y = m0 + pc; y < cy1 - pc / 2; y += pc) {
    for (int x = m0; x < cx1; x += pc) {
      const int x1 = std::min(x + pc, cx1);
      fill(x, y, x1, y + t, maps::kOccupied);
      if (x1 - x > door + 2 * t) {
        const int d =
            x + t + static_cast<int>(rng.below(static_cast<std::uint64_t>(x1 - x - door - 2 * t)));
        fill(d, y, d + door, y + t, maps::kFree);
      }
    }
  }
  // Clutter: boxes in each room, at least 1 m from the walls and from the room centre
  // (the centre stays free for the robot poses the benchmarks use).
  const int keep = cell(1.0);
  for (int ry = m0; ry + pc <= cy1; ry += pc) {
    for (int rx = m0; rx + pc <= cx1; rx += pc) {
      const int span = pc - 2 * keep;
      if (span <= cell(0.8) + 1) continue;
      for (int k = 0; k < s.clutter_per_room; ++k) {
        const int bw = cell(0.2 + 0.6 * rng.uniform()) + 1;
        const int bh = cell(0.2 + 0.6 * rng.uniform()) + 1;
        const int c0 =
            rx + keep + static_cast<int>(rng.below(static_cast<std::uint64_t>(span - bw)));
        const int r0 =
            ry + keep + static_cast<int>(rng.below(static_cast<std::uint64_t>(span - bh)));
        const int mid_c = rx + pc / 2, mid_r = ry + pc / 2;
        if (std::abs(c0 + bw / 2 - mid_c) < keep && std::abs(r0 + bh / 2 - mid_r) < keep) continue;
        fill(c0, r0, c0 + bw, r0 + bh, maps::kOccupied);
      }
    }
  }
  return g;
}

/// The per-process world of a benchmark binary for one map size, built on first use and
/// shared by every benchmark after it: `World` has an `OfficeSpec spec`, which is set to a
/// size_m x size_m floor before `build(World&)` fills in the rest. One cache per World type
/// and `build` (each call site's lambda is its own type).
template <class World, class Build>
World& world_of_size(int size_m, Build build) {
  static std::map<int, std::unique_ptr<World>> worlds;
  std::unique_ptr<World>& w = worlds[size_m];
  if (!w) {
    w = std::make_unique<World>();
    w->spec.width_m = w->spec.height_m = size_m;
    build(*w);
  }
  return *w;
}

/// The likelihood table of `kind` for `grid` with the engine's default beam model and
/// table options, except that oriented tables stay oriented even for near-isotropic
/// kernels (isotropy_tolerance 0), so each kind is measured as itself.
inline std::shared_ptr<const maps::LikelihoodField> make_table(const maps::OccupancyGrid& grid,
                                                               maps::TableKind kind) {
  const LocalizerConfig defaults;
  maps::LikelihoodFieldOptions opt = defaults.likelihood.table;
  opt.kind = kind;
  opt.isotropy_tolerance = 0.0;
  return std::make_shared<const maps::LikelihoodField>(grid, defaults.likelihood.beam, opt);
}

/// Centre of room (i, j) (map-local metres); free by construction.
inline Pose2 room_centre(const OfficeSpec& s, int i, int j, double theta = 0.3) {
  const double pitch =
      std::max(2.0 * s.resolution, std::floor(room_pitch(s) / s.resolution) * s.resolution);
  return {s.margin + (i + 0.5) * pitch, s.margin + (j + 0.5) * pitch, theta};
}

/// A 270 deg scan of `beams` readings cast from `pose` (map-local) on `caster`, with
/// Gaussian range noise of `noise_sigma` metres on the returns (misses stay at range_max).
inline LaserScan cast_scan(const sims::RayCaster& caster, const Pose2& pose, int beams,
                           double noise_sigma = 0.01, std::uint64_t seed = 3) {
  LaserScan scan;
  scan.angle_min = -0.75 * std::numbers::pi;
  scan.angle_increment = beams > 1 ? 1.5 * std::numbers::pi / (beams - 1) : 0.0;
  scan.range_min = 0.1;
  scan.range_max = 30.0;
  scan.ranges.resize(static_cast<std::size_t>(beams));
  sims::BeamFan fan{scan.angle_min, scan.angle_increment, beams, scan.range_max};
  caster.cast_scan(pose, fan, scan.ranges);
  Rng rng(seed);
  for (float& r : scan.ranges) {
    if (r < static_cast<float>(scan.range_max))
      r = std::max(0.0f, r + static_cast<float>(rng.normal(noise_sigma)));
  }
  return scan;
}

/// A robot driving a small loop in one room: `n` poses on a circle of radius 0.45 m around
/// `centre` (map-local), heading along it, and the 1081-beam scan cast at each (1 cm noise).
inline void circle_drive(const sims::RayCaster& caster, const Pose2& centre, int n,
                         std::vector<Pose2>& poses, std::vector<LaserScan>& scans) {
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * std::numbers::pi * k / n;
    const Pose2 p{centre.x + 0.45 * std::cos(a), centre.y + 0.45 * std::sin(a),
                  wrap_angle(a + std::numbers::pi / 2)};
    poses.push_back(p);
    scans.push_back(cast_scan(caster, p, 1081, 0.01, 100 + static_cast<std::uint64_t>(k)));
  }
}

/// n particles around `centre` (map-local): N(0, sigma_xy^2) in x and y, N(0, sigma_theta^2)
/// in heading: the cloud of a filter that is tracking.
inline ParticleSet tracking_cloud(const Pose2& centre, std::size_t n, double sigma_xy = 0.25,
                                  double sigma_theta = 0.1, std::uint64_t seed = 11) {
  ParticleSet p;
  p.resize(n);
  Rng rng(seed);
  for (std::size_t i = 0; i < n; ++i) {
    p.x[i] = static_cast<float>(centre.x + rng.normal(sigma_xy));
    p.y[i] = static_cast<float>(centre.y + rng.normal(sigma_xy));
    p.theta[i] = wrap_angle(static_cast<float>(centre.theta + rng.normal(sigma_theta)));
  }
  p.set_uniform_weights();
  return p;
}

/// n particles uniform over the free cells, uniform heading: global localisation.
inline ParticleSet global_cloud(const maps::OccupancyGrid& g, std::size_t n,
                                std::uint64_t seed = 13) {
  std::vector<std::uint32_t> free;
  for (int r = 0; r < g.height(); ++r)
    for (int c = 0; c < g.width(); ++c)
      if (g.free(c, r)) free.push_back(static_cast<std::uint32_t>(g.index(c, r)));
  ParticleSet p;
  p.resize(n);
  Rng rng(seed);
  const auto w = static_cast<std::uint32_t>(g.width());
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t k = free[rng.below(free.size())];
    p.x[i] = static_cast<float>(((k % w) + rng.uniform()) * g.resolution());
    p.y[i] = static_cast<float>(((k / w) + rng.uniform()) * g.resolution());
    p.theta[i] = static_cast<float>(rng.uniform(-std::numbers::pi, std::numbers::pi));
  }
  p.set_uniform_weights();
  return p;
}

/// Splits "a,b,c" into its parts.
inline std::vector<std::string> split_list(const std::string& s) {
  std::vector<std::string> out;
  std::size_t b = 0;
  while (b <= s.size()) {
    const std::size_t e = s.find(',', b);
    const std::string part = s.substr(b, e == std::string::npos ? std::string::npos : e - b);
    if (!part.empty()) out.push_back(part);
    if (e == std::string::npos) break;
    b = e + 1;
  }
  return out;
}

/// Least-squares slope of log(y) against log(x): the scaling exponent.
inline double loglog_slope(const std::vector<double>& x, const std::vector<double>& y) {
  const std::size_t n = x.size();
  if (n < 2) return std::nan("");
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < n; ++i) {
    mx += std::log(x[i]);
    my += std::log(y[i]);
  }
  mx /= static_cast<double>(n);
  my /= static_cast<double>(n);
  double sxy = 0, sxx = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double dx = std::log(x[i]) - mx;
    sxy += dx * (std::log(y[i]) - my);
    sxx += dx * dx;
  }
  return sxx > 0 ? sxy / sxx : std::nan("");
}

}  // namespace pgmcl::bench
