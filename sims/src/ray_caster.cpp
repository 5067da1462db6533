#include "pgmcl/sims/ray_caster.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>

namespace pgmcl::sims {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

void face_normal(HitFace face, float dx, float dy, float& nx, float& ny) noexcept {
  switch (face) {
    case HitFace::kMinX:
      nx = -1.0F;
      ny = 0.0F;
      return;
    case HitFace::kMaxX:
      nx = 1.0F;
      ny = 0.0F;
      return;
    case HitFace::kMinY:
      nx = 0.0F;
      ny = -1.0F;
      return;
    case HitFace::kMaxY:
      nx = 0.0F;
      ny = 1.0F;
      return;
    default:
      nx = -dx;
      ny = -dy;
      return;
  }
}

/// One slab of the ray-rectangle clip along one axis: the ray s + t d (inv_d = 1 / d) within
/// [0, extent]. Narrows [t_enter, t_exit] (entry_face records the face crossed last on entry);
/// false when a ray parallel to the slab lies outside it.
bool clip_to_slab(float s, float d, float inv_d, float extent, HitFace min_face, HitFace max_face,
                  float& t_enter, float& t_exit, HitFace& entry_face) noexcept {
  if (d == 0.0F) return !(s < 0.0F || s > extent);  // a NaN start is left to the walk
  float t0 = (0.0F - s) * inv_d;
  float t1 = (extent - s) * inv_d;
  if (t0 > t1) std::swap(t0, t1);
  if (t0 > t_enter) {
    t_enter = t0;
    entry_face = d > 0.0F ? min_face : max_face;
  }
  t_exit = std::min(t_exit, t1);
  return true;
}

/// Casts the beams of `fan` from `local` (the sensor in the grid frame), in parallel for large
/// fans, and hands beam i's hit to store(i, hit).
template <class Store>
void cast_fan(const RayCaster& caster, const Pose2& local, const BeamFan& fan, Store&& store) {
  const auto x = static_cast<float>(local.x);
  const auto y = static_cast<float>(local.y);
  const auto max_range = static_cast<float>(fan.max_range);
  const int n = fan.count;
#ifdef _OPENMP
#pragma omp parallel for schedule(static) if (n >= 256)
#endif
  for (int i = 0; i < n; ++i) {
    const auto a = static_cast<float>(local.theta + fan.angle_min + i * fan.angle_increment);
    store(static_cast<std::size_t>(i),
          caster.cast_local_dir(x, y, std::cos(a), std::sin(a), max_range));
  }
}

}  // namespace

void ScanHits::resize(std::size_t n) {
  range.resize(n);
  col.resize(n);
  row.resize(n);
  face.resize(n);
}

RayCaster::RayCaster(const maps::OccupancyGrid& grid, RayCastOptions options)
    : width_(grid.width()),
      height_(grid.height()),
      resolution_(static_cast<float>(grid.resolution())),
      inv_resolution_(static_cast<float>(1.0 / grid.resolution())),
      origin_(grid.origin()),
      options_(options) {
  if (grid.empty()) throw std::invalid_argument("RayCaster: the occupancy grid is empty");
  const std::uint8_t unknown_state = options.unknown == UnknownCellPolicy::kBlock ? kBlockingCell
                                     : options.unknown == UnknownCellPolicy::kAbsorb
                                         ? kAbsorbingCell
                                         : kFreeCell;
  const auto threshold = grid.occupied_threshold();
  state_.resize(grid.size());
  const auto& cells = grid.cells();
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const std::int8_t v = cells[i];
    state_[i] = v < 0 ? unknown_state : (v >= threshold ? kBlockingCell : kFreeCell);
  }
}

RayHit RayCaster::cast_local(float x, float y, float angle, float max_range) const noexcept {
  return cast_local_dir(x, y, std::cos(angle), std::sin(angle), max_range);
}

