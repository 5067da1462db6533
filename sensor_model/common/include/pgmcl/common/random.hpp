#pragma once
/// Explicit, seedable random streams. No global state: every consumer owns its generator.
/// Parallel code draws from one stream per particle block, keyed by (seed, step, block),
/// so the same seed gives the same numbers for any thread count.

#include <cmath>
#include <cstdint>
#include <numbers>

namespace pgmcl {

/// SplitMix64 finaliser: a good 64-bit mixer used to derive stream seeds.
[[nodiscard]] constexpr std::uint64_t splitmix64(std::uint64_t z) noexcept {
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

/// xoshiro256** (Blackman & Vigna): small state, fast, good quality.
class Rng {
 public:
  explicit Rng(std::uint64_t seed = 0x5EEDu) noexcept { reseed(seed); }

  /// An independent stream for (seed, step, block): the per-particle-block stream.
  [[nodiscard]] static Rng for_block(std::uint64_t seed, std::uint64_t step,
                                     std::uint64_t block) noexcept {
    return Rng(splitmix64(seed ^ splitmix64(step * 0x9E3779B97F4A7C15ull ^ splitmix64(block))));
  }

  void reseed(std::uint64_t seed) noexcept {
    std::uint64_t z = seed;
    for (auto& w : s_) w = splitmix64(z += 0x9E3779B97F4A7C15ull);
    has_spare_ = false;
  }

  [[nodiscard]] std::uint64_t next_u64() noexcept {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }
  /// Uniform in [0, 1).
  [[nodiscard]] double uniform() noexcept {
    return static_cast<double>(next_u64() >> 11) * 0x1.0p-53;
  }
  /// Uniform in [lo, hi).
  [[nodiscard]] double uniform(double lo, double hi) noexcept { return lo + (hi - lo) * uniform(); }
  /// Uniform integer in [0, n), n > 0 (Lemire's nearly-divisionless method, unbiased).
  [[nodiscard]] std::uint64_t below(std::uint64_t n) noexcept {
    __uint128_t m = static_cast<__uint128_t>(next_u64()) * n;
    auto low = static_cast<std::uint64_t>(m);
    if (low < n) {
      const std::uint64_t threshold = (0 - n) % n;
      while (low < threshold) {
        m = static_cast<__uint128_t>(next_u64()) * n;
        low = static_cast<std::uint64_t>(m);
      }
    }
    return static_cast<std::uint64_t>(m >> 64);
  }
  /// Standard normal (Marsaglia polar method; deterministic across platforms given libm).
  [[nodiscard]] double normal() noexcept {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    double u = 0.0, v = 0.0, s = 0.0;
    do {
      u = 2.0 * uniform() - 1.0;
      v = 2.0 * uniform() - 1.0;
      s = u * u + v * v;
    } while (s >= 1.0 || s == 0.0);
    const double f = std::sqrt(-2.0 * std::log(s) / s);
    spare_ = v * f;
    has_spare_ = true;
    return u * f;
  }
  /// N(0, sigma^2); sigma <= 0 gives 0.
  [[nodiscard]] double normal(double sigma) noexcept {
    return sigma > 0.0 ? sigma * normal() : 0.0;
  }

 private:
  static constexpr std::uint64_t rotl(std::uint64_t x, int k) noexcept {
    return (x << k) | (x >> (64 - k));
  }
  std::uint64_t s_[4]{};
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace pgmcl
