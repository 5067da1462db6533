#include "pgmcl/maps/likelihood_field.hpp"

#include <algorithm>
#include <chrono>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "likelihood_field_detail.hpp"
#include "pgmcl/sensor_model/sigma_models.hpp"

namespace pgmcl::maps {
namespace {

constexpr int kLutBins = 4096;  // offset-field LUT bins over m2 in [0, reach^2)
constexpr int kMaxStampReach = 1000;
constexpr double kNegInf = -std::numeric_limits<double>::infinity();

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("LikelihoodField: " + what);
}

void validate(const OccupancyGrid& grid, const BeamLikelihoodParams& p,
              const LikelihoodFieldOptions& o) {
  auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  auto unit = [](double v) { return std::isfinite(v) && v >= 0.0 && v <= 1.0; };
  require(!grid.empty(), "the occupancy grid is empty");
  require(positive(p.sigma_along),
          "sigma_along must be positive and finite (got " + std::to_string(p.sigma_along) + " m)");
  require(positive(p.sigma_across), "sigma_across must be positive and finite (got " +
                                        std::to_string(p.sigma_across) + " m)");
  require(
      std::isfinite(p.model_mismatch) && p.model_mismatch >= 0.0,
      "model_mismatch must be finite and >= 0 (got " + std::to_string(p.model_mismatch) + " m)");
  require(unit(p.w_hit), "w_hit must be in [0, 1] (got " + std::to_string(p.w_hit) + ")");
  require(unit(p.w_rand), "w_rand must be in [0, 1] (got " + std::to_string(p.w_rand) + ")");
  require(std::abs(p.w_hit + p.w_rand - 1.0) <= 1e-9,
          "w_hit + w_rand must be 1 within 1e-9 (got " + std::to_string(p.w_hit + p.w_rand) + ")");
  require(positive(p.max_range),
          "max_range must be positive and finite (got " + std::to_string(p.max_range) + " m)");
  require(o.orientation_bins >= 1,
          "orientation_bins must be >= 1 (got " + std::to_string(o.orientation_bins) + ")");
  require(positive(o.reach_sigmas),
          "reach_sigmas must be positive and finite (got " + std::to_string(o.reach_sigmas) + ")");
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

detail::Stamp make_stamp(const detail::CellMetric& metric, int reach, const LikelihoodField& f,
                         std::uint8_t background) {
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
      const std::uint8_t q = f.quantise_m2(metric(vx, vy));
      st.q[row * static_cast<std::size_t>(side) + static_cast<std::size_t>(vx + reach)] = q;
      if (q < background) {  // q(m2) is monotone and m2 convex in vx: one interval per row
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
  switch (kind) {
    case TableKind::kIsotropic:
      return "isotropic";
    case TableKind::kOrientedBins:
      return "oriented";
    case TableKind::kOffsetField:
      return "offset";
  }
  return "unknown";
}

TableKind table_kind_from_string(const std::string& name) {
  for (TableKind k : {TableKind::kIsotropic, TableKind::kOrientedBins, TableKind::kOffsetField})
    if (name == to_string(k)) return k;
  throw std::invalid_argument("unknown likelihood table kind '" + name +
                              "' (expected isotropic, oriented or offset)");
}

LikelihoodField::LikelihoodField(const OccupancyGrid& grid, const BeamLikelihoodParams& params,
                                 const LikelihoodFieldOptions& options)
    : params_(params), options_(options) {
  const auto t0 = std::chrono::steady_clock::now();
  validate(grid, params, options);
  width_ = grid.width();
  height_ = grid.height();
  resolution_ = grid.resolution();
  origin_ = grid.origin();
  const double res = resolution_;

  // Effective sigmas (sensor_model/sigma_models.hpp): sensor + uniform position within a
  // cell (variance res^2 / 12, unless switched off) + model mismatch, in quadrature.
  const double cell = params.add_discretisation ? res : 0.0;
  const double sa = sensor_model::effective_sigma(params.sigma_along, cell, params.model_mismatch);
  const double sc = sensor_model::effective_sigma(params.sigma_across, cell, params.model_mismatch);
  stats_.sigma_along_eff = sa;
  stats_.sigma_across_eff = sc;

  kind_ = options.kind;
  if (kind_ == TableKind::kOrientedBins && std::abs(sa / sc - 1.0) < options.isotropy_tolerance) {
    kind_ = TableKind::kIsotropic;
    stats_.orientation_skipped = true;
  }
  bins_ = kind_ == TableKind::kOrientedBins ? options.orientation_bins : 1;

  // The per-beam model (see the header): along-beam normaliser of Eq. (4) on the hit term.
  reach_m2_ = options.reach_sigmas * options.reach_sigmas;
  log_hit_norm_ = params.w_hit > 0.0
                      ? std::log(params.w_hit / (std::sqrt(2.0 * std::numbers::pi) * sa))
                      : kNegInf;
  log_floor_ = params.w_rand > 0.0 ? std::log(params.w_rand / params.max_range) : kNegInf;
  stats_.ll_background = params.w_rand > 0.0 ? log_floor_ : log_hit_norm_ - 0.5 * reach_m2_;
  stats_.nats_per_step = 1.0;  // provisional: log_likelihood_of_m2 does not read it
  stats_.ll_max = log_likelihood_of_m2(0.0);
  const double range = stats_.ll_max - stats_.ll_background;
  stats_.nats_per_step = range > 1e-12 ? range / 255.0 : 1.0;
  background_ = quantise_m2(std::numeric_limits<double>::infinity());

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
    lut_steps_per_unit_ = static_cast<float>(kLutBins / reach_m2_);
    lut_.resize(static_cast<std::size_t>(lut_size_));
    for (int i = 0; i < kLutBins; ++i)  // bin i covers m2 in [i, i + 1) / steps: its centre
      lut_[static_cast<std::size_t>(i)] = quantise_m2((i + 0.5) * reach_m2_ / kLutBins);
    lut_[kLutBins] = background_;
    auto scan = detail::scan_obstacles(grid, false, detail::TableInit::kOffsets, nullptr, 0,
                                       background_, offsets_.data());
    const double reach_cells = reach_m / res;
    stats_.cells_computed = detail::stamp_offsets(scan, reach, reach_cells * reach_cells, width_,
                                                  height_, offsets_.data());
    stats_.sources_stamped = scan.sources_total;
    obstacle_bits_ = std::move(scan.bits);
    words_per_row_ = scan.words_per_row;
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
      boundary_only = boundary_only && detail::interior_cells_never_nearest(m, reach_m2_, reach);
    std::vector<detail::Stamp> stamps;
    for (const auto& m : metrics) stamps.push_back(make_stamp(m, reach, *this, background_));
    q_.resize(cells * static_cast<std::size_t>(bins_));
    auto scan = detail::scan_obstacles(grid, !boundary_only, detail::TableInit::kBytes, q_.data(),
                                       bins_, background_, nullptr);
    stats_.cells_computed =
        detail::stamp_min(scan, stamps, width_, height_, background_, q_.data());
    stats_.sources_stamped = scan.sources_total;
    obstacle_bits_ = std::move(scan.bits);
    words_per_row_ = scan.words_per_row;
  }
  stats_.oracle_bytes = obstacle_bits_.size() * sizeof(std::uint64_t);
  stats_.build_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double LikelihoodField::log_likelihood_of_m2(double m2) const noexcept {
  if (!(m2 < reach_m2_)) return stats_.ll_background;
  const double a = log_hit_norm_ - 0.5 * m2, b = log_floor_;
  const double hi = std::max(a, b), lo = std::min(a, b);
  return lo == kNegInf ? hi : hi + std::log1p(std::exp(lo - hi));
}

std::uint8_t LikelihoodField::quantise_m2(double m2) const noexcept {
  const double steps = (stats_.ll_max - log_likelihood_of_m2(m2)) / stats_.nats_per_step;
  return static_cast<std::uint8_t>(std::clamp(std::lround(steps), 0L, 255L));
}

IsotropicView LikelihoodField::isotropic() const noexcept {
  if (kind_ != TableKind::kIsotropic) return {nullptr, 0, 0, background_};
  return {q_.data(), width_, height_, background_};
}

OrientedView LikelihoodField::oriented() const noexcept {
  OrientedView v;
  v.background = background_;
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
  v.background = background_;
  if (kind_ != TableKind::kOffsetField) return v;
  const double sa_c = stats_.sigma_along_eff / resolution_;
  const double sc_c = stats_.sigma_across_eff / resolution_;
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

double LikelihoodField::exact_log_likelihood(double x, double y, double beam_angle) const {
  if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(beam_angle)) {
    throw std::invalid_argument("LikelihoodField::exact_log_likelihood: non-finite input");
  }
  const double cx = x / resolution_, cy = y / resolution_;  // cells
  const auto metric = detail::CellMetric::beam(beam_angle, stats_.sigma_along_eff / resolution_,
                                               stats_.sigma_across_eff / resolution_);
  // Every obstacle with m2 < reach^2 lies within reach_sigmas * max(sigma) of the endpoint.
  const double r = std::sqrt(reach_m2_) *
                       std::max(stats_.sigma_along_eff, stats_.sigma_across_eff) / resolution_ +
                   1.0;
  const double c0 = std::max(std::floor(cx - r), 0.0);
  const double c1 = std::min(std::ceil(cx + r), static_cast<double>(width_ - 1));
  const double r0 = std::max(std::floor(cy - r), 0.0);
  const double r1 = std::min(std::ceil(cy + r), static_cast<double>(height_ - 1));
  double best = std::numeric_limits<double>::infinity();
  if (c0 > c1 || r0 > r1) return log_likelihood_of_m2(best);  // no map cell within reach
  for (auto row = static_cast<int>(r0); row <= static_cast<int>(r1); ++row) {
    for (auto col = static_cast<int>(c0); col <= static_cast<int>(c1); ++col) {
      if (obstacle_bit(col, row)) best = std::min(best, metric(col + 0.5 - cx, row + 0.5 - cy));
    }
  }
  return log_likelihood_of_m2(best);
}

}  // namespace pgmcl::maps
