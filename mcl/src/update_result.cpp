#include "pgmcl/mcl/update_result.hpp"

#include <array>

#include "pgmcl/common/enum_names.hpp"

namespace pgmcl {

const char* to_string(SkipReason reason) noexcept {
  static constexpr std::array<EnumName<SkipReason>, 4> kNames{{
      {SkipReason::kNone, "none"},
      {SkipReason::kNotMoved, "not_moved"},
      {SkipReason::kNoValidBeams, "no_valid_beams"},
      {SkipReason::kTimeWentBackwards, "time_went_backwards"},
  }};
  return name_of(reason, kNames, "unknown");
}

}  // namespace pgmcl
