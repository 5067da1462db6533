// PoseSearch per scan and per query: the scan's beams and headings, branch and bound
// over the pyramid (pose_search_pyramid.cpp), single poses' pooled costs.
#include "pgmcl/mcl/pose_search.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace pgmcl {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
// bound() compares its partial sum with the limit every this many beams (a power of two).
constexpr std::size_t kBoundCheck = 8;

}  // namespace

bool PoseSearch::set_scan(const PreparedBeams& beams) {
  full_circle_leaf_ = -1;
  const std::size_t m = beams.size();
  const std::size_t k = std::min(m, cfg_.max_beams);
  bx_.resize(k);
  by_.resize(k);
  ranges_.resize(k);
  // Beams evenly spread over the selection, in bit-reversed order: every prefix spans the
  // scan, so bound() finds a node past its limit after a few of them.
  int bits = 0;
  while ((std::size_t{1} << bits) < k) ++bits;
  std::size_t j = 0;
  for (std::size_t r = 0; r < (std::size_t{1} << bits); ++r) {
    std::size_t v = 0;
    for (int b = 0; b < bits; ++b)
      if ((r >> b) & 1u) v |= std::size_t{1} << (bits - 1 - b);
    if (v >= k) continue;
    const std::size_t i = (v * m) / k;
    bx_[j] = beams.ex[i];
    by_[j] = beams.ey[i];
    ranges_[j] = std::hypot(bx_[j], by_[j]);
    ++j;
  }
  // A rotated endpoint's coordinates lie within its range.
  padded_ =
      std::all_of(ranges_.begin(), ranges_.end(), [&](float r) { return r <= padded_reach_; });
  if (k == 0) return false;
  // An endpoint at range r moves r * step between neighbouring headings: keep that within
  // a leaf for 90 % of the beams.
  std::nth_element(ranges_.begin(), ranges_.begin() + static_cast<std::ptrdiff_t>((9 * k) / 10),
                   ranges_.end());
  const double r90 = std::max(1.0, static_cast<double>(ranges_[(9 * k) / 10]));
  angle_step_ =
      std::clamp(static_cast<double>(leaf_cells_) / r90, cfg_.min_angle_step, cfg_.max_angle_step);
  return true;
}

std::uint64_t PoseSearch::root_cost() const noexcept {
  if (bx_.empty()) return 0;
  const auto n = static_cast<std::uint64_t>(std::max(8.0, std::ceil(kTwoPi / angle_step_)));
  return n * bx_.size();
}

void PoseSearch::prepare_angles(const PoseSearchQuery& q, int leaf) {
  // A sweep searches the map a slice per query, all at the same headings: rotate once a scan.
  if (!q.windowed && full_circle_leaf_ == leaf) return;
  full_circle_leaf_ = q.windowed ? -1 : leaf;
  angles_.clear();
  const double step =
      std::min(angle_step_ * static_cast<double>(1 << leaf), 4.0 * cfg_.max_angle_step);
  if (q.windowed) {
    const int a = static_cast<int>(std::ceil(std::max(0.0, q.half_theta) / step));
    for (int i = -a; i <= a; ++i)
      angles_.push_back(wrap_angle(q.theta + static_cast<double>(i) * step));
  } else {
    const int n = std::max(8, static_cast<int>(std::ceil(kTwoPi / step)));
    for (int i = 0; i < n; ++i)
      angles_.push_back(
          wrap_angle(-std::numbers::pi + kTwoPi * (static_cast<double>(i) + 0.5) / n));
  }
  // Node corners are whole cells, so floor((col + x) / 2^k) = (col + floor(x)) >> k: the
  // rotated endpoints are floored once here and bound() needs only integer steps. They lie
  // within the scan's reach, where the clamps of floor_to_cell never act: without them the
  // same cells come out of a loop GCC vectorises (a sweep rotates hundreds of headings).
  const std::size_t m = bx_.size();
  rx_.resize(angles_.size() * m);
  ry_.resize(angles_.size() * m);
  for (std::size_t a = 0; a < angles_.size(); ++a) {
    const float c = static_cast<float>(std::cos(angles_[a]));
    const float s = static_cast<float>(std::sin(angles_[a]));
    for (std::size_t j = 0; j < m; ++j) {
      rx_[a * m + j] = maps::floor_to_cell_unclamped(c * bx_[j] - s * by_[j]);
      ry_[a * m + j] = maps::floor_to_cell_unclamped(s * bx_[j] + c * by_[j]);
    }
  }
}

