#include "free_space.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "pgmcl/maps/distance_transform.hpp"
#include "pgmcl/maps/likelihood_field.hpp"

namespace pgmcl::detail {
namespace {

// Past a cell edge, into the next cell (cells; rays are at most a few thousand cells long).
constexpr float kNudge = 1e-3f;

// Distance along a ray with direction component u from coordinate v to the next cell edge.
float to_next_cell(float v, float u) noexcept {
  if (u > 0.0f) return (std::floor(v) + 1.0f - v) / u;
  if (u < 0.0f) return (v - std::floor(v)) / -u;
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

std::uint8_t FreeSpace::clearance_at(float col, float row) const noexcept {
  const int c = maps::floor_to_cell(col), r = maps::floor_to_cell(row);
  if (c < 0 || r < 0 || c >= width_ || r >= height_) return 0;  // off the map: never seen
  return clearance_[static_cast<std::size_t>(r) * static_cast<std::size_t>(width_) +
                    static_cast<std::size_t>(c)];
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
  for (std::size_t j = 0; j < beams.size(); ++j) {
    const float ex = px + c * beams.ex[j] - s * beams.ey[j];
    const float ey = py + s * beams.ex[j] + c * beams.ey[j];
    const float dx = ex - sx, dy = ey - sy;
    const float length = std::sqrt(dx * dx + dy * dy);
    const float stop = length - ray_margin_;
    if (!(stop > 0.0f)) continue;
    const float ux = dx / length, uy = dy / length;
    for (float t = 0.0f; t < stop;) {
      const float x = sx + ux * t, y = sy + uy * t;
      const std::uint8_t k = clearance_at(x, y);
      if (k == 0) {
        on_blocked(j);
        break;
      }
      // Sphere tracing: from a cell whose centre lies k cells from every blocked cell's
      // centre the ray may advance k - 1.5 cells and touch none of them. Near walls it
      // steps cell by cell (to the next cell edge it crosses), so no corner is cut.
      t += k >= 3                                      ? static_cast<float>(k) - 1.5f
           : to_next_cell(x, ux) < to_next_cell(y, uy) ? to_next_cell(x, ux) + kNudge
                                                       : to_next_cell(y, uy) + kNudge;
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
}

}  // namespace pgmcl::detail
