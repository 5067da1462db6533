#include "pgmcl/sims/obstacles.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace pgmcl::sims {

namespace {
constexpr float kInf = std::numeric_limits<float>::infinity();
}  // namespace

Point2 ObstaclePath::position_at(double t) const noexcept {
  if (waypoints.empty()) return {};
  const std::size_t n = waypoints.size();
  double total = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto& a = waypoints[i];
    const auto& b = waypoints[(i + 1) % n];
    total += std::hypot(b.x - a.x, b.y - a.y);
  }
  if (n == 1 || total <= 0.0) return waypoints.front();
  double s = std::fmod(start_offset + speed * t, total);
  if (s < 0.0) s += total;
  for (std::size_t i = 0; i < n; ++i) {
    const auto& a = waypoints[i];
    const auto& b = waypoints[(i + 1) % n];
    const double len = std::hypot(b.x - a.x, b.y - a.y);
    if (s <= len || i + 1 == n) {
      const double f = len > 0.0 ? std::min(s / len, 1.0) : 0.0;
      return {a.x + f * (b.x - a.x), a.y + f * (b.y - a.y)};
    }
    s -= len;
  }
  return waypoints.front();
}

void ObstaclePath::validate(const std::string& context) const {
  if (waypoints.empty()) throw std::invalid_argument(context + ".waypoints: need at least one");
  for (std::size_t i = 0; i < waypoints.size(); ++i) {
    if (!std::isfinite(waypoints[i].x) || !std::isfinite(waypoints[i].y)) {
      throw std::invalid_argument(context + ".waypoints[" + std::to_string(i) + "] is not finite");
    }
  }
  if (!(speed >= 0.0) || !std::isfinite(speed)) {
    throw std::invalid_argument(context + ".speed must be finite and >= 0 (m/s)");
  }
  if (!std::isfinite(start_offset)) {
    throw std::invalid_argument(context + ".start_offset must be finite (m)");
  }
}

float ray_disc(float ox, float oy, float dx, float dy, float cx, float cy, float radius, float& nx,
               float& ny) noexcept {
  const float px = ox - cx, py = oy - cy;
  const float b = px * dx + py * dy;
  const float c = px * px + py * py - radius * radius;
  if (c <= 0.0F) {
    nx = -dx;
    ny = -dy;
    return 0.0F;
  }
  const float disc = b * b - c;
  if (disc < 0.0F || b > 0.0F) return kInf;  // missed, or the disc lies behind the start
  const float t = -b - std::sqrt(disc);
  if (t < 0.0F) return kInf;
  nx = (px + t * dx) / radius;
  ny = (py + t * dy) / radius;
  return t;
}

float ray_box(float ox, float oy, float dx, float dy, float cx, float cy, float cos_yaw,
              float sin_yaw, float half_length, float half_width, float& nx, float& ny) noexcept {
  // Into the box frame.
  const float rx = ox - cx, ry = oy - cy;
  const float p[2] = {cos_yaw * rx + sin_yaw * ry, -sin_yaw * rx + cos_yaw * ry};
  const float d[2] = {cos_yaw * dx + sin_yaw * dy, -sin_yaw * dx + cos_yaw * dy};
  const float half[2] = {half_length, half_width};
  float t_enter = -kInf, t_exit = kInf;
  int axis = -1;
  float sign = 0.0F;
  for (int k = 0; k < 2; ++k) {
    if (d[k] == 0.0F) {
      if (p[k] < -half[k] || p[k] > half[k]) return kInf;
      continue;
    }
    const float inv = 1.0F / d[k];
    float t0 = (-half[k] - p[k]) * inv;
    float t1 = (half[k] - p[k]) * inv;
    const float s = d[k] > 0.0F ? -1.0F : 1.0F;  // the entered face's outward normal sign
    if (t0 > t1) std::swap(t0, t1);
    if (t0 > t_enter) {
      t_enter = t0;
      axis = k;
      sign = s;
    }
    t_exit = std::min(t_exit, t1);
  }
  if (t_enter > t_exit || t_exit < 0.0F) return kInf;
  if (t_enter <= 0.0F || axis < 0) {  // the start lies inside the box
    nx = -dx;
    ny = -dy;
    return 0.0F;
  }
  const float lx = axis == 0 ? sign : 0.0F;
  const float ly = axis == 1 ? sign : 0.0F;
  nx = cos_yaw * lx - sin_yaw * ly;
  ny = sin_yaw * lx + cos_yaw * ly;
  return t_enter;
}

}  // namespace pgmcl::sims
