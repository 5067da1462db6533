#pragma once
/// KLD-sampling (Fox 2003, "Adapting the sample size in particle filters through
/// KLD-sampling", IJRR 22(12)): the number of particles needed so that, with probability
/// 1 - delta, the KL divergence between the sample-based and the true posterior stays below
/// epsilon, given the number k of histogram bins the particles occupy.

#include <cstddef>
#include <cstdint>
#include <numbers>
#include <vector>

namespace pgmcl {

/// Quantile function (inverse CDF) of the standard normal: Acklam's rational approximation
/// (relative error 1.15e-9) refined by one Halley step on erfc, giving ~1e-15.
/// normal_quantile(1 - delta) is Fox's z_{1-delta} (2.326348 for delta = 0.01).
/// p = 0 gives -inf, p = 1 gives +inf; throws std::invalid_argument outside [0, 1] or NaN.
[[nodiscard]] double normal_quantile(double p);

/// Fox 2003, Eq. (13), the Wilson-Hilferty approximation of the chi-square quantile:
///   n = (k - 1) / (2 epsilon) * (1 - 2 / (9 (k - 1)) + sqrt(2 / (9 (k - 1))) z)^3
/// rounded up, with z = normal_quantile(1 - delta). k <= 1 (or a negative bracket, which
/// needs delta > 0.5) gives 0: the bound is void there and the caller's minimum applies.
/// Min/max clamping of the particle count is the caller's. Throws std::invalid_argument
/// unless epsilon > 0 and z are finite.
[[nodiscard]] std::size_t kld_required_particles(std::size_t k_bins, double epsilon,
                                                 double z_quantile);

/// Counts the occupied (x, y, theta) histogram bins of KLD-sampling. An open-addressing
/// hash set of packed bin keys: insert() never allocates while the set holds fewer than
/// `reserve()`d bins, and clear() is O(1) (generation stamps), so the per-draw loop of
/// KLD-sampling runs allocation-free after the first resampling.
/// Heading bins split the circle into round(2 pi / bin_theta) equal sectors (at least 1),
/// so the seam at +/-pi is a bin edge and pi and -pi share a bin. x and y bin indices are
/// clamped to +/-2^23 (e.g. +/-1678 km at 0.2 m bins).
class KldBinner {
 public:
  /// Defaults: 0.2 m x 0.2 m x 10 degrees, room for 4096 bins before growing.
  KldBinner() : KldBinner(0.2, 0.2, 10.0 * std::numbers::pi / 180.0) {}
  /// Throws std::invalid_argument unless the bin sizes are finite and > 0 and the heading
  /// bins number at most 65535.
  KldBinner(double bin_x, double bin_y, double bin_theta);

  /// Makes room for `max_bins` occupied bins (e.g. the maximum particle count).
  void reserve(std::size_t max_bins);
  /// Forgets all bins; keeps the capacity.
  void clear() noexcept;
  /// Adds a particle's bin; returns true if the bin was not occupied yet.
  bool insert(double x, double y, double theta);
  [[nodiscard]] std::size_t occupied() const noexcept { return occupied_; }

  [[nodiscard]] double bin_x() const noexcept { return bin_x_; }
  [[nodiscard]] double bin_y() const noexcept { return bin_y_; }
  [[nodiscard]] std::size_t theta_bins() const noexcept { return theta_bins_; }

 private:
  [[nodiscard]] std::uint64_t key_of(double x, double y, double theta) const noexcept;
  bool insert_key(std::uint64_t key) noexcept;  // capacity must allow it
  void rehash(std::size_t slots);

  double bin_x_, bin_y_, bin_theta_;
  double inv_x_, inv_y_, inv_theta_;
  std::size_t theta_bins_;
  std::vector<std::uint64_t> keys_;
  std::vector<std::uint32_t> stamps_;  // slot is live iff stamps_[i] == generation_
  std::uint32_t generation_ = 1;
  std::size_t occupied_ = 0;
};

}  // namespace pgmcl
