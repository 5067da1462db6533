// Localizer::update(): boundary validation, gating, motion and measurement updates.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "hypothesis_tracker.hpp"
#include "motion_noise_adaptation.hpp"
#include "parallel_blocks.hpp"
#include "pgmcl/mcl/localizer.hpp"
#include "pgmcl/mcl/weights.hpp"
#include "tempering.hpp"

namespace pgmcl {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) noexcept {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}
bool finite(const Pose2& p) noexcept {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta);
}
// The tempering limit is lifted once one cluster has held nearly all the weight for this
// many scans in a row.
constexpr int kUnimodalUpdates = 3;
// The usual fit follows about the last 100 converged updates (the tracker's own rate).
constexpr double kUsualFitRate = 0.01;

[[noreturn]] void bad_scan(const std::string& why) {
  throw std::invalid_argument("Localizer::update: " + why);
}

}  // namespace

void Localizer::validate_scan(const LaserScan& scan) const {
  const std::size_t expected = cfg_.likelihood.expected_beams;
  if (expected != 0 && scan.ranges.size() != expected)
    bad_scan("scan has " + std::to_string(scan.ranges.size()) + " readings, the sensor is " +
             "configured for " + std::to_string(expected) + " (likelihood.expected_beams)");
  if (scan.ranges.size() > std::numeric_limits<std::uint32_t>::max())
    bad_scan("scan has more than 2^32 readings");
  if (!std::isfinite(scan.angle_min) || !std::isfinite(scan.angle_increment))
    bad_scan("scan angle_min / angle_increment must be finite");
  if (!(std::isfinite(scan.range_min) && scan.range_min >= 0.0))
    bad_scan("scan range_min must be finite and >= 0 (got " + std::to_string(scan.range_min) + ")");
  if (!(scan.range_max > scan.range_min))  // +Inf allowed; NaN rejected
    bad_scan("scan range_max must exceed range_min (got " + std::to_string(scan.range_max) + ")");
  if (!finite(scan.sensor_pose)) bad_scan("scan sensor_pose must be finite");
}

