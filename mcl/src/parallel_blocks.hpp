#pragma once
// Internal: run fn(block) for every block index, serially or with OpenMP.
// Deterministic by construction as long as fn(block) touches only its own block's data
// and draws only from its own stream (Rng::for_block(seed, step, block)).

#include <cstddef>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace pgmcl::detail {

/// Particles per block: the unit of RNG streams and of parallel work. Fixed, so the
/// random numbers a particle sees do not depend on the thread count.
inline constexpr std::size_t kParticleBlock = 256;

[[nodiscard]] inline std::size_t block_count(std::size_t n) noexcept {
  return (n + kParticleBlock - 1) / kParticleBlock;
}

/// threads == 1: plain serial loop (the reference); otherwise an OpenMP loop with a
/// num_threads clause (0 = OpenMP's default), never omp_set_num_threads (global state).
/// Blocks are handed out one at a time (dynamic schedule): a thread whose core is shared
/// with another process takes fewer of them instead of holding the team up. Which thread
/// runs a block does not change its result.
template <class Fn>
void for_each_block(std::size_t blocks, int threads, Fn&& fn) {
#ifdef _OPENMP
  if (threads != 1) {
    const int nt = threads > 0 ? threads : omp_get_max_threads();
    const auto nb = static_cast<std::ptrdiff_t>(blocks);
#pragma omp parallel for schedule(dynamic, 1) num_threads(nt)
    for (std::ptrdiff_t b = 0; b < nb; ++b) fn(static_cast<std::size_t>(b));
    return;
  }
#else
  (void)threads;
#endif
  for (std::size_t b = 0; b < blocks; ++b) fn(b);
}

/// Runs side() on one thread of a team while the others work through fn(block) for every
/// block, and that thread joins them once side() returns; threads == 1: side(), then the
/// blocks in order. side() must touch nothing the blocks read or write.
template <class Side, class Fn>
void alongside(int threads, Side&& side, std::size_t blocks, Fn&& fn) {
#ifdef _OPENMP
  if (threads != 1) {
    const int nt = threads > 0 ? threads : omp_get_max_threads();
    const auto nb = static_cast<std::ptrdiff_t>(blocks);
#pragma omp parallel num_threads(nt)
    {
#pragma omp single nowait
      side();
#pragma omp for schedule(dynamic, 1) nowait
      for (std::ptrdiff_t b = 0; b < nb; ++b) fn(static_cast<std::size_t>(b));
    }
    return;
  }
#else
  (void)threads;
#endif
  side();
  for (std::size_t b = 0; b < blocks; ++b) fn(b);
}

}  // namespace pgmcl::detail
