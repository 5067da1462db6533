#include "pgmcl/sims/beam_noise.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace pgmcl::sims {

namespace {

void check_rate(double rate, const char* field) {
  if (!(rate >= 0.0 && rate <= 1.0)) {
    throw std::invalid_argument(std::string("BeamNoise.") + field + " must lie in [0, 1] (got " +
                                std::to_string(rate) + ")");
  }
}

void check_non_negative(double v, const char* field) {
  if (!(v >= 0.0) || !std::isfinite(v)) {
    throw std::invalid_argument(std::string("BeamNoise.") + field +
                                " must be finite and >= 0 (got " + std::to_string(v) + ")");
  }
}

}  // namespace

BeamNoise BeamNoise::none() noexcept {
  BeamNoise n;
  n.along_beam = false;
  n.across_beam = false;
  return n;
}

void BeamNoise::validate() const {
  check_non_negative(range_growth, "range_growth");
  check_non_negative(sigma_y, "sigma_y");
  check_non_negative(quantum, "quantum");
  check_rate(dropouts.rate, "dropouts.rate");
  check_rate(short_returns.rate, "short_returns.rate");
  check_rate(specular.rate, "specular.rate");
  if (!(short_returns.lambda > 0.0) || !std::isfinite(short_returns.lambda)) {
    throw std::invalid_argument("BeamNoise.short_returns.lambda must be > 0 (1/m)");
  }
  if (!(specular.min_incidence >= 0.0 && specular.min_incidence <= std::numbers::pi / 2)) {
    throw std::invalid_argument("BeamNoise.specular.min_incidence must lie in [0, pi/2] rad");
  }
}

float incidence_angle(float dx, float dy, float nx, float ny) noexcept {
  const float c = std::clamp(-(dx * nx + dy * ny), 0.0F, 1.0F);
  return std::acos(c);
}

float render_beam(const Scene& scene, float x, float y, float dx, float dy,
                  const RangeLimits& limits, const BeamNoise& noise, Rng& rng) noexcept {
  if (noise.dropouts.enabled && rng.uniform() < noise.dropouts.rate) return limits.range_max;
  // Lateral footprint shift along the left normal (-dy, dx); the parallel ray through the
  // shifted footprint finds what the displaced beam would have hit.
  const double shift = noise.across_beam ? rng.normal(noise.sigma_y) : 0.0;
  const auto s = static_cast<float>(shift);
  const SceneHit hit = scene.cast(x - s * dy, y + s * dx, dx, dy, limits.range_max);
  if (!hit.hit) return limits.range_max;

  const SurfaceMaterial& mat = scene.surfaces().material(hit.material);
  const float incidence = incidence_angle(dx, dy, hit.nx, hit.ny);
  if (noise.specular.enabled && mat.specular &&
      static_cast<double>(incidence) >= noise.specular.min_incidence &&
      rng.uniform() < noise.specular.rate) {
    return limits.range_max;
  }
  // Range of the shifted point as seen from the sensor.
  double r = std::hypot(static_cast<double>(hit.range), shift);
  if (noise.along_beam) {
    const double sigma =
        std::hypot(mat.sigma.sigma(static_cast<double>(incidence)), noise.range_growth * r);
    r += rng.normal(sigma);
  }
  if (noise.short_returns.enabled && rng.uniform() < noise.short_returns.rate) {
    // Inverse CDF of the exponential truncated to [0, r].
    const double lambda = noise.short_returns.lambda;
    const double mass = -std::expm1(-lambda * std::max(r, 0.0));
    r = -std::log1p(-rng.uniform() * mass) / lambda;
  }
  if (noise.quantum > 0.0) r = std::round(r / noise.quantum) * noise.quantum;
  if (r >= static_cast<double>(limits.range_max)) return limits.range_max;
  return static_cast<float>(std::max(r, 0.0));
}

}  // namespace pgmcl::sims
