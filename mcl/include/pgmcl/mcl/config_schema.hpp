#pragma once
/// The one description of LocalizerConfig's fields: for each, its key, unit, allowed values
/// and a short meaning (the default is the struct's own), as a visitor over the struct tree.
/// validate(), the YAML reader and writer, --set, the unknown-key suggestions and the
/// reference table (`pgmcl config --reference`) all walk describe_config(); bindings and
/// node parameters can walk it too.
///
/// A visitor provides:
///   section(name, body)                 nested struct; body() visits its fields
///   number(field, double&, Bounds)      a real number
///   integer(field, T&, IntRange)        int / size_t / uint64_t
///   flag(field, bool&)
///   choice(field, E&, names)            an enumeration written as a name
///   rule(name, ok, problem)             a check across fields, reported at field `name`
/// References are const when the visited config is.

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "pgmcl/common/enum_names.hpp"
#include "pgmcl/mcl/localizer_config.hpp"

namespace pgmcl::config_schema {

/// Unit, meaning and key of one field.
struct Field {
  const char* name;
  const char* unit;  ///< "m", "rad", ... or "" for plain numbers
  const char* doc;
};

/// Allowed values of a real number: always finite, within [lo, hi] with open ends where
/// stated.
struct Bounds {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false;
  bool hi_open = false;

