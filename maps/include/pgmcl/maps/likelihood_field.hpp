#pragma once
/// Precomputed likelihood tables for the planar Gaussian beam model
/// (Dekan et al., Eq. (6)), rasterised on an occupancy grid.
///
/// Quantisation (all kinds): a table stores q in 0..255 per lookup, meaning the per-beam
/// log-likelihood  ll = ll_max - q * nats_per_step.  q = background (255 unless stated) is
/// the floor: the uniform "random reading" term, read for cells beyond the kernel's reach
/// and outside the map. The filter sums q over beams in integers (exact, order-independent)
/// and converts once per particle: log w = -nats_per_step * sum_q (+ constant).
///
/// Three kinds:
///  - kIsotropic:    1 byte/cell, a function of the distance to the nearest obstacle.
///  - kOrientedBins: K bytes/cell, one plane per beam-direction bin over [0, pi)
///                   (the planar Gaussian is symmetric under u -> -u).
///  - kOffsetField:  2 bytes/cell, the offset (in cells) to the nearest obstacle cell centre;
///                   at lookup it is projected onto the beam direction and its normal and
///                   the squared Mahalanobis distance indexes a 1D quantised table.
/// The hot loop reads these through the trivially-copyable *View structs below.
///
/// The per-beam likelihood (one definition for all kinds, so kinds are comparable).
/// With d the vector from the endpoint to an obstacle cell centre, u the beam direction and
///   m2 = (d.u)^2 / sigma_along_eff^2 + (d x u)^2 / sigma_across_eff^2
/// its squared Mahalanobis distance in the metric of Eq. (6), minimised over obstacle cells:
///   p(endpoint) = w_hit * exp(-m2 / 2) / (sqrt(2 pi) sigma_along_eff) + w_rand / max_range.
/// Eq. (6) is a density per m^2; a range reading is a density per metre along the beam, so
/// the hit term keeps the along-beam normaliser of Eq. (4) and uses the across-beam factor
/// exp(-y^2 / 2 sigma_y^2) unnormalised (peak 1), i.e. as a penalty for lateral misfit.
/// Both terms are then per metre and the mixture with the uniform term is well defined.
/// Endpoints with m2 >= reach_sigmas^2 (and cells farther than reach_sigmas * max(sigma_eff)
/// from every obstacle) read the background ll_background = log(w_rand / max_range)
/// (with w_rand = 0: the hit term's value at m2 = reach_sigmas^2).
///
/// Quantisation scale: nats_per_step = (ll_max - ll_background) / 255, ll_max = ll(m2 = 0),
/// q = round((ll_max - ll) / nats_per_step), so q = 0 is a perfect hit and 255 the floor.
/// Paper sigmas on a 5 mm grid: 0.0414 nats per step; on a 5 cm grid: 0.0376.
/// (If w_hit = 0 the model is flat: every q, the background included, is 0.)

#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "pgmcl/maps/occupancy_grid.hpp"
#include "pgmcl/sensor_model/paper_constants.hpp"

namespace pgmcl::maps {

enum class TableKind : std::uint8_t { kIsotropic, kOrientedBins, kOffsetField };

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

  /// (col, row) are fractional cell coordinates in the map-local grid frame.
  [[nodiscard]] std::uint8_t lookup(float col, float row) const noexcept {
    const int c = floor_to_cell(col), r = floor_to_cell(row);
    if (static_cast<unsigned>(c) >= static_cast<unsigned>(width) ||
        static_cast<unsigned>(r) >= static_cast<unsigned>(height))
      return background;
    return q[static_cast<std::size_t>(r) * static_cast<std::size_t>(width) +
             static_cast<std::size_t>(c)];
  }
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

