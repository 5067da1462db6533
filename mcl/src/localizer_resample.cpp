// Localizer: selective resampling, KLD-sized output, augmented-MCL random injection.
#include <algorithm>
#include <cmath>
#include <utility>

#include "pgmcl/mcl/kld_sampling.hpp"
#include "pgmcl/mcl/localizer.hpp"
#include "pgmcl/mcl/resampling.hpp"
#include "stream_keys.hpp"

namespace pgmcl {

std::size_t Localizer::kld_sample_count(Rng& rng, double p_inject, Rng& inject_rng) {
  // Fox 2003, Table 1: draw particles one at a time, count the histogram bins k they
  // occupy, and stop once n reaches the bound n(k) for (epsilon, delta). Each draw is,
  // with probability p_inject, a random free-space pose (Table 8.3), kept in inj_*; those
  // fill new bins, so a lost filter automatically gets more particles (as in AMCL).
  // The draws from the weighted set only size the output: its particles then come from
  // the low-variance systematic sampler (lower variance than i.i.d. draws, same count).
  const KldConfig& kc = cfg_.filter.kld;
  const std::size_t n = p_.size();
  cum_.resize(n);
  double acc = 0.0;
  for (std::size_t i = 0; i < n; ++i) cum_[i] = (acc += p_.w[i]);
  binner_.clear();
  inj_x_.clear();
  inj_y_.clear();
  inj_theta_.clear();
  std::size_t drawn = 0, bound = kc.min_particles;
  while (drawn < kc.max_particles && (drawn < bound || drawn < kc.min_particles)) {
    float x = 0.0f, y = 0.0f, theta = 0.0f;
    if (p_inject > 0.0 && inject_rng.uniform() < p_inject) {
      const Pose2 q = random_free_pose(inject_rng);
      x = static_cast<float>(q.x);
      y = static_cast<float>(q.y);
      theta = wrap_angle(static_cast<float>(q.theta));
      inj_x_.push_back(x);
      inj_y_.push_back(y);
      inj_theta_.push_back(theta);
    } else {
      const double u = rng.uniform() * acc;
      const auto it = std::upper_bound(cum_.begin(), cum_.end(), u);
      const auto i = std::min<std::size_t>(static_cast<std::size_t>(it - cum_.begin()), n - 1);
      x = p_.x[i];
      y = p_.y[i];
      theta = p_.theta[i];
    }
    if (binner_.insert(x, y, theta))
      bound = kld_required_particles(binner_.occupied(), kc.epsilon, kld_z_);
    ++drawn;
  }
  return std::max<std::size_t>(drawn, 1);
}

void Localizer::resample(UpdateResult& r) {
  const std::size_t n = p_.size();
  const RecoveryConfig& rc = cfg_.filter.recovery;
  // Probabilistic Robotics, Table 8.3, line 13: inject with probability
  // max(0, 1 - w_fast / w_slow), with w_slow scaled by RecoveryConfig::threshold.
  const double p_inject = (rc.enabled && have_averages_ && w_slow_ > 0.0)
                              ? std::max(0.0, 1.0 - w_fast_ / (rc.threshold * w_slow_))
                              : 0.0;
  const bool degenerate = r.n_eff < cfg_.filter.resample_threshold * static_cast<double>(n);
  // Resample when the weights degenerated, or when at least one injection is expected
  // (injection happens during resampling, Table 8.3).
  const bool inject = p_inject * static_cast<double>(n) >= 1.0;
  if (!degenerate && !inject) return;

  const std::uint64_t step = next_step();
  Rng rng = Rng::for_block(cfg_.seed, step, detail::kStreamResample);
  Rng irng = Rng::for_block(cfg_.seed, step, detail::kStreamInject);
  std::size_t n_out = 0;
  if (cfg_.filter.kld.enabled) {
    n_out = kld_sample_count(rng, p_inject, irng);
  } else {
    n_out = cfg_.filter.particles;
    inj_x_.clear();
    inj_y_.clear();
    inj_theta_.clear();
    for (std::size_t i = 0; i < n_out; ++i) {
      if (p_inject <= 0.0 || irng.uniform() >= p_inject) continue;
      const Pose2 q = random_free_pose(irng);
      inj_x_.push_back(static_cast<float>(q.x));
      inj_y_.push_back(static_cast<float>(q.y));
      inj_theta_.push_back(wrap_angle(static_cast<float>(q.theta)));
    }
  }
  const std::size_t injected = std::min(inj_x_.size(), n_out);
  const std::size_t n_keep = n_out - injected;
  if (n_keep > 0) systematic_resample(p_.w, n_keep, rng, idx_);
  tmp_x_.resize(n_out);
  tmp_y_.resize(n_out);
  tmp_theta_.resize(n_out);
  const std::span<const std::uint32_t> idx(idx_.data(), n_keep);
  gather<float>(p_.x, idx, std::span<float>(tmp_x_).first(n_keep));
  gather<float>(p_.y, idx, std::span<float>(tmp_y_).first(n_keep));
  gather<float>(p_.theta, idx, std::span<float>(tmp_theta_).first(n_keep));
  std::copy_n(inj_x_.begin(), injected, tmp_x_.begin() + static_cast<std::ptrdiff_t>(n_keep));
  std::copy_n(inj_y_.begin(), injected, tmp_y_.begin() + static_cast<std::ptrdiff_t>(n_keep));
  std::copy_n(inj_theta_.begin(), injected,
              tmp_theta_.begin() + static_cast<std::ptrdiff_t>(n_keep));
  std::swap(p_.x, tmp_x_);
  std::swap(p_.y, tmp_y_);
  std::swap(p_.theta, tmp_theta_);
  p_.resize(n_out);
  if (injected > 0) w_fast_ = w_slow_;  // bursts, see RecoveryConfig
  tmp_probation_.resize(n_out);
  gather<std::uint8_t>(probation_, idx, std::span<std::uint8_t>(tmp_probation_).first(n_keep));
  std::fill(tmp_probation_.begin() + static_cast<std::ptrdiff_t>(n_keep), tmp_probation_.end(),
            static_cast<std::uint8_t>(rc.probation));
  std::swap(probation_, tmp_probation_);
  p_.set_uniform_weights();
  r.resampled = true;
  r.injected = injected;
}

}  // namespace pgmcl