  [[nodiscard]] bool contains(double v) const noexcept {
    return std::isfinite(v) && (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
  }
  /// "finite and > 0", "in (0, 1]", ...: what the error message and the reference say.
  [[nodiscard]] std::string text() const;
};

inline constexpr double kInf = std::numeric_limits<double>::infinity();
inline constexpr Bounds kAnyFinite{};
inline constexpr Bounds kPositive{0.0, kInf, true, false};
inline constexpr Bounds kNonNegative{0.0, kInf, false, false};
inline constexpr Bounds kNegative{-kInf, 0.0, false, true};
inline constexpr Bounds kUnit{0.0, 1.0, false, false};      ///< [0, 1]
inline constexpr Bounds kOpenUnit{0.0, 1.0, true, true};    ///< (0, 1)
inline constexpr Bounds kUpperUnit{0.0, 1.0, true, false};  ///< (0, 1]
inline constexpr Bounds kLowerUnit{0.0, 1.0, false, true};  ///< [0, 1)

/// Allowed values of an integer field, inclusive.
struct IntRange {
  std::int64_t lo = 0;
  std::uint64_t hi = std::numeric_limits<std::uint64_t>::max();
  double unit_bytes = 0.0;  ///< memory one unit costs, for the message (0: not a size)
  [[nodiscard]] std::string text() const;
  /// " (about 110 bytes each: 1e+12 would take 1.1e+05 GB)" for a size above hi, else "".
  [[nodiscard]] std::string memory(std::uint64_t v) const;
};

/// Particle counts: the particle set and the filter's scratch take about 110 bytes per
/// particle (tests/stress, MillionParticles), so 10^7 particles hold about 1 GB.
inline constexpr IntRange kParticleCount{1, 10'000'000, 110.0};

/// Readings per scan: as many as the log readers accept (CARMEN num_readings), 4 bytes each
/// in every scan the filter holds.
inline constexpr IntRange kBeamCount{0, 1u << 20, 4.0};

/// OpenMP threads: libgomp crashes creating tens of thousands, and past the core count more
/// threads only take turns.
inline constexpr int kMaxThreads = 1024;

/// Beam sigmas and the map error, metres: a sigma of 10 m already spreads one reading over a
/// room; far larger ones only make the kernel reach overflow with a message about cells.
inline constexpr Bounds kSigma{0.0, 10.0, true, false};
inline constexpr Bounds kMismatch{0.0, 10.0, false, false};

using pgmcl::EnumName;
using pgmcl::name_of;

inline constexpr std::array<EnumName<MotionModelKind>, 4> kMotionKinds{{
    {MotionModelKind::kDifferentialDrive, "differential_drive"},
    {MotionModelKind::kOmnidirectional, "omnidirectional"},
    {MotionModelKind::kDifferentialDrive, "diff_drive"},
    {MotionModelKind::kOmnidirectional, "omni"},
}};
inline constexpr const std::array<EnumName<maps::TableKind>, 3>& kTableKinds =
    maps::kTableKindNames;
inline constexpr std::array<EnumName<BeamSelectionMode>, 3> kSelectionModes{{
    {BeamSelectionMode::kAll, "all"},
    {BeamSelectionMode::kStride, "stride"},
    {BeamSelectionMode::kMaxBeams, "max_beams"},
}};
inline constexpr std::array<EnumName<TimeBackwardsPolicy>, 2> kTimePolicies{{
    {TimeBackwardsPolicy::kThrow, "throw"},
    {TimeBackwardsPolicy::kReset, "reset"},
}};

/// Variance-form motion alphas above this mean odometry carries no information (a std of
/// 10x the motion itself); far larger ones overflow the sampled poses.
inline constexpr double kMaxMotionAlpha = 100.0;

template <class V, class Config>
void describe_motion(V& v, Config& c) {
  v.section("motion", [&] {
    v.choice(Field{"kind", "", "odometry model (Probabilistic Robotics, Table 5.6 / omni)"},
             c.motion.kind, kMotionKinds);
    v.section("noise", [&] {
      constexpr Bounds alpha{0.0, kMaxMotionAlpha};
      auto& n = c.motion.noise;
      v.number(Field{"a1", "rad²/rad²", "rotation noise from rotation (variance form)"}, n.a1,
               alpha);
      v.number(Field{"a2", "rad²/m²", "rotation noise from translation"}, n.a2, alpha);
      v.number(Field{"a3", "m²/m²", "translation noise from translation"}, n.a3, alpha);
      v.number(Field{"a4", "m²/rad²", "translation noise from rotation"}, n.a4, alpha);
      v.number(Field{"a5", "m²/m²", "omnidirectional only: strafe noise from translation"}, n.a5,
               alpha);
    });
    v.flag(Field{"per_reading_noise", "",
                 "heading noise summed over the odometry readings the gating skipped"},
           c.motion.per_reading_noise);
    v.section("adaptation", [&] {
      auto& a = c.motion.adaptation;
      v.flag(Field{"enabled", "", "inflate the noise while the odometry misses the estimates"},
             a.enabled);
      v.integer(Field{"window", "updates", "updates whose residuals are pooled (median)"}, a.window,
                IntRange{3, 100'000});
      v.number(Field{"margin", "", "on the factor the residuals show (they understate it)"},
               a.margin, Bounds{1.0, kMaxMotionAlpha});
      v.number(Field{"max_inflation", "", "largest factor on the noise variances"}, a.max_inflation,
               Bounds{1.0, kMaxMotionAlpha});
    });
  });
}

template <class V, class Config>
void describe_likelihood(V& v, Config& c) {
  auto& l = c.likelihood;
  v.section("likelihood", [&] {
    v.section("beam", [&] {
      auto& b = l.beam;
      v.number(Field{"sigma_along", "m", "sensor sigma along the beam (Dekan et al., Sec. 5)"},
               b.sigma_along, kSigma);
      v.number(Field{"sigma_across", "m", "sensor sigma across the beam (Dekan et al., Sec. 5)"},
               b.sigma_across, kSigma);
      v.number(Field{"model_mismatch", "m", "map error, added in quadrature to both sigmas"},
               b.model_mismatch, kMismatch);
      v.flag(Field{"add_discretisation", "", "add res²/12 for the position within a cell"},
             b.add_discretisation);
      v.number(Field{"w_hit", "", "weight of the Gaussian hit term"}, b.w_hit, kUnit);
      v.number(Field{"w_rand", "", "weight of the uniform floor"}, b.w_rand, kUnit);
      v.rule("w_rand", std::abs(b.w_hit + b.w_rand - 1.0) <= 1e-9,
             "must make w_hit + w_rand = 1 within 1e-9");
      v.number(Field{"max_range", "m", "support of the uniform term; longer readings are skipped"},
               b.max_range, kPositive);
    });
    v.section("table", [&] {
      auto& t = l.table;
      v.choice(Field{"kind", "", "likelihood table: one byte/cell, K planes, or offsets"}, t.kind,
               kTableKinds);
      v.integer(Field{"orientation_bins", "", "planes of the oriented table over [0, pi)"},
                t.orientation_bins, IntRange{1, 1024});
      v.number(Field{"reach_sigmas", "", "kernel reach; the floor beyond it"}, t.reach_sigmas,
               Bounds{0.0, 100.0, true, false});
      v.number(Field{"isotropy_tolerance", "", "oriented falls back to isotropic below this"},
               t.isotropy_tolerance, kNonNegative);
      v.integer(Field{"max_table_bytes", "bytes", "a larger table is an error"}, t.max_table_bytes,
                IntRange{1});
    });
    v.number(Field{"effective_beams", "", "independent readings a scan is worth; <= 0: tempering"},
             l.effective_beams, kAnyFinite);
    v.number(Field{"tempering", "", "fixed exponent when effective_beams <= 0"}, l.tempering,
             kUpperUnit);
    v.number(Field{"min_ess_ratio", "", "while not converged, one scan keeps this much N_eff"},
             l.min_ess_ratio, kLowerUnit);
    v.section("selection", [&] {
      auto& s = l.selection;
      v.choice(Field{"mode", "", "which valid readings are scored"}, s.mode, kSelectionModes);
      v.integer(Field{"stride", "", "every stride-th reading (mode stride)"}, s.stride,
                IntRange{0});
      v.rule("stride", s.mode != BeamSelectionMode::kStride || s.stride >= 1,
             "must be >= 1 with mode stride");
      v.integer(Field{"max_beams", "", "at most this many, evenly spread (mode max_beams)"},
                s.max_beams, IntRange{0});
      v.rule("max_beams", s.mode != BeamSelectionMode::kMaxBeams || s.max_beams >= 1,
             "must be >= 1 with mode max_beams");
    });
    v.integer(Field{"expected_beams", "", "readings per scan; 0 accepts any count"},
              l.expected_beams, kBeamCount);
  });
}

template <class V, class Config>
void describe_filter(V& v, Config& c) {
  auto& f = c.filter;
  v.section("filter", [&] {
    v.integer(Field{"particles", "", "after set_pose(); the fixed count without KLD"}, f.particles,
              kParticleCount);
    v.integer(Field{"global_particles", "", "after global_localize() and at construction"},
              f.global_particles, kParticleCount);
    v.number(Field{"resample_threshold", "", "resample when N_eff < this x N"},
             f.resample_threshold, kUnit);
    v.section("kld", [&] {
      auto& k = f.kld;
      v.flag(Field{"enabled", "", "KLD-sampling (Fox 2003) sizes the set after resampling"},
             k.enabled);
      v.integer(Field{"min_particles", "", "lower bound on the particle count"}, k.min_particles,
                kParticleCount);
      v.integer(Field{"max_particles", "", "upper bound on the particle count"}, k.max_particles,
                kParticleCount);
      v.rule("max_particles", k.max_particles >= k.min_particles,
             "must be >= filter.kld.min_particles");
      v.number(Field{"epsilon", "", "KL bound"}, k.epsilon, kPositive);
      v.number(Field{"delta", "", "z = normal quantile of 1 - delta"}, k.delta, kOpenUnit);
      v.number(Field{"bin_xy", "m", "histogram bin side in x and y"}, k.bin_xy, kPositive);
      v.number(Field{"bin_theta", "rad", "histogram bin width in heading"}, k.bin_theta, kPositive);
    });
    v.section("recovery", [&] {
      auto& r = f.recovery;
      v.flag(Field{"enabled", "", "augmented MCL (Table 8.3): random poses when the fit drops"},
             r.enabled);
      v.number(Field{"alpha_slow", "", "long-term average rate, per measurement update"},
               r.alpha_slow, kOpenUnit);
      v.number(Field{"alpha_fast", "", "short-term average rate, per measurement update"},
               r.alpha_fast, kUpperUnit);
      v.rule("alpha_fast", r.alpha_fast > r.alpha_slow, "must be > filter.recovery.alpha_slow");
      v.integer(Field{"probation", "updates", "a redrawn lineage waits this long to compete"},
                r.probation, IntRange{0, 255});
      v.number(Field{"probation_weight", "", "total weight the lineages on probation may hold"},
               r.probation_weight, kOpenUnit);
    });
  });
}

template <class V, class Config>
void describe_gating_and_estimate(V& v, Config& c) {
  v.section("gating", [&] {
    v.flag(Field{"enabled", "", "skip updates while the robot has not moved"}, c.gating.enabled);
    v.number(Field{"d_min", "m", "translation that triggers an update"}, c.gating.d_min,
             kNonNegative);
    v.number(Field{"theta_min", "rad", "rotation that triggers an update"}, c.gating.theta_min,
             kNonNegative);
  });
  v.section("estimate", [&] {
    auto& e = c.estimate;
    v.number(Field{"cluster_xy", "m", "clustering cell side in x and y"}, e.cluster_xy, kPositive);
    v.number(Field{"cluster_theta", "rad", "clustering cell width in heading"}, e.cluster_theta,
             kPositive);
    v.number(Field{"converged_weight", "", "converged: the best cluster holds more than this"},
             e.converged_weight, kUpperUnit);
    v.number(Field{"converged_xy_std", "m", "converged: its position std is below this"},
             e.converged_xy_std, kPositive);
    v.number(Field{"converged_theta_std", "rad", "converged: its heading std is below this"},
             e.converged_theta_std, kPositive);
    v.number(Field{"converged_fit_ratio", "", "converged: the scan fits this share of usual"},
             e.converged_fit_ratio, Bounds{0.0, 1.0});
  });
}

template <class V, class Config>
void describe_hypotheses(V& v, Config& c) {
  auto& h = c.hypotheses;
  v.section("hypotheses", [&] {
    v.flag(Field{"enabled", "", "competing hypotheses from scan-to-map search"}, h.enabled);
    v.section("search", [&] {
      auto& s = h.search;
      v.number(Field{"leaf_size", "m", "candidate spacing, rounded to 2^k cells"}, s.leaf_size,
               kPositive);
      v.integer(Field{"root_levels", "", "root node side = leaf x 2^root_levels"}, s.root_levels,
                IntRange{1, 12});
      v.integer(Field{"max_beams", "", "beams the search scores"}, s.max_beams, IntRange{1});
      v.number(Field{"min_angle_step", "rad", "finest heading step"}, s.min_angle_step, kPositive);
      v.number(Field{"max_angle_step", "rad", "coarsest heading step"}, s.max_angle_step,
               kPositive);
      v.rule("max_angle_step", s.max_angle_step >= s.min_angle_step,
             "must be >= hypotheses.search.min_angle_step");
    });
    v.integer(Field{"global_candidates", "", "distinct places seeded per global search"},
              h.global_candidates, IntRange{1, 100'000});
    v.number(Field{"global_seed_fraction", "", "particles redrawn around them per update"},
             h.global_seed_fraction, kUnit);
    v.number(Field{"candidate_margin", "nats", "global candidates within this of the best"},
             h.candidate_margin, kNonNegative);
    v.integer(Field{"global_budget", "lookups", "beam lookups per global search"}, h.global_budget,
              IntRange{1});
    v.integer(Field{"max_competitors", "", "hypotheses tracked beside the estimate"},
              h.max_competitors, IntRange{0, 1000});
    v.number(Field{"switch_evidence", "nats", "tempered evidence a competitor needs to win"},
             h.switch_evidence, kPositive);
    v.number(Field{"drop_evidence", "nats", "a competitor below this is dropped"}, h.drop_evidence,
             kNegative);
    v.number(Field{"switch_seed_fraction", "", "particles redrawn around a winner"},
             h.switch_seed_fraction, kUnit);
    v.number(Field{"rival_view", "m", "new view a globally proposed place must stay ahead"},
             h.rival_view, kNonNegative);
    v.number(Field{"rescue_fit_ratio", "", "search around the prediction below this x its fit"},
             h.rescue_fit_ratio, kUnit);
    v.number(Field{"rescue_xy", "m", "half-width of that search"}, h.rescue_xy, kNonNegative);
    v.number(Field{"rescue_theta", "rad", "half-width of that search in heading"}, h.rescue_theta,
             kNonNegative);
    v.integer(Field{"rescue_budget", "lookups", "beam lookups per rescue search"}, h.rescue_budget,
              IntRange{1});
    v.flag(Field{"glitch_search", "", "that search also fine-searches a heading glitch's reach"},
           h.glitch_search);
    v.number(Field{"sweep_share", "", "map sweep lookups per update / the particles' own"},
             h.sweep_share, kNonNegative);
    v.number(Field{"separation_xy", "m", "closer hypotheses are the same place"}, h.separation_xy,
             kPositive);
    v.number(Field{"separation_theta", "rad", "closer headings are the same place"},
             h.separation_theta, kPositive);
    v.flag(Field{"free_space", "", "judge hypotheses also by rays that cross walls"}, h.free_space);
    v.flag(
        Field{"free_space_weights", "", "while misfit, leading particles lose wall-crossing beams"},
        h.free_space_weights);
    v.flag(Field{"sustained_lead", "", "a shift that fits far better for 3 scans wins"},
           h.sustained_lead);
  });
}

/// Visits every field of `c` (a LocalizerConfig, const or not) in the YAML layout's order.
template <class V, class Config>
void describe_config(V& v, Config& c) {
  describe_motion(v, c);
  describe_likelihood(v, c);
  describe_filter(v, c);
  describe_gating_and_estimate(v, c);
  describe_hypotheses(v, c);
  v.choice(Field{"time_backwards", "", "a stamp earlier than the last: throw or reset"},
           c.time_backwards, kTimePolicies);
  v.integer(Field{"threads", "", "OpenMP threads; 0 = OpenMP's default"}, c.threads,
            IntRange{0, kMaxThreads});
  v.flag(Field{"adaptive_threads", "", "one thread while the team is slower (a busy core)"},
         c.adaptive_threads);
  v.integer(Field{"seed", "", "every random stream derives from it"}, c.seed, IntRange{});
}

}  // namespace pgmcl::config_schema
