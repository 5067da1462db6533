#include "pgmcl/mcl/measurement_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "parallel_blocks.hpp"
#include "pgmcl/maps/table_kernels.hpp"

namespace pgmcl {
namespace {

// The single piece of code that scores a particle range. Both the serial reference and
// every OpenMP work item call this same (non-inlined) function, so serial and parallel
// runs execute identical instructions per particle.
template <class Kernel>
[[gnu::noinline]] void score_range(const Kernel& k, const float* x, const float* y,
                                   const float* theta, std::size_t begin, std::size_t end,
                                   std::uint32_t* out) noexcept {
  for (std::size_t i = begin; i < end; ++i)
    out[i] = maps::score_pose<false>(k, x[i], y[i], theta[i], nullptr);
}

}  // namespace

MeasurementModel::MeasurementModel(std::shared_ptr<const maps::LikelihoodField> field)
    : field_(std::move(field)) {
  if (!field_) throw std::invalid_argument("MeasurementModel: likelihood field is null");
  // Below the background, so a beam off the map or beyond the kernel never counts as fitting.
  const sensor_model::BeamLikelihood& m = field_->model();
  fit_q_ = std::min<std::uint8_t>(m.quantise_m2(kFitSigmas * kFitSigmas),
                                  m.background() > 0 ? m.background() - 1 : 0);
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
  const int bins = field_->oriented().bins;
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
    beams_.bin[k] = oriented ? maps::direction_in_bins(dir, bins) : 0.0f;
  }
  beams_.reach = reach;
}

void MeasurementModel::score_serial(std::span<const float> x, std::span<const float> y,
                                    std::span<const float> theta,
                                    std::span<std::uint32_t> sum_q) const noexcept {
  maps::with_kernel(*field_, beams_.arrays(), fit_q_, [&](const auto& k) {
    score_range(k, x.data(), y.data(), theta.data(), 0, sum_q.size(), sum_q.data());
  });
}

void MeasurementModel::score_parallel(std::span<const float> x, std::span<const float> y,
                                      std::span<const float> theta, std::span<std::uint32_t> sum_q,
                                      int threads) const noexcept {
  maps::with_kernel(*field_, beams_.arrays(), fit_q_, [&](const auto& k) {
    const std::size_t n = sum_q.size();
    detail::for_each_block(detail::block_count(n), threads, [&](std::size_t b) {
      const std::size_t lo = b * detail::kParticleBlock;
      score_range(k, x.data(), y.data(), theta.data(), lo, std::min(n, lo + detail::kParticleBlock),
                  sum_q.data());
    });
  });
}

void MeasurementModel::score_block(std::span<const float> x, std::span<const float> y,
                                   std::span<const float> theta, std::size_t begin, std::size_t end,
                                   std::span<std::uint32_t> sum_q) const noexcept {
  maps::with_kernel(*field_, beams_.arrays(), fit_q_, [&](const auto& k) {
    score_range(k, x.data(), y.data(), theta.data(), begin, end, sum_q.data());
  });
}

PoseScore MeasurementModel::score_pose(double x, double y, double theta) const noexcept {
  PoseScore out;
  maps::with_kernel(*field_, beams_.arrays(), fit_q_, [&](const auto& k) {
    maps::BeamTally tally;
    out.sum_q = maps::score_pose<true>(k, static_cast<float>(x), static_cast<float>(y),
                                       static_cast<float>(theta), &tally);
    out.background = tally.background;
    out.fitting = tally.fitting;
  });
  return out;
}

}  // namespace pgmcl
