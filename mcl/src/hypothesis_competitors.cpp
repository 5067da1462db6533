// HypothesisTracker while tracking: the prediction and its competitors, the rescue search
// around a prediction that stopped fitting, the map sweep, and when a competitor wins.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "hypothesis_tracker.hpp"

namespace pgmcl::detail {
namespace {

// Running means of the prediction's fit: over ~10 tracking updates (has the scan stopped
// fitting?) and ~100 (how well does the map usually fit here?).
constexpr double kFitMeanRate = 0.1;
constexpr double kFitUsualRate = 0.01;
// New view per update: metres travelled plus this many metres per radian turned (a turn
// of a radian shows about as much new scene as a metre of travel).
constexpr double kViewPerRadian = 1.0;
// Evidence fades over this much view (metres): what a place fitted 50 m ago says little
// about whether it fits better now.
constexpr double kEvidenceView = 10.0;
// A glitch candidate explains the scan about as well as the map usually does here: in
// clutter nothing does, and a place that merely fits better is no glitch ...
constexpr double kNormalFit = 0.9;
// ... and this much (fraction of the probe beams) better than the prediction. A fall of
// the prediction's fit by as much within one update is an abrupt loss.
constexpr double kGlitchGain = 0.3;
// A candidate whose readings cross clearly fewer walls needs only this much more fit.
constexpr double kConfirmGain = 0.1;
// A fit this far below its running mean, and this many of its running standard deviations,
// starts a search around the prediction even when it is not lost.
constexpr double kMinDrop = 0.1;
constexpr double kDropSpreads = 4.0;
// Metres a heading glitch may displace the pose at least (more on longer steps): farther
// candidates (slips) need a second scan.
constexpr double kGlitchReach = 1.2;
// A candidate found while the fit faded (rather than fell) must correct the heading by at
// least this much (radians): along a corridor some shifted pose fits better wherever the
// map is wrong.
constexpr double kFadedHeading = 0.17;
// Metres of new view over which a place the sweep found must stay ahead of a prediction
// that still fits, before the filter moves there.
constexpr double kSettledView = 10.0;
// Scans a shift beyond a glitch's reach must have been tracked before it may win while the
// prediction is not lost and the free space does not confirm it: aliases 2 m along fr079's
// and aces's corridors won one or two updates after they were proposed, and lost again.
constexpr int kSlipScans = 3;
// The map sweep's budget while the prediction is lost.
constexpr double kLostSweepBoost = 4.0;
// Coarse candidates a rescue search refines, and the best of them it keeps. The coarse
// bound ranks poorly: on intel a 2 m slip's true pose was fourth of the coarse candidates
// and first once refined. More coarse ones weaken the search's pruning (its threshold is
// the worst kept candidate); more kept ones add competitors that may win by chance.
constexpr std::size_t kRescueCoarse = 5;
constexpr std::size_t kRescueCandidates = 3;

}  // namespace

void HypothesisTracker::track(const Pose2& prediction, const Pose2& delta, std::size_t particles,
                              HypothesisStep& out) {
  const Scored ref = climb(prediction);
  const double fit = fit_of(ref);
  const double step = std::hypot(delta.x, delta.y);
  const double view = step + kViewPerRadian * std::abs(delta.theta);
  const double fade = std::exp(-view / kEvidenceView);
  // Clutter (people around the robot) lowers the prediction's fit for as long as it stays:
  // new view seen meanwhile is no sign that the filter settled on the wrong place.
  const bool steady = !have_fit_mean_ || fit >= kNormalFit * fit_usual_;
  for (Competitor& c : competitors_) {
    const Scored k = climb(c.pose.compose(delta));
    c.pose = k.pose;
    c.last = evidence(ref.score.sum_q, k.score.sum_q);
    c.evidence = c.evidence * fade + c.last;
    c.fit = fit_of(k);
    c.view += view;
    if (steady) c.steady_view += view;
    c.led = leads(c.fit, fit) ? c.led + 1 : 0;
    ++c.age;
  }

  // A fit far below its usual spread is no noise: where the scan fits steadily, a fall a
  // tenth of the beams is one; in clutter only a fall beyond the clutter's own scatter.
  const double drop_limit = std::max(kMinDrop, kDropSpreads * std::sqrt(fit_var_));
  const bool fell = have_fit_mean_ && last_fit_ - fit >= std::min(drop_limit, kGlitchGain);
  const bool dropped = have_fit_mean_ && fit_mean_ - fit >= drop_limit;
  // Readings that suddenly cross walls at the prediction show a glitch even where clutter
  // hides it in the fit.
  const std::size_t blocked = blocked_beams(ref.pose);
  const bool crossed = have_fit_mean_ && static_cast<double>(blocked) >
                                             blocked_mean_ + static_cast<double>(blocked_margin());
  const bool lost = have_fit_mean_ && fit < cfg_.rescue_fit_ratio * fit_mean_;
  lost_updates_ = lost ? lost_updates_ + 1 : 0;
  if (lost_updates_ == 1) abrupt_loss_ = fell || crossed;
  last_fit_ = fit;
  if (lost) {
    rescue(ref, lost_updates_, abrupt_loss_, step, out);
  } else {
    // A drop short of lost, a fall at once or readings through walls still get a search
    // but do not stop the means.
    if (dropped || fell || crossed) rescue(ref, 1, fell || crossed, step, out);
    blocked_mean_ =
        have_fit_mean_
            ? blocked_mean_ + kFitMeanRate * (static_cast<double>(blocked) - blocked_mean_)
            : static_cast<double>(blocked);
    const double d = fit - fit_mean_;
    fit_var_ = have_fit_mean_ ? fit_var_ + kFitMeanRate * (d * d - fit_var_) : 0.0;
    fit_mean_ = have_fit_mean_ ? fit_mean_ + kFitMeanRate * d : fit;
    fit_usual_ = have_fit_mean_ ? fit_usual_ + kFitUsualRate * (fit - fit_usual_) : fit;
    have_fit_mean_ = true;
  }
  sweep(ref, particles, lost);
  prune(ref);
  maybe_switch(ref, fit, blocked, step, lost, particles, out);
  out.competitors = competitors_.size();
  // A competitor counts once it has outlasted the scan that proposed it.
  for (const Competitor& c : competitors_)
    if (c.age >= 1) out.alternative_evidence = std::max(out.alternative_evidence, c.evidence);
}

void HypothesisTracker::rescue(const Scored& ref, int widen, bool abrupt, double step,
                               HypothesisStep& out) {
  // Around the prediction, over a wider range of headings each update it stays lost (the
  // odometry may keep turning a robot that stands still: Table 5.6's rot1 on jitter).
  PoseSearchQuery q;
  q.windowed = true;
  q.x = ref.pose.x;
  q.y = ref.pose.y;
  q.theta = ref.pose.theta;
  q.half_xy = cfg_.rescue_xy;
  q.half_theta = rescue_half_theta(widen);
  q.max_candidates = kRescueCoarse;
  q.separation_xy = 0.5 * cfg_.separation_xy;
  q.separation_theta = 0.5 * cfg_.separation_theta;
  q.max_cost = search_.pooled_cost(ref.pose.x, ref.pose.y, ref.pose.theta);
  q.budget = cfg_.rescue_budget;
  q.coarse_levels = 1;
  out.searched = true;
  refined_.clear();
  for (const PoseCandidate& c : search_.search(q).candidates) refined_.push_back(refine(c));
  // A heading glitch moves the pose by little, at most the step turned through the window.
  // Amid people, the coarse bound ranks far poses their readings happen to fit above the
  // turned one, so that reach is searched again on the fine leaves.
  if (cfg_.glitch_search) {
    PoseSearchQuery near = q;
    const double reach = std::sin(std::min(q.half_theta, 0.5 * std::numbers::pi)) * step;
    near.half_xy = std::min(cfg_.rescue_xy, std::max(2.0 * search_.leaf_size(), reach));
    near.max_candidates = 1;
    near.coarse_levels = 0;
    for (const PoseCandidate& c : search_.search(near).candidates)
      refined_.push_back(climb({c.x, c.y, c.theta}));
  }
  // Best first; a stable insertion sort of a handful (ties keep the coarse order).
  for (std::size_t i = 1; i < refined_.size(); ++i)
    for (std::size_t j = i; j > 0 && refined_[j].score.sum_q < refined_[j - 1].score.sum_q; --j)
      std::swap(refined_[j], refined_[j - 1]);
  if (refined_.size() > kRescueCandidates) refined_.resize(kRescueCandidates);
  for (const Scored& c : refined_) add(c, ref, Competitor::Origin::kRescue, abrupt);
}

double HypothesisTracker::rescue_half_theta(int widen) const noexcept {
  return std::min(std::numbers::pi, heading_window_ * std::max(1, widen));
}

bool HypothesisTracker::in_rescue_window(const Pose2& pose, const Pose2& ref) const noexcept {
  return std::abs(pose.x - ref.x) <= cfg_.rescue_xy && std::abs(pose.y - ref.y) <= cfg_.rescue_xy &&
         std::abs(wrap_angle(pose.theta - ref.theta)) <= rescue_half_theta(lost_updates_);
}

void HypothesisTracker::sweep(const Scored& ref, std::size_t particles, bool lost) {
  // Root blocks in turn, within a budget of lookups per update (a share of the particles'
  // own), for places that fit at least as well as the prediction.
  const std::size_t roots = search_.root_count();
  if (!(cfg_.sweep_share > 0.0) || roots == 0) return;
  const double share = (lost && abrupt_loss_ ? kLostSweepBoost : 1.0) * cfg_.sweep_share;
  sweep_credit_ += share * static_cast<double>(particles * beams_used_);
  const auto per_root = static_cast<double>(search_.root_cost());
  while (sweep_credit_ >= per_root) {
    if (sweep_cursor_ >= roots) sweep_cursor_ = 0;
    PoseSearchQuery q;
    q.max_candidates = 1;
    q.separation_xy = cfg_.separation_xy;
    q.separation_theta = cfg_.separation_theta;
    q.max_cost = search_.pooled_cost(ref.pose.x, ref.pose.y, ref.pose.theta);
    q.root_begin = sweep_cursor_;
    q.root_end = ++sweep_cursor_;
    q.budget = static_cast<std::uint64_t>(sweep_credit_);
    const PoseSearchResult res = search_.search(q);
    sweep_credit_ -= static_cast<double>(res.lookups);
    for (const PoseCandidate& c : res.candidates)
      add(climb({c.x, c.y, c.theta}), ref, Competitor::Origin::kSweep, lost && abrupt_loss_);
  }
}

void HypothesisTracker::add(const Scored& c, const Scored& ref, Competitor::Origin origin,
                            bool abrupt) {
  // A robot stands in free space: a pose inside furniture may fit a scan perfectly.
  if (near_prediction(c.pose, ref.pose) || !is_free(c.pose.x, c.pose.y)) return;
  const double e = evidence(ref.score.sum_q, c.score.sum_q);
  for (Competitor& k : competitors_) {
    if (!same_place(k.pose, c.pose, 0.5)) continue;
    // Already tracked: a fresh search result is the better pose for it (climb() lags
    // behind large odometry errors); its record stays.
    if (e > k.last) {
      k.pose = c.pose;
      k.evidence += e - k.last;
      k.last = e;
      k.fit = fit_of(c);
    }
    return;
  }
  const double fit = fit_of(c);
  const int led = leads(fit, fit_of(ref)) ? 1 : 0;
  competitors_.push_back({.pose = c.pose,
                          .evidence = e,
                          .last = e,
                          .fit = fit,
                          .led = led,
                          .origin = origin,
                          .abrupt = abrupt});
}

void HypothesisTracker::prune(const Scored& ref) {
  // Strongest first; forget what fell behind, merged with the prediction or a stronger
  // competitor, or left free space.
  std::sort(competitors_.begin(), competitors_.end(),
            [](const Competitor& a, const Competitor& b) { return a.evidence > b.evidence; });
  std::size_t kept = 0;  // competitors_[0, kept) are kept, compacted in place
  for (std::size_t i = 0; i < competitors_.size(); ++i) {
    const Competitor& c = competitors_[i];
    if (c.evidence < cfg_.drop_evidence || near_prediction(c.pose, ref.pose) ||
        !is_free(c.pose.x, c.pose.y))
      continue;
    bool dup = false;
    for (std::size_t k = 0; k < kept; ++k)
      dup = dup || same_place(competitors_[k].pose, c.pose, 0.5);
    if (!dup && kept < cfg_.max_competitors) competitors_[kept++] = competitors_[i];
  }
  competitors_.resize(kept);
}

bool HypothesisTracker::leads(double place_fit, double prediction_fit) const noexcept {
  return have_fit_mean_ && place_fit >= kNormalFit * usual_fit() &&
         place_fit >= prediction_fit + kGlitchGain;
}

bool HypothesisTracker::may_switch(const Competitor& c, const Scored& ref, double fit,
                                   std::size_t blocked, double step, bool lost) const {
  // Every winner outweighs the prediction, gained on this scan, and is not contradicted by
  // the free space its readings crossed.
  if (c.evidence < cfg_.switch_evidence || !(c.last > 0.0)) return false;
  const std::size_t crossing = blocked_beams(c.pose), margin = blocked_margin();
  if (crossing > blocked + margin) return false;
  // A place the global search proposed (as likely a priori as the one the filter settled
  // on) needs only to stay ahead over rival_view metres of new view, and to explain the
  // scan as the map usually does here: where neither fits as usual, the prediction is
  // more likely off by a glitch than in the wrong place.
  if (c.origin == Competitor::Origin::kGlobal)
    return c.view >= cfg_.rival_view && c.age >= 1 && c.fit >= usual_fit();
  const double moved = std::hypot(c.pose.x - ref.pose.x, c.pose.y - ref.pose.y);
  const bool nearby =
      moved <=
      std::max(kGlitchReach, std::sin(std::min(heading_window_, 0.5 * std::numbers::pi)) * step);
  const double turned = std::abs(wrap_angle(c.pose.theta - ref.pose.theta));
  // A shift the scans have settled: for kSlipScans scans in a row the place explained the
  // scan as the map usually does, and clearly better than the prediction. Where the map
  // shows what is not there now (a door shut when mapped), its rays may cross more walls
  // than the prediction's, and the free-space rules below would hold it back for good.
  if (cfg_.sustained_lead && c.led >= kSlipScans && turned < kFadedHeading &&
      (c.origin == Competitor::Origin::kRescue || in_rescue_window(c.pose, ref.pose)))
    return true;
  // Confirmed by the free space: its readings cross clearly fewer walls than the
  // prediction's, and more of them fit. Within a glitch's reach they must cross almost
  // none; farther (a slip), on a second scan, at most half as many as the prediction's.
  // Where clutter keeps every fit low, the true pose's too, that is what tells it apart.
  const bool fewer_walls = crossing + margin <= blocked && c.fit >= fit + kConfirmGain;
  const bool confirmed =
      cfg_.free_space && fewer_walls &&
      ((nearby && crossing <= margin) || (c.age >= 1 && 2 * crossing <= blocked));
  const bool abrupt = c.abrupt || confirmed;
  // The others must explain the scan as the map usually does here: with some slack when
  // they were found as the prediction's fit fell at once, fully when it faded (clutter,
  // or a part of the map that is wrong, where some other pose fits better by chance).
  const double usual = usual_fit();
  if (!confirmed && c.fit < (c.abrupt ? kNormalFit : 1.0) * usual) return false;
  if (c.age == 0)  // at once, with this very scan: a glitch-sized correction only
    return c.origin == Competitor::Origin::kRescue && abrupt && lost && nearby &&
           turned <= heading_window_ && c.fit >= fit + (confirmed ? kConfirmGain : kGlitchGain);
  if (c.origin == Competitor::Origin::kSweep) {
    // A kidnapping: several scans, still lost.
    if (c.abrupt && lost && c.age + 1 >= kKidnapScans && lost_updates_ >= kKidnapScans &&
        c.fit >= fit + kGlitchGain)
      return true;
    // Or the filter settled on a wrong place that fits almost as well (a building's
    // near-symmetry): the other place stayed ahead over a long stretch of new view while
    // the prediction fitted as usual, fits as the map usually does, and its readings cross
    // no more walls.
    if (cfg_.free_space && crossing <= blocked && c.steady_view >= kSettledView &&
        c.fit >= kNormalFit * usual && c.fit > fit)
      return true;
    // Within the rescue window it is a glitch candidate, whichever search found it: the
    // sweep also finds corrected poses the rescue search misses (a window widened past its
    // budget, or a fit that faded without a fall that would have started a search).
    if (!in_rescue_window(c.pose, ref.pose)) return false;
  }
  // A shift without a turn (a slip) is where a corridor's aliases lie, each fitting about
  // as well as the next: the free space must not speak for the prediction.
  if (turned < kFadedHeading && crossing > blocked) return false;
  if (!abrupt && !(nearby && turned >= kFadedHeading)) return false;
  // Beyond a glitch's reach from a prediction that is not lost lie a corridor's aliases,
  // which one update's people or dropout can favour: unless the free space confirms it,
  // such a shift wins only once tracked for kSlipScans scans. An alias's lead fades within
  // them; a slip's true pose keeps it.
  if (!nearby && !lost && !confirmed && c.age < kSlipScans) return false;
  return c.fit >= fit + (abrupt ? 0.5 : 1.0) * kGlitchGain;
}

bool HypothesisTracker::overshadowed(const Competitor& c) const {
  // competitors_ is sorted by evidence: those before c are stronger.
  const auto stronger = competitors_.begin() + (&c - competitors_.data());
  const std::size_t crossing = blocked_beams(c.pose);
  return std::any_of(competitors_.begin(), stronger, [&](const Competitor& d) {
    return d.age >= 1 && d.fit >= c.fit + kConfirmGain && blocked_beams(d.pose) <= crossing;
  });
}

void HypothesisTracker::maybe_switch(const Scored& ref, double fit, std::size_t blocked,
                                     double step, bool lost, std::size_t particles,
                                     HypothesisStep& out) {
  // competitors_ is sorted by evidence: the first that may switch is the strongest. Not if
  // a place no farther from the prediction fits this very scan clearly better: a fresh
  // rescue candidate that may not switch yet, found where a noisy odometry step left the
  // prediction behind, would otherwise let a weaker, older one farther off take the set
  // (one scan's evidence against that prediction is large for every place near the truth).
  const std::span<const Competitor> all(competitors_);
  const auto winner =
      std::find_if(competitors_.begin(), competitors_.end(), [&](const Competitor& c) {
        return may_switch(c, ref, fit, blocked, step, lost) &&
               !outscored_on_this_scan(all, c, ref.pose, cfg_.switch_evidence) && !overshadowed(c);
      });
  if (winner == competitors_.end()) return;
  out.seed = {{winner->pose},
              static_cast<std::size_t>(
                  std::lround(cfg_.switch_seed_fraction * static_cast<double>(particles))),
              0.5 * search_.leaf_size(),
              search_.angle_step()};
  out.switched = true;
  // The old prediction becomes a competitor, with the evidence against it; it may come back
  // as a glitch candidate would, should the switch have been wrong.
  *winner = {.pose = ref.pose,
             .evidence = -winner->evidence,
             .last = -winner->last,
             .fit = fit,
             .origin = Competitor::Origin::kRescue,
             .abrupt = true};
}

}  // namespace pgmcl::detail