// Amanatides & Woo (1987) in cell units. t is the distance along the ray in cells; each
// next-boundary distance is recomputed from the integer boundary, so no error accumulates
// over long rays.
RayHit RayCaster::cast_local_dir(float x, float y, float dx, float dy,
                                 float max_range) const noexcept {
  assert(std::abs(dx * dx + dy * dy - 1.0F) < 1e-3F);
  RayHit out;
  out.range = max_range;
  out.x = static_cast<double>(x + max_range * dx);
  out.y = static_cast<double>(y + max_range * dy);

  const float sx = x * inv_resolution_;
  const float sy = y * inv_resolution_;
  const float t_limit = max_range * inv_resolution_;
  const auto w = static_cast<float>(width_);
  const auto h = static_cast<float>(height_);
  const float inv_dx = dx != 0.0F ? 1.0F / dx : kInf;
  const float inv_dy = dy != 0.0F ? 1.0F / dy : kInf;

  // Clip the ray to the grid rectangle [0, w] x [0, h] (slab method), so starts outside
  // the grid are handled too.
  float t_enter = 0.0F;
  float t_exit = t_limit;
  HitFace entry_face = HitFace::kStart;
  if (!clip_to_slab(sx, dx, inv_dx, w, HitFace::kMinX, HitFace::kMaxX, t_enter, t_exit,
                    entry_face) ||
      !clip_to_slab(sy, dy, inv_dy, h, HitFace::kMinY, HitFace::kMaxY, t_enter, t_exit,
                    entry_face) ||
      t_enter > t_exit) {
    return out;
  }

  int col = std::clamp(static_cast<int>(std::floor(sx + t_enter * dx)), 0, width_ - 1);
  int row = std::clamp(static_cast<int>(std::floor(sy + t_enter * dy)), 0, height_ - 1);
  const int step_x = dx > 0.0F ? 1 : (dx < 0.0F ? -1 : 0);
  const int step_y = dy > 0.0F ? 1 : (dy < 0.0F ? -1 : 0);
  const int off_x = dx > 0.0F ? 1 : 0;  // the next x boundary is col + off_x
  const int off_y = dy > 0.0F ? 1 : 0;
  float t_max_x = step_x != 0 ? (static_cast<float>(col + off_x) - sx) * inv_dx : kInf;
  float t_max_y = step_y != 0 ? (static_cast<float>(row + off_y) - sy) * inv_dy : kInf;
  float t = t_enter;
  HitFace face = entry_face;

  for (;;) {
    const std::uint8_t s = state(col, row);
    if (s == kBlockingCell) break;
    if (s == kAbsorbingCell) return out;
    if (t_max_x < t_max_y) {
      t = t_max_x;
      col += step_x;
      if (col < 0 || col >= width_) return out;
      t_max_x = (static_cast<float>(col + off_x) - sx) * inv_dx;
      face = step_x > 0 ? HitFace::kMinX : HitFace::kMaxX;
    } else {
      t = t_max_y;
      row += step_y;
      if (row < 0 || row >= height_) return out;
      t_max_y = (static_cast<float>(row + off_y) - sy) * inv_dy;
      face = step_y > 0 ? HitFace::kMinY : HitFace::kMaxY;
    }
    if (t > t_limit) return out;
  }

  const float range = std::max(t, 0.0F) * resolution_;
  if (range > max_range) return out;
  float px = sx + t * dx;
  float py = sy + t * dy;
  // The crossed coordinate lies exactly on the cell boundary; snap it so the hit point
  // carries no rounding error across the wall.
  switch (face) {
    case HitFace::kMinX:
      px = static_cast<float>(col);
      break;
    case HitFace::kMaxX:
      px = static_cast<float>(col + 1);
      break;
    case HitFace::kMinY:
      py = static_cast<float>(row);
      break;
    case HitFace::kMaxY:
      py = static_cast<float>(row + 1);
      break;
    default:
      break;
  }
  out.range = range;
  out.hit = true;
  out.col = col;
  out.row = row;
  out.face = face;
  out.x = static_cast<double>(px * resolution_);
  out.y = static_cast<double>(py * resolution_);
  return out;
}

RayHit RayCaster::cast(const Pose2& ray, double max_range) const noexcept {
  const Pose2 local = origin_.between(ray);
  RayHit hit = cast_local(static_cast<float>(local.x), static_cast<float>(local.y),
                          static_cast<float>(local.theta), static_cast<float>(max_range));
  double gx = 0.0, gy = 0.0;
  origin_.transform_point(hit.x, hit.y, gx, gy);
  hit.x = gx;
  hit.y = gy;
  return hit;
}

