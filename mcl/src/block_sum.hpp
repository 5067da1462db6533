#pragma once
// Internal: deterministic parallel sums. The range is cut into fixed-size blocks, each
// block is summed serially into its own partial, and the partials are added in block
// order. The blocking does not depend on the thread count or on which thread sums a block
// (blocks are handed out dynamically, see parallel_blocks.hpp), so threads = 1 (the serial
// reference) and any OpenMP team give bit-identical doubles.

#include <array>
#include <cstddef>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace pgmcl::detail {

inline constexpr std::size_t kSumBlock = 1024;  // particles per partial sum

/// Returns sum over blocks of body(begin, end, partial), where body adds the terms of
/// [begin, end) into `partial` (zero-initialised). threads: 1 = serial, 0 = OpenMP default,
/// n = a team of n (a num_threads clause, never the global omp_set_num_threads).
template <std::size_t K, class Body>
[[nodiscard]] std::array<double, K> block_sum(std::size_t n, int threads, Body&& body) {
  using Partial = std::array<double, K>;
  const std::size_t blocks = (n + kSumBlock - 1) / kSumBlock;
  std::vector<Partial> partials(blocks, Partial{});
  const auto run = [&](std::size_t b) {
    const std::size_t begin = b * kSumBlock;
    const std::size_t end = begin + kSumBlock < n ? begin + kSumBlock : n;
    body(begin, end, partials[b]);
  };
#ifdef _OPENMP
  if (threads != 1 && blocks > 1) {
    const int team = threads > 0 ? threads : omp_get_max_threads();
    const auto nb = static_cast<std::ptrdiff_t>(blocks);
#pragma omp parallel for schedule(dynamic, 1) num_threads(team)
    for (std::ptrdiff_t b = 0; b < nb; ++b) run(static_cast<std::size_t>(b));
  } else {
    for (std::size_t b = 0; b < blocks; ++b) run(b);
  }
#else
  (void)threads;
  for (std::size_t b = 0; b < blocks; ++b) run(b);
#endif
  Partial total{};
  for (const Partial& p : partials) {
    for (std::size_t k = 0; k < K; ++k) total[k] += p[k];
  }
  return total;
}

}  // namespace pgmcl::detail