UpdateResult Localizer::update(const Pose2& odometry_pose, const LaserScan& scan, double stamp) {
  const auto t0 = Clock::now();
  // ---- Boundary: everything that can throw happens before any state changes. ----
  validate_scan(scan);
  if (!finite(odometry_pose)) bad_scan("odometry pose must be finite");
  if (!std::isfinite(stamp)) bad_scan("stamp must be finite");
  const bool backwards = have_stamp_ && stamp < last_stamp_;
  if (backwards && cfg_.time_backwards == TimeBackwardsPolicy::kThrow)
    bad_scan("stamp " + std::to_string(stamp) + " s is earlier than the previous update's " +
             std::to_string(last_stamp_) + " s (time_backwards = kThrow)");

  threads_ = cfg_.adaptive_threads ? thread_policy_.next() : cfg_.threads;
  UpdateResult r = last_;  // estimate fields carry over on skipped updates
  r.threads = threads_;
  r.skipped = SkipReason::kNone;
  r.motion_applied = r.resampled = false;
  r.injected = 0;
  r.seeded = 0;
  r.switched = r.searched = false;
  r.tempering = 0.0;
  r.beams_total = scan.ranges.size();
  r.beams_invalid = r.beams_used = r.beams_background = 0;
  r.timings = {};
  last_stamp_ = stamp;
  have_stamp_ = true;

  if (backwards) {  // kReset: start a fresh odometry chain, keep the particles
    have_odom_ = false;
    rotation_moment_ = 0.0;
    force_ = true;
    r.skipped = SkipReason::kTimeWentBackwards;
    r.timings.total_ms = ms_since(t0);
    last_ = r;
    return r;
  }

  // ---- Gating and motion (Probabilistic Robotics, Table 5.6). ----
  Pose2 delta{};
  if (have_odom_) {
    delta = odom_ref_.between(odometry_pose);
    if (cfg_.motion.per_reading_noise)
      rotation_moment_ +=
          rotation_moment(cfg_.motion.kind, decompose_odometry(odom_last_, odometry_pose));
    odom_last_ = odometry_pose;
    const bool moved = std::hypot(delta.x, delta.y) >= cfg_.gating.d_min ||
                       std::abs(delta.theta) >= cfg_.gating.theta_min;
    if (cfg_.gating.enabled && !moved && !force_) {
      r.skipped = SkipReason::kNotMoved;
      r.estimate = anchor_.compose(delta);  // dead reckoning since the last update
      r.timings.total_ms = ms_since(t0);
      last_ = r;
      return r;
    }
    const auto tm = Clock::now();
    motion_update(odom_ref_, odometry_pose);
    r.motion_applied = true;
    r.timings.motion_ms = ms_since(tm);
  }
  have_odom_ = true;
  odom_ref_ = odom_last_ = odometry_pose;

  // ---- Measurement (Dekan et al., Eq. (6), tempered) ----
  const auto tz = Clock::now();
  const bool measured = measurement_update(scan, delta, r);
  r.timings.measurement_ms = ms_since(tz);
  if (!measured) r.skipped = SkipReason::kNoValidBeams;
  force_ = false;

  // ---- Estimate before resampling (resampling only adds noise to it). ----
  const auto te = Clock::now();
  const double full_tau = cfg_.likelihood.tempering_for(static_cast<double>(r.beams_used));
  compute_estimate(r, measured ? full_tau - r.tempering : 0.0);
  if (measured) {
    count_background(r);
    if (hypotheses_ && r.converged && hypotheses_->global()) {
      const Pose2 local = origin_.between(r.estimate);
      hypotheses_->converged(local);
      hold_other_places(local);
    }
  }
  // The filter's own dynamics (tempering limit, recovery averages) follow the cluster;
  // what it reports also doubts a cluster that another place outweighs so far.
  clustered_ = r.converged;
  unimodal_ = one_mode_ ? unimodal_ + 1 : 0;
  // The odometry's error between two converged estimates sizes the next motion noise.
  // Not while another place outweighs the estimate: a filter lost in the wrong place sees
  // its odometry "miss", and a wider proposal would only spread it further.
  const bool adaptable = measured && r.converged && !r.switched && r.alternative_evidence <= 0.0;
  if (adaptable && adaptable_ && r.motion_applied)
    motion_noise_->observe(delta, rotation_moment_, anchor_, last_.covariance, r.estimate,
                           r.covariance);
  rotation_moment_ = 0.0;  // the next update's readings start here
  adaptable_ = adaptable;
  r.rotation_noise_factor = motion_noise_->rotation_factor();
  r.translation_noise_factor = motion_noise_->translation_factor();
  if (r.alternative_evidence > 0.0) r.converged = false;
  if (measured && r.converged) confirm_by_fit(r);
  r.timings.estimate_ms = ms_since(te);

  const std::size_t scored = p_.size();
  if (measured) {
    const auto tr = Clock::now();
    resample(r);
    r.timings.resample_ms = ms_since(tr);
  }
  r.particles = p_.size();
  anchor_ = r.estimate;
  r.timings.total_ms = ms_since(t0);
  if (measured)
    thread_policy_.record(threads_, r.timings.total_ms,
                          static_cast<double>(scored) * static_cast<double>(r.beams_used));
  last_ = r;
  return r;
}

void Localizer::confirm_by_fit(UpdateResult& r) noexcept {
  // Converged updates learn how well the map fits here; one whose scan fits the estimate far
  // worse cannot confirm its pose, as the tracker's prediction counts as lost on such a fall.
  if (!have_usual_fit_) {
    usual_fit_ = r.fit;
    have_usual_fit_ = true;
  }
  const bool fits = r.fit >= cfg_.estimate.converged_fit_ratio * usual_fit_;
  usual_fit_ += kUsualFitRate * (r.fit - usual_fit_);
  if (!fits) r.converged = false;
}

