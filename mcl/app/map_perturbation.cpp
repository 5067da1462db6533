#include "map_perturbation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace pgmcl::app {
namespace {

using maps::kOccupied;
using maps::OccupancyGrid;

bool known(std::int8_t v) noexcept {
  return v >= 0 && v <= kOccupied;
}

/// One 1-D pass of a separable filter along rows (`along_rows`) or columns: out[i] =
/// combine over the cells within `radius` of i (clipped to the grid) of in[j] weighted by
/// `weight(|i - j|)`, starting from `init`.
template <typename T, typename Combine>
std::vector<T> separable_pass(const std::vector<T>& in, int width, int height, bool along_rows,
                              int radius, T init, Combine combine) {
  std::vector<T> out(in.size(), init);
  const int len = along_rows ? width : height;
  const int lines = along_rows ? height : width;
  for (int line = 0; line < lines; ++line) {
    for (int i = 0; i < len; ++i) {
      T acc = init;
      const int lo = std::max(0, i - radius), hi = std::min(len - 1, i + radius);
      for (int j = lo; j <= hi; ++j) {
        const std::size_t at = along_rows ? static_cast<std::size_t>(line) * width + j
                                          : static_cast<std::size_t>(j) * width + line;
        acc = combine(acc, in[at], std::abs(i - j));
      }
      const std::size_t at = along_rows ? static_cast<std::size_t>(line) * width + i
                                        : static_cast<std::size_t>(i) * width + line;
      out[at] = acc;
    }
  }
  return out;
}

}  // namespace

EraseResult erase_blocks(OccupancyGrid& grid, int block, double fraction, Rng& rng) {
  EraseResult r;
  const int bw = (grid.width() + block - 1) / block;
  const int bh = (grid.height() + block - 1) / block;
  std::vector<std::size_t> walled;
  for (int by = 0; by < bh; ++by) {
    for (int bx = 0; bx < bw; ++bx) {
      bool any = false;
      for (int row = by * block; row < std::min(grid.height(), (by + 1) * block) && !any; ++row) {
        for (int col = bx * block; col < std::min(grid.width(), (bx + 1) * block); ++col) {
          if (grid.occupied(col, row)) {
            any = true;
            break;
          }
        }
      }
      if (any) walled.push_back(static_cast<std::size_t>(by) * bw + bx);
    }
  }
  r.blocks_with_walls = walled.size();
  r.blocks_erased =
      static_cast<std::size_t>(std::llround(fraction * static_cast<double>(walled.size())));
  // Partial Fisher-Yates: the first blocks_erased entries become a uniform random subset.
  for (std::size_t k = 0; k < r.blocks_erased; ++k) {
    std::swap(walled[k], walled[k + rng.below(walled.size() - k)]);
  }
  for (std::size_t k = 0; k < r.blocks_erased; ++k) {
    const int bx = static_cast<int>(walled[k] % bw), by = static_cast<int>(walled[k] / bw);
    for (int row = by * block; row < std::min(grid.height(), (by + 1) * block); ++row) {
      for (int col = bx * block; col < std::min(grid.width(), (bx + 1) * block); ++col) {
        if (grid.occupied(col, row)) {
          grid.set(col, row, maps::kFree);
          ++r.cells_erased;
        }
      }
    }
  }
  return r;
}

std::size_t thicken_walls(OccupancyGrid& grid, int cells) {
  if (cells <= 0) return 0;
  std::vector<std::uint8_t> wall(grid.size());
  for (std::size_t i = 0; i < grid.size(); ++i) {
    wall[i] = grid.cells()[i] >= grid.occupied_threshold() ? 1 : 0;
  }
  const auto max_of = [](std::uint8_t acc, std::uint8_t v, int) -> std::uint8_t {
    return std::max(acc, v);
  };
  const int w = grid.width(), h = grid.height();
  wall = separable_pass<std::uint8_t>(wall, w, h, true, cells, 0, max_of);
  wall = separable_pass<std::uint8_t>(wall, w, h, false, cells, 0, max_of);
  std::size_t made = 0;
  for (std::size_t i = 0; i < grid.size(); ++i) {
    std::int8_t& v = grid.cells()[i];
    if (wall[i] != 0 && known(v) && v < grid.occupied_threshold()) {
      v = kOccupied;
      ++made;
    }
  }
  return made;
}

void blur_known_cells(OccupancyGrid& grid, double sigma) {
  const int radius = static_cast<int>(std::ceil(3.0 * sigma));
  std::vector<double> weight(static_cast<std::size_t>(radius) + 1);
  for (int k = 0; k <= radius; ++k) weight[k] = std::exp(-0.5 * k * k / (sigma * sigma));
  // Numerator (weighted p over known cells) and denominator (weights of known cells)
  // are both plain separable convolutions.
  std::vector<std::pair<double, double>> acc(grid.size());
  for (std::size_t i = 0; i < grid.size(); ++i) {
    const std::int8_t v = grid.cells()[i];
    acc[i] = known(v) ? std::pair{v / 100.0, 1.0} : std::pair{0.0, 0.0};
  }
  using Sum = std::pair<double, double>;
  const auto gauss = [&weight](Sum a, Sum v, int d) -> Sum {
    return {a.first + weight[d] * v.first, a.second + weight[d] * v.second};
  };
  const int w = grid.width(), h = grid.height();
  acc = separable_pass<Sum>(acc, w, h, true, radius, Sum{0.0, 0.0}, gauss);
  acc = separable_pass<Sum>(acc, w, h, false, radius, Sum{0.0, 0.0}, gauss);
  for (std::size_t i = 0; i < grid.size(); ++i) {
    std::int8_t& v = grid.cells()[i];
    if (!known(v)) continue;
    const double p = acc[i].first / acc[i].second;  // >= weight[0] > 0 for a known cell
    v = static_cast<std::int8_t>(std::lround(100.0 * std::clamp(p, 0.0, 1.0)));
  }
}

}  // namespace pgmcl::app
