#pragma once
/// Occupancy grid mapping with known poses: Probabilistic Robotics (Thrun, Burgard, Fox),
/// Table 9.1 (occupancy_grid_mapping, log-odds form) with the inverse range sensor model of
/// Table 9.2: cells a ray passes through before its endpoint are "free", the endpoint cell
/// is "occupied", cells beyond are untouched.
///
/// Details that Table 9.2 leaves open, chosen here (and why):
///  - Each cell is updated at most once per scan, and "occupied" wins over "free" within a
///    scan (as OctoMap does). Without this, cells near the robot get one free update per
///    beam and a wall cell grazed by neighbouring beams is cleared by the very scan that
///    hit it.
///  - "No return" readings (range >= the scan's no_return_range, e.g. 81.9 m or 50 m for
///    SICK scanners) mark nothing occupied and clear free space only up to
///    `no_return_clear_range`: glass, black surfaces and open doors also give no return,
///    so clearing the whole ray would erase real walls (Cartographer clears such "missing
///    data" rays to missing_data_ray_length, 5 m by default, for the same reason).
///  - Log-odds are clamped to [l_min, l_max] so the map can still change (OctoMap's
///    clamping policy).
///
/// Pure numerics: no I/O. The caller supplies global sensor poses and ranges.

#include <cstdint>
#include <span>
#include <vector>

#include "pgmcl/common/se2.hpp"
#include "pgmcl/maps/occupancy_grid.hpp"

namespace pgmcl::maps {

/// Parameters of the log-odds mapper. Defaults follow OctoMap's sensor model
/// (p_hit 0.7, p_miss 0.4, clamping 0.12 .. 0.97).
struct OccupancyMappingConfig {
  double resolution = 0.05;            ///< metres per cell, > 0
  double margin = 1.0;                 ///< metres added around the data bounds, >= 0
  double l_occ = 0.85;                 ///< log-odds added for the endpoint cell (p = 0.7)
  double l_free = -0.4;                ///< log-odds added for traversed cells (p = 0.4)
  double l_min = -2.0;                 ///< clamp, log-odds (p = 0.12)
  double l_max = 3.5;                  ///< clamp, log-odds (p = 0.97)
  double no_return_clear_range = 5.0;  ///< metres cleared along a "no return" beam
  double max_hit_range = 1e9;          ///< metres; longer real returns are treated as no return
  double occupied_thresh = 0.65;       ///< output: p >= this -> occupied (100)
  double free_thresh = 0.35;           ///< output: p <= this -> free (0); between -> unknown

  /// Throws std::invalid_argument naming the offending field.
  void validate() const;
};

/// One scan as the mapper needs it: ranges along beams from a known global sensor pose.
struct RangeScanView {
  Pose2 sensor_pose{};            ///< global pose of the sensor (metres, radians)
  double angle_min = 0.0;         ///< radians, first beam in the sensor frame
  double angle_increment = 0.0;   ///< radians between consecutive beams
  double range_min = 0.0;         ///< metres; shorter readings are ignored
  double no_return_range = 1e9;   ///< metres; readings at or beyond mean "no return"
  std::span<const float> ranges;  ///< metres; NaN / negative readings are ignored
};

/// Axis-aligned bounds (global frame, metres) of everything the scans touch, plus the
/// configured margin, snapped outwards to multiples of the resolution.
struct MapBounds {
  double min_x = 0.0, min_y = 0.0, max_x = 0.0, max_y = 0.0;
};
[[nodiscard]] MapBounds compute_map_bounds(std::span<const RangeScanView> scans,
                                           const OccupancyMappingConfig& config);

/// Accumulates log-odds over a fixed axis-aligned grid.
class OccupancyMapper {
 public:
  /// Throws std::invalid_argument for an invalid config or empty bounds.
  OccupancyMapper(const MapBounds& bounds, const OccupancyMappingConfig& config);

  /// Table 9.1's loop body for one scan. Rays leaving the grid are clipped to it.
  void integrate(const RangeScanView& scan);

  /// Trinary grid (0 / 100 / -1) by thresholding p = 1 - 1 / (1 + exp(l)).
  [[nodiscard]] OccupancyGrid to_grid() const;

  [[nodiscard]] int width() const noexcept { return width_; }
  [[nodiscard]] int height() const noexcept { return height_; }
  [[nodiscard]] double log_odds(int col, int row) const noexcept {
    return log_odds_[index(col, row)];
  }
  [[nodiscard]] std::size_t scans_integrated() const noexcept { return scans_; }

 private:
  [[nodiscard]] std::size_t index(int col, int row) const noexcept {
    return static_cast<std::size_t>(row) * static_cast<std::size_t>(width_) +
           static_cast<std::size_t>(col);
  }
  /// Marks the cells strictly between (c0, r0) and (c1, r1) (fractional cell coordinates)
  /// as seen free in this scan (Amanatides & Woo grid traversal).
  void traverse_free(double c0, double r0, double c1, double r1);

  OccupancyMappingConfig config_;
  int width_ = 0;
  int height_ = 0;
  double origin_x_ = 0.0;
  double origin_y_ = 0.0;
  std::vector<float> log_odds_;
  // Per-scan bookkeeping: the scan number that last marked a cell hit / free.
  std::vector<std::uint32_t> hit_stamp_;
  std::vector<std::uint32_t> free_stamp_;
  std::vector<std::size_t> touched_;  // cells marked free in the current scan
  std::vector<std::size_t> hits_;     // cells marked hit in the current scan
  std::uint32_t stamp_ = 0;
  std::size_t scans_ = 0;
};

/// Convenience: bounds from all scans, integrate them in order, return the trinary grid.
[[nodiscard]] OccupancyGrid build_occupancy_map(std::span<const RangeScanView> scans,
                                                const OccupancyMappingConfig& config);

}  // namespace pgmcl::maps
