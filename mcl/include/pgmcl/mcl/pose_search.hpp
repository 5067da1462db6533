#pragma once
/// Correlative scan-to-map search by branch and bound over a min-pooled pyramid of the
/// likelihood table (Olson 2009, "Real-time correlative scan matching"; Hess et al. 2016,
/// Cartographer's fast correlative matcher), used to propose pose hypotheses: for global
/// localisation, for catching a filter that settled on the wrong place, and for absorbing
/// motion that odometry cannot explain.
///
/// Cost of a pose = sum over the search beams of the table's q (0 = perfect hit, the
/// background for no fit), each beam read from a pooled table: level k stores, per coarse
/// cell C, the minimum q over the 2^(k+1) x 2^(k+1) fine cells from C * 2^k. A node of the
/// search covers the translations of one 2^k-aligned block at one heading, and its pooled
/// cost is a lower bound of the pooled cost of every leaf inside it, so pruning is exact.
/// Leaves are blocks of `leaf_size`; their cost is the pooled cost at the leaf level,
/// which tolerates the misalignment of a pose on the leaf grid (up to about one leaf).
/// Memory: about a third of a byte per map cell (pooled levels) plus a bit mask.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "pgmcl/maps/likelihood_field.hpp"
#include "pgmcl/mcl/measurement_model.hpp"

namespace pgmcl {

struct PoseSearchConfig {
  double leaf_size = 0.2;          ///< metres: candidate spacing, rounded to 2^k cells (k >= 1)
  int root_levels = 5;             ///< root node side = leaf * 2^root_levels
  std::size_t max_beams = 60;      ///< beams of the scan the search scores (evenly spread)
  double min_angle_step = 0.0044;  ///< radians (0.25 deg)
  double max_angle_step = 0.0524;  ///< radians (3 deg)
};

/// A pose hypothesis in the map-local grid frame.
struct PoseCandidate {
  double x = 0.0;          ///< metres, map-local
  double y = 0.0;          ///< metres, map-local
  double theta = 0.0;      ///< radians
  std::uint32_t cost = 0;  ///< pooled cost (lower is better)
};

struct PoseSearchQuery {
  /// false: the whole map, every heading. true: translations within half_xy of (x, y)
  /// and headings within half_theta of theta (map-local).
  bool windowed = false;
  double x = 0.0, y = 0.0, theta = 0.0;
  double half_xy = 0.0;     ///< metres
  double half_theta = 0.0;  ///< radians
  std::size_t max_candidates = 32;
  /// Candidates closer than both separations to a better one are dropped (non-maximum
  /// suppression), so the list holds distinct places.
  double separation_xy = 1.0;           ///< metres
  double separation_theta = 0.35;       ///< radians
  std::uint32_t max_cost = UINT32_MAX;  ///< only candidates at or below this cost
  std::uint64_t budget = 0;             ///< beam lookups before the search stops; 0 = no limit
  /// Leaves this many levels above the finest (each doubles the leaf and the heading
  /// step): a coarse pass for many hypotheses, to be refined on the exact table.
  int coarse_levels = 0;
  /// Global searches: only root blocks [root_begin, root_end) of root_count(), so a
  /// search can be spread over several calls. root_end = 0 means all.
  std::size_t root_begin = 0;
  std::size_t root_end = 0;
};

struct PoseSearchResult {
  std::vector<PoseCandidate> candidates;  ///< best first
  std::uint64_t lookups = 0;              ///< beam lookups spent
  bool truncated = false;                 ///< the budget ran out before the search finished
};

/// Holds the pyramid for one likelihood field; cheap queries once a scan is set.
/// Not thread-safe (scratch buffers); one per Localizer.
class PoseSearch {
 public:
  /// `free_cells`: linear indices of the cells a robot may stand in (the Localizer's).
  PoseSearch(const maps::LikelihoodField& field, std::span<const std::uint32_t> free_cells,
             const PoseSearchConfig& cfg = {});