void Localizer::motion_update(const Pose2& odom_prev, const Pose2& odom_now) {
  const OdometryIncrement inc = decompose_odometry(odom_prev, odom_now);
  const std::uint64_t step = next_step();
  const std::size_t n = p_.size();
  float* x = p_.x.data();
  float* y = p_.y.data();
  float* th = p_.theta.data();
  const MotionModelKind kind = cfg_.motion.kind;
  const MotionNoise noise =
      detail::spanning_readings(kind, motion_noise_->noise(), inc, rotation_moment_);
  const std::uint64_t seed = cfg_.seed;
  detail::for_each_block(detail::block_count(n), threads_, [&](std::size_t b) {
    Rng rng = Rng::for_block(seed, step, b);
    const std::size_t hi = std::min(n, (b + 1) * detail::kParticleBlock);
    for (std::size_t i = b * detail::kParticleBlock; i < hi; ++i) {
      const Pose2 q = sample_motion(kind, noise, inc, {x[i], y[i], th[i]}, rng);
      x[i] = static_cast<float>(q.x);
      y[i] = static_cast<float>(q.y);
      th[i] = wrap_angle(static_cast<float>(q.theta));
    }
  });
}

bool Localizer::measurement_update(const LaserScan& scan, const Pose2& delta, UpdateResult& r) {
  valid_beam_indices(scan, field_->model().params().max_range, ws_.valid_beams);
  r.beams_invalid = scan.ranges.size() - ws_.valid_beams.size();
  select_beams(ws_.valid_beams, cfg_.likelihood.selection, ws_.selected_beams);
  r.beams_used = ws_.selected_beams.size();
  if (ws_.selected_beams.empty()) return false;

  model_.prepare(scan, ws_.selected_beams);
  const Pose2 prediction = origin_.between(anchor_).compose(delta);  // map-local
  bool judge_free_space = false;
  const std::size_t n = p_.size();
  ws_.beam_sums.resize(n);
  bool scored = false;
  if (hypotheses_) {
    // Competing hypotheses may redraw some particles before the scan scores them all.
    // The rescue search covers at least the heading error the motion noise allows (3 sigma):
    // a long turn between sparse scans on noisy odometry can exceed its fixed window.
    const double heading_spread = 3.0 * motion_noise_->heading_sigma(delta, rotation_moment_);
    detail::HypothesisStep h;
    const auto follow_hypotheses = [&] {
      const auto th = Clock::now();
      h = hypotheses_->update(scan, ws_.selected_beams, model_.beams(), prediction, delta, n,
                              heading_spread);
      r.timings.hypotheses_ms = ms_since(th);
    };
    // While tracking, a team scores the particles alongside the hypotheses' search, which is
    // serial; the few particles a switch redraws are scored again. A global search redraws
    // half the set every update, so there it goes first.
    if (threads_ != 1 && !hypotheses_->global()) {
      detail::alongside(threads_, follow_hypotheses, detail::block_count(n), [&](std::size_t b) {
        const std::size_t lo = b * detail::kParticleBlock;
        model_.score_block(p_.x, p_.y, p_.theta, lo, std::min(n, lo + detail::kParticleBlock),
                           ws_.beam_sums);
      });
      scored = true;
    } else {
      follow_hypotheses();
    }
    r.seeded = seed_particles(h.seed);
    if (scored)  // the team scored the redrawn particles at their old poses
      for (const std::uint32_t i : std::span(ws_.seed_victims).first(r.seeded))
        model_.score_block(p_.x, p_.y, p_.theta, i, i + 1, ws_.beam_sums);
    r.switched = h.switched;
    r.searched = h.searched;
    r.competitors = h.competitors;
    r.alternative_evidence = h.alternative_evidence;
    // The particles are judged by the free space while tracking a set that was one compact
    // cluster (clustered_) when the scan stopped fitting it (a rescue search ran). Not for a
    // spread cloud: one spread by a 100 m odometry spike found its way back without it and
    // not with it. Not on the update a competitor wins: the switch has weighed the free
    // space already, and judging the redrawn set again delayed a slip's absorption amid a
    // crowd (the unit test's seed 4: 4 -> 12 updates).
    judge_free_space = cfg_.hypotheses.free_space && cfg_.hypotheses.free_space_weights &&
                       clustered_ && h.searched && !hypotheses_->global() && !h.switched;
  }
  if (!scored) {
    if (threads_ == 1)
      model_.score_serial(p_.x, p_.y, p_.theta, ws_.beam_sums);
    else
      model_.score_parallel(p_.x, p_.y, p_.theta, ws_.beam_sums, threads_);
  }

  // Per-particle log-likelihood of the scan (sum over beams).
  const auto m = static_cast<double>(ws_.selected_beams.size());
  ws_.scan_ll.resize(n);
  for (std::size_t i = 0; i < n; ++i) ws_.scan_ll[i] = model_.log_likelihood(ws_.beam_sums[i]);
  // The averages start once the filter has converged (set_pose() counts as converged when
  // its covariance is within the convergence bounds): while a global search is under way
  // the set is spread anyway, and a long-term average seeded by that search's poor fit
  // would later hide a kidnapping for dozens of scans.
  if (cfg_.filter.recovery.enabled && (have_averages_ || clustered_)) {
    // Augmented MCL's average likelihood, under the weights before this scan (Table 8.3
    // line 6), per beam: sum_i w_i exp(ll_i / M).
    double w_avg = 0.0;
    for (std::size_t i = 0; i < n; ++i) w_avg += p_.w[i] * std::exp(ws_.scan_ll[i] / m);
    update_recovery_averages(w_avg, r);
  }

  // Tempered sum of per-beam log-likelihoods (see LikelihoodConfig for why). While the
  // set holds several hypotheses, the exponent is also lowered where this scan alone
  // would collapse the effective sample size (LikelihoodConfig::min_ess_ratio). Once
  // converged, or once a single cluster has held nearly all the weight for a few scans,
  // the limit is off: no other mode is left to keep, and it would only slow the
  // contraction of a compact but offset, or broad, cluster (sparse scans re-spread it
  // every step). One scan is not enough: a sparse one can single out a wrong place.
  const LikelihoodConfig& lc = cfg_.likelihood;
  const double tau_cfg = lc.tempering_for(m);
  const double tau =
      clustered_ || unimodal_ >= kUnimodalUpdates
          ? tau_cfg
          : detail::limit_tempering(p_.log_w, ws_.scan_ll, tau_cfg, lc.min_ess_ratio);
  r.tempering = tau;
  for (std::size_t i = 0; i < n; ++i) p_.log_w[i] += tau * ws_.scan_ll[i];
  if (judge_free_space) {
    const auto tf = Clock::now();
    discount_blocked_readings(tau);
    r.timings.free_space_ms = ms_since(tf);
  }
  (void)normalise_log_weights(p_.log_w, p_.w);
  limit_probation_weight(prediction);
  r.n_eff = effective_sample_size(p_.w);
  return true;
}

