#include "pgmcl/mcl/measurement_model.hpp"

#include <algorithm>
#include <cmath>
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

// The three kernels share one shape: transform the base-frame endpoint of beam j by the
// particle pose (in cells), read q, add. Only the lookup differs.
struct IsotropicKernel {
  maps::IsotropicView view;
  const float* ex;
  const float* ey;
  std::size_t m;
  float inv_res;

  template <bool kCountBackground>
  std::uint32_t score(float x, float y, float theta, std::uint32_t* background) const noexcept {
    const float px = x * inv_res, py = y * inv_res;
    const Rot r = rotation_of(theta);
    std::uint32_t sum = 0, bg = 0;
    for (std::size_t j = 0; j < m; ++j) {
      const float col = px + (r.c * ex[j] - r.s * ey[j]);
      const float row = py + (r.s * ex[j] + r.c * ey[j]);
      const std::uint8_t q = view.lookup(col, row);
      sum += q;
      if constexpr (kCountBackground) bg += (q == view.background) ? 1u : 0u;
    }
    if constexpr (kCountBackground) *background = bg;
    return sum;
  }
};

struct OrientedKernel {
  maps::OrientedView view;
  const float* ex;
  const float* ey;
  const float* bin;  // beam direction in the base frame, in bins, [0, bins)
  std::size_t m;
  float inv_res;

  template <bool kCountBackground>
  std::uint32_t score(float x, float y, float theta, std::uint32_t* background) const noexcept {
    const float px = x * inv_res, py = y * inv_res;
    const Rot r = rotation_of(theta);
    const int bins = view.bins;
    const auto period = static_cast<float>(bins);
    // theta in (-pi, pi] -> [0, bins]; plus bin[j] in [0, bins) gives [0, 2 bins]:
    // two conditional subtractions bring any of those back to [0, bins).
    float tb = theta * view.bins_per_radian;
    tb += (tb < 0.0f) ? period : 0.0f;
    std::uint32_t sum = 0, bg = 0;
    for (std::size_t j = 0; j < m; ++j) {
      const float col = px + (r.c * ex[j] - r.s * ey[j]);
      const float row = py + (r.s * ex[j] + r.c * ey[j]);
      int b = static_cast<int>(tb + bin[j]);
      b = b >= bins ? b - bins : b;
      b = b >= bins ? b - bins : b;
      const std::uint8_t q = view.lookup(col, row, b);
      sum += q;
      if constexpr (kCountBackground) bg += (q == view.background) ? 1u : 0u;
    }
    if constexpr (kCountBackground) *background = bg;
    return sum;
  }
};

struct OffsetKernel {
  maps::OffsetView view;
  const float* ex;
  const float* ey;
  const float* ux;
  const float* uy;
  std::size_t m;
  float inv_res;

  template <bool kCountBackground>
  std::uint32_t score(float x, float y, float theta, std::uint32_t* background) const noexcept {
    const float px = x * inv_res, py = y * inv_res;
    const Rot r = rotation_of(theta);
    std::uint32_t sum = 0, bg = 0;
    for (std::size_t j = 0; j < m; ++j) {
      const float col = px + (r.c * ex[j] - r.s * ey[j]);
      const float row = py + (r.s * ex[j] + r.c * ey[j]);
      const float dx = r.c * ux[j] - r.s * uy[j];
      const float dy = r.s * ux[j] + r.c * uy[j];
      const std::uint8_t q = view.lookup(col, row, dx, dy);
      sum += q;
      if constexpr (kCountBackground) bg += (q == view.background) ? 1u : 0u;
    }
    if constexpr (kCountBackground) *background = bg;
    return sum;
  }
};

// The single piece of code that scores a particle range. Both the serial reference and
// every OpenMP work item call this same (non-inlined) function, so serial and parallel
// runs execute identical instructions per particle.
template <class Kernel>
[[gnu::noinline]] void score_range(const Kernel& k, const float* x, const float* y,
                                   const float* theta, std::size_t begin, std::size_t end,
                                   std::uint32_t* out) noexcept {
  for (std::size_t i = begin; i < end; ++i)
    out[i] = k.template score<false>(x[i], y[i], theta[i], nullptr);
}

}  // namespace

MeasurementModel::MeasurementModel(std::shared_ptr<const maps::LikelihoodField> field)
    : field_(std::move(field)) {
  if (!field_) throw std::invalid_argument("MeasurementModel: likelihood field is null");
  inv_res_ = static_cast<float>(1.0 / field_->resolution());
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
  for (std::size_t k = 0; k < m; ++k) {
    const std::uint32_t i = selected[k];
    const double a = scan.beam_angle(i);
    const double r = static_cast<double>(scan.ranges[i]);
    double bx = 0.0, by = 0.0;
    mount.transform_point(r * std::cos(a), r * std::sin(a), bx, by);
    const double dir = mount.theta + a;  // beam direction in the base frame
    beams_.ex[k] = static_cast<float>(bx * inv_res);
    beams_.ey[k] = static_cast<float>(by * inv_res);
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
}

namespace {

// Builds the kernel for the field's kind and hands it to `fn`: the one dispatch per call.
template <class Fn>
void with_kernel(const maps::LikelihoodField& field, const PreparedBeams& b, float inv_res,
                 Fn&& fn) {
  switch (field.kind()) {
    case maps::TableKind::kIsotropic:
      fn(IsotropicKernel{field.isotropic(), b.ex.data(), b.ey.data(), b.size(), inv_res});
      return;
    case maps::TableKind::kOrientedBins:
      fn(OrientedKernel{field.oriented(), b.ex.data(), b.ey.data(), b.bin.data(), b.size(),
                        inv_res});
      return;
    case maps::TableKind::kOffsetField:
      fn(OffsetKernel{field.offset(), b.ex.data(), b.ey.data(), b.ux.data(), b.uy.data(), b.size(),
                      inv_res});
      return;
  }
}

}  // namespace

void MeasurementModel::score_serial(std::span<const float> x, std::span<const float> y,
                                    std::span<const float> theta,
                                    std::span<std::uint32_t> sum_q) const noexcept {
  with_kernel(*field_, beams_, inv_res_, [&](const auto& k) {
    score_range(k, x.data(), y.data(), theta.data(), 0, sum_q.size(), sum_q.data());
  });
}

void MeasurementModel::score_parallel(std::span<const float> x, std::span<const float> y,
                                      std::span<const float> theta, std::span<std::uint32_t> sum_q,
                                      int threads) const noexcept {
  with_kernel(*field_, beams_, inv_res_, [&](const auto& k) {
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
  with_kernel(*field_, beams_, inv_res_, [&](const auto& k) {
    out.sum_q = k.template score<true>(static_cast<float>(x), static_cast<float>(y),
                                       static_cast<float>(theta), &out.background);
  });
  return out;
}

}  // namespace pgmcl
