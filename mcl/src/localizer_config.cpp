#include "pgmcl/mcl/localizer_config.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace pgmcl {
namespace {

[[noreturn]] void fail(const std::string& field, const std::string& why) {
  throw std::invalid_argument("LocalizerConfig: " + field + " " + why);
}
void require_finite_nonneg(double v, const char* field) {
  if (!std::isfinite(v) || v < 0.0)
    fail(field, "must be finite and >= 0 (got " + std::to_string(v) + ")");
}
void require_positive(double v, const char* field) {
  if (!std::isfinite(v) || v <= 0.0)
    fail(field, "must be finite and > 0 (got " + std::to_string(v) + ")");
}

constexpr double kMaxMotionAlpha = 100.0;

}  // namespace

void LocalizerConfig::validate() const {
  const MotionNoise& n = motion.noise;
  // Variance-form alphas above kMaxAlpha mean odometry carries no information (a std of
  // 10x the motion itself); far larger ones overflow the sampled poses to Inf/NaN.
  for (const auto& [alpha, field] :
       {std::pair{n.a1, "motion.noise.a1"}, std::pair{n.a2, "motion.noise.a2"},
        std::pair{n.a3, "motion.noise.a3"}, std::pair{n.a4, "motion.noise.a4"},
        std::pair{n.a5, "motion.noise.a5"}}) {
    require_finite_nonneg(alpha, field);
    if (alpha > kMaxMotionAlpha)
      fail(field, "must be <= " + std::to_string(kMaxMotionAlpha) + " (got " +
                      std::to_string(alpha) + ")");
  }

  const LikelihoodConfig& l = likelihood;
  require_positive(l.beam.sigma_along, "likelihood.beam.sigma_along");
  require_positive(l.beam.sigma_across, "likelihood.beam.sigma_across");
  require_finite_nonneg(l.beam.model_mismatch, "likelihood.beam.model_mismatch");
  require_positive(l.beam.max_range, "likelihood.beam.max_range");
  if (!std::isfinite(l.effective_beams)) fail("likelihood.effective_beams", "must be finite");
  if (l.effective_beams <= 0.0 && !(l.tempering > 0.0 && l.tempering <= 1.0))
    fail("likelihood.tempering", "must be in (0, 1] (got " + std::to_string(l.tempering) + ")");
  if (!(l.min_ess_ratio >= 0.0 && l.min_ess_ratio < 1.0))
    fail("likelihood.min_ess_ratio", "must be in [0, 1)");
  if (l.selection.mode == BeamSelectionMode::kStride && l.selection.stride < 1)
    fail("likelihood.selection.stride", "must be >= 1");
  if (l.selection.mode == BeamSelectionMode::kMaxBeams && l.selection.max_beams < 1)
    fail("likelihood.selection.max_beams", "must be >= 1");

  const FilterConfig& f = filter;
  if (f.particles < 1) fail("filter.particles", "must be >= 1");
  if (f.global_particles < 1) fail("filter.global_particles", "must be >= 1");
  if (!(f.resample_threshold >= 0.0 && f.resample_threshold <= 1.0))
    fail("filter.resample_threshold",
         "must be in [0, 1] (got " + std::to_string(f.resample_threshold) + ")");
  if (f.kld.enabled) {
    if (f.kld.min_particles < 1) fail("filter.kld.min_particles", "must be >= 1");
    if (f.kld.max_particles < f.kld.min_particles)
      fail("filter.kld.max_particles", "must be >= filter.kld.min_particles");
    if (!(f.kld.epsilon > 0.0 && std::isfinite(f.kld.epsilon)))
      fail("filter.kld.epsilon", "must be finite and > 0");
    if (!(f.kld.delta > 0.0 && f.kld.delta < 1.0)) fail("filter.kld.delta", "must be in (0, 1)");
    require_positive(f.kld.bin_xy, "filter.kld.bin_xy");
    require_positive(f.kld.bin_theta, "filter.kld.bin_theta");
  }
  if (f.recovery.enabled) {
    if (!(f.recovery.alpha_slow > 0.0 && f.recovery.alpha_slow < 1.0))
      fail("filter.recovery.alpha_slow", "must be in (0, 1)");
    if (!(f.recovery.alpha_fast > f.recovery.alpha_slow && f.recovery.alpha_fast <= 1.0))
      fail("filter.recovery.alpha_fast", "must be in (alpha_slow, 1]");
    if (f.recovery.probation > 255) fail("filter.recovery.probation", "must be <= 255");
    if (!(f.recovery.probation_weight > 0.0 && f.recovery.probation_weight < 1.0))
      fail("filter.recovery.probation_weight", "must be in (0, 1)");
  }

  require_finite_nonneg(gating.d_min, "gating.d_min");
  require_finite_nonneg(gating.theta_min, "gating.theta_min");

  const EstimateConfig& e = estimate;
  require_positive(e.cluster_xy, "estimate.cluster_xy");
  require_positive(e.cluster_theta, "estimate.cluster_theta");
  if (!(e.converged_weight > 0.0 && e.converged_weight <= 1.0))
    fail("estimate.converged_weight", "must be in (0, 1]");
  require_positive(e.converged_xy_std, "estimate.converged_xy_std");
  require_positive(e.converged_theta_std, "estimate.converged_theta_std");

  const HypothesesConfig& h = hypotheses;
  if (h.enabled) {
    require_positive(h.search.leaf_size, "hypotheses.search.leaf_size");
    if (h.search.root_levels < 1 || h.search.root_levels > 12)
      fail("hypotheses.search.root_levels", "must be in [1, 12]");
    if (h.search.max_beams < 1) fail("hypotheses.search.max_beams", "must be >= 1");
    require_positive(h.search.min_angle_step, "hypotheses.search.min_angle_step");
    if (!(h.search.max_angle_step >= h.search.min_angle_step &&
          std::isfinite(h.search.max_angle_step)))
      fail("hypotheses.search.max_angle_step", "must be finite and >= min_angle_step");
    if (!(h.global_seed_fraction >= 0.0 && h.global_seed_fraction <= 1.0))
      fail("hypotheses.global_seed_fraction", "must be in [0, 1]");
    if (!(h.switch_seed_fraction >= 0.0 && h.switch_seed_fraction <= 1.0))
      fail("hypotheses.switch_seed_fraction", "must be in [0, 1]");
    require_finite_nonneg(h.candidate_margin, "hypotheses.candidate_margin");
    require_positive(h.switch_evidence, "hypotheses.switch_evidence");
    if (!(std::isfinite(h.drop_evidence) && h.drop_evidence < 0.0))
      fail("hypotheses.drop_evidence", "must be finite and < 0");
    if (!(h.rescue_fit_ratio >= 0.0 && h.rescue_fit_ratio <= 1.0))
      fail("hypotheses.rescue_fit_ratio", "must be in [0, 1]");
    require_finite_nonneg(h.rescue_xy, "hypotheses.rescue_xy");
    require_finite_nonneg(h.rescue_theta, "hypotheses.rescue_theta");
    require_finite_nonneg(h.sweep_share, "hypotheses.sweep_share");
    require_finite_nonneg(h.rival_view, "hypotheses.rival_view");
    require_positive(h.separation_xy, "hypotheses.separation_xy");
    require_positive(h.separation_theta, "hypotheses.separation_theta");
  }

  if (threads < 0) fail("threads", "must be >= 0 (0 = OpenMP default)");
}

}  // namespace pgmcl
