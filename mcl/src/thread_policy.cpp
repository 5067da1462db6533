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

double ThreadPolicy::Samples::median() const noexcept {
  std::array<double, kWindow> s = v;
  for (std::size_t i = 1; i < n; ++i)  // insertion sort of the n samples held
    for (std::size_t j = i; j > 0 && s[j - 1] > s[j]; --j) std::swap(s[j - 1], s[j]);
  return n % 2 == 1 ? s[n / 2] : 0.5 * (s[n / 2 - 1] + s[n / 2]);
}

int ThreadPolicy::next() noexcept {
  if (team_ == 1) return 1;
  ++updates_;
  const Samples& other = team_preferred_ ? serial_ : team_samples_;
  const bool tryout = updates_ > kWarmup && (other.n == 0 || retry_ || updates_ % kProbeEvery == 0);
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
  // A try that beat the preferred count is repeated until its median decides.
  if (team != team_preferred_ && preferred.n > 0 && cost < preferred.median()) retry_ = true;
  mine.add(cost);
  const bool was = team_preferred_;
  if (serial_.n > 0 && team_samples_.n > 0)
    team_preferred_ = team_samples_.median() <= serial_.median();
  if (team_preferred_ != was) retry_ = false;
}

}  // namespace pgmcl
