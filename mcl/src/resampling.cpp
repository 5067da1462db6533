#include "pgmcl/mcl/resampling.hpp"

#include <cmath>
#include <limits>
#include <string>

namespace pgmcl {

void systematic_resample(std::span<const double> w, std::size_t n_out, Rng& rng,
                         std::vector<std::uint32_t>& indices_out) {
  if (w.size() > std::numeric_limits<std::uint32_t>::max()) {
    throw std::invalid_argument("systematic_resample: more than 2^32 - 1 particles");
  }
  double total = 0.0;
  std::size_t last_positive = 0;
  for (std::size_t i = 0; i < w.size(); ++i) {
    if (!(w[i] >= 0.0) || !std::isfinite(w[i])) {
      throw std::invalid_argument("systematic_resample: weight " + std::to_string(i) + " is " +
                                  std::to_string(w[i]) + ", expected finite and >= 0");
    }
    if (w[i] > 0.0) last_positive = i;
    total += w[i];
  }
  indices_out.resize(n_out);
  if (n_out == 0) return;
  if (!(total > 0.0) || !std::isfinite(total)) {
    throw std::invalid_argument("systematic_resample: weights sum to " + std::to_string(total) +
                                ", expected a positive finite sum");
  }

  const double step = total / static_cast<double>(n_out);
  const double u0 = rng.uniform() * step;
  std::size_t i = 0;
  double cumulative = w[0];
  for (std::size_t k = 0; k < n_out; ++k) {
    // Pointer from k directly (not accumulated) so rounding does not drift over n_out.
    const double u = u0 + static_cast<double>(k) * step;
    // Stopping at the last positive weight absorbs round-off in the cumulative sum, and
    // `u >= cumulative` skips zero-weight particles (their interval is empty).
    while (u >= cumulative && i < last_positive) cumulative += w[++i];
    indices_out[k] = static_cast<std::uint32_t>(i);
  }
}

}  // namespace pgmcl
