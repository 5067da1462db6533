#include "pgmcl/sims/scene.hpp"

#include <cmath>
#include <string>

namespace pgmcl::sims {

void Scene::set_obstacles(const std::vector<DiscObstacle>& discs,
                          const std::vector<BoxObstacle>& boxes, double t) {
  clear_obstacles();
  const Pose2 to_local = caster_->origin().inverse();
  for (std::size_t i = 0; i < discs.size(); ++i) {
    const auto& d = discs[i];
    const Point2 p = d.path.position_at(t);
    double lx = 0.0, ly = 0.0;
    to_local.transform_point(p.x, p.y, lx, ly);
    discs_.push_back(
        {static_cast<float>(lx), static_cast<float>(ly), static_cast<float>(d.radius),
         surfaces_->index_of(d.material, "discs[" + std::to_string(i) + "].material")});
  }
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const auto& b = boxes[i];
    const Point2 p = b.path.position_at(t);
    double lx = 0.0, ly = 0.0;
    to_local.transform_point(p.x, p.y, lx, ly);
    const double yaw = b.yaw - caster_->origin().theta;
    boxes_.push_back(
        {static_cast<float>(lx), static_cast<float>(ly), static_cast<float>(std::cos(yaw)),
         static_cast<float>(std::sin(yaw)), static_cast<float>(b.half_length),
         static_cast<float>(b.half_width),
         surfaces_->index_of(b.material, "boxes[" + std::to_string(i) + "].material")});
  }
}

SceneHit Scene::cast(float x, float y, float dx, float dy, float max_range) const noexcept {
  SceneHit out;
  const RayHit g = caster_->cast_local_dir(x, y, dx, dy, max_range);
  out.range = g.range;
  out.hit = g.hit;
  if (g.hit) {
    caster_->surface_normal(g.col, g.row, g.face, dx, dy, out.nx, out.ny);
    out.material = surfaces_->at(g.col, g.row);
  }
  // Obstacles occlude whatever the grid returned if they are nearer.
  for (const auto& d : discs_) {
    float nx = 0.0F, ny = 0.0F;
    const float t = ray_disc(x, y, dx, dy, d.cx, d.cy, d.radius, nx, ny);
    if (t < out.range) {
      out = {t, true, nx, ny, d.material};
    }
  }
  for (const auto& b : boxes_) {
    float nx = 0.0F, ny = 0.0F;
    const float t = ray_box(x, y, dx, dy, b.cx, b.cy, b.cos_yaw, b.sin_yaw, b.half_length,
                            b.half_width, nx, ny);
    if (t < out.range) {
      out = {t, true, nx, ny, b.material};
    }
  }
  return out;
}

}  // namespace pgmcl::sims
