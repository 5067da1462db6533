#pragma once
/// The only code that reads the likelihood tables per beam: one kernel per table kind.
///
/// A kernel scores one pose (map-local, in cells) against the beams of a scan prepared in
/// the robot's base frame (in cells): it rotates and translates every endpoint, floors it to
/// a cell, reads one q per beam (the background off the map) and sums q in uint32, which is
/// exact and order-independent. Beams go in chunks of kChunk through passes: the first,
/// shared by all kinds, maps endpoints to cells touching no memory but the beam arrays (the
/// compiler vectorises it); the kind's own passes then gather from its table.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>

#include "pgmcl/maps/likelihood_field.hpp"

namespace pgmcl::maps {

/// Beams of one scan in the robot base frame, in cells, as structure-of-arrays pointers.
struct BeamArrays {
  const float* ex = nullptr;   ///< endpoint x
  const float* ey = nullptr;   ///< endpoint y
  const float* ux = nullptr;   ///< unit direction x (offset kind)
  const float* uy = nullptr;   ///< unit direction y (offset kind)
  const float* bin = nullptr;  ///< direction in orientation bins, [0, bins) (oriented kind)
  std::size_t count = 0;
  float reach = 0.0f;  ///< max over beams of |ex| + |ey|: bounds any rotated endpoint
};

/// What a kernel counts besides the sum when asked to (kTally).
struct BeamTally {
  std::uint32_t background = 0;  ///< beams that read the background
  std::uint32_t fitting = 0;     ///< beams with q <= the kernel's fit_q
};

/// A beam direction (radians, grid frame, any value) in orientation bins over [0, pi): the
/// planar Gaussian is symmetric under u -> -u, so directions are taken modulo pi.
[[nodiscard]] inline float direction_in_bins(double direction, int bins) noexcept {
  const auto period = static_cast<double>(bins);
  double b = direction * (period / std::numbers::pi);
  b -= period * std::floor(b / period);
  const auto bf = static_cast<float>(b);  // rounding may reach `bins`: wrap to 0
  return bf >= static_cast<float>(bins) ? 0.0f : bf;
}

namespace detail {

inline constexpr std::size_t kChunk = 128;  // beams per pass (stack buffers of 512 bytes)

// A pose's rotation, computed in double and rounded once, so the value cannot depend on
// whether a compiler vectorises cos/sin differently in two call sites.
struct Rotation {
  float c, s;
  explicit Rotation(float theta) noexcept
      : c(static_cast<float>(std::cos(static_cast<double>(theta)))),
        s(static_cast<float>(std::sin(static_cast<double>(theta)))) {}
};

// Below this bound on |pose| + reach, floor_to_cell's clamps cannot act and the kernels use
// floor_to_cell_unclamped: same cells, but the transform loops vectorise (the clamps compile
// to branches there). Only poses thrown far off (or NaN) take the clamped path.
inline constexpr float kUnclampedLimit = 5.0e8f;
[[nodiscard]] inline bool needs_clamp(float px, float py, float reach) noexcept {
  return !(std::abs(px) + reach < kUnclampedLimit && std::abs(py) + reach < kUnclampedLimit);
}
template <bool kClamp>
[[nodiscard]] inline int to_cell(float c) noexcept {
  if constexpr (kClamp) return floor_to_cell(c);
  return floor_to_cell_unclamped(c);
}

// The shared first pass over beams [j0, j0 + len): endpoint cells, rows[k] = -1 off the map;
// kKeepCoords also keeps the fractional coordinates.
template <bool kClamp, bool kKeepCoords>
inline void endpoint_cells(const BeamArrays& b, std::size_t j0, std::size_t len, Rotation r,
                           float px, float py, int width, int height, std::int32_t* cols,
                           std::int32_t* rows, float* colf, float* rowf) noexcept {
  const float* const bx = b.ex + j0;
  const float* const by = b.ey + j0;
  for (std::size_t k = 0; k < len; ++k) {
    const float col = px + (r.c * bx[k] - r.s * by[k]);
    const float row = py + (r.s * bx[k] + r.c * by[k]);
    const int c = to_cell<kClamp>(col), rr = to_cell<kClamp>(row);
    const bool inside = (c >= 0) & (c < width) & (rr >= 0) & (rr < height);
    if constexpr (kKeepCoords) {
      colf[k] = col;
      rowf[k] = row;
    }
    cols[k] = c;
    rows[k] = inside ? rr : -1;
  }
}

// Sum of q, and with kTally the background and fitting counts.
template <bool kTally>
struct Accumulator {
  std::uint8_t background, fit_q;
  std::uint32_t sum = 0, bg = 0, fit = 0;
  void add(std::uint8_t q) noexcept {
    sum += q;
    if constexpr (kTally) {
      bg += (q == background) ? 1u : 0u;
      fit += (q <= fit_q) ? 1u : 0u;
    }
  }
  std::uint32_t finish(BeamTally* tally) const noexcept {
    if constexpr (kTally) *tally = {bg, fit};
    return sum;
  }
};

}  // namespace detail

/// Common part of the kernels: the beams, the cell size and the fitting threshold.
struct KernelBeams {
  BeamArrays beams;
  float inv_res = 1.0f;    ///< cells per metre
  std::uint8_t fit_q = 0;  ///< q at or below this counts as fitting the map
};

/// Isotropic table: after the shared pass, a bare byte gather.
struct IsotropicKernel {
  IsotropicView view;
  KernelBeams k;

