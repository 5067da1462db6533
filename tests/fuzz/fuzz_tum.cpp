// libFuzzer target: the TUM trajectory reader (pgmcl::io::parse_tum) and writer.
// Oracles beyond "no crash": only FormatError escapes (tum.hpp); every pose read is finite
// with a wrapped heading in (-pi, pi]; format_tum/parse_tum gives back the stamp and x, y
// exactly and the heading to 1e-12 rad; the trajectory lookups stay finite; read_tum on
// the same bytes in a file gives the same poses, or fails at the same line and field.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <string>
#include <string_view>
#include <utility>

#include "fuzz_util.hpp"
#include "pgmcl/io/errors.hpp"
#include "pgmcl/io/trajectory.hpp"
#include "pgmcl/io/tum.hpp"

namespace {

using namespace pgmcl;

void check_pose(const io::StampedPose& p, const char* what) {
  if (!std::isfinite(p.stamp) || !std::isfinite(p.pose.x) || !std::isfinite(p.pose.y) ||
      !std::isfinite(p.pose.theta))
    fuzz::fail(what, "non-finite pose or stamp: theta " + std::to_string(p.pose.theta));
  if (!(p.pose.theta > -std::numbers::pi && p.pose.theta <= std::numbers::pi))
    fuzz::fail(what, "heading not wrapped to (-pi, pi]: " + std::to_string(p.pose.theta));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  auto parsed = fuzz::accepted<io::FormatError>(
      [&] { return io::parse_tum(fuzz::as_text(data, size), "fuzz.tum"); });
  if (!parsed) return 0;
  io::Trajectory t = *std::move(parsed);
  {
    const std::string path = fuzz::write_scratch("fuzz.tum", fuzz::as_text(data, size));
    const std::string mem = fuzz::outcome<io::FormatError>(
        [&] { return io::parse_tum(fuzz::as_text(data, size), "fuzz.tum"); });
    std::string file;
    try {
      file = fuzz::outcome<io::FormatError>([&] { return io::read_tum(path); });
    } catch (const std::exception& e) {
      fuzz::undocumented(e);
    }
    if (mem != file) fuzz::fail("read_tum(file) and parse_tum(text) disagree", mem + " vs " + file);
  }
  std::string text;
  try {
    for (const io::StampedPose& p : t) {
      check_pose(p, "parse_tum");
      text += io::format_tum(p) + "\n";
    }
    const io::Trajectory back = io::parse_tum(text, "rewritten.tum");
    if (back.size() != t.size()) fuzz::fail("round trip changed the pose count");
    for (std::size_t i = 0; i < t.size(); ++i) {
      const Pose2 &a = t[i].pose, &b = back[i].pose;
      if (back[i].stamp != t[i].stamp || a.x != b.x || a.y != b.y)
        fuzz::fail("round trip changed a stamp or position", text);
      if (std::abs(wrap_angle(a.theta - b.theta)) > 1e-12)
        fuzz::fail("round trip changed a heading", std::to_string(a.theta - b.theta));
    }
  } catch (const std::exception& e) {
    fuzz::undocumented(e);
  }

  io::sort_by_stamp(t);
  if (!io::is_sorted_by_stamp(t)) fuzz::fail("sort_by_stamp left the trajectory unsorted");
  for (const io::StampedPose& p : t) {
    for (const double dt : {0.0, 0.25, -1e-3}) {
      if (const auto q = io::interpolate_at(t, p.stamp + dt, 1.0))
        check_pose({p.stamp, *q}, "interpolate_at");
      if (const auto i = io::nearest_index(t, p.stamp + dt, 0.5); i && *i >= t.size())
        fuzz::fail("nearest_index out of range");
    }
  }
  return 0;
}
