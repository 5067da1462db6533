#include "pgmcl/nav/stored_pose.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>

namespace pgmcl::nav {
namespace {

constexpr std::array<const char*, 6> kKeys = {"initial_pose_x", "initial_pose_y", "initial_pose_a",
                                              "initial_cov_xx", "initial_cov_yy", "initial_cov_aa"};

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
    s.remove_suffix(1);
  return s;
}

[[noreturn]] void fail(const std::string& source, std::size_t line, std::string_view key,
                       const std::string& problem) {
  throw std::invalid_argument(source + ":" + std::to_string(line) + ": " + std::string(key) + ": " +
                              problem);
}

}  // namespace

StoredPose StoredPose::of(const Pose2& pose, const Eigen::Matrix3d& c) noexcept {
  return {pose, std::max(0.0, c(0, 0)), std::max(0.0, c(1, 1)), std::max(0.0, c(2, 2))};
}

Eigen::Matrix3d StoredPose::covariance() const noexcept {
  return Eigen::Vector3d(cov_xx, cov_yy, cov_aa).asDiagonal();
}

bool StoredPose::valid() const noexcept {
  const double v[6] = {pose.x, pose.y, pose.theta, cov_xx, cov_yy, cov_aa};
  return std::all_of(v, v + 6, [](double d) { return std::isfinite(d); }) && cov_xx >= 0.0 &&
         cov_yy >= 0.0 && cov_aa >= 0.0;
}

std::string format_stored_pose(const StoredPose& p) {
  const double v[6] = {p.pose.x, p.pose.y, p.pose.theta, p.cov_xx, p.cov_yy, p.cov_aa};
  std::string out = "# pgmcl: the last pose and its covariance (amcl's parameter names)\n";
  for (std::size_t i = 0; i < kKeys.size(); ++i) {
    char buf[64];
    const auto res = std::to_chars(buf, buf + sizeof buf, v[i]);
    out += std::string(kKeys[i]) + ": " + std::string(buf, res.ptr) + "\n";
  }
  return out;
}

StoredPose parse_stored_pose(std::string_view text, const std::string& source) {
  std::array<double, 6> v{};
  std::array<std::size_t, 6> seen{};  // line of each key, 0 = not yet
  std::size_t line = 0;
  while (!text.empty()) {
    const std::size_t nl = text.find('\n');
    std::string_view raw = text.substr(0, nl);
    text.remove_prefix(nl == std::string_view::npos ? text.size() : nl + 1);
    ++line;
    const std::string_view s = trim(raw);
    if (s.empty() || s.front() == '#') continue;
    const std::size_t colon = s.find(':');
    if (colon == std::string_view::npos) fail(source, line, s, "expected 'key: value'");
    const std::string_view key = trim(s.substr(0, colon));
    const std::string_view value = trim(s.substr(colon + 1));
    const auto it = std::find(kKeys.begin(), kKeys.end(), key);
    if (it == kKeys.end())
      fail(source, line, key, "unknown key (expected initial_pose_x/y/a, initial_cov_xx/yy/aa)");
    const auto k = static_cast<std::size_t>(it - kKeys.begin());
    if (seen[k] != 0)
      fail(source, line, key, "repeated (first on line " + std::to_string(seen[k]) + ")");
    double d = 0.0;
    const auto res = std::from_chars(value.data(), value.data() + value.size(), d);
    if (res.ec != std::errc{} || res.ptr != value.data() + value.size() || !std::isfinite(d))
      fail(source, line, key, "expected a finite number, got '" + std::string(value) + "'");
    if (k >= 3 && d < 0.0) fail(source, line, key, "a variance must be >= 0");
    v[k] = d;
    seen[k] = line;
  }
  for (std::size_t k = 0; k < kKeys.size(); ++k)
    if (seen[k] == 0) fail(source, line, kKeys[k], "missing");
  return {{v[0], v[1], wrap_angle(v[2])}, v[3], v[4], v[5]};
}

void save_stored_pose(const std::string& path, const StoredPose& p) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp, std::ios::trunc);
    f << format_stored_pose(p);
    f.flush();
    if (!f) throw std::runtime_error(tmp + ": cannot write the pose file");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw std::runtime_error(path + ": cannot replace the pose file: " + ec.message());
}

std::optional<StoredPose> load_stored_pose(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return std::nullopt;
  std::ifstream f(path);
  std::ostringstream text;
  text << f.rdbuf();
  if (!f) throw std::runtime_error(path + ": cannot read the pose file");
  return parse_stored_pose(text.str(), path);
}

}  // namespace pgmcl::nav
