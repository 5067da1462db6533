#include "pgmcl/io/tum.hpp"

#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "fields.hpp"
#include "pgmcl/io/errors.hpp"
#include "pgmcl/io/line_io.hpp"

namespace pgmcl::io {
namespace {

constexpr std::array<std::string_view, 8> kFields = {"timestamp", "tx", "ty", "tz",
                                                     "qx",        "qy", "qz", "qw"};

/// Parses one line into `out` (unless blank or a comment); throws FormatError.
void parse_line(std::string_view line, std::size_t line_no, const std::string& source,
                std::vector<std::string_view>& tokens, Trajectory& out) {
  detail::split_fields(line, tokens);
  if (tokens.empty() || tokens.front().front() == '#') return;
  std::array<double, 8> v{};
  detail::parse_fixed_numbers(tokens, kFields, v, source, line_no);
  const double norm = std::sqrt(v[4] * v[4] + v[5] * v[5] + v[6] * v[6] + v[7] * v[7]);
  if (!(norm > 1e-9)) {
    throw FormatError(source, line_no, "quaternion",
                      "norm " + std::to_string(norm) + " is too small to be a rotation");
  }
  check_record_memory(out.size() + 1, sizeof(StampedPose), source, line_no);
  out.push_back({v[0], {v[1], v[2], yaw_from_quaternion(v[4], v[5], v[6], v[7])}});
}

}  // namespace

double yaw_from_quaternion(double qx, double qy, double qz, double qw) noexcept {
  // Z-Y-X Euler yaw; both atan2 arguments scale with |q|^2, so no normalisation is needed
  // for the angle itself (read_tum still rejects ~zero quaternions).
  return wrap_angle(std::atan2(2.0 * (qw * qz + qx * qy), qw * qw + qx * qx - qy * qy - qz * qz));
}

Trajectory read_tum(const std::string& path) {
  Trajectory out;
  std::vector<std::string_view> tokens;
  detail::for_each_file_line(
      path, [&](std::string_view line, std::size_t n) { parse_line(line, n, path, tokens, out); });
  return out;
}

Trajectory parse_tum(std::string_view text, const std::string& source) {
  Trajectory out;
  std::vector<std::string_view> tokens;
  detail::for_each_text_line(text, [&](std::string_view line, std::size_t n) {
    parse_line(line, n, source, tokens, out);
  });
  return out;
}

std::string format_tum(const StampedPose& p) {
  if (!std::isfinite(p.stamp) || !std::isfinite(p.pose.x) || !std::isfinite(p.pose.y) ||
      !std::isfinite(p.pose.theta)) {
    throw std::invalid_argument("TUM pose at stamp " + std::to_string(p.stamp) + " is not finite");
  }
  std::string s;
  detail::append_fixed(s, p.stamp);
  const double half = 0.5 * p.pose.theta;
  for (const double v : {p.pose.x, p.pose.y, 0.0, 0.0, 0.0, std::sin(half), std::cos(half)}) {
    s += ' ';
    detail::append_number(s, v);
  }
  return s;
}

void write_tum(const std::string& path, const Trajectory& trajectory) {
  LineWriter out(path);
  out.write_line("# timestamp tx ty tz qx qy qz qw");
  for (const StampedPose& p : trajectory) out.write_line(format_tum(p));
  out.close();
}

}  // namespace pgmcl::io