  template <bool kTally, bool kClamp>
  std::uint32_t score(float px, float py, float theta, BeamTally* tally) const noexcept {
    const IsotropicView v = view;
    const detail::Rotation r(theta);
    alignas(16) std::int32_t cols[detail::kChunk], rows[detail::kChunk];
    detail::Accumulator<kTally> acc{v.background, k.fit_q};
    for (std::size_t j0 = 0; j0 < k.beams.count; j0 += detail::kChunk) {
      const std::size_t len = std::min(detail::kChunk, k.beams.count - j0);
      detail::endpoint_cells<kClamp, false>(k.beams, j0, len, r, px, py, v.width, v.height, cols,
                                            rows, nullptr, nullptr);
      for (std::size_t j = 0; j < len; ++j)
        acc.add(rows[j] >= 0
                    ? v.q[static_cast<std::size_t>(rows[j]) * static_cast<std::size_t>(v.width) +
                          static_cast<std::size_t>(cols[j])]
                    : v.background);
    }
    return acc.finish(tally);
  }
};

/// Oriented tables: the plane of each beam from its base-frame bin plus the pose's heading.
struct OrientedKernel {
  OrientedView view;
  KernelBeams k;

  template <bool kTally, bool kClamp>
  std::uint32_t score(float px, float py, float theta, BeamTally* tally) const noexcept {
    const OrientedView v = view;
    const detail::Rotation r(theta);
    const int bins = v.bins;
    const auto period = static_cast<float>(bins);
    // theta in (-pi, pi] -> [0, bins]; plus bin[j] in [0, bins) gives [0, 2 bins]: two
    // conditional subtractions bring any of those back to [0, bins).
    float tb = theta * v.bins_per_radian;
    tb += (tb < 0.0f) ? period : 0.0f;
    alignas(16) std::int32_t cols[detail::kChunk], rows[detail::kChunk], planes[detail::kChunk];
    detail::Accumulator<kTally> acc{v.background, k.fit_q};
    for (std::size_t j0 = 0; j0 < k.beams.count; j0 += detail::kChunk) {
      const std::size_t len = std::min(detail::kChunk, k.beams.count - j0);
      detail::endpoint_cells<kClamp, false>(k.beams, j0, len, r, px, py, v.width, v.height, cols,
                                            rows, nullptr, nullptr);
      const float* const bb = k.beams.bin + j0;
      for (std::size_t j = 0; j < len; ++j) {
        int b = static_cast<int>(tb + bb[j]);
        b = b >= bins ? b - bins : b;
        planes[j] = b >= bins ? b - bins : b;
      }
      for (std::size_t j = 0; j < len; ++j)
        acc.add(rows[j] >= 0
                    ? v.q[static_cast<std::size_t>(planes[j]) * v.plane_stride +
                          static_cast<std::size_t>(rows[j]) * static_cast<std::size_t>(v.width) +
                          static_cast<std::size_t>(cols[j])]
                    : v.background);
    }
    return acc.finish(tally);
  }
};

/// Offset field: gather the offset to the nearest obstacle, project it on the rotated beam
/// direction and its normal, and read q from the LUT over the squared Mahalanobis distance.
struct OffsetKernel {
  OffsetView view;
  KernelBeams k;

