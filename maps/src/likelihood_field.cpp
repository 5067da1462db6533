#include "pgmcl/maps/likelihood_field.hpp"

#include <algorithm>
#include <chrono>
#include <numbers>
#include <stdexcept>

#include "likelihood_field_detail.hpp"

namespace pgmcl::maps {
namespace {

constexpr int kLutBins = 4096;  // offset-field LUT bins over m2 in [0, reach^2)
constexpr int kMaxStampReach = 1000;

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("LikelihoodField: " + what);
}

void validate(const OccupancyGrid& grid, const LikelihoodFieldOptions& o) {
  require(!grid.empty(), "the occupancy grid is empty");
  require(o.orientation_bins >= 1,
          "orientation_bins must be >= 1 (got " + std::to_string(o.orientation_bins) + ")");
  require(std::isfinite(o.isotropy_tolerance) && o.isotropy_tolerance >= 0.0,
          "isotropy_tolerance must be finite and >= 0");
}

// Table bytes; std::length_error when they exceed the cap (or size_t).
std::size_t table_bytes(std::size_t cells, std::size_t per_cell, std::size_t extra, std::size_t cap,
                        const char* kind) {
  std::size_t bytes = 0;
  if (__builtin_mul_overflow(cells, per_cell, &bytes) ||
      __builtin_add_overflow(bytes, extra, &bytes) || bytes > cap) {
    const long double want = static_cast<long double>(cells) * per_cell + extra;
    throw std::length_error("LikelihoodField: the " + std::string(kind) + " table needs " +
                            std::to_string(static_cast<unsigned long long>(want)) + " bytes (" +
                            std::to_string(per_cell) + " per cell x " + std::to_string(cells) +
                            " cells), above max_table_bytes = " + std::to_string(cap));
  }
  return bytes;
}

detail::Stamp make_stamp(const detail::CellMetric& metric, int reach,
                         const sensor_model::BeamLikelihood& model) {
  detail::Stamp st;
  st.reach = reach;
  const int side = 2 * reach + 1;
  st.q.resize(static_cast<std::size_t>(side) * static_cast<std::size_t>(side));
  st.lo.assign(static_cast<std::size_t>(side), reach + 1);
  st.hi.assign(static_cast<std::size_t>(side), -reach - 1);
  st.argmin.assign(static_cast<std::size_t>(side), 0);
  for (int vy = -reach; vy <= reach; ++vy) {
    const auto row = static_cast<std::size_t>(vy + reach);
    for (int vx = -reach; vx <= reach; ++vx) {
      const std::uint8_t q = model.quantise_m2(metric(vx, vy));
      st.q[row * static_cast<std::size_t>(side) + static_cast<std::size_t>(vx + reach)] = q;
      if (q < model.background()) {  // q(m2) is monotone and m2 convex in vx: one interval per row
        st.lo[row] = std::min(st.lo[row], vx);
        st.hi[row] = std::max(st.hi[row], vx);
      }
    }
    const std::uint8_t* r = st.q.data() + row * static_cast<std::size_t>(side) + reach;
    for (int vx = st.lo[row]; vx <= st.hi[row]; ++vx)
      if (r[vx] < r[st.argmin[row]] || vx == st.lo[row]) st.argmin[row] = vx;
  }
  return st;
}

}  // namespace

const char* to_string(TableKind kind) noexcept {
  return name_of(kind, kTableKindNames, "unknown");
}

TableKind table_kind_from_string(const std::string& name) {
  if (const auto kind = value_of(name, kTableKindNames)) return *kind;
  throw std::invalid_argument("unknown likelihood table kind '" + name +
                              "' (expected isotropic, oriented or offset)");
}

