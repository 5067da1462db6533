#include "pgmcl/maps/occupancy_mapping.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace pgmcl::maps {
namespace {

[[noreturn]] void bad_field(const std::string& field, const std::string& problem) {
  throw std::invalid_argument("OccupancyMappingConfig." + field + ": " + problem);
}

[[nodiscard]] double logit(double p) {
  return std::log(p / (1.0 - p));
}

/// What one beam contributes: the segment to clear and whether its end is a hit.
struct BeamSegment {
  double length = 0.0;  ///< metres cleared (up to the endpoint)
  bool hit = false;     ///< endpoint is an obstacle
  bool valid = false;   ///< false: reading ignored altogether
};

[[nodiscard]] BeamSegment classify_beam(double r, const RangeScanView& scan,
                                        const OccupancyMappingConfig& config) {
  BeamSegment seg;
  if (!(r >= 0.0) || r < scan.range_min) return seg;  // NaN, negative or below range_min
  seg.valid = true;
  if (r >= scan.no_return_range || r > config.max_hit_range || !std::isfinite(r)) {
    seg.length = std::min(r, config.no_return_clear_range);
    return seg;
  }
  seg.length = r;
  seg.hit = true;
  return seg;
}

/// Liang-Barsky clipping of p0 + t (p1 - p0), t in [0, 1], to [0, w] x [0, h].
/// Returns false when the segment misses the box.
[[nodiscard]] bool clip_segment(double w, double h, double& x0, double& y0, double& x1,
                                double& y1) {
  const double dx = x1 - x0, dy = y1 - y0;
  double t0 = 0.0, t1 = 1.0;
  const double p[4] = {-dx, dx, -dy, dy};
  const double q[4] = {x0, w - x0, y0, h - y0};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0.0) {
      if (q[i] < 0.0) return false;
      continue;
    }
    const double t = q[i] / p[i];
    if (p[i] < 0.0) {
      t0 = std::max(t0, t);
    } else {
      t1 = std::min(t1, t);
    }
    if (t0 > t1) return false;
  }
  const double ox = x0, oy = y0;
  x0 = ox + t0 * dx;
  y0 = oy + t0 * dy;
  x1 = ox + t1 * dx;
  y1 = oy + t1 * dy;
  return true;
}

}  // namespace

void OccupancyMappingConfig::validate() const {
  if (!(resolution > 0.0) || !std::isfinite(resolution)) bad_field("resolution", "must be > 0");
  if (!(margin >= 0.0) || !std::isfinite(margin)) bad_field("margin", "must be >= 0");
  if (!(l_occ > 0.0)) bad_field("l_occ", "must be > 0");
  if (!(l_free < 0.0)) bad_field("l_free", "must be < 0");
  if (!(l_min < 0.0)) bad_field("l_min", "must be < 0");
  if (!(l_max > 0.0)) bad_field("l_max", "must be > 0");
  if (!(no_return_clear_range >= 0.0)) bad_field("no_return_clear_range", "must be >= 0");
  if (!(max_hit_range > 0.0)) bad_field("max_hit_range", "must be > 0");
  if (!(occupied_thresh > 0.5 && occupied_thresh < 1.0))
    bad_field("occupied_thresh", "must be in (0.5, 1)");
  if (!(free_thresh > 0.0 && free_thresh < 0.5)) bad_field("free_thresh", "must be in (0, 0.5)");
}

MapBounds compute_map_bounds(std::span<const RangeScanView> scans,
                             const OccupancyMappingConfig& config) {
  config.validate();
  constexpr double kInf = std::numeric_limits<double>::infinity();
  MapBounds b{kInf, kInf, -kInf, -kInf};
  auto grow = [&b](double x, double y) {
    b.min_x = std::min(b.min_x, x);
    b.min_y = std::min(b.min_y, y);
    b.max_x = std::max(b.max_x, x);
    b.max_y = std::max(b.max_y, y);
  };
  for (const auto& scan : scans) {
    const Pose2& s = scan.sensor_pose;
    if (!std::isfinite(s.x) || !std::isfinite(s.y) || !std::isfinite(s.theta)) {
      throw std::invalid_argument("compute_map_bounds: non-finite sensor pose");
    }
    grow(s.x, s.y);
    for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
      const BeamSegment seg = classify_beam(scan.ranges[i], scan, config);
      if (!seg.valid) continue;
      const double a = s.theta + scan.angle_min + static_cast<double>(i) * scan.angle_increment;
      grow(s.x + seg.length * std::cos(a), s.y + seg.length * std::sin(a));
    }
  }
  if (!(b.min_x <= b.max_x)) throw std::invalid_argument("compute_map_bounds: no scans");
  const double res = config.resolution;
  // k * res carries the binary error of res (418 * 0.05 = 20.900000000000002): snapped to
  // the nanometre, the origin a map file records is the decimal a person would write.
  auto snap = [](double v) { return std::abs(v) < 1e6 ? std::round(v * 1e9) / 1e9 : v; };
  b.min_x = snap(std::floor((b.min_x - config.margin) / res) * res);
  b.min_y = snap(std::floor((b.min_y - config.margin) / res) * res);
  b.max_x = snap(std::ceil((b.max_x + config.margin) / res) * res);
  b.max_y = snap(std::ceil((b.max_y + config.margin) / res) * res);
  // A degenerate extent (one pose, no readings, zero margin) still gets one cell.
  if (b.max_x <= b.min_x) b.max_x = b.min_x + res;
  if (b.max_y <= b.min_y) b.max_y = b.min_y + res;
  return b;
}