template <bool kPadded>
std::uint32_t PoseSearch::bound(const Level& lv, std::int32_t col, std::int32_t row,
                                std::size_t angle, std::uint64_t limit) const noexcept {
  const std::size_t m = bx_.size();
  const std::int32_t* rx = rx_.data() + angle * m;
  const std::int32_t* ry = ry_.data() + angle * m;
  const int shift = lv.shift;
  const std::ptrdiff_t stride = lv.stride;
  const std::uint8_t* origin = lv.origin() + stride + 1;  // pooled index C + 1 for C
  std::uint32_t sum = 0;
  for (std::size_t j = 0; j < m; ++j) {
    // Costs are not negative: a partial sum at the limit prunes the node already.
    if ((j & (kBoundCheck - 1)) == 0 && sum >= limit) return sum;
    const int c = (col + rx[j]) >> shift;  // arithmetic shift: floor division
    const int r = (row + ry[j]) >> shift;
    if constexpr (kPadded) {
      sum += origin[r * stride + c];
    } else {
      const bool inside = static_cast<unsigned>(c + 1) < static_cast<unsigned>(lv.width) &&
                          static_cast<unsigned>(r + 1) < static_cast<unsigned>(lv.height);
      sum += inside ? origin[r * stride + c] : background_;
    }
  }
  return sum;
}

bool PoseSearch::has_free(const Level& lv, std::int32_t col, std::int32_t row) const noexcept {
  const int c = col >> lv.shift, r = row >> lv.shift;
  if (c < 0 || r < 0 || c >= lv.free_width || r >= lv.free_height) return false;
  return lv.has_free[static_cast<std::size_t>(r) * static_cast<std::size_t>(lv.free_width) +
                     static_cast<std::size_t>(c)] != 0;
}

std::uint32_t PoseSearch::pooled_cost(double x, double y, double theta) const {
  if (bx_.empty()) return 0;
  const Level& lv = levels_.front();
  const float inv = 1.0f / static_cast<float>(leaf_cells_);
  const double half = 0.5 * leaf_cells_;
  const auto fc = static_cast<float>(x / resolution_ - half);
  const auto fr = static_cast<float>(y / resolution_ - half);
  const float c = static_cast<float>(std::cos(theta)), s = static_cast<float>(std::sin(theta));
  std::uint32_t sum = 0;
  for (std::size_t j = 0; j < bx_.size(); ++j) {
    const int col = maps::floor_to_cell((fc + c * bx_[j] - s * by_[j]) * inv) + 1;
    const int row = maps::floor_to_cell((fr + s * bx_[j] + c * by_[j]) * inv) + 1;
    const bool inside = static_cast<unsigned>(col) < static_cast<unsigned>(lv.width) &&
                        static_cast<unsigned>(row) < static_cast<unsigned>(lv.height);
    sum += inside ? lv.origin()[row * lv.stride + col] : background_;
  }
  return sum;
}

void PoseSearch::record(const PoseSearchQuery& q, const Node& leaf,
                        std::vector<PoseCandidate>& out) const {
  const double half = 0.5 * static_cast<double>(1 << levels_[leaf.level].shift);
  PoseCandidate c{(leaf.col + half) * resolution_, (leaf.row + half) * resolution_,
                  angles_[leaf.angle], leaf.cost};
  // Non-maximum suppression: one candidate per place.
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (std::abs(out[i].x - c.x) < q.separation_xy && std::abs(out[i].y - c.y) < q.separation_xy &&
        std::abs(wrap_angle(out[i].theta - c.theta)) < q.separation_theta) {
      if (c.cost >= out[i].cost) return;
      out.erase(out.begin() + static_cast<std::ptrdiff_t>(i));
      break;
    }
  }
  const auto at = std::upper_bound(
      out.begin(), out.end(), c,
      [](const PoseCandidate& a, const PoseCandidate& b) { return a.cost < b.cost; });
  out.insert(at, c);
  if (out.size() > q.max_candidates) out.pop_back();
}

