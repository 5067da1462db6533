#pragma once
/// Dynamic, unmapped obstacles: discs and boxes moving along their own looping paths.
/// They occlude beams in the simulator but never appear in the map.

#include <string>
#include <vector>

#include "pgmcl/common/se2.hpp"

namespace pgmcl::sims {

struct Point2 {
  double x = 0.0;  ///< metres
  double y = 0.0;  ///< metres
};

/// A closed polyline traversed at constant speed: after the last waypoint the obstacle
/// returns straight to the first and starts over. One waypoint (or speed 0) = static.
struct ObstaclePath {
  std::vector<Point2> waypoints;  ///< global frame; at least one
  double speed = 0.5;             ///< m/s along the path, >= 0
  double start_offset = 0.0;      ///< metres along the loop at t = 0
  /// Position at time t [s] (global frame). Requires a validated path.
  [[nodiscard]] Point2 position_at(double t) const noexcept;
  /// Throws std::invalid_argument prefixed with `context`.
  void validate(const std::string& context) const;
};

struct DiscObstacle {
  double radius = 0.25;  ///< metres, > 0 (a person: ~0.25 m)
  ObstaclePath path;
  std::string material = "average";  ///< a SurfaceLayout material name
};

/// A rectangle of 2 half_length x 2 half_width whose orientation is fixed at `yaw`.
struct BoxObstacle {
  double half_length = 0.5;  ///< metres along the box's x axis, > 0
  double half_width = 0.3;   ///< metres along its y axis, > 0
  double yaw = 0.0;          ///< radians, global frame
  ObstaclePath path;         ///< positions of the box centre
  std::string material = "average";
};

/// Analytic ray intersections in any common frame; the ray direction (dx, dy) is a unit
/// vector. They return the distance t >= 0 to the first crossing of the shape's boundary
/// and its outward normal, or +infinity when the ray misses. A start inside the shape
/// gives t = 0 and the normal -direction (the beam starts in the obstacle).
[[nodiscard]] float ray_disc(float ox, float oy, float dx, float dy, float cx, float cy,
                             float radius, float& nx, float& ny) noexcept;
/// Box centred at (cx, cy) with axes (cos_yaw, sin_yaw) and (-sin_yaw, cos_yaw).
[[nodiscard]] float ray_box(float ox, float oy, float dx, float dy, float cx, float cy,
                            float cos_yaw, float sin_yaw, float half_length, float half_width,
                            float& nx, float& ny) noexcept;

}  // namespace pgmcl::sims
