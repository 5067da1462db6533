#pragma once
/// Exact ray casting on an occupancy grid: the voxel traversal of Amanatides & Woo,
/// "A Fast Voxel Traversal Algorithm for Ray Tracing" (Eurographics 1987), in 2D.
///
/// Every cell the ray passes through is visited in order, from any sub-cell start, so the
/// returned range is the distance to the boundary of the first blocking cell (not a
/// sampled approximation). Work is done in the map-local (grid) frame in float; the
/// global-frame entry points map poses through the grid origin (including its yaw).

#include <cstdint>
#include <span>
#include <vector>

#include "pgmcl/common/se2.hpp"
#include "pgmcl/maps/occupancy_grid.hpp"

namespace pgmcl::sims {

/// What a beam does when it enters a cell of unknown occupancy (value -1).
enum class UnknownCellPolicy : std::uint8_t {
  /// Default. Unknown cells are transparent: in a map built by SLAM, unknown cells inside
  /// the mapped area are mostly unobserved free space, and unknown cells outside it lie
  /// beyond the walls the beam would hit first. A beam that reaches the grid edge through
  /// unknown cells returns no hit (max range).
  kPassThrough,
  kBlock,   ///< unknown cells reflect like occupied cells
  kAbsorb,  ///< the beam ends in the first unknown cell without a return (max range)
};

struct RayCastOptions {
  UnknownCellPolicy unknown = UnknownCellPolicy::kPassThrough;
};

/// The grid face a ray crossed to enter the hit cell. kStart: the ray started inside a
/// blocking cell (range 0).
enum class HitFace : std::uint8_t { kNone, kStart, kMinX, kMaxX, kMinY, kMaxY };

/// One ray's result. Frame of x/y and normal: whichever frame the cast was called in.
struct RayHit {
  float range = 0.0F;  ///< metres to the first blocking cell boundary, or max_range
  bool hit = false;    ///< false: nothing within max_range (or absorbed / left the grid)
  int col = -1;        ///< hit cell, -1 without a hit
  int row = -1;
  HitFace face = HitFace::kNone;
  double x = 0.0;  ///< hit point (the ray end point at max_range without a hit)
  double y = 0.0;
};

/// Beam geometry of one scan, as in LaserScan: beam i at angle_min + i * angle_increment.
struct BeamFan {
  double angle_min = 0.0;        ///< radians, sensor frame
  double angle_increment = 0.0;  ///< radians
  int count = 0;
  double max_range = 30.0;  ///< metres
};

/// Per-beam results of a full-scan cast, structure of arrays (map-local frame).
struct ScanHits {
  std::vector<float> range;       ///< metres
  std::vector<std::int32_t> col;  ///< -1 without a hit
  std::vector<std::int32_t> row;
  std::vector<HitFace> face;
  void resize(std::size_t n);
};

/// Snapshot of a grid's blocking state prepared for casting. Holds no reference to the grid.
class RayCaster {
 public:
  /// Throws std::invalid_argument for an empty grid.
  explicit RayCaster(const maps::OccupancyGrid& grid, RayCastOptions options = {});

  /// Ray from (x, y) [map-local metres] along direction `angle` [map-local radians].
  /// The start may lie anywhere, inside or outside the grid. A start inside a blocking
  /// cell gives range 0 and HitFace::kStart.
  [[nodiscard]] RayHit cast_local(float x, float y, float angle, float max_range) const noexcept;
  /// Same with a precomputed unit direction (dx, dy).
  [[nodiscard]] RayHit cast_local_dir(float x, float y, float dx, float dy,
                                      float max_range) const noexcept;
  /// Ray in the global frame: from (ray.x, ray.y) along heading ray.theta. The hit point is
  /// returned in the global frame.
  [[nodiscard]] RayHit cast(const Pose2& ray, double max_range) const noexcept;

  /// Noise-free ranges of a full scan from `sensor` (global pose of the laser), parallel
  /// over beams with OpenMP. `ranges.size()` must equal fan.count (throws otherwise).
  void cast_scan(const Pose2& sensor, const BeamFan& fan, std::span<float> ranges) const;
  /// Same, keeping hit cells and faces.
  void cast_scan(const Pose2& sensor, const BeamFan& fan, ScanHits& hits) const;

  /// Outward surface normal of the hit cell in the map-local frame, from the Sobel gradient
  /// of the blocking mask around (col, row). Falls back to the crossed face's normal when
  /// the gradient vanishes or faces away from the incoming ray (dx, dy), and to -dir for
  /// kStart. Used for the angle of incidence of the beam noise model.
  void surface_normal(int col, int row, HitFace face, float dx, float dy, float& nx,
                      float& ny) const noexcept;

  [[nodiscard]] bool blocking(int col, int row) const noexcept {
    return state(col, row) == kBlockingCell;
  }
  [[nodiscard]] int width() const noexcept { return width_; }
  [[nodiscard]] int height() const noexcept { return height_; }
  [[nodiscard]] float resolution() const noexcept { return resolution_; }
  [[nodiscard]] const Pose2& origin() const noexcept { return origin_; }
  [[nodiscard]] const RayCastOptions& options() const noexcept { return options_; }

 private:
  static constexpr std::uint8_t kFreeCell = 0;
  static constexpr std::uint8_t kBlockingCell = 1;
  static constexpr std::uint8_t kAbsorbingCell = 2;
  [[nodiscard]] std::uint8_t state(int col, int row) const noexcept {
    return state_[static_cast<std::size_t>(row) * static_cast<std::size_t>(width_) +
                  static_cast<std::size_t>(col)];
  }

  int width_ = 0;
  int height_ = 0;
  float resolution_ = 0.05F;
  float inv_resolution_ = 20.0F;
  Pose2 origin_{};
  RayCastOptions options_{};
  std::vector<std::uint8_t> state_;  // row-major, one byte per cell
};

/// Convenience: one global-frame ray on `grid` (builds a RayCaster; cache one for loops).
[[nodiscard]] RayHit cast_ray(const maps::OccupancyGrid& grid, const Pose2& ray, double max_range,
                              RayCastOptions options = {});

}  // namespace pgmcl::sims
