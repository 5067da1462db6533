#include "pgmcl/mcl/clustering.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#include "grid_key.hpp"
#include "pgmcl/common/random.hpp"
#include "weighted_moments.hpp"

namespace pgmcl {
namespace {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

}  // namespace

ParticleClusterer::ParticleClusterer(const ClusterConfig& config) : config_(config) {
  const auto ok = [](double v) { return v > 0.0 && std::isfinite(v); };
  if (!ok(config.cell_xy) || !ok(config.cell_theta)) {
    throw std::invalid_argument("ParticleClusterer: cell_xy = " + std::to_string(config.cell_xy) +
                                " m and cell_theta = " + std::to_string(config.cell_theta) +
                                " rad must be finite and > 0");
  }
  const double sectors = detail::sector_count(config.cell_theta);
  if (sectors > static_cast<double>(detail::kMaxSectors)) {
    throw std::invalid_argument(
        "ParticleClusterer: cell_theta = " + std::to_string(config.cell_theta) +
        " rad gives more than 65535 heading cells");
  }
  sectors_ = static_cast<std::size_t>(sectors);
  sectors_per_radian_ = sectors / (2.0 * std::numbers::pi);
  inv_xy_ = 1.0 / config.cell_xy;
}

std::uint32_t ParticleClusterer::find(std::uint32_t c) noexcept {
  while (parent_[c] != c) {
    parent_[c] = parent_[parent_[c]];  // path halving
    c = parent_[c];
  }
  return c;
}

std::uint32_t ParticleClusterer::lookup(std::uint64_t key) const noexcept {
  const std::size_t mask = slot_keys_.size() - 1;
  for (std::size_t i = splitmix64(key) & mask;; i = (i + 1) & mask) {
    if (slot_cells_[i] == kNone) return kNone;
    if (slot_keys_[i] == key) return slot_cells_[i];
  }
}

void ParticleClusterer::build_cells(std::span<const float> x, std::span<const float> y,
                                    std::span<const float> theta) {
  const std::size_t n = x.size();
  const std::size_t slots = std::bit_ceil(std::max<std::size_t>(16, 2 * n));
  slot_keys_.resize(slots);
  slot_cells_.assign(slots, kNone);
  cell_keys_.clear();
  cell_keys_.reserve(n);
  cell_of_.resize(n);
  const std::size_t mask = slots - 1;
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint64_t key =
        detail::pack_cell(detail::cell_field(x[i] * inv_xy_), detail::cell_field(y[i] * inv_xy_),
                          detail::sector_of(theta[i], sectors_per_radian_, sectors_));
    std::size_t s = splitmix64(key) & mask;
    while (slot_cells_[s] != kNone && slot_keys_[s] != key) s = (s + 1) & mask;
    if (slot_cells_[s] == kNone) {
      slot_keys_[s] = key;
      slot_cells_[s] = static_cast<std::uint32_t>(cell_keys_.size());
      cell_keys_.push_back(key);
    }
    cell_of_[i] = slot_cells_[s];
  }
}

void ParticleClusterer::link_cells() {
  const std::size_t cells = cell_keys_.size();
  parent_.resize(cells);
  std::iota(parent_.begin(), parent_.end(), 0u);
  const auto sectors = static_cast<std::int64_t>(sectors_);
  const auto field_end = static_cast<std::int64_t>(detail::kCellFieldMask) + 1;
  for (std::size_t c = 0; c < cells; ++c) {
    const std::uint64_t key = cell_keys_[c];
    const auto fx = static_cast<std::int64_t>(key >> 40);
    const auto fy = static_cast<std::int64_t>((key >> 16) & detail::kCellFieldMask);
    const auto fs = static_cast<std::int64_t>(key & 0xFFFFu);
    // Half of the 26 neighbours suffices: adjacency is symmetric, so every touching pair
    // is seen from the cell whose offset to the other is lexicographically positive.
    for (std::int64_t dx = 0; dx <= 1; ++dx) {
      for (std::int64_t dy = (dx == 0 ? 0 : -1); dy <= 1; ++dy) {
        for (std::int64_t ds = (dx == 0 && dy == 0 ? 1 : -1); ds <= 1; ++ds) {
          const std::int64_t nx = fx + dx, ny = fy + dy;
          if (nx >= field_end || ny < 0 || ny >= field_end) continue;
          const std::int64_t ns = ((fs + ds) % sectors + sectors) % sectors;  // wraps at pi
          const std::uint32_t m = lookup(detail::pack_cell(static_cast<std::uint64_t>(nx),
                                                           static_cast<std::uint64_t>(ny),
                                                           static_cast<std::uint64_t>(ns)));
          if (m == kNone) continue;
          const std::uint32_t a = find(static_cast<std::uint32_t>(c)), b = find(m);
          if (a != b) parent_[std::max(a, b)] = std::min(a, b);  // deterministic roots
        }
      }
    }
  }
}