  /// Bin of a beam direction (radians, any value): the direction is taken modulo pi.
  [[nodiscard]] int bin_of(float beam_angle) const noexcept {
    float b = beam_angle * bins_per_radian;  // in bins; period = bins
    const float period = static_cast<float>(bins);
    b -= period * std::floor(b / period);
    int ib = static_cast<int>(b);
    return ib >= bins ? 0 : ib;
  }
  [[nodiscard]] std::uint8_t lookup(float col, float row, int bin) const noexcept {
    const int c = floor_to_cell(col), r = floor_to_cell(row);
    if (static_cast<unsigned>(c) >= static_cast<unsigned>(width) ||
        static_cast<unsigned>(r) >= static_cast<unsigned>(height))
      return background;
    return q[static_cast<std::size_t>(bin) * plane_stride +
             static_cast<std::size_t>(r) * static_cast<std::size_t>(width) +
             static_cast<std::size_t>(c)];
  }
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

  /// (ux, uy) is the unit beam direction in the grid frame.
  [[nodiscard]] std::uint8_t lookup(float col, float row, float ux, float uy) const noexcept {
    const int c = floor_to_cell(col), r = floor_to_cell(row);
    if (static_cast<unsigned>(c) >= static_cast<unsigned>(width) ||
        static_cast<unsigned>(r) >= static_cast<unsigned>(height))
      return background;
    const std::size_t i = 2 * (static_cast<std::size_t>(r) * static_cast<std::size_t>(width) +
                               static_cast<std::size_t>(c));
    const std::int8_t dc = off[i];
    if (dc == kNoObstacle) return background;
    // Vector from the endpoint to the obstacle cell's centre, in cells.
    const float dx = static_cast<float>(c + dc) + 0.5f - col;
    const float dy = static_cast<float>(r + off[i + 1]) + 0.5f - row;
    const float along = dx * ux + dy * uy;
    const float across = dy * ux - dx * uy;
    const float m2 = along * along * inv_var_along + across * across * inv_var_across;
    const float idx = m2 * lut_steps_per_unit;
    return idx < static_cast<float>(lut_size - 1) ? lut[static_cast<int>(idx)] : lut[lut_size - 1];
  }
};

/// Parameters of the per-beam likelihood rasterised into the tables.
/// sigma_* are the sensor's own (Dekan et al., Section 5: sigma_x = 5.6894 mm along the
/// beam, sigma_y = 3 mm across). The effective variance used for the tables is
///   sigma_eff^2 = sigma^2 + (add_discretisation ? res^2 / 12 : 0) + model_mismatch^2,
/// see docs in the README ("Effective sigma").
struct BeamLikelihoodParams {
  double sigma_along = sensor_model::paper::kSigmaAlong;    ///< metres, Dekan et al. Section 5
  double sigma_across = sensor_model::paper::kSigmaAcross;  ///< metres, Dekan et al. Section 5
  double model_mismatch = 0.0;     ///< metres, added in quadrature to both sigmas
  bool add_discretisation = true;  ///< add res^2/12 (uniform position within a cell)
  double w_hit = 0.95;             ///< mixture weight of the Gaussian hit term, in [0, 1]
  double w_rand = 0.05;            ///< mixture weight of the uniform term, in [0, 1]
  double max_range = 30.0;         ///< metres; support of the uniform term
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
  double sigma_along_eff = 0.0;   ///< metres
  double sigma_across_eff = 0.0;  ///< metres
  double nats_per_step = 0.0;
  double ll_max = 0.0;         ///< log-likelihood at q = 0 (per beam, nats)
  double ll_background = 0.0;  ///< log-likelihood of the background value
  int reach_cells = 0;
  bool orientation_skipped = false;  ///< oriented requested but kernel isotropic at this res
  std::size_t cells_computed = 0;   ///< cells holding a non-background value (within reach)
  std::size_t sources_stamped = 0;  ///< obstacle cells whose kernel was stamped
  std::size_t bytes = 0;            ///< hot tables + LUT
  std::size_t oracle_bytes = 0;     ///< obstacle bitmask kept for exact_log_likelihood()
  double build_seconds = 0.0;
};

