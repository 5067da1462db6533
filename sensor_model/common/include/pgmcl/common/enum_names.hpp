#pragma once
/// An enumeration's names as one table read both ways, so the name a value is written as and
/// the name it is parsed from cannot drift apart.

#include <array>
#include <cstddef>
#include <optional>
#include <string_view>

namespace pgmcl {

template <class E>
struct EnumName {
  E value;
  const char* name;  ///< the first name of a value is the one written; later ones are aliases
};

/// The name written for `value` (its first entry in `names`); `fallback` for a value not listed.
template <class E, std::size_t N>
[[nodiscard]] constexpr const char* name_of(E value, const std::array<EnumName<E>, N>& names,
                                            const char* fallback = "?") noexcept {
  for (const auto& n : names)
    if (n.value == value) return n.name;
  return fallback;
}

/// The value any of whose names is `name`; nullopt for a name not listed.
template <class E, std::size_t N>
[[nodiscard]] constexpr std::optional<E> value_of(
    std::string_view name, const std::array<EnumName<E>, N>& names) noexcept {
  for (const auto& n : names)
    if (name == n.name) return n.value;
  return std::nullopt;
}

}  // namespace pgmcl
