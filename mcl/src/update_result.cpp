#include "pgmcl/mcl/update_result.hpp"

namespace pgmcl {

const char* to_string(SkipReason reason) noexcept {
  switch (reason) {
    case SkipReason::kNone:
      return "none";
    case SkipReason::kNotMoved:
      return "not_moved";
    case SkipReason::kNoValidBeams:
      return "no_valid_beams";
    case SkipReason::kTimeWentBackwards:
      return "time_went_backwards";
  }
  return "unknown";
}

}  // namespace pgmcl
