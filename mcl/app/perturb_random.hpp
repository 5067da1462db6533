#pragma once
/// The random streams of `pgmcl perturb` and `pgmcl perturb-map`, all derived from --seed.
///
/// The odometry noise draws from Rng(seed), as it did before the other conditions existed,
/// so an old case reproduces bit for bit. Every other condition draws from its own stream
/// (Rng::for_block(seed, stream, 0)): switching one condition on or off, or changing its
/// rate, leaves the draws of all the others unchanged, and `--glitch 0,30` reproduces the
/// case without glitches exactly.

#include <cstdint>

#include "pgmcl/common/random.hpp"

namespace pgmcl::app {

enum class PerturbStream : std::uint64_t {
  kHeadingGlitch = 1,      ///< --glitch: which steps, magnitude, sign
  kTranslationGlitch = 2,  ///< --translation-glitch: which steps, direction
  kBeamDropout = 3,        ///< --beam-dropout: sector lengths and positions
  kMapErase = 4,           ///< perturb-map --erase: which blocks
};

[[nodiscard]] inline Rng perturb_rng(std::uint64_t seed, PerturbStream stream) noexcept {
  return Rng::for_block(seed, static_cast<std::uint64_t>(stream), 0);
}

}  // namespace pgmcl::app
