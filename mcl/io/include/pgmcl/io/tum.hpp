#pragma once
/// TUM RGB-D trajectory files, the format the `evo` tool reads (`evo_ape tum ...`):
/// one pose per line, `timestamp tx ty tz qx qy qz qw`, space separated, `#` comments.
/// pgmcl is planar: it writes z = 0 and the quaternion of a rotation about z by theta, and
/// reads theta as the yaw (Z-Y-X Euler) of the quaternion after normalising it, ignoring z.

#include <string>
#include <string_view>

#include "pgmcl/io/trajectory.hpp"

namespace pgmcl::io {

/// Reads a TUM file (plain or .gz). Throws IoError if unreadable and FormatError
/// ("file:line: field: ...") for a line without exactly 8 numbers, a NaN/Inf field, or a
/// (near-)zero quaternion. Non-unit quaternions are normalised.
[[nodiscard]] Trajectory read_tum(const std::string& path);
/// Same, from text in memory; `source` names it in messages.
[[nodiscard]] Trajectory parse_tum(std::string_view text, const std::string& source);

/// "t x y 0 0 0 sin(theta/2) cos(theta/2)", every number in its shortest exact form (the
/// stamp in fixed notation, at full double precision).
[[nodiscard]] std::string format_tum(const StampedPose& p);
/// Writes a header comment and one line per pose (gzip if the path ends in ".gz").
void write_tum(const std::string& path, const Trajectory& trajectory);

/// Yaw of the rotation (qx, qy, qz, qw); the quaternion need not be unit length.
[[nodiscard]] double yaw_from_quaternion(double qx, double qy, double qz, double qw) noexcept;

}  // namespace pgmcl::io