OccupancyMapper::OccupancyMapper(const MapBounds& bounds, const OccupancyMappingConfig& config)
    : config_(config), origin_x_(bounds.min_x), origin_y_(bounds.min_y) {
  config_.validate();
  const double w = std::round((bounds.max_x - bounds.min_x) / config_.resolution);
  const double h = std::round((bounds.max_y - bounds.min_y) / config_.resolution);
  constexpr double kMaxCells = 1u << 30;  // 1 Gi cells: a bogus pose, not a building
  if (!(w >= 1.0) || !(h >= 1.0) || w * h > kMaxCells) {
    throw std::invalid_argument("OccupancyMapper: bounds give a " + std::to_string(w) + " x " +
                                std::to_string(h) + " cell grid (need 1 .. 2^30 cells)");
  }
  width_ = static_cast<int>(w);
  height_ = static_cast<int>(h);
  const auto n = static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
  log_odds_.assign(n, 0.0f);
  hit_stamp_.assign(n, 0u);
  free_stamp_.assign(n, 0u);
}

void OccupancyMapper::traverse_free(double c0, double r0, double c1, double r1) {
  if (!clip_segment(width_, height_, c0, r0, c1, r1)) return;
  int c = static_cast<int>(std::floor(c0)), r = static_cast<int>(std::floor(r0));
  const int ce = static_cast<int>(std::floor(c1)), re = static_cast<int>(std::floor(r1));
  const double dc = c1 - c0, dr = r1 - r0;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const int step_c = dc > 0.0 ? 1 : -1, step_r = dr > 0.0 ? 1 : -1;
  // Amanatides & Woo: t at which the ray crosses the next column / row boundary.
  const double delta_c = dc != 0.0 ? 1.0 / std::abs(dc) : kInf;
  const double delta_r = dr != 0.0 ? 1.0 / std::abs(dr) : kInf;
  double t_c = dc != 0.0 ? (step_c > 0 ? (c + 1 - c0) : (c0 - c)) * delta_c : kInf;
  double t_r = dr != 0.0 ? (step_r > 0 ? (r + 1 - r0) : (r0 - r)) * delta_r : kInf;
  const int max_steps = std::abs(ce - c) + std::abs(re - r) + 1;
  for (int k = 0; k < max_steps && (c != ce || r != re); ++k) {
    if (c >= 0 && r >= 0 && c < width_ && r < height_) {
      const std::size_t i = index(c, r);
      if (free_stamp_[i] != stamp_) {
        free_stamp_[i] = stamp_;
        touched_.push_back(i);
      }
    }
    if (t_c < t_r) {
      c += step_c;
      t_c += delta_c;
    } else {
      r += step_r;
      t_r += delta_r;
    }
  }
}

void OccupancyMapper::integrate(const RangeScanView& scan) {
  ++stamp_;
  ++scans_;
  touched_.clear();
  hits_.clear();
  const double inv_res = 1.0 / config_.resolution;
  const Pose2& s = scan.sensor_pose;
  const double c0 = (s.x - origin_x_) * inv_res, r0 = (s.y - origin_y_) * inv_res;
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    const BeamSegment seg = classify_beam(scan.ranges[i], scan, config_);
    if (!seg.valid) continue;
    const double a = s.theta + scan.angle_min + static_cast<double>(i) * scan.angle_increment;
    const double c1 = c0 + seg.length * inv_res * std::cos(a);
    const double r1 = r0 + seg.length * inv_res * std::sin(a);
    traverse_free(c0, r0, c1, r1);
    if (!seg.hit) continue;
    const int hc = static_cast<int>(std::floor(c1)), hr = static_cast<int>(std::floor(r1));
    if (hc < 0 || hr < 0 || hc >= width_ || hr >= height_) continue;
    const std::size_t h = index(hc, hr);
    if (hit_stamp_[h] != stamp_) {
      hit_stamp_[h] = stamp_;
      hits_.push_back(h);
    }
  }
  const auto lmin = static_cast<float>(config_.l_min), lmax = static_cast<float>(config_.l_max);
  // Table 9.1: l <- l + inverse_sensor_model - l0 (l0 = 0, prior p = 0.5), clamped.
  for (const std::size_t i : touched_) {
    if (hit_stamp_[i] == stamp_) continue;  // occupied wins within a scan
    log_odds_[i] = std::clamp(log_odds_[i] + static_cast<float>(config_.l_free), lmin, lmax);
  }
  for (const std::size_t i : hits_) {
    log_odds_[i] = std::clamp(log_odds_[i] + static_cast<float>(config_.l_occ), lmin, lmax);
  }
}

OccupancyGrid OccupancyMapper::to_grid() const {
  OccupancyGrid grid(width_, height_, config_.resolution, Pose2{origin_x_, origin_y_, 0.0},
                     kUnknown);
  const auto occ = static_cast<float>(logit(config_.occupied_thresh));
  const auto fre = static_cast<float>(logit(config_.free_thresh));
  auto& cells = grid.cells();
  for (std::size_t i = 0; i < log_odds_.size(); ++i) {
    if (log_odds_[i] >= occ) {
      cells[i] = kOccupied;
    } else if (log_odds_[i] <= fre) {
      cells[i] = kFree;
    }
  }
  return grid;
}

OccupancyGrid build_occupancy_map(std::span<const RangeScanView> scans,
                                  const OccupancyMappingConfig& config) {
  OccupancyMapper mapper(compute_map_bounds(scans, config), config);
  for (const auto& scan : scans) mapper.integrate(scan);
  return mapper.to_grid();
}

}  // namespace pgmcl::maps
