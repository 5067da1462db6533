#include "pgmcl/mcl/thread_policy.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace pgmcl {

void ThreadPolicy::Samples::add(double x) noexcept {
  v[next] = x;
  next = (next + 1) % kWindow;
  n = std::min(n + 1, kWindow);
}

double ThreadPolicy::Samples::mean() const noexcept {
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) sum += v[i];
  return n > 0 ? sum / static_cast<double>(n) : 0.0;
}

int ThreadPolicy::next() noexcept {
  if (team_ == 1) return 1;
  ++updates_;
  const Samples& other = team_preferred_ ? serial_ : team_samples_;
  const bool tryout = updates_ > kWarmup && (other.n == 0 || retry_ || updates_ >= next_try_);
  retry_ = false;
  return team_preferred_ != tryout ? team_ : 1;
}

void ThreadPolicy::record(int threads, double ms, double work) noexcept {
  if (team_ == 1 || !(ms > 0.0) || !(work > 0.0) || !std::isfinite(ms) || !std::isfinite(work))
    return;
  const double cost = ms / work;
  const bool team = threads != 1;
  Samples& mine = team ? team_samples_ : serial_;
  const Samples& preferred = team_preferred_ ? team_samples_ : serial_;
  if (team != team_preferred_) {
    // A try: one that beat the preferred count is repeated until the means decide; one
    // that lost makes the next try wait twice as long.
    const bool won = preferred.n == 0 || cost < preferred.mean();
    retry_ = won && preferred.n > 0;
    schedule_try(won ? kProbeEvery : std::min(2 * interval_, kMaxProbeEvery));
  }
  mine.add(cost);
  const bool was = team_preferred_;
  if (serial_.n > 0 && team_samples_.n > 0)
    team_preferred_ = team_samples_.mean() <= serial_.mean();
  if (team_preferred_ != was) {
    retry_ = false;
    schedule_try(kProbeEvery);
  }
}

void ThreadPolicy::schedule_try(std::uint64_t interval) noexcept {
  interval_ = interval;
  next_try_ = updates_ + interval;
}

}  // namespace pgmcl
