#pragma once
// Internal: competing hypotheses from scan-to-map search (HypothesesConfig), beside the
// particle set. Per measurement update, after MeasurementModel::prepare():
//  - global mode (after global_localize(), until the first convergence): a coarse global
//    search over a slice of the map; the particle set is asked to seed its places;
//  - tracking: the prediction (last estimate moved by odometry) and each competitor are
//    scored on a few beams; a scan that stops fitting the prediction starts a search
//    around it (odometry glitches, slips), and a slice of the map is searched for places
//    that fit as well (a wrong place, a kidnapping); a competitor whose evidence passes
//    the switch rules asks the set to seed there.
// The tracker only proposes; the Localizer draws the particles and scores them.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "free_space.hpp"
#include "pgmcl/common/laser_scan.hpp"
#include "pgmcl/maps/likelihood_field.hpp"
#include "pgmcl/mcl/localizer_config.hpp"
#include "pgmcl/mcl/measurement_model.hpp"
#include "pgmcl/mcl/pose_search.hpp"

namespace pgmcl::detail {

/// Particles to redraw around `poses` (map-local), an equal share each.
struct SeedRequest {
  std::vector<Pose2> poses;
  std::size_t count = 0;
  double sigma_xy = 0.0;     ///< metres
  double sigma_theta = 0.0;  ///< radians
};

struct HypothesisStep {
  SeedRequest seed;
  bool searched = false;  ///< a global or rescue search ran
  bool switched = false;  ///< the seeds are a competitor that outweighed the prediction
  std::size_t competitors = 0;
  double alternative_evidence = 0.0;  ///< largest competitor evidence, tempered nats (>= 0)
};

/// Whether another of `hypotheses`, no farther from `prediction` than `h`, fits this scan
/// better than `h` by more than `margin` (`last`: each one's evidence from this scan alone,
/// tempered nats). A farther one may fit better and still be the less likely place: the
/// farther a correction, the rarer the odometry error it needs.
template <class Hypothesis>
[[nodiscard]] bool outscored_on_this_scan(std::span<const Hypothesis> hypotheses,
                                          const Hypothesis& h, const Pose2& prediction,
                                          double margin) noexcept {
  const auto distance = [&](const Hypothesis& k) {
    return std::hypot(k.pose.x - prediction.x, k.pose.y - prediction.y);
  };
  return std::any_of(hypotheses.begin(), hypotheses.end(), [&](const Hypothesis& o) {
    return &o != &h && o.last > h.last + margin && distance(o) <= distance(h);
  });
}

class HypothesisTracker {
 public:
  /// `free_cells`: linear indices into the field's grid (the Localizer's).
  HypothesisTracker(std::shared_ptr<const maps::LikelihoodField> field,
                    std::span<const std::uint32_t> free_cells, const HypothesesConfig& cfg,
                    const LikelihoodConfig& likelihood);

  /// Forgets everything; `global`: start in global mode (global_localize()).
  void reset(bool global);
  [[nodiscard]] bool global() const noexcept { return global_; }
  /// The filter converged: leave global mode, keeping the other places of the last global
  /// search as competitors (the filter may have settled on one that only fits almost as
  /// well), and start the running fit from this update's scan at `estimate` (map-local).
  /// Called after update(), on the same scan.
  void converged(const Pose2& estimate);

  /// One update. `selected` indexes scan.ranges; `beams` is the prepared selection;
  /// `prediction` (map-local) the last estimate moved by `delta`, the odometry increment.
  /// `heading_spread` (radians): how far the odometry's heading may be off over `delta`
  /// under the motion noise in use (3 sigma); the rescue window is at least that wide.
  HypothesisStep update(const LaserScan& scan, std::span<const std::uint32_t> selected,
                        const PreparedBeams& beams, const Pose2& prediction, const Pose2& delta,
                        std::size_t particles, double heading_spread);

  /// While tracking, a redrawn lineage farther than this (metres) from the prediction stays
  /// on probation (RecoveryConfig) until the prediction has lost the scan for
  /// kKidnapScans updates: a far place takes the estimate only as may_switch() allows.
  [[nodiscard]] double hold_radius() const noexcept {
    return global_ || lost_updates_ >= kKidnapScans ? -1.0 : cfg_.rescue_xy;
  }
  // A place elsewhere on the map (a kidnapping) must explain this many scans in a row while
  // the prediction stays lost: clutter can make a far place fit better for a few scans.
  static constexpr int kKidnapScans = 10;

  /// Map-local metres in a free cell.
  [[nodiscard]] bool is_free(double x, double y) const noexcept { return free_.is_free(x, y); }

  /// Beams of this update's scan whose ray, from the sensor to near its endpoint, crosses
  /// a cell that is not free at `pose` (map-local).
  [[nodiscard]] std::size_t blocked_beams(const Pose2& pose) const noexcept;
  /// The beams of `beams` (prepared from this update's scan) that blocked_beams() would
  /// count, as indices into `beams`, into `out`.
  void blocked_beam_indices(const Pose2& pose, const PreparedBeams& beams,
                            std::vector<std::uint32_t>& out) const;
  // Free-space evidence counts from a tenth of the beams on: grazing rays along corridor
  // walls cross them at right poses too, after a fraction of a degree of heading error.
  static constexpr std::size_t kBlockedMargin = 10;