void Localizer::update_recovery_averages(double w_avg, UpdateResult& r) noexcept {
  // Table 8.3 averages the scan likelihood p(z | x_i) over the particles; pgmcl averages
  // its per-beam geometric mean p(z | x_i)^(1/M) instead: the raw scan likelihood scales
  // exponentially with the beam count (and underflows), which would make the injection
  // rate depend on the beam selection. Values stay within exp(ll_background .. ll_max).
  // Probabilistic Robotics, Table 8.3, lines 9-10, seeded with the first value (why not a
  // start-up correction: configs/experiments/README.md, "Why the defaults").
  if (!have_averages_) {
    w_slow_ = w_fast_ = w_avg;
    have_averages_ = true;
  } else {
    w_slow_ += cfg_.filter.recovery.alpha_slow * (w_avg - w_slow_);
    w_fast_ += cfg_.filter.recovery.alpha_fast * (w_avg - w_fast_);
  }
  r.w_slow = w_slow_;
  r.w_fast = w_fast_;
}

void Localizer::limit_probation_weight(const Pose2& prediction) {
  // Together, the particles on probation hold at most RecoveryConfig::probation_weight
  // (see there for why). Compared in log space: a random pose that fits 100 nats better
  // than the cluster has a weight share of 1 - 1e-44, which is 1.0 in double.
  ws_.log_w_probation.clear();
  ws_.log_w_tracked.clear();
  for (std::size_t i = 0; i < p_.size(); ++i)
    (probation_[i] != 0 ? ws_.log_w_probation : ws_.log_w_tracked).push_back(p_.log_w[i]);
  const double lse_probation = log_sum_exp(ws_.log_w_probation);
  const double lse_tracked = log_sum_exp(ws_.log_w_tracked);
  if (std::isfinite(lse_probation) && std::isfinite(lse_tracked)) {  // both groups hold weight
    const double share = cfg_.filter.recovery.probation_weight;
    const double log_ratio = lse_probation - lse_tracked;
    const double log_target = std::log(share / (1.0 - share));
    if (log_ratio > log_target) {
      for (std::size_t i = 0; i < p_.size(); ++i)
        if (probation_[i] != 0) p_.log_w[i] += log_target - log_ratio;
      (void)normalise_log_weights(p_.log_w, p_.w);
    }
  }
  // Far from the prediction, probation waits for the tracker (HypothesisTracker::
  // hold_radius()): in clutter a random pose can fit better than the true one for longer
  // than any probation, and one that does is no evidence of a kidnapping by itself.
  const double hold = hypotheses_ ? hypotheses_->hold_radius() : -1.0;
  const auto hold2 = static_cast<float>(hold * hold);
  const auto px = static_cast<float>(prediction.x), py = static_cast<float>(prediction.y);
  for (std::size_t i = 0; i < p_.size(); ++i) {
    if (probation_[i] == 0) continue;
    const float dx = p_.x[i] - px, dy = p_.y[i] - py;
    if (hold < 0.0 || dx * dx + dy * dy <= hold2) --probation_[i];
  }
}

