#pragma once
// Internal: the block keys of the Localizer's random streams. Motion uses the particle
// block index (< 2^32) as the key; everything else draws from a stream whose key cannot
// collide with a block index. Each operation also takes a fresh `step`.

#include <cstdint>

namespace pgmcl::detail {

inline constexpr std::uint64_t kStreamInit = 0x8000'0000'0000'0001ull;      // set_pose / global
inline constexpr std::uint64_t kStreamResample = 0x8000'0000'0000'0002ull;  // KLD + systematic
inline constexpr std::uint64_t kStreamInject = 0x8000'0000'0000'0003ull;    // augmented MCL
inline constexpr std::uint64_t kStreamSeed = 0x8000'0000'0000'0004ull;      // hypotheses

}  // namespace pgmcl::detail
