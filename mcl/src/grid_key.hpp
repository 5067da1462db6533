#pragma once
// Internal: packs an (x, y, heading) histogram cell into one 64-bit key, shared by the
// KLD bin counter and the clustering grid. Layout: x index in bits 40-63, y index in bits
// 16-39 (both signed, offset by 2^23, clamped), heading sector in bits 0-15.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>

#include "pgmcl/common/se2.hpp"

namespace pgmcl::detail {

inline constexpr std::int64_t kCellLimit = std::int64_t{1} << 23;
inline constexpr std::uint64_t kCellFieldMask = (std::uint64_t{1} << 24) - 1;
inline constexpr std::size_t kMaxSectors = 65535;

/// floor(v) as a cell field in [0, 2^24): clamped to +/-2^23, NaN maps to the low end.
[[nodiscard]] inline std::uint64_t cell_field(double v) noexcept {
  double f = std::floor(v);
  if (!(f >= -static_cast<double>(kCellLimit))) f = -static_cast<double>(kCellLimit);
  if (f > static_cast<double>(kCellLimit - 1)) f = static_cast<double>(kCellLimit - 1);
  return static_cast<std::uint64_t>(static_cast<std::int64_t>(f) + kCellLimit);
}

/// Number of equal heading sectors closest to a sector width (at least 1).
[[nodiscard]] inline double sector_count(double width) noexcept {
  const double s = std::round(2.0 * std::numbers::pi / width);
  return s < 1.0 ? 1.0 : s;
}

/// Sector of a heading: sectors * (wrap(theta) + pi) / (2 pi), with pi and -pi in sector 0.
[[nodiscard]] inline std::uint64_t sector_of(double theta, double sectors_per_radian,
                                             std::size_t sectors) noexcept {
  const double t = std::floor((wrap_angle(theta) + std::numbers::pi) * sectors_per_radian);
  auto s = static_cast<std::size_t>(t > 0.0 ? t : 0.0);  // NaN and -0 give sector 0
  if (s >= sectors) s -= sectors;                        // theta = pi lands on `sectors`
  if (s >= sectors) s = 0;
  return s;
}

[[nodiscard]] inline std::uint64_t pack_cell(std::uint64_t fx, std::uint64_t fy,
                                             std::uint64_t sector) noexcept {
  return (fx << 40) | (fy << 16) | sector;
}

}  // namespace pgmcl::detail
