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
  ws_.cumulative_w.resize(n);
  double acc = 0.0;
  for (std::size_t i = 0; i < n; ++i) ws_.cumulative_w[i] = (acc += p_.w[i]);
  binner_.clear();
  ws_.injected_x.clear();
  ws_.injected_y.clear();
  ws_.injected_theta.clear();
  std::size_t drawn = 0, bound = kc.min_particles;
  while (drawn < kc.max_particles && (drawn < bound || drawn < kc.min_particles)) {
    float x = 0.0f, y = 0.0f, theta = 0.0f;
    if (p_inject > 0.0 && inject_rng.uniform() < p_inject) {
      const Pose2 q = random_free_pose(inject_rng);
      x = static_cast<float>(q.x);
      y = static_cast<float>(q.y);
      theta = wrap_angle(static_cast<float>(q.theta));
      ws_.injected_x.push_back(x);
      ws_.injected_y.push_back(y);
      ws_.injected_theta.push_back(theta);
    } else {
      const double u = rng.uniform() * acc;
      const auto it = std::upper_bound(ws_.cumulative_w.begin(), ws_.cumulative_w.end(), u);
      const auto i =
          std::min<std::size_t>(static_cast<std::size_t>(it - ws_.cumulative_w.begin()), n - 1);
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
  // max(0, 1 - w_fast / w_slow).
  const double p_inject = (rc.enabled && have_averages_ && w_slow_ > 0.0)
                              ? std::max(0.0, 1.0 - w_fast_ / w_slow_)
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
    ws_.injected_x.clear();
    ws_.injected_y.clear();
    ws_.injected_theta.clear();
    for (std::size_t i = 0; i < n_out; ++i) {
      if (p_inject <= 0.0 || irng.uniform() >= p_inject) continue;
      const Pose2 q = random_free_pose(irng);
      ws_.injected_x.push_back(static_cast<float>(q.x));
      ws_.injected_y.push_back(static_cast<float>(q.y));
      ws_.injected_theta.push_back(wrap_angle(static_cast<float>(q.theta)));
    }
  }
  const std::size_t injected = std::min(ws_.injected_x.size(), n_out);
  const std::size_t n_keep = n_out - injected;
  if (n_keep > 0) systematic_resample(p_.w, n_keep, rng, ws_.ancestors);
  ws_.next_x.resize(n_out);
  ws_.next_y.resize(n_out);
  ws_.next_theta.resize(n_out);
  const std::span<const std::uint32_t> idx(ws_.ancestors.data(), n_keep);
  gather<float>(p_.x, idx, std::span<float>(ws_.next_x).first(n_keep));
  gather<float>(p_.y, idx, std::span<float>(ws_.next_y).first(n_keep));
  gather<float>(p_.theta, idx, std::span<float>(ws_.next_theta).first(n_keep));
  std::copy_n(ws_.injected_x.begin(), injected,
              ws_.next_x.begin() + static_cast<std::ptrdiff_t>(n_keep));
  std::copy_n(ws_.injected_y.begin(), injected,
              ws_.next_y.begin() + static_cast<std::ptrdiff_t>(n_keep));
  std::copy_n(ws_.injected_theta.begin(), injected,
              ws_.next_theta.begin() + static_cast<std::ptrdiff_t>(n_keep));
  std::swap(p_.x, ws_.next_x);
  std::swap(p_.y, ws_.next_y);
  std::swap(p_.theta, ws_.next_theta);
  p_.resize(n_out);
  if (injected > 0) w_fast_ = w_slow_;  // bursts, see RecoveryConfig
  ws_.next_probation.resize(n_out);
  gather<std::uint8_t>(probation_, idx, std::span<std::uint8_t>(ws_.next_probation).first(n_keep));
  std::fill(ws_.next_probation.begin() + static_cast<std::ptrdiff_t>(n_keep),
            ws_.next_probation.end(), static_cast<std::uint8_t>(rc.probation));
  std::swap(probation_, ws_.next_probation);
  p_.set_uniform_weights();
  r.resampled = true;
  r.injected = injected;
}

}  // namespace pgmcl