/// Owns the tables for one grid. Built once, read concurrently (all const methods are
/// thread-safe).
class LikelihoodField {
 public:
  /// Throws std::invalid_argument for invalid params (sigmas not positive and finite,
  /// model_mismatch < 0, weights outside [0, 1] or not summing to 1 within 1e-9,
  /// max_range <= 0, bins < 1, reach_sigmas <= 0, an empty grid, or an offset-field reach
  /// beyond 127 cells) and std::length_error (with the byte count) when the table would
  /// exceed options.max_table_bytes; both before allocating the table.
  LikelihoodField(const OccupancyGrid& grid, const BeamLikelihoodParams& params,
                  const LikelihoodFieldOptions& options = {});

  [[nodiscard]] TableKind kind() const noexcept { return kind_; }  ///< after any fallback
  [[nodiscard]] const LikelihoodFieldStats& stats() const noexcept { return stats_; }
  [[nodiscard]] const BeamLikelihoodParams& params() const noexcept { return params_; }
  [[nodiscard]] int width() const noexcept { return width_; }
  [[nodiscard]] int height() const noexcept { return height_; }
  [[nodiscard]] double resolution() const noexcept { return resolution_; }
  [[nodiscard]] const Pose2& origin() const noexcept { return origin_; }

  [[nodiscard]] IsotropicView isotropic() const noexcept;  ///< valid when kind()==kIsotropic
  [[nodiscard]] OrientedView oriented() const noexcept;    ///< valid when kind()==kOrientedBins
  [[nodiscard]] OffsetView offset() const noexcept;        ///< valid when kind()==kOffsetField

  /// Quantised value -> per-beam log-likelihood (nats).
  [[nodiscard]] double log_likelihood(std::uint8_t q) const noexcept {
    return stats_.ll_max - static_cast<double>(q) * stats_.nats_per_step;
  }
  /// Exact (unquantised) per-beam log-likelihood of an endpoint at map-local metres (x, y)
  /// for a beam of map-local direction `beam_angle`: the oracle for the tables, Eq. (6)
  /// evaluated against the nearest obstacle in the Mahalanobis metric of that direction.
  /// Outside the map it still evaluates the model (the views return background there).
  /// Throws std::invalid_argument for non-finite input.
  [[nodiscard]] double exact_log_likelihood(double x, double y, double beam_angle) const;
  /// The per-beam log-likelihood as a function of the squared Mahalanobis distance m2
  /// (see the file comment), unquantised; background for m2 >= reach_sigmas^2.
  [[nodiscard]] double log_likelihood_of_m2(double m2) const noexcept;
  /// Quantised value of log_likelihood_of_m2(m2): what the tables store.
  [[nodiscard]] std::uint8_t quantise_m2(double m2) const noexcept;

 private:
  TableKind kind_ = TableKind::kIsotropic;
  BeamLikelihoodParams params_{};
  LikelihoodFieldOptions options_{};
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
  double log_hit_norm_ = 0.0;  // log(w_hit / (sqrt(2 pi) sigma_along_eff)), -inf if w_hit = 0
  double log_floor_ = 0.0;     // log(w_rand / max_range), -inf if w_rand = 0
  double reach_m2_ = 0.0;      // reach_sigmas^2
  std::uint8_t background_ = 255;
  // Exact oracle: obstacle bitmask, one padded run of 64-bit words per row.
  std::vector<std::uint64_t> obstacle_bits_;
  int words_per_row_ = 0;

  [[nodiscard]] bool obstacle_bit(int col, int row) const noexcept {
    const std::uint64_t w =
        obstacle_bits_[static_cast<std::size_t>(row) * static_cast<std::size_t>(words_per_row_) +
                       static_cast<std::size_t>(col >> 6)];
    return ((w >> (col & 63)) & 1u) != 0;
  }
};

}  // namespace pgmcl::maps
