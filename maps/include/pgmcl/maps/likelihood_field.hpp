#pragma once
/// Precomputed likelihood tables: sensor_model::BeamLikelihood (the per-beam model of Dekan
/// et al., Eq. (6), with its floor and quantisation) rasterised on an occupancy grid.
///
/// A table stores q in 0..255 per lookup, the model's quantised log-likelihood; q =
/// background is the floor, read for cells beyond the kernel's reach and outside the map.
/// Three kinds:
///  - kIsotropic:    1 byte/cell, a function of the distance to the nearest obstacle,
///                   with sigma_along_eff for both axes (exact when the sigmas agree).
///  - kOrientedBins: K bytes/cell, one plane per beam-direction bin over [0, pi)
///                   (the planar Gaussian is symmetric under u -> -u).
///  - kOffsetField:  2 bytes/cell, the offset (in cells) to the nearest obstacle cell centre;
///                   at lookup it is projected onto the beam direction and its normal and
///                   the squared Mahalanobis distance indexes a 1D quantised table.
/// The views below describe the tables; table_kernels.hpp holds the code that reads them.

#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "pgmcl/common/enum_names.hpp"
#include "pgmcl/maps/occupancy_grid.hpp"
#include "pgmcl/sensor_model/beam_likelihood.hpp"

namespace pgmcl::maps {

enum class TableKind : std::uint8_t { kIsotropic, kOrientedBins, kOffsetField };

/// The names of the table kinds, as configs and the command line write them.
inline constexpr std::array<EnumName<TableKind>, 3> kTableKindNames{{
    {TableKind::kIsotropic, "isotropic"},
    {TableKind::kOrientedBins, "oriented"},
    {TableKind::kOffsetField, "offset"},
}};

[[nodiscard]] const char* to_string(TableKind kind) noexcept;
/// Parses "isotropic" | "oriented" | "offset"; throws std::invalid_argument otherwise.
[[nodiscard]] TableKind table_kind_from_string(const std::string& name);

/// floor_to_cell without the clamps: exact for c >= -1024, still negative (off the map)
/// below that. The caller guarantees |c| < 1e9 (or NaN-free values in int range); the
/// measurement kernels check that once per particle, because the clamps keep GCC from
/// vectorising their per-beam transform loops.
[[nodiscard]] inline int floor_to_cell_unclamped(float c) noexcept {
  return static_cast<int>(c + 1024.0f) - 1024;
}

/// floor() for the hot path, without a libm call (see floor_to_cell_unclamped).
/// Coordinates are clamped to +/-1e9 cells first: a float beyond int range (particles
/// thrown off by absurd odometry) must read "off the map", and converting it would be
/// undefined behaviour. NaN fails the first comparison and goes to -1e9 (off the map) too.
[[nodiscard]] inline int floor_to_cell(float c) noexcept {
  c = c > -1.0e9f ? c : -1.0e9f;
  c = c < 1.0e9f ? c : 1.0e9f;
  return floor_to_cell_unclamped(c);
}

/// Isotropic table: q[row * width + col].
struct IsotropicView {
  const std::uint8_t* q = nullptr;
  int width = 0;
  int height = 0;
  std::uint8_t background = 255;
};

/// Oriented tables: plane b holds the field for beam directions in [b, b+1) * pi / bins.
struct OrientedView {
  const std::uint8_t* q = nullptr;
  int width = 0;
  int height = 0;
  int bins = 1;
  std::size_t plane_stride = 0;  ///< width * height
  float bins_per_radian = 0.0f;  ///< bins / pi
  std::uint8_t background = 255;
};

/// Offset field: off[2 * (row * width + col)] = (dcol, drow) from the cell to the nearest
/// obstacle cell, in cells; dcol == kNoObstacle marks cells beyond the kernel's reach.
struct OffsetView {
  static constexpr std::int8_t kNoObstacle = -128;
  const std::int8_t* off = nullptr;
  int width = 0;
  int height = 0;
  const std::uint8_t* lut = nullptr;  ///< q as a function of squared Mahalanobis distance
  int lut_size = 0;
  float lut_steps_per_unit = 0.0f;  ///< LUT index = m2 * lut_steps_per_unit
  float inv_var_along = 0.0f;       ///< 1 / sigma_along^2, in 1/cells^2
  float inv_var_across = 0.0f;      ///< 1 / sigma_across^2, in 1/cells^2
  std::uint8_t background = 255;
};

struct LikelihoodFieldOptions {
  TableKind kind = TableKind::kIsotropic;
  int orientation_bins = 16;  ///< K for kOrientedBins
  /// Background from m2 = reach_sigmas^2 on; cells farther than reach_sigmas * max(sigma_eff)
  /// from every obstacle are never computed.
  double reach_sigmas = 4.0;
  /// |sigma_along_eff / sigma_across_eff - 1| below this: oriented -> isotropic. 0.1 makes
  /// the paper's sigmas isotropic at 5 cm (ratio 1.052) and anisotropic at 2.5 cm (1.176).
  double isotropy_tolerance = 0.1;
  std::size_t max_table_bytes = std::size_t{8} << 30;  ///< clear error beyond this
};

/// What a build did, for reports and tests.
struct LikelihoodFieldStats {
  int reach_cells = 0;
  bool orientation_skipped = false;  ///< oriented requested but kernel isotropic at this res
  std::size_t cells_computed = 0;    ///< cells holding a non-background value (within reach)
  std::size_t sources_stamped = 0;   ///< obstacle cells whose kernel was stamped
  std::size_t bytes = 0;             ///< hot tables + LUT
  double build_seconds = 0.0;
};

/// Owns the tables for one grid. Built once, read concurrently (all const methods are
/// thread-safe).
class LikelihoodField {
 public:
  /// Throws std::invalid_argument for invalid params (see BeamLikelihoodParams::validate),
  /// bins < 1, reach_sigmas <= 0, an empty grid, or an offset-field reach beyond 127 cells,
  /// and std::length_error (with the byte count) when the table would exceed
  /// options.max_table_bytes; both before allocating the table.
  LikelihoodField(const OccupancyGrid& grid, const sensor_model::BeamLikelihoodParams& params,
                  const LikelihoodFieldOptions& options = {});