void Localizer::hold_other_places(const Pose2& estimate) {
  // The global search seeded other places until this update, and its seeded particles are
  // tracked like the rest. With odometry noisier than the model the converged cluster can
  // misfit the next scan, and one of them then took the whole set in one update, 17-42 m
  // off (bench/robustness/README.md). Held, they win only as the tracker's competitors do.
  // The radius within which a lineage's probation counts down (limit_probation_weight()).
  const double radius = hypotheses_->hold_radius();
  if (radius < 0.0) return;
  const auto hold = static_cast<float>(radius);
  const auto ex = static_cast<float>(estimate.x), ey = static_cast<float>(estimate.y);
  const auto probation = static_cast<std::uint8_t>(cfg_.filter.recovery.probation);
  for (std::size_t i = 0; i < p_.size(); ++i) {
    const float dx = p_.x[i] - ex, dy = p_.y[i] - ey;
    if (dx * dx + dy * dy > hold * hold) probation_[i] = std::max(probation_[i], probation);
  }
}

void Localizer::count_background(UpdateResult& r) const noexcept {
  const Pose2 local = origin_.between(r.estimate);
  const PoseScore s = model_.score_pose(local.x, local.y, local.theta);
  r.beams_background = s.background;
  r.fit = static_cast<double>(s.fitting) /
          static_cast<double>(std::max<std::size_t>(1, model_.beams().size()));
}

}  // namespace pgmcl