LikelihoodField::LikelihoodField(const OccupancyGrid& grid,
                                 const sensor_model::BeamLikelihoodParams& params,
                                 const LikelihoodFieldOptions& options)
    : model_(params, grid.resolution(), options.reach_sigmas) {
  const auto t0 = std::chrono::steady_clock::now();
  validate(grid, options);
  width_ = grid.width();
  height_ = grid.height();
  resolution_ = grid.resolution();
  origin_ = grid.origin();
  const double res = resolution_;
  const double sa = model_.sigma_along_eff(), sc = model_.sigma_across_eff();
  const double reach_m2 = model_.reach_m2();
  const std::uint8_t background = model_.background();

  kind_ = options.kind;
  if (kind_ == TableKind::kOrientedBins && std::abs(sa / sc - 1.0) < options.isotropy_tolerance) {
    kind_ = TableKind::kIsotropic;
    stats_.orientation_skipped = true;
  }
  bins_ = kind_ == TableKind::kOrientedBins ? options.orientation_bins : 1;

  const double reach_m = options.reach_sigmas * std::max(sa, sc);
  // Clamped before the cast (a reach beyond int range is UB), so the check below reports it.
  stats_.reach_cells =
      static_cast<int>(std::min(std::ceil(reach_m / res - 1e-9), kMaxStampReach + 1.0));
  stats_.reach_cells = std::max(stats_.reach_cells, 1);
  const int reach = stats_.reach_cells;
  require(reach <= kMaxStampReach, "the kernel reach of " + std::to_string(reach) +
                                       " cells exceeds " + std::to_string(kMaxStampReach) +
                                       " (sigmas too large for the resolution)");
  require(kind_ != TableKind::kOffsetField || reach <= 127,
          "the offset field stores int8 offsets; the kernel reach of " + std::to_string(reach) +
              " cells exceeds 127");

  const std::size_t cells = grid.size();
  const char* name = to_string(kind_);
  if (kind_ == TableKind::kOffsetField) {
    stats_.bytes = table_bytes(cells, 2, kLutBins + 1, options.max_table_bytes, name);
  } else {
    stats_.bytes =
        table_bytes(cells, static_cast<std::size_t>(bins_), 0, options.max_table_bytes, name);
  }

  const double sa_c = sa / res, sc_c = sc / res;  // sigmas in cells
  if (kind_ == TableKind::kOffsetField) {
    offsets_.resize(2 * cells);
    lut_size_ = kLutBins + 1;
    lut_steps_per_unit_ = static_cast<float>(kLutBins / reach_m2);
    lut_.resize(static_cast<std::size_t>(lut_size_));
    for (int i = 0; i < kLutBins; ++i)  // bin i covers m2 in [i, i + 1) / steps: its centre
      lut_[static_cast<std::size_t>(i)] = model_.quantise_m2((i + 0.5) * reach_m2 / kLutBins);
    lut_[kLutBins] = background;
    auto scan = detail::scan_obstacles(grid, false, detail::TableInit::kOffsets, nullptr, 0,
                                       background, offsets_.data());
    const double reach_cells = reach_m / res;
    stats_.cells_computed = detail::stamp_offsets(scan, reach, reach_cells * reach_cells, width_,
                                                  height_, offsets_.data());
    stats_.sources_stamped = scan.sources_total;
  } else {
    std::vector<detail::CellMetric> metrics;
    if (kind_ == TableKind::kIsotropic) {  // one sigma: sigma_along_eff (see the header)
      metrics.push_back({1.0 / (sa_c * sa_c), 0.0, 1.0 / (sa_c * sa_c)});
    } else {
      for (int b = 0; b < bins_; ++b)  // bin b is sampled at its centre direction
        metrics.push_back(
            detail::CellMetric::beam((b + 0.5) * std::numbers::pi / bins_, sa_c, sc_c));
    }
    bool boundary_only = true;
    for (const auto& m : metrics)
      boundary_only = boundary_only && detail::interior_cells_never_nearest(m, reach_m2, reach);
    std::vector<detail::Stamp> stamps;
    for (const auto& m : metrics) stamps.push_back(make_stamp(m, reach, model_));
    q_.resize(cells * static_cast<std::size_t>(bins_));
    auto scan = detail::scan_obstacles(grid, !boundary_only, detail::TableInit::kBytes, q_.data(),
                                       bins_, background, nullptr);
    stats_.cells_computed = detail::stamp_min(scan, stamps, width_, height_, background, q_.data());
    stats_.sources_stamped = scan.sources_total;
  }
  stats_.build_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

IsotropicView LikelihoodField::isotropic() const noexcept {
  if (kind_ != TableKind::kIsotropic) return {nullptr, 0, 0, model_.background()};
  return {q_.data(), width_, height_, model_.background()};
}

OrientedView LikelihoodField::oriented() const noexcept {
  OrientedView v;
  v.background = model_.background();
  if (kind_ != TableKind::kOrientedBins) return v;  // 0 x 0: every lookup is background
  v.q = q_.data();
  v.width = width_;
  v.height = height_;
  v.bins = bins_;
  v.plane_stride = static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
  v.bins_per_radian = static_cast<float>(bins_ / std::numbers::pi);
  return v;
}

OffsetView LikelihoodField::offset() const noexcept {
  OffsetView v;
  v.background = model_.background();
  if (kind_ != TableKind::kOffsetField) return v;
  const double sa_c = model_.sigma_along_eff() / resolution_;
  const double sc_c = model_.sigma_across_eff() / resolution_;
  v.off = offsets_.data();
  v.width = width_;
  v.height = height_;
  v.lut = lut_.data();
  v.lut_size = lut_size_;
  v.lut_steps_per_unit = lut_steps_per_unit_;
  v.inv_var_along = static_cast<float>(1.0 / (sa_c * sa_c));
  v.inv_var_across = static_cast<float>(1.0 / (sc_c * sc_c));
  return v;
}

std::vector<std::uint8_t> LikelihoodField::best_case_table() const {
  const std::size_t n = static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
  std::vector<std::uint8_t> q(n);
  switch (kind_) {
    case TableKind::kIsotropic:
      std::copy_n(q_.begin(), n, q.begin());
      break;
    case TableKind::kOrientedBins:  // the minimum over the direction planes
      std::copy_n(q_.begin(), n, q.begin());
      for (int b = 1; b < bins_; ++b)
        for (std::size_t i = 0; i < n; ++i)
          q[i] = std::min(q[i], q_[static_cast<std::size_t>(b) * n + i]);
      break;
    case TableKind::kOffsetField: {  // q at the offset's smallest Mahalanobis distance
      const OffsetView v = offset();
      const float inv_var = std::max(v.inv_var_along, v.inv_var_across);
      for (std::size_t i = 0; i < n; ++i) {
        const std::int8_t dc = v.off[2 * i];
        if (dc == OffsetView::kNoObstacle) {
          q[i] = v.background;
          continue;
        }
        const auto dx = static_cast<float>(dc), dy = static_cast<float>(v.off[2 * i + 1]);
        // The endpoint may sit anywhere in its cell: half a cell closer along each axis.
        const float ax = std::max(0.0f, std::abs(dx) - 0.5f),
                    ay = std::max(0.0f, std::abs(dy) - 0.5f);
        const float idx =
            (ax * ax + ay * ay) * std::min(v.inv_var_along, inv_var) * v.lut_steps_per_unit;
        q[i] = idx < static_cast<float>(v.lut_size - 1) ? v.lut[static_cast<int>(idx)]
                                                        : v.lut[v.lut_size - 1];
      }
      break;
    }
  }
  return q;
}

}  // namespace pgmcl::maps