  /// Takes up to cfg.max_beams of the prepared beams (base frame, cells) and picks the
  /// heading step from their ranges. Returns false when there are none.
  bool set_scan(const PreparedBeams& beams);

  [[nodiscard]] PoseSearchResult search(const PoseSearchQuery& query);
  /// Pooled cost of one pose (map-local metres), comparable with candidate costs.
  [[nodiscard]] std::uint32_t pooled_cost(double x, double y, double theta) const;

  [[nodiscard]] double leaf_size() const noexcept { return leaf_cells_ * resolution_; }
  [[nodiscard]] double angle_step() const noexcept { return angle_step_; }
  [[nodiscard]] std::size_t beams() const noexcept { return bx_.size(); }
  [[nodiscard]] std::size_t root_count() const noexcept { return root_cells_.size(); }
  /// Lookups to bound one root block at every heading of a global search (the least a
  /// global search spends per root).
  [[nodiscard]] std::uint64_t root_cost() const noexcept;
  [[nodiscard]] std::size_t bytes() const noexcept;
  /// Nats per unit of cost (the field's quantisation step).
  [[nodiscard]] double nats_per_step() const noexcept { return nats_per_step_; }

 private:
  struct Level {
    int shift = 0;              // 2^shift cells per node side
    int width = 0, height = 0;  // pooled dims, index C + 1 for C in [-1, ceil(W / 2^k))
    // Row-major with `pad` nodes of background on every side: bound() reads any node a
    // scan within the padded reach lands on without checking the edges.
    std::vector<std::uint8_t> cost;
    int pad = 0;
    std::ptrdiff_t stride = 0;            // width + 2 pad
    int free_width = 0, free_height = 0;  // aligned dims ceil(W / 2^k)
    std::vector<std::uint8_t> has_free;
    /// The cost at pooled index (c, r), for c in [-pad, width + pad), r likewise.
    [[nodiscard]] const std::uint8_t* origin() const noexcept {
      return cost.data() + static_cast<std::ptrdiff_t>(pad) * stride + pad;
    }
  };
  struct Node {
    std::int32_t col = 0, row = 0;  // lower corner, fine cells
    std::uint32_t cost = 0;         // pooled bound
    std::uint16_t angle = 0;
    std::uint8_t level = 0;
  };

  /// The node's pooled cost, or a partial sum of it once that reaches `limit`. kPadded:
  /// the scan lies within the levels' padding (padded_reach_).
  template <bool kPadded>
  [[nodiscard]] std::uint32_t bound(const Level& lv, std::int32_t col, std::int32_t row,
                                    std::size_t angle, std::uint64_t limit) const noexcept;
  void prepare_angles(const PoseSearchQuery& q, int leaf);
  [[nodiscard]] bool has_free(const Level& lv, std::int32_t col, std::int32_t row) const noexcept;
  void record(const PoseSearchQuery& q, const Node& leaf, std::vector<PoseCandidate>& out) const;

  double resolution_ = 0.0;
  int width_ = 0, height_ = 0;
  int leaf_level_ = 1;
  int leaf_cells_ = 2;
  std::uint8_t background_ = 255;
  double nats_per_step_ = 0.0;
  std::vector<Level> levels_;              // leaf level first, root level last
  std::vector<std::uint32_t> root_cells_;  // root blocks with free cells, row-major
  PoseSearchConfig cfg_;
  // Scan: base-frame endpoints in cells.
  std::vector<float> bx_, by_;
  float padded_reach_ = 0.0f;  // cells: a scan whose ranges are all within it ...
  bool padded_ = false;        // ... this one, reads the levels unchecked
  std::vector<float> ranges_;  // set_scan(): the endpoints' ranges, for the angle step
  double angle_step_ = 0.0;
  // Per query: headings and rotated endpoints (angle-major).
  std::vector<double> angles_;
  std::vector<std::int32_t> rx_, ry_;  // floored rotated endpoints, cells, per angle
  int full_circle_leaf_ = -1;          // rx_, ry_ hold the whole circle at this leaf level (-1: no)
  std::vector<Node> stack_;
};

}  // namespace pgmcl