PoseSearchResult PoseSearch::search(const PoseSearchQuery& q) {
  PoseSearchResult res;
  if (bx_.empty() || q.max_candidates == 0) return res;
  const int leaf = std::clamp(q.coarse_levels, 0, static_cast<int>(levels_.size()) - 1);
  prepare_angles(q, leaf);
  const std::uint64_t per_node = bx_.size();
  const Level& root = levels_.back();
  const int rs = 1 << root.shift;

  // Translation window in fine cells (continuous), for windowed queries.
  const double wx0 = (q.x - q.half_xy) / resolution_, wx1 = (q.x + q.half_xy) / resolution_;
  const double wy0 = (q.y - q.half_xy) / resolution_, wy1 = (q.y + q.half_xy) / resolution_;
  auto overlaps = [&](std::int32_t col, std::int32_t row, int side) {
    return !q.windowed || (col + side > wx0 && col < wx1 && row + side > wy0 && row < wy1);
  };

  // Roots: every (root block, heading) with free space, sorted onto the stack best last.
  stack_.clear();
  // Nodes at or above the threshold are pruned when popped, and the threshold only falls:
  // such nodes are not kept at all. Lookups are counted as if every bound ran to the end,
  // so budgets and the sweep's pace do not depend on how early a bound stops.
  const std::uint64_t cap = static_cast<std::uint64_t>(q.max_cost) + 1;  // prune at >= cap
  auto add_root = [&](std::int32_t col, std::int32_t row) {
    for (std::size_t a = 0; a < angles_.size(); ++a) {
      const std::uint32_t cost =
          padded_ ? bound<true>(root, col, row, a, cap) : bound<false>(root, col, row, a, cap);
      res.lookups += per_node;
      if (cost < cap)
        stack_.push_back({col, row, cost, static_cast<std::uint16_t>(a),
                          static_cast<std::uint8_t>(levels_.size() - 1)});
    }
  };
  if (q.windowed) {
    const int c0 = std::max(0, static_cast<int>(std::floor(wx0 / rs)));
    const int c1 = std::min(root.free_width - 1, static_cast<int>(std::floor(wx1 / rs)));
    const int r0 = std::max(0, static_cast<int>(std::floor(wy0 / rs)));
    const int r1 = std::min(root.free_height - 1, static_cast<int>(std::floor(wy1 / rs)));
    for (int r = r0; r <= r1; ++r)
      for (int c = c0; c <= c1; ++c)
        if (has_free(root, c * rs, r * rs)) add_root(c * rs, r * rs);
  } else {
    const std::size_t end =
        q.root_end == 0 ? root_cells_.size() : std::min(q.root_end, root_cells_.size());
    for (std::size_t i = q.root_begin; i < end; ++i) {
      const auto cell = static_cast<std::int32_t>(root_cells_[i]);
      add_root((cell % root.free_width) * rs, (cell / root.free_width) * rs);
    }
  }
  std::sort(stack_.begin(), stack_.end(), [](const Node& a, const Node& b) {
    return a.cost != b.cost ? a.cost > b.cost : a.angle > b.angle;  // best last (top of stack)
  });

  auto threshold = [&]() -> std::uint64_t {
    if (res.candidates.size() < q.max_candidates) return cap;
    return std::min<std::uint64_t>(cap, res.candidates.back().cost);
  };
  Node children[4];
  while (!stack_.empty()) {
    const Node n = stack_.back();
    stack_.pop_back();
    if (n.cost >= threshold()) continue;
    if (n.level == leaf) {
      const double half = 0.5 * static_cast<double>(1 << levels_[n.level].shift);
      const double cx = n.col + half, cy = n.row + half;
      if (!q.windowed || (cx >= wx0 && cx <= wx1 && cy >= wy0 && cy <= wy1))
        record(q, n, res.candidates);
      continue;
    }
    if (q.budget != 0 && res.lookups >= q.budget) {
      res.truncated = true;
      break;
    }
    const Level& lv = levels_[n.level - 1u];
    const int s = 1 << lv.shift;
    const std::uint64_t limit = threshold();
    int k = 0;
    for (int dr = 0; dr < 2; ++dr)
      for (int dc = 0; dc < 2; ++dc) {
        const std::int32_t col = n.col + dc * s, row = n.row + dr * s;
        if (!has_free(lv, col, row) || !overlaps(col, row, s)) continue;
        const std::uint32_t cost = padded_ ? bound<true>(lv, col, row, n.angle, limit)
                                           : bound<false>(lv, col, row, n.angle, limit);
        res.lookups += per_node;
        if (cost < limit)
          children[k++] = {col, row, cost, n.angle, static_cast<std::uint8_t>(n.level - 1u)};
      }
    // Worst first, so the best child ends on top of the stack (insertion sort of <= 4).
    for (int i = 1; i < k; ++i)
      for (int j = i; j > 0 && children[j - 1].cost < children[j].cost; --j)
        std::swap(children[j - 1], children[j]);
    for (int i = 0; i < k; ++i) stack_.push_back(children[i]);
  }
  return res;
}

}  // namespace pgmcl
