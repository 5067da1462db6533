// HypothesisTracker: construction, scoring single hypotheses, global mode.
#include "hypothesis_tracker.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

namespace pgmcl::detail {
namespace {

// Beams that score single hypotheses (the prediction, competitors): enough to tell places
// apart, few enough that following a handful of them costs a fraction of the particles'.
constexpr std::size_t kProbeBeams = 40;
// Later passes of the global search only top the particle set up, so that places the
// first scans could not tell apart do not keep it from settling.
constexpr double kTopUp = 0.1;
// Cells a wall may be drawn thicker than it is (hand-made and blurred maps).
constexpr double kWallCells = 2.0;

}  // namespace

HypothesisTracker::HypothesisTracker(std::shared_ptr<const maps::LikelihoodField> field,
                                     std::span<const std::uint32_t> free_cells,
                                     const HypothesesConfig& cfg,
                                     const LikelihoodConfig& likelihood)
    : field_(std::move(field)),
      cfg_(cfg),
      likelihood_(likelihood),
      search_(*field_, free_cells, cfg.search),
      // Rays stop where the endpoint's own uncertainty begins, plus the cells a wall may
      // be drawn thick by.
      free_(
          field_->width(), field_->height(), field_->resolution(), free_cells,
          static_cast<float>(kFitSigmas * field_->model().sigma_along_eff() / field_->resolution() +
                             kWallCells)),
      probe_(field_),
      resolution_(field_->resolution()) {}

void HypothesisTracker::reset(bool global) {
  global_ = global;
  global_places_.clear();
  global_cursor_ = global_passes_ = 0;
  global_root_cost_ = 0.0;
  competitors_.clear();
  have_fit_mean_ = abrupt_loss_ = false;
  fit_mean_ = fit_var_ = fit_usual_ = last_fit_ = blocked_mean_ = 0.0;
  lost_updates_ = 0;
  sweep_cursor_ = 0;
  sweep_credit_ = 0.0;
}

void HypothesisTracker::converged(const Pose2& estimate) {
  if (!global_) return;
  global_ = false;
  // The scan that converged shows how well the map fits here. Were the running fit to
  // start from the next scan instead, a glitch on that scan would set it, and the fall
  // would never show (a 60 deg glitch there went unabsorbed on 28 of 40 seeds).
  if (beams_ != nullptr) {
    const Scored ref = climb(estimate);
    fit_mean_ = fit_usual_ = last_fit_ = fit_of(ref);
    fit_var_ = 0.0;
    blocked_mean_ = static_cast<double>(blocked_beams(ref.pose));
    have_fit_mean_ = true;
  }
  competitors_.clear();
  for (const Pose2& p : global_places_) {
    if (competitors_.size() >= cfg_.max_competitors) break;
    bool dup = same_place(p, estimate);
    for (const Competitor& c : competitors_) dup = dup || same_place(c.pose, p);
    if (!dup) competitors_.push_back({.pose = p, .origin = Competitor::Origin::kGlobal});
  }
}

HypothesisStep HypothesisTracker::update(const LaserScan& scan,
                                         std::span<const std::uint32_t> selected,
                                         const PreparedBeams& beams, const Pose2& prediction,
                                         const Pose2& delta, std::size_t particles,
                                         double heading_spread) {
  HypothesisStep out;
  heading_window_ = std::min(std::numbers::pi, std::max(cfg_.rescue_theta, heading_spread));
  if (!search_.set_scan(beams)) return out;
  beams_used_ = beams.size();
  beams_ = &beams;
  sensor_x_ = static_cast<float>(scan.sensor_pose.x / resolution_);
  sensor_y_ = static_cast<float>(scan.sensor_pose.y / resolution_);
  const std::size_t m = selected.size(), k = std::min(m, kProbeBeams);
  probe_beams_.resize(k);
  for (std::size_t j = 0; j < k; ++j) probe_beams_[j] = selected[(j * m) / k];
  probe_.prepare(scan, probe_beams_);
  if (global_)
    global_step(particles, out);
  else
    track(prediction, delta, particles, out);
  return out;
}

void HypothesisTracker::global_step(std::size_t particles, HypothesisStep& out) {
  // A coarse pass (leaves of two search leaves) over as many root blocks as the budget
  // allows, so a large map is covered over several updates; the seeded particles carry
  // each slice's places forward.
  const std::size_t roots = search_.root_count();
  if (roots == 0) return;
  if (global_cursor_ >= roots) {
    global_cursor_ = 0;
    ++global_passes_;
  }
  const double slice = static_cast<double>(cfg_.global_budget) / std::max(1.0, global_root_cost_);
  PoseSearchQuery q;
  q.max_candidates = cfg_.global_candidates;
  q.separation_xy = cfg_.separation_xy;
  q.separation_theta = cfg_.separation_theta;
  q.budget = cfg_.global_budget;
  q.coarse_levels = 1;
  q.root_begin = global_cursor_;
  q.root_end = std::min(roots, global_cursor_ + static_cast<std::size_t>(std::clamp(
                                                    slice, 1.0, static_cast<double>(roots))));
  global_cursor_ = q.root_end;
  const PoseSearchResult res = search_.search(q);
  global_root_cost_ =
      static_cast<double>(res.lookups) / static_cast<double>(q.root_end - q.root_begin);
  out.searched = true;
  global_places_.clear();
  if (res.candidates.empty()) return;
  // Candidates within candidate_margin (tempered nats) of this slice's best, refined.
  const auto beams = static_cast<double>(search_.beams());
  const double tau = likelihood_.tempering_for(beams);
  const double margin = cfg_.candidate_margin / (tau * search_.nats_per_step());
  for (const PoseCandidate& c : res.candidates) {
    if (static_cast<double>(c.cost - res.candidates.front().cost) > margin) break;
    const Pose2 p = refine(c).pose;
    if (is_free(p.x, p.y) && !contradicted(p, beams_->size() / 2)) global_places_.push_back(p);
  }
  const double fraction = cfg_.global_seed_fraction * (global_passes_ == 0 ? 1.0 : kTopUp);
  out.seed = {global_places_,
              static_cast<std::size_t>(std::lround(fraction * static_cast<double>(particles))),
              search_.leaf_size(), 2.0 * search_.angle_step()};
}

std::size_t HypothesisTracker::blocked_beams(const Pose2& pose) const noexcept {
  // Off, every pose crosses nothing: no veto, confirmation or search comes from it.
  if (!cfg_.free_space || beams_ == nullptr) return 0;
  return free_.blocked_beams(pose, *beams_, sensor_x_, sensor_y_);
}

void HypothesisTracker::blocked_beam_indices(const Pose2& pose, const PreparedBeams& beams,
                                             std::vector<std::uint32_t>& out) const {
  if (cfg_.free_space)
    free_.blocked_beam_indices(pose, beams, sensor_x_, sensor_y_, out);
  else
    out.clear();
}

bool HypothesisTracker::contradicted(const Pose2& pose, std::size_t ref_blocked) const noexcept {
  // At a right pose a reading crosses a wall only where the map is wrong or the ray grazes
  // a corner; at a wrong one that fits by chance (clutter, people, furniture missing from
  // the map), many do.
  return blocked_beams(pose) > ref_blocked + blocked_margin();
}

HypothesisTracker::Scored HypothesisTracker::climb(const Pose2& start) const {
  // Coordinate descent on the exact table cost, two kernel sigmas and about two degrees per
  // step, then half steps: follows a hypothesis through the odometry error of one update.
  const double sigma = field_->model().sigma_along_eff();
  Scored best{start, probe_.score_pose(start.x, start.y, start.theta)};
  for (const double step : {2.0 * sigma, sigma}) {
    const double dth = step / 3.0;  // moves an endpoint 3 m away by one step
    for (int it = 0; it < 3; ++it) {
      const Pose2 p = best.pose;
      bool moved = false;
      for (const Pose2& d : {Pose2{step, 0, 0}, Pose2{-step, 0, 0}, Pose2{0, step, 0},
                             Pose2{0, -step, 0}, Pose2{0, 0, dth}, Pose2{0, 0, -dth}}) {
        const Pose2 q{p.x + d.x, p.y + d.y, wrap_angle(p.theta + d.theta)};
        const PoseScore s = probe_.score_pose(q.x, q.y, q.theta);
        if (s.sum_q < best.score.sum_q) {
          best = {q, s};
          moved = true;
        }
      }
      if (!moved) break;
    }
  }
  return best;
}

HypothesisTracker::Scored HypothesisTracker::refine(const PoseCandidate& coarse) {
  // A coarse candidate to the best fine leaf within a coarse leaf and two coarse heading
  // steps, then onto the exact table.
  PoseSearchQuery q;
  q.windowed = true;
  q.x = coarse.x;
  q.y = coarse.y;
  q.theta = coarse.theta;
  q.half_xy = 2.0 * search_.leaf_size();
  q.half_theta = 4.0 * search_.angle_step();
  q.max_candidates = 1;
  const PoseSearchResult fine = search_.search(q);
  const PoseCandidate& c = fine.candidates.empty() ? coarse : fine.candidates.front();
  return climb({c.x, c.y, c.theta});
}

double HypothesisTracker::fit_of(const Scored& s) const noexcept {
  return static_cast<double>(s.score.fitting) /
         static_cast<double>(std::max<std::size_t>(1, probe_.beams().size()));
}

double HypothesisTracker::evidence(std::uint32_t q_ref, std::uint32_t q) const noexcept {
  // The filter's own weighting, tau * (ll - ll_ref) (LikelihoodConfig), on the probe beams.
  const auto m = static_cast<double>(probe_.beams().size());
  const double tau = likelihood_.tempering_for(m);
  return tau * field_->model().nats_per_step() *
         (static_cast<double>(q_ref) - static_cast<double>(q));
}

bool HypothesisTracker::same_place(const Pose2& a, const Pose2& b, double scale) const noexcept {
  return std::hypot(a.x - b.x, a.y - b.y) < scale * cfg_.separation_xy &&
         std::abs(wrap_angle(a.theta - b.theta)) < scale * cfg_.separation_theta;
}

bool HypothesisTracker::near_prediction(const Pose2& a, const Pose2& ref) const noexcept {
  // Within what climb() from the prediction reaches anyway: a search leaf and two heading
  // steps. A glitch-corrected pose 25 deg off is a different hypothesis.
  return std::hypot(a.x - ref.x, a.y - ref.y) < search_.leaf_size() &&
         std::abs(wrap_angle(a.theta - ref.theta)) < 2.0 * search_.angle_step();
}

}  // namespace pgmcl::detail
