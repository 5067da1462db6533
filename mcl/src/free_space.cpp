#include "free_space.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "pgmcl/maps/distance_transform.hpp"
#include "pgmcl/maps/likelihood_field.hpp"

namespace pgmcl::detail {
namespace {

// Past a cell edge, into the next cell (cells; rays are at most a few thousand cells long).
constexpr float kNudge = 1e-3f;
// Rays marched at once: enough to overlap the lookups' latency (4 beat 1, 8 and 16 on aces).
constexpr std::size_t kRaysInFlight = 4;

// floor(v) for v within int range, without a libm call.
float floor_in_range(float v) noexcept {
  const auto t = static_cast<float>(static_cast<int>(v));
  return t > v ? t - 1.0f : t;
}

// Distance along a ray with direction component u from coordinate v to the next cell edge.
float to_next_cell(float v, float u) noexcept {
  const float edge = floor_in_range(v);
  if (u > 0.0f) return (edge + 1.0f - v) / u;
  if (u < 0.0f) return (v - edge) / -u;
  return std::numeric_limits<float>::infinity();
}

}  // namespace

FreeSpace::FreeSpace(int width, int height, double resolution,
                     std::span<const std::uint32_t> free_cells, float ray_margin)
    : width_(width), height_(height), resolution_(resolution), ray_margin_(ray_margin) {
  const auto cells = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  std::vector<std::uint8_t> blocked(cells, 1);
  for (const std::uint32_t c : free_cells) blocked[c] = 0;
  const maps::DistanceField d = maps::euclidean_distance_transform(blocked, width, height);
  clearance_.resize(cells);
  for (std::size_t i = 0; i < cells; ++i) {
    const std::uint32_t sq = d.sq_dist[i];
    clearance_[i] =
        sq >= 255u * 255u ? 255 : static_cast<std::uint8_t>(std::sqrt(static_cast<double>(sq)));
  }
}

bool FreeSpace::is_free(double x, double y) const noexcept {
  return clearance_at(static_cast<float>(x / resolution_), static_cast<float>(y / resolution_)) > 0;
}

template <class OnBlocked>
void FreeSpace::for_each_blocked(const Pose2& pose, const PreparedBeams& beams, float sensor_x,
                                 float sensor_y, OnBlocked&& on_blocked) const {
  const auto c = static_cast<float>(std::cos(pose.theta));
  const auto s = static_cast<float>(std::sin(pose.theta));
  const auto px = static_cast<float>(pose.x / resolution_);
  const auto py = static_cast<float>(pose.y / resolution_);
  const float sx = px + c * sensor_x - s * sensor_y, sy = py + s * sensor_x + c * sensor_y;
  // Several rays are marched in turn, a step each: a ray's next step waits for its lookup,
  // while different rays' lookups overlap. Each ray's own arithmetic is that of one ray.
  struct Ray {
    float ux, uy, t, stop;
    std::size_t j;
  };
  std::array<Ray, kRaysInFlight> rays{};
  // Every ray's first sample is the sensor's cell: looked up once, and where it is clear of
  // walls, every ray starts with the sphere step from it.
  const std::uint8_t at_sensor = clearance_at(sx, sy);
  const float first_step = at_sensor >= 3 ? static_cast<float>(at_sensor) - 1.5f : 0.0f;
  std::size_t next = 0;  // the next beam to start
  const auto start = [&](Ray& ray) {
    for (; next < beams.size(); ++next) {
      const float ex = px + c * beams.ex[next] - s * beams.ey[next];
      const float ey = py + s * beams.ex[next] + c * beams.ey[next];
      const float dx = ex - sx, dy = ey - sy;
      const float length = std::sqrt(dx * dx + dy * dy);
      const float stop = length - ray_margin_;
      if (!(stop > 0.0f)) continue;
      if (at_sensor == 0) {
        on_blocked(next);
        continue;
      }
      if (!(first_step < stop)) continue;
      ray = {dx / length, dy / length, first_step, stop, next++};
      return true;
    }
    return false;
  };
  std::size_t flying = 0;
  while (flying < kRaysInFlight && start(rays[flying])) ++flying;
  while (flying > 0) {
    for (std::size_t r = 0; r < flying;) {
      Ray& ray = rays[r];
      const float x = sx + ray.ux * ray.t, y = sy + ray.uy * ray.t;
      const std::uint8_t k = clearance_near(x, y);  // the sensor is on the map
      bool landed = k == 0;
      if (landed) {
        on_blocked(ray.j);
      } else {
        // Sphere tracing: from a cell whose centre lies k cells from every blocked cell's
        // centre the ray may advance k - 1.5 cells and touch none of them. Near walls it
        // steps cell by cell (to the next cell edge it crosses), so no corner is cut.
        if (k >= 3) {
          ray.t += static_cast<float>(k) - 1.5f;
        } else {
          const float across_x = to_next_cell(x, ray.ux), across_y = to_next_cell(y, ray.uy);
          ray.t += (across_x < across_y ? across_x : across_y) + kNudge;
        }
        landed = !(ray.t < ray.stop);
      }
      if (!landed) {
        ++r;
      } else if (!start(ray)) {
        ray = rays[--flying];  // the last ray in flight takes this one's place
      }
    }
  }
}

std::size_t FreeSpace::blocked_beams(const Pose2& pose, const PreparedBeams& beams, float sensor_x,
                                     float sensor_y) const noexcept {
  std::size_t blocked = 0;
  for_each_blocked(pose, beams, sensor_x, sensor_y, [&](std::size_t) { ++blocked; });
  return blocked;
}

void FreeSpace::blocked_beam_indices(const Pose2& pose, const PreparedBeams& beams, float sensor_x,
                                     float sensor_y, std::vector<std::uint32_t>& out) const {
  out.clear();
  for_each_blocked(pose, beams, sensor_x, sensor_y,
                   [&](std::size_t j) { out.push_back(static_cast<std::uint32_t>(j)); });
  std::sort(out.begin(), out.end());
}

}  // namespace pgmcl::detail
