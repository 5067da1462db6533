#pragma once
/// The world one scan sees: the static grid (with surface materials) plus the dynamic
/// obstacles frozen at the scan's time, all in the map-local frame.

#include <cstdint>
#include <vector>

#include "pgmcl/sims/obstacles.hpp"
#include "pgmcl/sims/ray_caster.hpp"
#include "pgmcl/sims/surfaces.hpp"

namespace pgmcl::sims {

/// A disc in the map-local frame.
struct DiscShape {
  float cx = 0.0F, cy = 0.0F, radius = 0.0F;  ///< metres
  std::uint8_t material = 0;                  ///< palette index
};

/// A box in the map-local frame.
struct BoxShape {
  float cx = 0.0F, cy = 0.0F;            ///< centre, metres
  float cos_yaw = 1.0F, sin_yaw = 0.0F;  ///< orientation in the map-local frame
  float half_length = 0.0F, half_width = 0.0F;
  std::uint8_t material = 0;
};

/// What a beam hit, map-local frame.
struct SceneHit {
  float range = 0.0F;  ///< metres from the ray start, or max_range without a hit
  bool hit = false;
  float nx = 0.0F;  ///< outward unit normal of the surface at the hit
  float ny = 0.0F;
  std::uint8_t material = 0;  ///< palette index
};

/// Holds references to the caster and surface field: both must outlive the Scene.
class Scene {
 public:
  Scene(const RayCaster& caster, const SurfaceField& surfaces) noexcept
      : caster_(&caster), surfaces_(&surfaces) {}

  /// Freezes the dynamic obstacles at time t [s]: global-frame paths are mapped into the
  /// map-local frame. Material names are resolved against the surface palette (throws
  /// std::invalid_argument for unknown names).
  void set_obstacles(const std::vector<DiscObstacle>& discs, const std::vector<BoxObstacle>& boxes,
                     double t);
  void clear_obstacles() noexcept {
    discs_.clear();
    boxes_.clear();
  }
  void add(const DiscShape& d) { discs_.push_back(d); }
  void add(const BoxShape& b) { boxes_.push_back(b); }

  /// Nearest of the grid hit and the obstacle hits along the unit direction (dx, dy).
  [[nodiscard]] SceneHit cast(float x, float y, float dx, float dy, float max_range) const noexcept;

  [[nodiscard]] const RayCaster& caster() const noexcept { return *caster_; }
  [[nodiscard]] const SurfaceField& surfaces() const noexcept { return *surfaces_; }
  [[nodiscard]] const std::vector<DiscShape>& discs() const noexcept { return discs_; }
  [[nodiscard]] const std::vector<BoxShape>& boxes() const noexcept { return boxes_; }

 private:
  const RayCaster* caster_;
  const SurfaceField* surfaces_;
  std::vector<DiscShape> discs_;
  std::vector<BoxShape> boxes_;
};

}  // namespace pgmcl::sims
