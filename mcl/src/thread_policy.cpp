#include "pgmcl/mcl/thread_policy.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#ifdef __linux__
#include <sched.h>
#endif

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

bool run_queue_full(const char* loadavg, int cores) noexcept {
  int running = 0, total = 0;  // "0.50 0.40 0.30 2/345 6789": runnable / all entities
  if (std::sscanf(loadavg, "%*f %*f %*f %d/%d", &running, &total) != 2) return false;
  // `running` counts the caller too: the others take every core but its own.
  return cores > 1 && running >= cores;
}

bool cores_taken() noexcept {
#ifdef __linux__
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  if (sched_getaffinity(0, sizeof(allowed), &allowed) != 0) return false;
  std::FILE* f = std::fopen("/proc/loadavg", "r");
  if (f == nullptr) return false;
  char text[128] = {};
  const bool read = std::fgets(text, sizeof(text), f) != nullptr;
  std::fclose(f);
  return read && run_queue_full(text, CPU_COUNT(&allowed));
#else
  return false;
#endif
}

int ThreadPolicy::next() noexcept {
  if (team_ == 1) return 1;
  ++updates_;
  // Beside busy cores, start on one thread; the team gets its tries as usual.
  if (updates_ == 1 && probe_ != nullptr && probe_()) team_preferred_ = false;
  bool tryout = updates_ > kWarmup && (updates_ == kWarmup + 1 || retry_ || updates_ >= next_try_);
  retry_ = false;
  if (tryout && !team_preferred_ && probe_ != nullptr && probe_()) {
    tryout = false;  // the team would wait out the others' time slices: a lost try
    schedule_try(std::min(2 * interval_, kMaxProbeEvery));
  }
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
