// Table builders for LikelihoodField: one O(cells) scan of the grid, then kernel stamps
// around obstacle cells only (see likelihood_field_detail.hpp).

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstring>

#include "likelihood_field_detail.hpp"

namespace pgmcl::maps::detail {

CellMetric CellMetric::beam(double phi, double sigma_along, double sigma_across) {
  // Q(d) = (d.u)^2 / sa^2 + (d x u)^2 / sc^2 with u = (cos phi, sin phi): Dekan et al.,
  // Eq. (6) exponent (times 2) for x along and y across the beam.
  const double c = std::cos(phi), s = std::sin(phi);
  const double ia = 1.0 / (sigma_along * sigma_along), ic = 1.0 / (sigma_across * sigma_across);
  return {c * c * ia + s * s * ic, c * s * (ia - ic), s * s * ia + c * c * ic};
}

bool interior_cells_never_nearest(const CellMetric& q, double reach_m2, int reach) {
  for (int vy = -reach - 1; vy <= reach + 1; ++vy) {
    for (int vx = -reach - 1; vx <= reach + 1; ++vx) {
      if (std::max(std::abs(vx), std::abs(vy)) < 2) continue;
      const double qv = q(vx, vy);
      if (!(qv < reach_m2)) continue;
      bool dominated = false;
      for (int ey = -1; ey <= 1 && !dominated; ++ey)
        for (int ex = -1; ex <= 1 && !dominated; ++ex)
          dominated = (ex != 0 || ey != 0) && q(vx - ex, vy - ey) < qv;
      if (!dominated) return false;
    }
  }
  return true;
}

ObstacleScan scan_obstacles(const OccupancyGrid& grid, bool all_obstacles, TableInit init,
                            std::uint8_t* table, int planes, std::uint8_t background,
                            std::int8_t* offsets) {
  const int w = grid.width(), h = grid.height();
  const std::int8_t thr = grid.occupied_threshold();
  const std::int8_t* cells = grid.cells().data();
  const std::size_t uw = static_cast<std::size_t>(w);
  const std::size_t stride = uw * static_cast<std::size_t>(h);
  ObstacleScan out;
  out.runs.resize(static_cast<std::size_t>(h));
#ifdef _OPENMP
#pragma omp parallel
#endif
  {
    std::vector<std::uint8_t> obs3(uw);  // obstacle in rows r-1, r and r+1 (all on the map)
#ifdef _OPENMP
#pragma omp for schedule(static)
#endif
    for (int r = 0; r < h; ++r) {
      const std::int8_t* cur = cells + static_cast<std::size_t>(r) * uw;
      const std::int8_t* prev = r > 0 ? cur - w : nullptr;
      const std::int8_t* next = r + 1 < h ? cur + w : nullptr;
      if (prev != nullptr && next != nullptr) {
        for (int c = 0; c < w; ++c)
          obs3[static_cast<std::size_t>(c)] =
              static_cast<std::uint8_t>((cur[c] >= thr) & (prev[c] >= thr) & (next[c] >= thr));
      } else {
        std::fill(obs3.begin(), obs3.end(), std::uint8_t{0});
      }
      auto& runs = out.runs[static_cast<std::size_t>(r)];
      for (int c = 0; c < w; ++c) {
        if (cur[c] < thr) continue;
        const bool interior = c > 0 && c + 1 < w && obs3[static_cast<std::size_t>(c) - 1] &&
                              obs3[static_cast<std::size_t>(c)] &&
                              obs3[static_cast<std::size_t>(c) + 1];
        if (!all_obstacles && interior) continue;
        if (!runs.empty() && runs.back()[1] == c - 1) {
          runs.back()[1] = c;
        } else {
          runs.push_back({c, c});
        }
      }
      const std::size_t base = static_cast<std::size_t>(r) * uw;
      if (init == TableInit::kBytes) {
        for (int p = 0; p < planes; ++p) {
          std::uint8_t* row = table + static_cast<std::size_t>(p) * stride + base;
          for (int c = 0; c < w; ++c) row[c] = cur[c] >= thr ? std::uint8_t{0} : background;
        }
      } else {
        std::int8_t* row = offsets + 2 * base;
        for (int c = 0; c < w; ++c) {
          row[2 * c] = cur[c] >= thr ? std::int8_t{0} : OffsetView::kNoObstacle;
          row[2 * c + 1] = 0;
        }
      }
    }
  }
  for (const auto& row : out.runs)
    for (const auto& run : row) out.sources_total += static_cast<std::size_t>(run[1] - run[0] + 1);
  return out;
}

std::size_t stamp_min(const ObstacleScan& scan, const std::vector<Stamp>& stamps, int width,
                      int height, std::uint8_t background, std::uint8_t* table) {
  const int reach = stamps.front().reach;
  const int side = 2 * reach + 1;
  const auto planes = static_cast<int>(stamps.size());
  const std::size_t uw = static_cast<std::size_t>(width);
  const std::size_t stride = uw * static_cast<std::size_t>(height);
  std::size_t computed = 0;
#ifdef _OPENMP
#pragma omp parallel reduction(+ : computed)
#endif
  {
    std::vector<std::uint8_t> hit(uw);  // cell of this row non-background in some plane
#ifdef _OPENMP
#pragma omp for schedule(dynamic, 16)
#endif
    for (int y = 0; y < height; ++y) {
      int xmin = INT_MAX, xmax = -1;
      for (int p = 0; p < planes; ++p) {
        const Stamp& st = stamps[static_cast<std::size_t>(p)];
        std::uint8_t* out =
            table + static_cast<std::size_t>(p) * stride + static_cast<std::size_t>(y) * uw;
        for (int vy = -reach; vy <= reach; ++vy) {
          const int sy = y - vy;  // v = cell - obstacle
          if (sy < 0 || sy >= height) continue;
          const auto& runs = scan.runs[static_cast<std::size_t>(sy)];
          const auto row = static_cast<std::size_t>(vy + reach);
          const int lo = st.lo[row], hi = st.hi[row], js = st.argmin[row];
          if (runs.empty() || lo > hi) continue;
          const std::uint8_t* s =
              st.q.data() + static_cast<std::ptrdiff_t>(row * static_cast<std::size_t>(side)) +
              reach;
          const std::uint8_t smin = s[js];
          for (const auto& [c0, c1] : runs) {
            // x - c1 > js: right flank anchored at c1; x - c0 < js: left flank at c0; else the
            // window [x - c1, x - c0] holds the row's minimum.
            for (int j = std::max(lo, -c0); j < js && c0 + j < width; ++j)
              out[c0 + j] = std::min(out[c0 + j], s[j]);
            for (int x = std::max(c0 + js, 0), xe = std::min(c1 + js, width - 1); x <= xe; ++x)
              out[x] = std::min(out[x], smin);
            for (int j = std::max(js + 1, -c1); j <= hi && c1 + j < width; ++j)
              out[c1 + j] = std::min(out[c1 + j], s[j]);
            xmin = std::min(xmin, std::max(c0 + lo, 0));
            xmax = std::max(xmax, std::min(c1 + hi, width - 1));
          }
        }
      }
      // Cells outside [xmin, xmax] were not stamped in this row; obstacle cells inside the
      // span hold q = 0. (An obstacle cell out of every stamp only happens when the kernel is
      // narrower than one cell; it then holds q = 0 but is not counted.) Plane by plane, so
      // the count reads memory contiguously.
      if (xmax < xmin) continue;
      std::fill(hit.begin() + xmin, hit.begin() + xmax + 1, std::uint8_t{0});
      for (int p = 0; p < planes; ++p) {
        const std::uint8_t* row =
            table + static_cast<std::size_t>(p) * stride + static_cast<std::size_t>(y) * uw;
        for (int x = xmin; x <= xmax; ++x) hit[static_cast<std::size_t>(x)] |= row[x] != background;
      }
      for (int x = xmin; x <= xmax; ++x) computed += hit[static_cast<std::size_t>(x)];
    }
  }
  return computed;
}

std::size_t stamp_offsets(const ObstacleScan& scan, int reach, double reach_cells2, int width,
                          int height, std::int8_t* offsets) {
  std::vector<int> half(static_cast<std::size_t>(2 * reach + 1), -1);  // max |vx| per vy
  for (int vy = -reach; vy <= reach; ++vy) {
    int hw = -1;
    while (hw + 1 <= reach && double((hw + 1) * (hw + 1) + vy * vy) < reach_cells2) ++hw;
    half[static_cast<std::size_t>(vy + reach)] = hw;
  }
  const std::size_t uw = static_cast<std::size_t>(width);
  std::size_t computed = 0;
#ifdef _OPENMP
#pragma omp parallel reduction(+ : computed)
#endif
  {
    std::vector<int> best(uw);
#ifdef _OPENMP
#pragma omp for schedule(dynamic, 16)
#endif
    for (int y = 0; y < height; ++y) {
      std::int8_t* out = offsets + 2 * static_cast<std::size_t>(y) * uw;
      int xmin = INT_MAX, xmax = -1;
      for (int vy = -reach; vy <= reach; ++vy) {
        const int sy = y - vy;
        const int hw = half[static_cast<std::size_t>(vy + reach)];
        if (sy < 0 || sy >= height || hw < 0) continue;
        const auto& runs = scan.runs[static_cast<std::size_t>(sy)];
        if (runs.empty()) continue;
        xmin = std::min(xmin, std::max(runs.front()[0] - hw, 0));
        xmax = std::max(xmax, std::min(runs.back()[1] + hw, width - 1));
      }
      if (xmax < xmin) continue;
      for (int x = xmin; x <= xmax; ++x) {  // obstacles already hold (0, 0)
        best[static_cast<std::size_t>(x)] = out[2 * x] == OffsetView::kNoObstacle ? INT_MAX : 0;
      }
      for (int vy = -reach; vy <= reach; ++vy) {
        const int sy = y - vy;
        const int hw = half[static_cast<std::size_t>(vy + reach)];
        if (sy < 0 || sy >= height || hw < 0) continue;
        for (const auto& [c0, c1] : scan.runs[static_cast<std::size_t>(sy)]) {
          // Within a run the nearest source to column x is the run cell closest to x.
          const int x0 = std::max(c0 - hw, 0), x1 = std::min(c1 + hw, width - 1);
          for (int x = x0; x <= x1; ++x) {
            const int vx = x - std::clamp(x, c0, c1);
            const int d2 = vx * vx + vy * vy;
            if (d2 < best[static_cast<std::size_t>(x)]) {
              best[static_cast<std::size_t>(x)] = d2;
              out[2 * x] = static_cast<std::int8_t>(-vx);  // cell -> obstacle
              out[2 * x + 1] = static_cast<std::int8_t>(-vy);
            }
          }
        }
      }
      for (int x = xmin; x <= xmax; ++x)
        computed += out[2 * x] != OffsetView::kNoObstacle ? 1u : 0u;
    }
  }
  return computed;
}

}  // namespace pgmcl::maps::detail