void RayCaster::cast_scan(const Pose2& sensor, const BeamFan& fan, std::span<float> ranges) const {
  if (fan.count < 0 || ranges.size() != static_cast<std::size_t>(fan.count)) {
    throw std::invalid_argument("RayCaster::cast_scan: ranges has " +
                                std::to_string(ranges.size()) + " entries for " +
                                std::to_string(fan.count) + " beams");
  }
  cast_fan(*this, origin_.between(sensor), fan,
           [ranges](std::size_t i, const RayHit& hit) { ranges[i] = hit.range; });
}

void RayCaster::cast_scan(const Pose2& sensor, const BeamFan& fan, ScanHits& hits) const {
  if (fan.count < 0) throw std::invalid_argument("RayCaster::cast_scan: negative beam count");
  hits.resize(static_cast<std::size_t>(fan.count));
  cast_fan(*this, origin_.between(sensor), fan, [&hits](std::size_t i, const RayHit& hit) {
    hits.range[i] = hit.range;
    hits.col[i] = hit.col;
    hits.row[i] = hit.row;
    hits.face[i] = hit.face;
  });
}

// The wall through the hit cell is fitted by principal components of the nearby surface
// cells: blocking cells within two cells of the hit cell that have a non-blocking
// 4-neighbour on the side the ray comes from. Restricting to that side keeps thick walls
// to their visible surface and makes one-cell-thick walls (whose plain occupancy gradient
// vanishes) work; an 8-connected 45-degree staircase gives exactly the diagonal normal.
void RayCaster::surface_normal(int col, int row, HitFace face, float dx, float dy, float& nx,
                               float& ny) const noexcept {
  face_normal(face, dx, dy, nx, ny);
  if (face == HitFace::kStart || face == HitFace::kNone) return;
  auto open = [this](int c, int r) {
    return c < 0 || r < 0 || c >= width_ || r >= height_ || state(c, r) != kBlockingCell;
  };
  constexpr int kRadius = 2;
  constexpr int kDirs[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
  float sum_x = 0.0F, sum_y = 0.0F, sxx = 0.0F, syy = 0.0F, sxy = 0.0F;
  int count = 0;
  for (int j = -kRadius; j <= kRadius; ++j) {
    for (int i = -kRadius; i <= kRadius; ++i) {
      const int c = col + i, r = row + j;
      if (open(c, r)) continue;
      bool surface = false;
      for (const auto& d : kDirs) {
        if (-(d[0] * dx + d[1] * dy) > 1e-6F && open(c + d[0], r + d[1])) surface = true;
      }
      if (!surface) continue;
      const auto fi = static_cast<float>(i), fj = static_cast<float>(j);
      sum_x += fi;
      sum_y += fj;
      sxx += fi * fi;
      syy += fj * fj;
      sxy += fi * fj;
      ++count;
    }
  }
  if (count < 3) return;
  const auto n = static_cast<float>(count);
  const float cxx = sxx / n - (sum_x / n) * (sum_x / n);
  const float cyy = syy / n - (sum_y / n) * (sum_y / n);
  const float cxy = sxy / n - (sum_x / n) * (sum_y / n);
  const float half_tr = 0.5F * (cxx + cyy);
  const float disc = std::sqrt(std::max(0.0F, 0.25F * (cxx - cyy) * (cxx - cyy) + cxy * cxy));
  const float l_max = half_tr + disc;
  const float l_min = half_tr - disc;
  // Corners and blobs have no dominant direction: keep the crossed face's normal.
  if (!(l_max > 0.0F) || l_min > 0.25F * l_max) return;
  // Tangent = eigenvector of l_max; the normal is perpendicular to it.
  float tx = cxy, ty = l_max - cxx;
  if (std::abs(tx) + std::abs(ty) < 1e-9F) {
    tx = l_max - cyy;
    ty = cxy;
  }
  const float len = std::hypot(tx, ty);
  if (!(len > 0.0F)) return;
  float mx = -ty / len, my = tx / len;
  if (mx * dx + my * dy > 0.0F) {
    mx = -mx;
    my = -my;
  }
  nx = mx;
  ny = my;
}

RayHit cast_ray(const maps::OccupancyGrid& grid, const Pose2& ray, double max_range,
                RayCastOptions options) {
  return RayCaster(grid, options).cast(ray, max_range);
}

}  // namespace pgmcl::sims
