// PoseSearch's pyramid: the min-pooled cost levels it bounds nodes with, built once per
// field, and the root blocks a global search walks.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "pgmcl/mcl/pose_search.hpp"

namespace pgmcl {
namespace {

// Cells of padding beyond the range model's support (a sensor mounted off the base).
constexpr double kPadMarginCells = 64.0;

// Minimum over the fine cells [C * s, C * s + 2 s) of one axis, for C in [-1, ceil(n / s)),
// stored at C + 1; empty windows read `background`.
template <class Get, class Put>
void pool_axis(int n, int s, std::uint8_t background, Get get, Put put) {
  const int coarse = (n + s - 1) / s;
  for (int c = -1; c < coarse; ++c) {
    std::uint8_t m = background;
    const int lo = std::max(0, c * s), hi = std::min(n, c * s + 2 * s);
    for (int i = lo; i < hi; ++i) m = std::min(m, get(i));
    put(c + 1, m);
  }
}

}  // namespace

PoseSearch::PoseSearch(const maps::LikelihoodField& field,
                       std::span<const std::uint32_t> free_cells, const PoseSearchConfig& cfg)
    : resolution_(field.resolution()),
      width_(field.width()),
      height_(field.height()),
      nats_per_step_(field.model().nats_per_step()),
      cfg_(cfg) {
  if (!(std::isfinite(cfg.leaf_size) && cfg.leaf_size > 0.0) || cfg.root_levels < 1 ||
      cfg.max_beams == 0 || !(cfg.min_angle_step > 0.0) ||
      !(cfg.max_angle_step >= cfg.min_angle_step))
    throw std::invalid_argument("PoseSearch: invalid PoseSearchConfig");
  background_ = field.model().background();

  leaf_level_ = std::max(1, static_cast<int>(std::lround(std::log2(cfg.leaf_size / resolution_))));
  leaf_level_ = std::min(leaf_level_, 20);
  leaf_cells_ = 1 << leaf_level_;
  int root_level = leaf_level_ + cfg.root_levels;
  while (root_level > leaf_level_ + 1 && (1 << (root_level - 1)) >= std::max(width_, height_))
    --root_level;

  // Leaf level straight from the fine table, separably; higher levels from the one below.
  const std::vector<std::uint8_t> fine = field.best_case_table();
  {
    Level lv;
    lv.shift = leaf_level_;
    const int s = 1 << lv.shift;
    lv.width = (width_ + s - 1) / s + 1;
    lv.height = (height_ + s - 1) / s + 1;
    std::vector<std::uint8_t> rows(static_cast<std::size_t>(lv.width) *
                                   static_cast<std::size_t>(height_));
    for (int r = 0; r < height_; ++r) {
      const std::uint8_t* src =
          fine.data() + static_cast<std::size_t>(r) * static_cast<std::size_t>(width_);
      std::uint8_t* dst =
          rows.data() + static_cast<std::size_t>(r) * static_cast<std::size_t>(lv.width);
      pool_axis(
          width_, s, background_, [&](int i) { return src[i]; },
          [&](int i, std::uint8_t v) { dst[i] = v; });
    }
    lv.cost.assign(static_cast<std::size_t>(lv.width) * static_cast<std::size_t>(lv.height),
                   background_);
    for (int c = 0; c < lv.width; ++c) {
      pool_axis(
          height_, s, background_,
          [&](int i) {
            return rows[static_cast<std::size_t>(i) * static_cast<std::size_t>(lv.width) +
                        static_cast<std::size_t>(c)];
          },
          [&](int i, std::uint8_t v) {
            lv.cost[static_cast<std::size_t>(i) * static_cast<std::size_t>(lv.width) +
                    static_cast<std::size_t>(c)] = v;
          });
    }
    lv.free_width = (width_ + s - 1) / s;
    lv.free_height = (height_ + s - 1) / s;
    lv.has_free.assign(
        static_cast<std::size_t>(lv.free_width) * static_cast<std::size_t>(lv.free_height), 0);
    const auto w = static_cast<std::uint32_t>(width_);
    for (const std::uint32_t cell : free_cells) {
      const auto col = static_cast<int>(cell % w), row = static_cast<int>(cell / w);
      if (row >= height_) throw std::invalid_argument("PoseSearch: free cell outside the grid");
      lv.has_free[static_cast<std::size_t>(row >> lv.shift) *
                      static_cast<std::size_t>(lv.free_width) +
                  static_cast<std::size_t>(col >> lv.shift)] = 1;
    }
    levels_.push_back(std::move(lv));
  }
  for (int k = leaf_level_ + 1; k <= root_level; ++k) {
    const Level& prev = levels_.back();
    Level lv;
    lv.shift = k;
    const int s = 1 << k;
    lv.width = (width_ + s - 1) / s + 1;
    lv.height = (height_ + s - 1) / s + 1;
    lv.cost.assign(static_cast<std::size_t>(lv.width) * static_cast<std::size_t>(lv.height),
                   background_);
    auto get = [&](int c, int r) -> std::uint8_t {  // prev level at coarse (c, r), stored at +1
      if (c + 1 < 0 || c + 1 >= prev.width || r + 1 < 0 || r + 1 >= prev.height) return background_;
      return prev.cost[static_cast<std::size_t>(r + 1) * static_cast<std::size_t>(prev.width) +
                       static_cast<std::size_t>(c + 1)];
    };
    for (int r = -1; r + 1 < lv.height; ++r)
      for (int c = -1; c + 1 < lv.width; ++c) {
        const std::uint8_t m = std::min({get(2 * c, 2 * r), get(2 * c + 2, 2 * r),
                                         get(2 * c, 2 * r + 2), get(2 * c + 2, 2 * r + 2)});
        lv.cost[static_cast<std::size_t>(r + 1) * static_cast<std::size_t>(lv.width) +
                static_cast<std::size_t>(c + 1)] = m;
      }
    lv.free_width = (width_ + s - 1) / s;
    lv.free_height = (height_ + s - 1) / s;
    lv.has_free.assign(
        static_cast<std::size_t>(lv.free_width) * static_cast<std::size_t>(lv.free_height), 0);
    for (int r = 0; r < prev.free_height; ++r)
      for (int c = 0; c < prev.free_width; ++c)
        if (prev.has_free[static_cast<std::size_t>(r) * static_cast<std::size_t>(prev.free_width) +
                          static_cast<std::size_t>(c)] != 0)
          lv.has_free[static_cast<std::size_t>(r >> 1) * static_cast<std::size_t>(lv.free_width) +
                      static_cast<std::size_t>(c >> 1)] = 1;
    levels_.push_back(std::move(lv));
  }
  // Padding: nodes lie within the root blocks, which reach past the map by less than a
  // root block, and a scan's rotated endpoints (floored) within padded_reach_ + 1 cells of
  // a node's corner. The range model's support bounds every reading the filter scores; on
  // a map smaller than that, its diagonal bounds the padding (memory), and the rare scan
  // that reaches farther takes the checked path.
  const double reach_cells = std::min(field.model().params().max_range / resolution_,
                                      std::hypot(static_cast<double>(width_), height_));
  padded_reach_ = static_cast<float>(std::ceil(reach_cells) + kPadMarginCells);
  const int root_side = 1 << levels_.back().shift;
  for (Level& lv : levels_) {
    const int s = 1 << lv.shift;
    lv.pad = (static_cast<int>(padded_reach_) + 1 + root_side) / s + 2;
    lv.stride = lv.width + 2 * lv.pad;
    std::vector<std::uint8_t> padded(
        static_cast<std::size_t>(lv.stride) * static_cast<std::size_t>(lv.height + 2 * lv.pad),
        background_);
    for (int r = 0; r < lv.height; ++r)
      std::copy_n(lv.cost.begin() + static_cast<std::ptrdiff_t>(r) * lv.width, lv.width,
                  padded.begin() + (r + lv.pad) * lv.stride + lv.pad);
    lv.cost = std::move(padded);
  }
  const Level& root = levels_.back();
  for (int r = 0; r < root.free_height; ++r)
    for (int c = 0; c < root.free_width; ++c)
      if (root.has_free[static_cast<std::size_t>(r) * static_cast<std::size_t>(root.free_width) +
                        static_cast<std::size_t>(c)] != 0)
        root_cells_.push_back(static_cast<std::uint32_t>(r * root.free_width + c));
}

std::size_t PoseSearch::bytes() const noexcept {
  std::size_t b = 0;
  for (const Level& lv : levels_) b += lv.cost.size() + lv.has_free.size();
  return b + root_cells_.size() * sizeof(std::uint32_t);
}

}  // namespace pgmcl
