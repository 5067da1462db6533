#include "pgmcl/mcl/measurement_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <utility>

#include "parallel_blocks.hpp"

namespace pgmcl {
namespace {

// Per-particle rotation, computed in double and rounded once, so the value cannot depend
// on whether a compiler vectorises cos/sin differently in two call sites.
struct Rot {
  float c, s;
};
inline Rot rotation_of(float theta) noexcept {
  const double t = static_cast<double>(theta);
  return {static_cast<float>(std::cos(t)), static_cast<float>(std::sin(t))};
}

// An endpoint is particle (px, py) + the rotated beam, so |endpoint| <= |p| + reach per
// axis. Below this bound maps::floor_to_cell's clamps cannot act and the kernels use
// floor_to_cell_unclamped: same cells, but the transform loops vectorise (the clamps
// compile to branches there). Only particles thrown far off (or NaN) take the clamped path.
constexpr float kUnclampedLimit = 5.0e8f;
inline bool needs_clamp(float px, float py, float reach) noexcept {
  return !(std::abs(px) + reach < kUnclampedLimit && std::abs(py) + reach < kUnclampedLimit);
}
template <bool kClamp>
inline int to_cell(float c) noexcept {
  if constexpr (kClamp) return maps::floor_to_cell(c);
  return maps::floor_to_cell_unclamped(c);
}

// The three kernels share one shape: transform the base-frame endpoint of beam j by the
// particle pose (in cells), read q, add. Only the lookup differs.
// Beams per chunk of the two-pass loops below (stack buffers of 2 x 512 bytes).
constexpr std::size_t kChunk = 128;

// IsotropicView::lookup split in two passes per chunk of beams: pass 1 maps endpoints to
// cells with no memory access but the beam arrays (the compiler vectorises it), marking
// off-map endpoints with row -1; pass 2 is the bare byte gather and add. Same cells, same
// bytes, same sums as calling lookup() per beam, about twice as fast.
struct IsotropicKernel {
  maps::IsotropicView view;
  const float* ex;
  const float* ey;
  std::size_t m;
  float inv_res;
  float reach;
  std::uint8_t fit_q;  // q at or below this: the beam fits the map (PoseScore::fitting)

  template <bool kCountBackground, bool kClamp>
  std::uint32_t score(float px, float py, float theta, PoseScore* counts) const noexcept {
    const maps::IsotropicView v = view;
    const Rot r = rotation_of(theta);
    alignas(16) std::int32_t cols[kChunk];
    alignas(16) std::int32_t rows[kChunk];
    std::uint32_t sum = 0, bg = 0, fit = 0;
    for (std::size_t j0 = 0; j0 < m; j0 += kChunk) {
      const std::size_t len = std::min(kChunk, m - j0);
      const float* const bx = ex + j0;
      const float* const by = ey + j0;
      for (std::size_t k = 0; k < len; ++k) {
        const int c = to_cell<kClamp>(px + (r.c * bx[k] - r.s * by[k]));
        const int rr = to_cell<kClamp>(py + (r.s * bx[k] + r.c * by[k]));
        const bool inside = (c >= 0) & (c < v.width) & (rr >= 0) & (rr < v.height);
        cols[k] = c;
        rows[k] = inside ? rr : -1;
      }
      for (std::size_t k = 0; k < len; ++k) {
        const std::uint8_t q =
            rows[k] >= 0
                ? v.q[static_cast<std::size_t>(rows[k]) * static_cast<std::size_t>(v.width) +
                      static_cast<std::size_t>(cols[k])]
                : v.background;
        sum += q;
        if constexpr (kCountBackground) {
          bg += (q == v.background) ? 1u : 0u;
          fit += (q <= fit_q) ? 1u : 0u;
        }
      }
    }
    if constexpr (kCountBackground) {
      counts->background = bg;
      counts->fitting = fit;
    }
    return sum;
  }
};

// OrientedView::lookup in the same two passes; the plane index is computed in pass 1.
struct OrientedKernel {
  maps::OrientedView view;
  const float* ex;
  const float* ey;
  const float* bin;  // beam direction in the base frame, in bins, [0, bins)
  std::size_t m;
  float inv_res;
  float reach;
  std::uint8_t fit_q;  // q at or below this: the beam fits the map (PoseScore::fitting)

