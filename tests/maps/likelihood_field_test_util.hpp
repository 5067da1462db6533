#pragma once
// Shared helpers of the LikelihoodField tests: synthetic grids (never map files), a brute-force
// oracle over all obstacle cells, and the isotropic-vs-EDT check (tables read through the
// production kernels, testkit::table_q).

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "pgmcl/maps/distance_transform.hpp"
#include "pgmcl/maps/likelihood_field.hpp"
#include "table_oracle.hpp"

namespace pgmcl::maps::lf_test {

using sensor_model::BeamLikelihoodParams;
using testkit::table_q;

// Room with thick outer walls, an inner wall, an L corner, a filled disk (interior obstacle
// cells), a ring, scattered single obstacles and an unknown patch.
inline OccupancyGrid room(int w, int h, double res, unsigned seed) {
  OccupancyGrid g(w, h, res, {}, kFree);
  auto box = [&](int c0, int r0, int c1, int r1, std::int8_t v) {
    for (int r = std::max(r0, 0); r < std::min(r1, h); ++r)
      for (int c = std::max(c0, 0); c < std::min(c1, w); ++c) g.set(c, r, v);
  };
  box(0, 0, w, 4, kOccupied);
  box(0, h - 3, w, h, kOccupied);
  box(0, 0, 3, h, kOccupied);
  box(w - 5, 0, w, h, kOccupied);
  box(w / 3, h / 5, w / 3 + 2, 3 * h / 5, kOccupied);
  box(w / 2, 2 * h / 3, 4 * w / 5, 2 * h / 3 + 6, kOccupied);
  box(4 * w / 5 - 6, h / 3, 4 * w / 5, 2 * h / 3 + 6, kOccupied);
  box(w / 6, 3 * h / 4, w / 4, h - 3, kUnknown);
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) {
      const double d = std::hypot(c - 0.62 * w, r - 0.3 * h);
      if (d < 0.08 * h || std::abs(d - 0.16 * h) < 0.6) g.set(c, r, kOccupied);
    }
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> uc(0, w - 1), ur(0, h - 1);
  for (int i = 0; i < w * h / 400; ++i) g.set(uc(rng), ur(rng), kOccupied);
  return g;
}

// Brute force over every obstacle cell: squared Mahalanobis distance of Eq. (6).
struct BruteForce {
  std::vector<std::array<double, 2>> obstacles;  // cell centres, metres
  double sa, sc;
  BruteForce(const OccupancyGrid& g, const LikelihoodField& f)
      : sa(f.model().sigma_along_eff()), sc(f.model().sigma_across_eff()) {
    for (int r = 0; r < g.height(); ++r)
      for (int c = 0; c < g.width(); ++c)
        if (g.occupied(c, r))
          obstacles.push_back({(c + 0.5) * g.resolution(), (r + 0.5) * g.resolution()});
  }
  [[nodiscard]] double m2(double x, double y, double phi) const {
    const double cs = std::cos(phi), sn = std::sin(phi);
    double best = INFINITY;
    for (const auto& o : obstacles) {
      const double dx = o[0] - x, dy = o[1] - y;
      const double a = dx * cs + dy * sn, b = -dx * sn + dy * cs;
      best = std::min(best, a * a / (sa * sa) + b * b / (sc * sc));
    }
    return best;
  }
};

// Random cells within reach + 1 of an obstacle (and some anywhere), as (col, row).
inline std::vector<std::array<int, 2>> cells_near_obstacles(const OccupancyGrid& g, int reach,
                                                            int n, std::mt19937& rng) {
  std::vector<std::array<int, 2>> obs;
  for (int r = 0; r < g.height(); ++r)
    for (int c = 0; c < g.width(); ++c)
      if (g.occupied(c, r)) obs.push_back({c, r});
  std::uniform_int_distribution<std::size_t> pick(0, obs.size() - 1);
  std::uniform_int_distribution<int> off(-reach - 1, reach + 1);
  std::vector<std::array<int, 2>> out;
  for (int i = 0; i < n; ++i) {
    const auto& o = obs[pick(rng)];
    out.push_back({std::clamp(o[0] + off(rng), 0, g.width() - 1),
                   std::clamp(o[1] + off(rng), 0, g.height() - 1)});
  }
  return out;
}

inline LikelihoodFieldOptions with_kind(TableKind k) {
  LikelihoodFieldOptions o;
  o.kind = k;
  return o;
}

inline double ratio(const LikelihoodField& f) {
  return f.model().sigma_along_eff() / f.model().sigma_across_eff();
}

// The isotropic table is the EDT distance through the model: within step/2 everywhere.
inline void check_isotropic_everywhere(const OccupancyGrid& g, const LikelihoodField& f) {
  const DistanceField df = euclidean_distance_transform(g);
  const double s = f.model().sigma_along_eff() / g.resolution();
  const double tol = f.model().nats_per_step() / 2 + 1e-9;
  for (int r = 0; r < g.height(); ++r)
    for (int c = 0; c < g.width(); ++c) {
      const double m2 = df.sq_dist_at(c, r) / (s * s);
      ASSERT_NEAR(f.model().log_likelihood_of_q(table_q(f, c + 0.5f, r + 0.5f, 0.0)),
                  f.model().log_likelihood_of_m2(m2), tol)
          << "cell (" << c << ", " << r << ")";
    }
}

}  // namespace pgmcl::maps::lf_test