 private:
  struct Scored {
    Pose2 pose{};
    PoseScore score{};
  };
  struct Competitor {
    Pose2 pose{};              // map-local
    double evidence = 0.0;     // tempered nats against the prediction, fading with view
    double last = 0.0;         // this update's share of it
    double fit = 0.0;          // fraction of the probe beams that fit the map there
    double view = 0.0;         // new view since it was found (metres, kViewPerRadian)
    double steady_view = 0.0;  // ... of it while the prediction fitted as the map usually does
    int age = 0;               // updates tracked
    int led = 0;               // updates in a row its fit led the prediction's (leads())
    // Where it came from decides what it may do (may_switch): a place the global search
    // proposed had the prior of the one the filter settled on; one found around a
    // prediction that stopped fitting is a glitch candidate; one the map sweep found
    // would be a kidnapping, or a glitch candidate while within the rescue window.
    enum class Origin : std::uint8_t { kGlobal, kRescue, kSweep } origin = Origin::kSweep;
    bool abrupt = false;  // found while the prediction's fit had fallen at once
  };

  void global_step(std::size_t particles, HypothesisStep& out);
  void track(const Pose2& prediction, const Pose2& delta, std::size_t particles,
             HypothesisStep& out);
  /// Searches around the prediction, over `widen` times the rescue heading window; the
  /// candidates are glitch candidates when `abrupt` (the fit fell at once). `step`: the
  /// odometry's translation this update (metres).
  void rescue(const Scored& ref, int widen, bool abrupt, double step, HypothesisStep& out);
  /// The rescue search's heading half-width on the `widen`-th update it runs in a row.
  [[nodiscard]] double rescue_half_theta(int widen) const noexcept;
  /// `pose` lies within this update's rescue window around `ref`.
  [[nodiscard]] bool in_rescue_window(const Pose2& pose, const Pose2& ref) const noexcept;
  void sweep(const Scored& ref, std::size_t particles, bool lost);
  /// A stronger competitor (more evidence, tracked over a scan) fits this scan clearly
  /// better than `c` and its readings cross no more walls: `c` must not take the set, or
  /// the filter may settle where it fits too well to count as lost.
  [[nodiscard]] bool overshadowed(const Competitor& c) const;
  void prune(const Scored& ref);
  /// `blocked`: blocked_beams() at the prediction.
  void maybe_switch(const Scored& ref, double fit, std::size_t blocked, double step, bool lost,
                    std::size_t particles, HypothesisStep& out);
  /// `blocked`: blocked_beams() at the prediction; the competitor's rays are cast here, once
  /// it has the evidence to win.
  [[nodiscard]] bool may_switch(const Competitor& c, const Scored& ref, double fit,
                                std::size_t blocked, double step, bool lost) const;
  /// How many more blocked beams than a reference count as evidence (kBlockedMargin).
  [[nodiscard]] std::size_t blocked_margin() const noexcept { return beams_used_ / kBlockedMargin; }
  void add(const Scored& c, const Scored& ref, Competitor::Origin origin, bool abrupt);

  /// The scan contradicts a robot at `pose`: a tenth of the beams more than `ref_blocked`
  /// would have passed through walls or unmapped space.
  [[nodiscard]] bool contradicted(const Pose2& pose, std::size_t ref_blocked) const noexcept;
  [[nodiscard]] Scored climb(const Pose2& start) const;
  [[nodiscard]] Scored refine(const PoseCandidate& coarse);
  [[nodiscard]] double fit_of(const Scored& s) const noexcept;
  /// How well the map usually explains the scan at the prediction: the higher of its fit's
  /// short and long running means.
  [[nodiscard]] double usual_fit() const noexcept { return std::max(fit_mean_, fit_usual_); }
  /// A place's fit leads the prediction's: it explains the scan as the map usually does
  /// (usual_fit()) and clearly better than the prediction.
  [[nodiscard]] bool leads(double place_fit, double prediction_fit) const noexcept;
  [[nodiscard]] double evidence(std::uint32_t q_ref, std::uint32_t q) const noexcept;
  [[nodiscard]] bool same_place(const Pose2& a, const Pose2& b, double scale = 1.0) const noexcept;
  [[nodiscard]] bool near_prediction(const Pose2& a, const Pose2& ref) const noexcept;

  std::shared_ptr<const maps::LikelihoodField> field_;
  HypothesesConfig cfg_;
  LikelihoodConfig likelihood_;  // the filter's tempering (LikelihoodConfig::tempering_for)
  PoseSearch search_;
  FreeSpace free_;
  MeasurementModel probe_;  // a few of the scan's beams, for scoring single hypotheses
  std::vector<std::uint32_t> probe_beams_;
  std::size_t beams_used_ = 0;               // beams the particles are scored on this update
  const PreparedBeams* beams_ = nullptr;     // this update's selected beams (from update() on)
  float sensor_x_ = 0.0f, sensor_y_ = 0.0f;  // the sensor in the base frame, cells
  double resolution_ = 0.0;
  double heading_window_ = 0.0;  // rescue_theta, or the odometry's heading spread if wider

  bool global_ = true;
  std::vector<Pose2> global_places_;  // the last global search's refined candidates
  std::size_t global_cursor_ = 0;     // next root block of the global search
  std::size_t global_passes_ = 0;     // complete passes over the map
  double global_root_cost_ = 0.0;     // lookups per root block of the last global search

  std::vector<Competitor> competitors_;
  std::vector<Scored> refined_;  // rescue(): its refined candidates, best first
  bool have_fit_mean_ = false;
  double fit_mean_ = 0.0;      // the prediction's fit, over ~10 tracking updates
  double fit_var_ = 0.0;       // its running variance, over ~10
  double fit_usual_ = 0.0;     // ... and over ~100
  double blocked_mean_ = 0.0;  // its blocked_beams(), over ~10
  double last_fit_ = 0.0;
  int lost_updates_ = 0;      // consecutive updates the prediction lost its fit
  bool abrupt_loss_ = false;  // ... and it fell within one update
  std::size_t sweep_cursor_ = 0;
  double sweep_credit_ = 0.0;  // beam lookups the sweep may still spend
};

}  // namespace pgmcl::detail