  template <bool kCountBackground, bool kClamp>
  std::uint32_t score(float px, float py, float theta, PoseScore* counts) const noexcept {
    const maps::OrientedView v = view;
    const Rot r = rotation_of(theta);
    const int bins = v.bins;
    const auto period = static_cast<float>(bins);
    // theta in (-pi, pi] -> [0, bins]; plus bin[j] in [0, bins) gives [0, 2 bins]:
    // two conditional subtractions bring any of those back to [0, bins).
    float tb = theta * v.bins_per_radian;
    tb += (tb < 0.0f) ? period : 0.0f;
    alignas(16) std::int32_t cols[kChunk];
    alignas(16) std::int32_t rows[kChunk];
    alignas(16) std::int32_t planes[kChunk];
    std::uint32_t sum = 0, bg = 0, fit = 0;
    for (std::size_t j0 = 0; j0 < m; j0 += kChunk) {
      const std::size_t len = std::min(kChunk, m - j0);
      const float* const bx = ex + j0;
      const float* const by = ey + j0;
      const float* const bb = bin + j0;
      for (std::size_t k = 0; k < len; ++k) {
        const int c = to_cell<kClamp>(px + (r.c * bx[k] - r.s * by[k]));
        const int rr = to_cell<kClamp>(py + (r.s * bx[k] + r.c * by[k]));
        int b = static_cast<int>(tb + bb[k]);
        b = b >= bins ? b - bins : b;
        b = b >= bins ? b - bins : b;
        const bool inside = (c >= 0) & (c < v.width) & (rr >= 0) & (rr < v.height);
        cols[k] = c;
        rows[k] = inside ? rr : -1;
        planes[k] = b;
      }
      for (std::size_t k = 0; k < len; ++k) {
        const std::uint8_t q =
            rows[k] >= 0
                ? v.q[static_cast<std::size_t>(planes[k]) * v.plane_stride +
                      static_cast<std::size_t>(rows[k]) * static_cast<std::size_t>(v.width) +
                      static_cast<std::size_t>(cols[k])]
                : v.background;
        sum += q;
        if constexpr (kCountBackground) {
          bg += (q == v.background) ? 1u : 0u;
          fit += (q <= fit_q) ? 1u : 0u;
        }
      }
    }
    if constexpr (kCountBackground) {
      counts->background = bg;
      counts->fitting = fit;
    }
    return sum;
  }
};

// OffsetView::lookup in four passes per chunk: (1) endpoints and beam directions in the
// grid frame, cells marked off-map (vectorised); (2) gather the offset to the nearest
// obstacle; (3) squared Mahalanobis distance -> LUT index (vectorised); (4) gather the LUT.
// The arithmetic is the view's, term for term, so the bytes read are the same.
struct OffsetKernel {
  maps::OffsetView view;
  const float* ex;
  const float* ey;
  const float* ux;
  const float* uy;
  std::size_t m;
  float inv_res;
  float reach;
  std::uint8_t fit_q;  // q at or below this: the beam fits the map (PoseScore::fitting)