  template <bool kTally, bool kClamp>
  std::uint32_t score(float px, float py, float theta, BeamTally* tally) const noexcept {
    const OffsetView v = view;
    const detail::Rotation r(theta);
    alignas(16) float colf[detail::kChunk], rowf[detail::kChunk];
    alignas(16) float dirx[detail::kChunk], diry[detail::kChunk];
    alignas(16) std::int32_t cols[detail::kChunk], rows[detail::kChunk];
    alignas(16) std::int32_t dcs[detail::kChunk], drs[detail::kChunk], lut_idx[detail::kChunk];
    const float lut_last = static_cast<float>(v.lut_size - 1);
    detail::Accumulator<kTally> acc{v.background, k.fit_q};
    for (std::size_t j0 = 0; j0 < k.beams.count; j0 += detail::kChunk) {
      const std::size_t len = std::min(detail::kChunk, k.beams.count - j0);
      detail::endpoint_cells<kClamp, true>(k.beams, j0, len, r, px, py, v.width, v.height, cols,
                                           rows, colf, rowf);
      const float* const bux = k.beams.ux + j0;
      const float* const buy = k.beams.uy + j0;
      for (std::size_t j = 0; j < len; ++j) {
        dirx[j] = r.c * bux[j] - r.s * buy[j];
        diry[j] = r.s * bux[j] + r.c * buy[j];
      }
      for (std::size_t j = 0; j < len; ++j) {
        dcs[j] = OffsetView::kNoObstacle;
        drs[j] = 0;
        if (rows[j] < 0) continue;
        const std::size_t i =
            2 * (static_cast<std::size_t>(rows[j]) * static_cast<std::size_t>(v.width) +
                 static_cast<std::size_t>(cols[j]));
        dcs[j] = v.off[i];
        drs[j] = v.off[i + 1];
      }
      for (std::size_t j = 0; j < len; ++j) {
        // Vector from the endpoint to the obstacle cell's centre, in cells.
        const float dx = static_cast<float>(cols[j] + dcs[j]) + 0.5f - colf[j];
        const float dy = static_cast<float>(rows[j] + drs[j]) + 0.5f - rowf[j];
        const float along = dx * dirx[j] + dy * diry[j];
        const float across = dy * dirx[j] - dx * diry[j];
        const float m2 = along * along * v.inv_var_along + across * across * v.inv_var_across;
        const float idx = m2 * v.lut_steps_per_unit;
        const int li = idx < lut_last ? static_cast<int>(idx) : v.lut_size - 1;
        lut_idx[j] = dcs[j] == OffsetView::kNoObstacle ? -1 : li;
      }
      for (std::size_t j = 0; j < len; ++j)
        acc.add(lut_idx[j] >= 0 ? v.lut[lut_idx[j]] : v.background);
    }
    return acc.finish(tally);
  }
};

/// One pose in map-local metres: to cells, then the clamped kernel only if the endpoints
/// could leave the range where the clamps are inactive.
template <bool kTally, class Kernel>
[[nodiscard]] inline std::uint32_t score_pose(const Kernel& kernel, float x, float y, float theta,
                                              BeamTally* tally) noexcept {
  const float px = x * kernel.k.inv_res, py = y * kernel.k.inv_res;
  return detail::needs_clamp(px, py, kernel.k.beams.reach)
             ? kernel.template score<kTally, true>(px, py, theta, tally)
             : kernel.template score<kTally, false>(px, py, theta, tally);
}

/// Builds the kernel for the field's kind and hands it to `fn`: the one dispatch per call.
template <class Fn>
void with_kernel(const LikelihoodField& field, const BeamArrays& beams, std::uint8_t fit_q,
                 Fn&& fn) {
  const KernelBeams k{beams, static_cast<float>(1.0 / field.resolution()), fit_q};
  switch (field.kind()) {
    case TableKind::kIsotropic:
      fn(IsotropicKernel{field.isotropic(), k});
      return;
    case TableKind::kOrientedBins:
      fn(OrientedKernel{field.oriented(), k});
      return;
    case TableKind::kOffsetField:
      fn(OffsetKernel{field.offset(), k});
      return;
  }
}

}  // namespace pgmcl::maps
