#pragma once
/// Private: parsers for single CARMEN message lines. Each takes the tokens of one line (token 0
/// is the message name) and throws detail::FieldError naming the offending field.

#include <array>
#include <span>
#include <string_view>
#include <utility>

#include "pgmcl/common/enum_names.hpp"
#include "pgmcl/io/carmen.hpp"

namespace pgmcl::io::detail {

/// Beam and remission counts above this are treated as corrupt (no scanner comes close).
inline constexpr std::size_t kMaxReadings = 1u << 20;

/// The laser message names, as read and written.
inline constexpr std::array<EnumName<LaserMessage>, 7> kLaserMessageNames{{
    {LaserMessage::kFlaser, "FLASER"},
    {LaserMessage::kRlaser, "RLASER"},
    {LaserMessage::kRobotLaser1, "ROBOTLASER1"},
    {LaserMessage::kRawLaser1, "RAWLASER1"},
    {LaserMessage::kRawLaser2, "RAWLASER2"},
    {LaserMessage::kRawLaser3, "RAWLASER3"},
    {LaserMessage::kRawLaser4, "RAWLASER4"},
}};

[[nodiscard]] std::pair<std::string, std::string> parse_param(
    std::span<const std::string_view> tokens);
[[nodiscard]] OdomRecord parse_odom(std::span<const std::string_view> tokens);
[[nodiscard]] TruePosRecord parse_truepos(std::span<const std::string_view> tokens);
/// FLASER / RLASER: angles from the SICK convention; range_max and sensor_pose are filled in
/// later by the reader (they depend on PARAMs and the whole log).
[[nodiscard]] CarmenScan parse_flaser(std::span<const std::string_view> tokens,
                                      LaserMessage message);
/// ROBOTLASER1 / RAWLASERn: angles and range_max from the logged config.
[[nodiscard]] CarmenScan parse_config_laser(std::span<const std::string_view> tokens,
                                            LaserMessage message);

}  // namespace pgmcl::io::detail