const std::vector<Cluster>& ParticleClusterer::cluster(std::span<const float> x,
                                                       std::span<const float> y,
                                                       std::span<const float> theta,
                                                       std::span<const double> w) {
  const std::size_t n = w.size();
  if (x.size() != n || y.size() != n || theta.size() != n) {
    throw std::invalid_argument("ParticleClusterer: x, y, theta, w have sizes " +
                                std::to_string(x.size()) + ", " + std::to_string(y.size()) + ", " +
                                std::to_string(theta.size()) + ", " + std::to_string(n));
  }
  if (n == 0) throw std::invalid_argument("ParticleClusterer: no particles");
  if (n >= kNone) throw std::invalid_argument("ParticleClusterer: too many particles");
  double total = 0.0;
  for (const double wi : w) total += wi;
  if (!(total > 0.0) || !std::isfinite(total)) {
    throw std::invalid_argument("ParticleClusterer: weights sum to " + std::to_string(total) +
                                ", expected a positive finite sum");
  }

  build_cells(x, y, theta);
  link_cells();

  // Clusters numbered by their first particle, so the numbering is reproducible.
  root_label_.assign(cell_keys_.size(), kNone);
  labels_.resize(n);
  first_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t r = find(cell_of_[i]);
    if (root_label_[r] == kNone) {
      root_label_[r] = static_cast<std::uint32_t>(first_.size());
      first_.push_back(static_cast<std::uint32_t>(i));
    }
    labels_[i] = root_label_[r];
  }
  const std::size_t k_count = first_.size();

  cluster_w_.assign(k_count, 0.0);
  count_.assign(k_count, 0);
  for (std::size_t i = 0; i < n; ++i) {
    cluster_w_[labels_[i]] += w[i];
    ++count_[labels_[i]];
  }
  // A zero-weight cluster still gets a finite summary: its particles count equally.
  const auto weight = [&](std::size_t i) { return cluster_w_[labels_[i]] > 0.0 ? w[i] : 1.0; };
  const auto reference = [&](std::uint32_t k) {
    const std::uint32_t f = first_[k];
    return detail::Reference{x[f], y[f], theta[f]};
  };

  first_moments_.assign(k_count, {});
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t k = labels_[i];
    detail::add_first(first_moments_[k], reference(k), x[i], y[i], theta[i], weight(i));
  }
  rel_mean_.resize(k_count);
  for (std::size_t k = 0; k < k_count; ++k) {
    const detail::RelativeMean rm = detail::relative_mean(first_moments_[k]);
    rel_mean_[k] = {rm.dx, rm.dy, rm.dtheta, rm.concentration};
  }
  second_moments_.assign(k_count, {});
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t k = labels_[i];
    const auto& m = rel_mean_[k];
    detail::add_second(second_moments_[k], reference(k), {m[0], m[1], m[2], m[3]}, x[i], y[i],
                       theta[i], weight(i));
  }

  order_.resize(k_count);
  std::iota(order_.begin(), order_.end(), 0u);
  std::stable_sort(order_.begin(), order_.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return cluster_w_[a] > cluster_w_[b]; });
  rank_.resize(k_count);
  clusters_.resize(k_count);
  for (std::size_t pos = 0; pos < k_count; ++pos) {
    const std::uint32_t k = order_[pos];
    rank_[k] = static_cast<std::uint32_t>(pos);
    const auto& m = rel_mean_[k];
    Cluster& c = clusters_[pos];
    c.weight = cluster_w_[k] / total;
    c.count = count_[k];
    c.mean = detail::absolute_mean(reference(k), {m[0], m[1], m[2], m[3]});
    c.covariance = detail::covariance_of(second_moments_[k], first_moments_[k][0]);
    c.heading_concentration = m[3];
  }
  for (auto& l : labels_) l = rank_[l];
  return clusters_;
}

std::vector<Cluster> cluster_particles(std::span<const float> x, std::span<const float> y,
                                       std::span<const float> theta, std::span<const double> w,
                                       const ClusterConfig& config) {
  ParticleClusterer clusterer(config);
  return clusterer.cluster(x, y, theta, w);
}

}  // namespace pgmcl