  template <bool kCountBackground, bool kClamp>
  std::uint32_t score(float px, float py, float theta, PoseScore* counts) const noexcept {
    const maps::OffsetView v = view;
    const Rot r = rotation_of(theta);
    alignas(16) float colf[kChunk], rowf[kChunk], dirx[kChunk], diry[kChunk];
    alignas(16) std::int32_t cols[kChunk], rows[kChunk], dcs[kChunk], drs[kChunk];
    alignas(16) std::int32_t lut_idx[kChunk];
    const float lut_last = static_cast<float>(v.lut_size - 1);
    std::uint32_t sum = 0, bg = 0, fit = 0;
    for (std::size_t j0 = 0; j0 < m; j0 += kChunk) {
      const std::size_t len = std::min(kChunk, m - j0);
      const float* const bx = ex + j0;
      const float* const by = ey + j0;
      const float* const bux = ux + j0;
      const float* const buy = uy + j0;
      for (std::size_t k = 0; k < len; ++k) {
        const float col = px + (r.c * bx[k] - r.s * by[k]);
        const float row = py + (r.s * bx[k] + r.c * by[k]);
        const int c = to_cell<kClamp>(col), rr = to_cell<kClamp>(row);
        const bool inside = (c >= 0) & (c < v.width) & (rr >= 0) & (rr < v.height);
        colf[k] = col;
        rowf[k] = row;
        cols[k] = c;
        rows[k] = inside ? rr : -1;
        dirx[k] = r.c * bux[k] - r.s * buy[k];
        diry[k] = r.s * bux[k] + r.c * buy[k];
      }
      for (std::size_t k = 0; k < len; ++k) {
        dcs[k] = maps::OffsetView::kNoObstacle;
        drs[k] = 0;
        if (rows[k] < 0) continue;
        const std::size_t i =
            2 * (static_cast<std::size_t>(rows[k]) * static_cast<std::size_t>(v.width) +
                 static_cast<std::size_t>(cols[k]));
        dcs[k] = v.off[i];
        drs[k] = v.off[i + 1];
      }
      for (std::size_t k = 0; k < len; ++k) {
        // Vector from the endpoint to the obstacle cell's centre, in cells.
        const float dx = static_cast<float>(cols[k] + dcs[k]) + 0.5f - colf[k];
        const float dy = static_cast<float>(rows[k] + drs[k]) + 0.5f - rowf[k];
        const float along = dx * dirx[k] + dy * diry[k];
        const float across = dy * dirx[k] - dx * diry[k];
        const float m2 = along * along * v.inv_var_along + across * across * v.inv_var_across;
        const float idx = m2 * v.lut_steps_per_unit;
        const int li = idx < lut_last ? static_cast<int>(idx) : v.lut_size - 1;
        lut_idx[k] = dcs[k] == maps::OffsetView::kNoObstacle ? -1 : li;
      }
      for (std::size_t k = 0; k < len; ++k) {
        const std::uint8_t q = lut_idx[k] >= 0 ? v.lut[lut_idx[k]] : v.background;
        sum += q;
        if constexpr (kCountBackground) {
          bg += (q == v.background) ? 1u : 0u;
          fit += (q <= fit_q) ? 1u : 0u;
        }
      }
    }
    if constexpr (kCountBackground) {
      counts->background = bg;
      counts->fitting = fit;
    }
    return sum;
  }
};

// One particle: metres to cells, then the clamped kernel only if the endpoints could
// leave the range where the clamps are inactive (needs_clamp).
template <bool kCountBackground, class Kernel>
std::uint32_t score_particle(const Kernel& k, float x, float y, float theta,
                             PoseScore* counts) noexcept {
  const float px = x * k.inv_res, py = y * k.inv_res;
  return needs_clamp(px, py, k.reach)
             ? k.template score<kCountBackground, true>(px, py, theta, counts)
             : k.template score<kCountBackground, false>(px, py, theta, counts);
}

// The single piece of code that scores a particle range. Both the serial reference and
// every OpenMP work item call this same (non-inlined) function, so serial and parallel
// runs execute identical instructions per particle.
template <class Kernel>
[[gnu::noinline]] void score_range(const Kernel& k, const float* x, const float* y,
                                   const float* theta, std::size_t begin, std::size_t end,
                                   std::uint32_t* out) noexcept {
  for (std::size_t i = begin; i < end; ++i)
    out[i] = score_particle<false>(k, x[i], y[i], theta[i], nullptr);
}

}  // namespace

MeasurementModel::MeasurementModel(std::shared_ptr<const maps::LikelihoodField> field)
    : field_(std::move(field)) {
  if (!field_) throw std::invalid_argument("MeasurementModel: likelihood field is null");
  inv_res_ = static_cast<float>(1.0 / field_->resolution());
  // Below the background, so a beam off the map or beyond the kernel never counts as fitting.
  const std::uint8_t background = field_->quantise_m2(std::numeric_limits<double>::infinity());
  fit_q_ = std::min<std::uint8_t>(field_->quantise_m2(kFitSigmas * kFitSigmas),
                                  background > 0 ? background - 1 : 0);
}

void MeasurementModel::prepare(const LaserScan& scan, std::span<const std::uint32_t> selected) {
  const std::size_t m = selected.size();
  beams_.ex.resize(m);
  beams_.ey.resize(m);
  beams_.ux.resize(m);
  beams_.uy.resize(m);
  beams_.bin.resize(m);
  const double inv_res = 1.0 / field_->resolution();
  const bool oriented = field_->kind() == maps::TableKind::kOrientedBins;
  const maps::OrientedView ov = oriented ? field_->oriented() : maps::OrientedView{};
  const double bins = static_cast<double>(ov.bins);
  const double bins_per_radian = bins / std::numbers::pi;
  const Pose2& mount = scan.sensor_pose;
  float reach = 0.0f;
  for (std::size_t k = 0; k < m; ++k) {
    const std::uint32_t i = selected[k];
    const double a = scan.beam_angle(i);
    const double r = static_cast<double>(scan.ranges[i]);
    double bx = 0.0, by = 0.0;
    mount.transform_point(r * std::cos(a), r * std::sin(a), bx, by);
    const double dir = mount.theta + a;  // beam direction in the base frame
    beams_.ex[k] = static_cast<float>(bx * inv_res);
    beams_.ey[k] = static_cast<float>(by * inv_res);
    reach = std::max(reach, std::abs(beams_.ex[k]) + std::abs(beams_.ey[k]));
    beams_.ux[k] = static_cast<float>(std::cos(dir));
    beams_.uy[k] = static_cast<float>(std::sin(dir));
    if (oriented) {
      // Directions are taken modulo pi (the planar Gaussian is symmetric under u -> -u).
      double b = dir * bins_per_radian;
      b -= bins * std::floor(b / bins);
      const auto bf = static_cast<float>(b);  // rounding may reach `bins`: wrap to 0
      beams_.bin[k] = bf >= static_cast<float>(bins) ? 0.0f : bf;
    } else {
      beams_.bin[k] = 0.0f;
    }
  }
  beams_.reach = reach;
}

namespace {

// Builds the kernel for the field's kind and hands it to `fn`: the one dispatch per call.
template <class Fn>
void with_kernel(const maps::LikelihoodField& field, const PreparedBeams& b, float inv_res,
                 std::uint8_t fit_q, Fn&& fn) {
  switch (field.kind()) {
    case maps::TableKind::kIsotropic:
      fn(IsotropicKernel{field.isotropic(), b.ex.data(), b.ey.data(), b.size(), inv_res, b.reach,
                         fit_q});
      return;
    case maps::TableKind::kOrientedBins:
      fn(OrientedKernel{field.oriented(), b.ex.data(), b.ey.data(), b.bin.data(), b.size(), inv_res,
                        b.reach, fit_q});
      return;
    case maps::TableKind::kOffsetField:
      fn(OffsetKernel{field.offset(), b.ex.data(), b.ey.data(), b.ux.data(), b.uy.data(), b.size(),
                      inv_res, b.reach, fit_q});
      return;
  }
}

}  // namespace

void MeasurementModel::score_serial(std::span<const float> x, std::span<const float> y,
                                    std::span<const float> theta,
                                    std::span<std::uint32_t> sum_q) const noexcept {
  with_kernel(*field_, beams_, inv_res_, fit_q_, [&](const auto& k) {
    score_range(k, x.data(), y.data(), theta.data(), 0, sum_q.size(), sum_q.data());
  });
}

void MeasurementModel::score_parallel(std::span<const float> x, std::span<const float> y,
                                      std::span<const float> theta, std::span<std::uint32_t> sum_q,
                                      int threads) const noexcept {
  with_kernel(*field_, beams_, inv_res_, fit_q_, [&](const auto& k) {
    const std::size_t n = sum_q.size();
    detail::for_each_block(detail::block_count(n), threads, [&](std::size_t b) {
      const std::size_t lo = b * detail::kParticleBlock;
      score_range(k, x.data(), y.data(), theta.data(), lo, std::min(n, lo + detail::kParticleBlock),
                  sum_q.data());
    });
  });
}

PoseScore MeasurementModel::score_pose(double x, double y, double theta) const noexcept {
  PoseScore out;
  with_kernel(*field_, beams_, inv_res_, fit_q_, [&](const auto& k) {
    out.sum_q = score_particle<true>(k, static_cast<float>(x), static_cast<float>(y),
                                     static_cast<float>(theta), &out);
  });
  return out;
}

}  // namespace pgmcl
