#include "pgmcl/sims/calibration.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string>

#include "pgmcl/sensor_model/planar_gaussian_beam_model.hpp"

namespace pgmcl::sims {

namespace {

// Beams this many sigmas below the edge are certain hits (Phi(-10) ~ 1e-23).
constexpr double kSureSigmas = 10.0;
constexpr double kSigmaLo = 1e-4;  // beam steps: search bounds of the estimators
constexpr double kSigmaHi = 50.0;

double hit_probability(double gap, double sigma) noexcept {
  if (sigma <= 0.0) return gap > 0.0 ? 1.0 : (gap == 0.0 ? 0.5 : 0.0);
  return 0.5 * std::erfc(-gap / (sigma * std::numbers::sqrt2));
}

}  // namespace

RangeSigmaEstimate estimate_range_sigma(const std::vector<std::vector<double>>& experiments) {
  RangeSigmaEstimate est;
  double sum_sq = 0.0, sum_all = 0.0;
  for (std::size_t e = 0; e < experiments.size(); ++e) {
    const auto& xs = experiments[e];
    double sum = 0.0;
    for (std::size_t i = 0; i < xs.size(); ++i) {
      if (!std::isfinite(xs[i])) {
        throw std::invalid_argument("estimate_range_sigma: experiment " + std::to_string(e) +
                                    ", reading " + std::to_string(i) + " is not finite");
      }
      sum += xs[i];
    }
    est.readings += xs.size();
    sum_all += sum;
    if (xs.size() < 2) continue;
    const double mean = sum / static_cast<double>(xs.size());
    for (const double x : xs) sum_sq += (x - mean) * (x - mean);
    ++est.experiments;
    est.dof += xs.size() - 1;
  }
  if (est.dof < 1) {
    throw std::invalid_argument(
        "estimate_range_sigma: need an experiment with at least 2 readings");
  }
  est.sigma = std::sqrt(sum_sq / static_cast<double>(est.dof));
  est.standard_error = est.sigma / std::sqrt(2.0 * static_cast<double>(est.dof));
  est.mean = sum_all / static_cast<double>(est.readings);
  return est;
}

std::vector<double> beam_readings(const std::vector<std::vector<float>>& scans, std::size_t beam,
                                  double range_min, double range_max) {
  std::vector<double> out;
  out.reserve(scans.size());
  for (std::size_t s = 0; s < scans.size(); ++s) {
    if (beam >= scans[s].size()) {
      throw std::invalid_argument("beam_readings: scan " + std::to_string(s) + " has " +
                                  std::to_string(scans[s].size()) + " beams, beam " +
                                  std::to_string(beam) + " requested");
    }
    const double r = scans[s][beam];
    if (r >= range_min && r < range_max) out.push_back(r);  // NaN fails both
  }
  return out;
}

long boundary_beam(std::span<const float> ranges, std::size_t first_beam, float split_range) {
  if (first_beam >= ranges.size()) {
    throw std::invalid_argument("boundary_beam: first_beam " + std::to_string(first_beam) +
                                " outside a scan of " + std::to_string(ranges.size()) + " beams");
  }
  std::size_t j = first_beam;
  while (j < ranges.size() && ranges[j] < split_range) ++j;  // NaN stops the walk
  return static_cast<long>(j) - 1;
}

std::size_t count_boundary_changes(std::span<const long> boundaries) {
  std::size_t n = 0;
  for (std::size_t i = 1; i < boundaries.size(); ++i) n += boundaries[i] != boundaries[i - 1];
  return n;
}

std::vector<double> boundary_distribution(double edge, double sigma_beams, int count) {
  std::vector<double> p(static_cast<std::size_t>(std::max(count, 0)) + 1, 0.0);
  double all_hit = 1.0;  // P(beams 0..b all hit)
  for (int b = -1; b < count; ++b) {
    const double h_next = b + 1 < count ? hit_probability(edge - (b + 1), sigma_beams) : 0.0;
    p[static_cast<std::size_t>(b + 1)] = all_hit * (1.0 - h_next);
    all_hit *= h_next;
  }
  return p;
}

double boundary_change_probability(double edge, double sigma_beams) {
  // Only the fraction matters; put enough sure hits in front of the edge.
  const double frac = edge - std::floor(edge);
  const int lead = static_cast<int>(std::ceil(kSureSigmas * sigma_beams)) + 2;
  const auto p = boundary_distribution(lead + frac, sigma_beams, 2 * lead + 2);
  double same = 0.0;
  for (const double x : p) same += x * x;
  return std::clamp(1.0 - same, 0.0, 1.0);
}

double sigma_beams_from_changes(std::size_t changes, std::size_t pairs, double edge_fraction) {
  if (pairs == 0 || changes > pairs) {
    throw std::invalid_argument("sigma_beams_from_changes: need 0 <= changes <= pairs, pairs > 0");
  }
  if (!(edge_fraction >= 0.0 && edge_fraction < 1.0)) {
    throw std::invalid_argument("sigma_beams_from_changes: edge_fraction must lie in [0, 1)");
  }
  const double rate = static_cast<double>(changes) / static_cast<double>(pairs);
  // The change probability grows with sigma; bisect on log(sigma).
  double lo = std::log(kSigmaLo), hi = std::log(kSigmaHi);
  if (boundary_change_probability(edge_fraction, kSigmaLo) >= rate) return kSigmaLo;
  if (boundary_change_probability(edge_fraction, kSigmaHi) <= rate) return kSigmaHi;
  for (int i = 0; i < 100 && hi - lo > 1e-10; ++i) {
    const double mid = 0.5 * (lo + hi);
    (boundary_change_probability(edge_fraction, std::exp(mid)) < rate ? lo : hi) = mid;
  }
  return std::exp(0.5 * (lo + hi));
}

double sigma_beams_mle(std::span<const long> boundaries, double edge) {
  if (boundaries.empty()) throw std::invalid_argument("sigma_beams_mle: no boundaries");
  if (!std::isfinite(edge)) throw std::invalid_argument("sigma_beams_mle: edge must be finite");
  std::map<long, std::size_t> hist;
  for (const long b : boundaries) ++hist[b];
  const long b_min = hist.begin()->first, b_max = hist.rbegin()->first;
  auto log_likelihood = [&](double log_sigma) {
    const double sigma = std::exp(log_sigma);
    const double reach = kSureSigmas * sigma + 2.0;
    const long base = static_cast<long>(std::floor(std::min<double>(b_min, edge - reach))) - 1;
    const long top = static_cast<long>(std::ceil(std::max<double>(b_max, edge + reach))) + 1;
    const auto p = boundary_distribution(edge - static_cast<double>(base), sigma,
                                         static_cast<int>(top - base + 1));
    double ll = 0.0;
    for (const auto& [b, n] : hist) {
      const double pb = p[static_cast<std::size_t>(b - base + 1)];
      ll += static_cast<double>(n) * std::log(std::max(pb, 1e-300));
    }
    return ll;
  };
  // Coarse log-spaced scan, then golden-section search around the best point.
  constexpr int kGrid = 120;
  const double lo = std::log(kSigmaLo), hi = std::log(kSigmaHi), step = (hi - lo) / kGrid;
  int best = 0;
  double best_ll = -std::numeric_limits<double>::infinity();
  for (int i = 0; i <= kGrid; ++i) {
    const double ll = log_likelihood(lo + i * step);
    if (ll > best_ll) {
      best_ll = ll;
      best = i;
    }
  }
  double a = lo + std::max(best - 1, 0) * step, b = lo + std::min(best + 1, kGrid) * step;
  const double g = (std::sqrt(5.0) - 1.0) / 2.0;
  double c = b - g * (b - a), d = a + g * (b - a);
  double fc = log_likelihood(c), fd = log_likelihood(d);
  for (int i = 0; i < 80 && b - a > 1e-9; ++i) {
    if (fc > fd) {
      b = d;
      d = c;
      fd = fc;
      c = b - g * (b - a);
      fc = log_likelihood(c);
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + g * (b - a);
      fd = log_likelihood(d);
    }
  }
  return std::exp(0.5 * (a + b));
}

AcrossBeamEstimate across_beam_estimate(double sigma_beams, double angular_step, double distance) {
  AcrossBeamEstimate e;
  e.sigma_beams = sigma_beams;
  e.y = sensor_model::boundary_shift(sigma_beams, angular_step, distance);  // Eq. (5)
  e.sigma_y = e.y / 3.0;
  return e;
}

}  // namespace pgmcl::sims
