#pragma once
/// Relation files of the SLAM benchmark (Kümmerle et al., "On measuring the accuracy of SLAM
/// algorithms", Autonomous Robots 27(4), 2009): `t1 t2 x y z roll pitch yaw` per line, the
/// pose of the scan at t2 in the frame of the scan at t1 (pgmcl uses x, y and yaw). Scoring
/// a trajectory against them: pgmcl/eval/relations_error.hpp.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "pgmcl/common/se2.hpp"

namespace pgmcl::io {

/// Intel Research Lab log time + this = the absolute time used by intel.relations
/// (data/README.md: matches within about 2 ms).
inline constexpr double kIntelRelationsTimeOffset = 976052857.338;  ///< seconds

struct Relation {
  double t1 = 0.0;                          ///< seconds, relation clock
  double t2 = 0.0;                          ///< seconds
  Pose2 delta{};                            ///< pose at t2 in the frame at t1 (x, y, yaw)
  double z = 0.0, roll = 0.0, pitch = 0.0;  ///< kept as read, unused in 2D
  std::size_t line = 0;
};

/// Reads a relations file (plain or .gz). Throws IoError if unreadable, FormatError
/// ("file:line: field: ...") for a line without exactly 8 finite numbers.
[[nodiscard]] std::vector<Relation> read_relations(const std::string& path);
[[nodiscard]] std::vector<Relation> parse_relations(std::string_view text,
                                                    const std::string& source);

}  // namespace pgmcl::io
