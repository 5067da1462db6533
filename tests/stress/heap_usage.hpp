#pragma once
// Bytes of heap in use (glibc mallinfo2: small-block arena + mmapped blocks), to check that
// a data structure holds what its stats say. Not available under AddressSanitizer, whose
// allocator glibc does not see: heap_in_use() then returns nullopt and the callers check
// the documented arithmetic only.

#include <cstddef>
#include <optional>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#if defined(__SANITIZE_ADDRESS__)
#define PGMCL_STRESS_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define PGMCL_STRESS_ASAN 1
#endif
#endif

namespace pgmcl::stress {

[[nodiscard]] inline std::optional<std::size_t> heap_in_use() {
#if defined(__GLIBC__) && !defined(PGMCL_STRESS_ASAN)
  const struct mallinfo2 mi = mallinfo2();
  return mi.uordblks + mi.hblkhd;
#else
  return std::nullopt;
#endif
}

/// Side, in cells, of the stress tests' huge map: 40000 (1.6e9 cells) in Release; 10000 in
/// Debug builds, which run under ASan (same code path, a 100 MB grid instead of 1.6 GB).
#ifdef NDEBUG
inline constexpr int kHugeMapSide = 40000;
#else
inline constexpr int kHugeMapSide = 10000;
#endif

}  // namespace pgmcl::stress
