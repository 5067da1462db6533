#pragma once
// Internal: free-space consistency of a scan at a pose, the negative information an
// endpoint model (the likelihood tables) ignores. A reading travelled through empty space
// up to its endpoint, so at a pose where it would have had to cross a wall, or space the
// map never saw, the scan contradicts the robot however well its endpoints fit. People and
// furniture missing from the map shorten readings; they never lengthen them.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "pgmcl/common/se2.hpp"
#include "pgmcl/maps/likelihood_field.hpp"
#include "pgmcl/mcl/measurement_model.hpp"

namespace pgmcl::detail {

class FreeSpace {
 public:
  /// `free_cells`: linear indices of the cells a robot may stand in and a beam may cross.
  /// `ray_margin`: cells before an endpoint where rays stop (the endpoint's own spread and
  /// the thickness walls may be drawn with).
  FreeSpace(int width, int height, double resolution, std::span<const std::uint32_t> free_cells,
            float ray_margin);

  /// Map-local metres in a free cell.
  [[nodiscard]] bool is_free(double x, double y) const noexcept;
  /// Beams of `beams` (base frame, cells) whose ray from the sensor (base frame, cells)
  /// crosses a cell that is not free before reaching the margin of its endpoint, with the
  /// robot at `pose` (map-local metres).
  [[nodiscard]] std::size_t blocked_beams(const Pose2& pose, const PreparedBeams& beams,
                                          float sensor_x, float sensor_y) const noexcept;
  /// The same beams' indices into `beams`, into `out` (cleared first).
  void blocked_beam_indices(const Pose2& pose, const PreparedBeams& beams, float sensor_x,
                            float sensor_y, std::vector<std::uint32_t>& out) const;
  [[nodiscard]] std::size_t bytes() const noexcept { return clearance_.size(); }

 private:
  [[nodiscard]] std::uint8_t clearance_at(float col, float row) const noexcept {
    return clearance_in(maps::floor_to_cell(col), maps::floor_to_cell(row));
  }
  // Inline: the ray march's inner loop calls it some ten times per beam. For points within
  // a scan's reach of a cell on the map, where floor_to_cell's clamps never act.
  [[nodiscard]] std::uint8_t clearance_near(float col, float row) const noexcept {
    return clearance_in(maps::floor_to_cell_unclamped(col), maps::floor_to_cell_unclamped(row));
  }
  [[nodiscard]] std::uint8_t clearance_in(int c, int r) const noexcept {
    if (c < 0 || r < 0 || c >= width_ || r >= height_) return 0;  // off the map: never seen
    return clearance_[static_cast<std::size_t>(r) * static_cast<std::size_t>(width_) +
                      static_cast<std::size_t>(c)];
  }
  /// Calls `on_blocked(j)` once for each blocked beam j, in no set order.
  template <class OnBlocked>
  void for_each_blocked(const Pose2& pose, const PreparedBeams& beams, float sensor_x,
                        float sensor_y, OnBlocked&& on_blocked) const;

  int width_ = 0, height_ = 0;
  double resolution_ = 0.0;
  float ray_margin_ = 0.0f;
  // Per cell, the distance in cells to the nearest cell that is not free (0: not free
  // itself), capped at 255: rays step that far at once (sphere tracing).
  std::vector<std::uint8_t> clearance_;
};

}  // namespace pgmcl::detail
