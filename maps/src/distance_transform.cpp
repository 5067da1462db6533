#include "pgmcl/maps/distance_transform.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace pgmcl::maps {
namespace {

constexpr std::int64_t kMinusInf = std::numeric_limits<std::int64_t>::min();
constexpr std::int64_t kPlusInf = std::numeric_limits<std::int64_t>::max();
// Columns per work item of the column pass: wide enough for contiguous row segments.
constexpr int kColumnBlock = 256;

// floor(a / b) for b > 0. Exact through double for |a| < 2^53: a non-integer quotient is at
// least 1/b from an integer, while its rounding error is below |a/b| * 2^-53 < 1/b.
// (Here |a| < 2 * (width^2 + height^2) < 2^34.) Much cheaper than 64-bit integer division.
[[nodiscard]] std::int64_t floor_div(std::int64_t a, std::int64_t b) noexcept {
  const double q = static_cast<double>(a) / static_cast<double>(b);
  const auto t = static_cast<std::int64_t>(q);  // truncates; step down for negatives
  return t - (static_cast<double>(t) > q ? 1 : 0);
}

void check_size(int width, int height) {
  if (width <= 0 || height <= 0) {
    throw std::invalid_argument("euclidean_distance_transform: sizes must be positive (got " +
                                std::to_string(width) + " x " + std::to_string(height) + ")");
  }
  const auto w = static_cast<std::uint64_t>(width), h = static_cast<std::uint64_t>(height);
  if (w * h > static_cast<std::uint64_t>(std::numeric_limits<std::int32_t>::max()) ||
      w * w + h * h >= DistanceField::kInfinite) {
    throw std::length_error("euclidean_distance_transform: grid " + std::to_string(width) + " x " +
                            std::to_string(height) +
                            " exceeds the 32-bit index / squared-distance range");
  }
}

// Pass 1 (columns). F&H run the 1D lower envelope on f = 0 at obstacles, +inf elsewhere;
// for such a 0/inf function the envelope is simply the nearest finite sample, which two
// sweeps find. Sweeping row by row over a block of columns keeps memory access contiguous.
// Leaves sq_dist = squared column distance and nearest = row of that obstacle (or kNone).
template <class IsObstacle>
void column_pass(const IsObstacle& is_obstacle, DistanceField& out) {
  const int w = out.width, h = out.height;
  const int blocks = (w + kColumnBlock - 1) / kColumnBlock;
#ifdef _OPENMP
#pragma omp parallel for schedule(static)
#endif
  for (int b = 0; b < blocks; ++b) {
    const int c0 = b * kColumnBlock, c1 = std::min(w, c0 + kColumnBlock);
    std::int32_t last[kColumnBlock];
    std::fill(last, last + (c1 - c0), DistanceField::kNone);
    // Branch-free so the inner loops vectorise. A missing obstacle is a sentinel row far
    // outside the grid, so plain distance comparisons pick the real one.
    constexpr std::int32_t kFarBelow = -(1 << 30), kFarAbove = 1 << 30;
    std::fill(last, last + (c1 - c0), kFarBelow);
    for (int r = 0; r < h; ++r) {  // nearest obstacle at or below r (rows counted upwards)
      const std::size_t base = static_cast<std::size_t>(r) * static_cast<std::size_t>(w);
      std::int32_t* near = out.nearest.data() + base;
      for (int c = c0; c < c1; ++c) {
        last[c - c0] = is_obstacle(base + static_cast<std::size_t>(c)) ? r : last[c - c0];
        near[c] = last[c - c0];
      }
    }
    std::fill(last, last + (c1 - c0), kFarAbove);
    for (int r = h - 1; r >= 0; --r) {  // nearest at or above r; keep the closer one
      const std::size_t base = static_cast<std::size_t>(r) * static_cast<std::size_t>(w);
      std::int32_t* near = out.nearest.data() + base;
      std::uint32_t* sq = out.sq_dist.data() + base;
      for (int c = c0; c < c1; ++c) {
        last[c - c0] = is_obstacle(base + static_cast<std::size_t>(c)) ? r : last[c - c0];
        const std::int32_t below = near[c], above = last[c - c0];
        const bool take_above = above - r < r - below;
        const std::int32_t best = take_above ? above : below;
        const bool none = take_above ? above == kFarAbove : below == kFarBelow;
        const auto d = static_cast<std::uint32_t>(take_above ? above - r : r - below);
        near[c] = none ? DistanceField::kNone : best;
        sq[c] = none ? DistanceField::kInfinite : d * d;
      }
    }
  }
}

// Pass 2 (rows): F&H's lower envelope of the parabolas (q - v)^2 + f(v) over the columns
// v with finite f (Algorithm DT(f), Section 3). The envelope boundaries z are kept as
// floor()s of the exact intersections: queries are integers, so an envelope piece whose
// exact interval holds no integer may be dropped, and all comparisons stay exact in int64.
void row_pass(DistanceField& out) {
  const int w = out.width, h = out.height;
#ifdef _OPENMP
#pragma omp parallel
#endif
  {
    std::vector<std::uint32_t> f(static_cast<std::size_t>(w));
    std::vector<std::int32_t> src_row(static_cast<std::size_t>(w));
    std::vector<std::int32_t> v(static_cast<std::size_t>(w));
    std::vector<std::int64_t> z(static_cast<std::size_t>(w) + 1);
#ifdef _OPENMP
#pragma omp for schedule(static)
#endif
    for (int r = 0; r < h; ++r) {
      const std::size_t base = static_cast<std::size_t>(r) * static_cast<std::size_t>(w);
      std::copy_n(out.sq_dist.begin() + static_cast<std::ptrdiff_t>(base), w, f.begin());
      std::copy_n(out.nearest.begin() + static_cast<std::ptrdiff_t>(base), w, src_row.begin());
      int k = -1;
      for (int q = 0; q < w; ++q) {
        if (f[static_cast<std::size_t>(q)] == DistanceField::kInfinite) continue;
        const std::int64_t fq =
            static_cast<std::int64_t>(f[static_cast<std::size_t>(q)]) + std::int64_t{q} * q;
        if (k < 0) {
          k = 0;
          v[0] = q;
          z[0] = kMinusInf;
          z[1] = kPlusInf;
          continue;
        }
        std::int64_t s = 0;
        for (;;) {
          const std::int32_t vk = v[static_cast<std::size_t>(k)];
          const std::int64_t fv =
              static_cast<std::int64_t>(f[static_cast<std::size_t>(vk)]) + std::int64_t{vk} * vk;
          s = floor_div(fq - fv, 2 * (std::int64_t{q} - vk));
          if (s > z[static_cast<std::size_t>(k)]) break;
          --k;  // z[0] = -inf ends this loop at k = 0
        }
        ++k;
        v[static_cast<std::size_t>(k)] = q;
        z[static_cast<std::size_t>(k)] = s;
        z[static_cast<std::size_t>(k) + 1] = kPlusInf;
      }
      if (k < 0) {  // no obstacle in any column: the whole row stays infinite / kNone
        continue;
      }
      k = 0;
      for (int q = 0; q < w; ++q) {
        while (z[static_cast<std::size_t>(k) + 1] < q) ++k;
        const std::int32_t vk = v[static_cast<std::size_t>(k)];
        const auto dq = static_cast<std::uint32_t>(std::abs(q - vk));
        const std::size_t i = base + static_cast<std::size_t>(q);
        out.sq_dist[i] = dq * dq + f[static_cast<std::size_t>(vk)];
        out.nearest[i] = src_row[static_cast<std::size_t>(vk)] * w + vk;
      }
    }
  }
}

template <class IsObstacle>
DistanceField transform(const IsObstacle& is_obstacle, int width, int height) {
  check_size(width, height);
  DistanceField out;
  out.width = width;
  out.height = height;
  const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  out.sq_dist.resize(n);
  out.nearest.resize(n);
  column_pass(is_obstacle, out);
  row_pass(out);
  return out;
}

}  // namespace

double DistanceField::distance_m(int col, int row, double resolution) const noexcept {
  const std::uint32_t d2 = sq_dist_at(col, row);
  if (d2 == kInfinite) return std::numeric_limits<double>::infinity();
  return std::sqrt(static_cast<double>(d2)) * resolution;
}

DistanceField euclidean_distance_transform(const OccupancyGrid& grid) {
  const std::int8_t* cells = grid.cells().data();
  const std::int8_t threshold = grid.occupied_threshold();
  return transform([cells, threshold](std::size_t i) { return cells[i] >= threshold; },
                   grid.width(), grid.height());
}

DistanceField euclidean_distance_transform(std::span<const std::uint8_t> obstacle, int width,
                                           int height) {
  check_size(width, height);
  if (obstacle.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height)) {
    throw std::invalid_argument("euclidean_distance_transform: mask has " +
                                std::to_string(obstacle.size()) + " bytes, expected " +
                                std::to_string(width) + " x " + std::to_string(height));
  }
  const std::uint8_t* m = obstacle.data();
  return transform([m](std::size_t i) { return m[i] != 0; }, width, height);
}

}  // namespace pgmcl::maps