  [[nodiscard]] TableKind kind() const noexcept { return kind_; }  ///< after any fallback
  /// The per-beam function the tables rasterise (at this grid's resolution and reach).
  [[nodiscard]] const sensor_model::BeamLikelihood& model() const noexcept { return model_; }
  [[nodiscard]] const LikelihoodFieldStats& stats() const noexcept { return stats_; }
  [[nodiscard]] int width() const noexcept { return width_; }
  [[nodiscard]] int height() const noexcept { return height_; }
  [[nodiscard]] double resolution() const noexcept { return resolution_; }
  [[nodiscard]] const Pose2& origin() const noexcept { return origin_; }

  [[nodiscard]] IsotropicView isotropic() const noexcept;  ///< valid when kind()==kIsotropic
  [[nodiscard]] OrientedView oriented() const noexcept;    ///< valid when kind()==kOrientedBins
  [[nodiscard]] OffsetView offset() const noexcept;        ///< valid when kind()==kOffsetField

  /// Per cell (row-major), the smallest q a beam of any direction can read with its endpoint
  /// anywhere in that cell: a lower bound for searches over poses.
  [[nodiscard]] std::vector<std::uint8_t> best_case_table() const;

 private:
  TableKind kind_ = TableKind::kIsotropic;
  sensor_model::BeamLikelihood model_;
  LikelihoodFieldStats stats_{};
  int width_ = 0;
  int height_ = 0;
  double resolution_ = 0.0;
  Pose2 origin_{};
  int bins_ = 1;
  std::vector<std::uint8_t> q_;       // isotropic / oriented planes
  std::vector<std::int8_t> offsets_;  // offset field
  std::vector<std::uint8_t> lut_;     // offset field LUT
  float lut_steps_per_unit_ = 0.0f;
  int lut_size_ = 0;
};

}  // namespace pgmcl::maps
