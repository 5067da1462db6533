#pragma once
/// Resampling of the particle set.

#include <cassert>
#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <vector>

#include "pgmcl/common/random.hpp"

namespace pgmcl {

/// Systematic (low-variance) resampling, Probabilistic Robotics, Table 4.4: one uniform
/// offset u in [0, W / n_out), then n_out pointers u + k W / n_out walked through the
/// cumulative weights, W = sum of w. O(N + n_out), one random number per call.
///
/// Properties: unbiased (E[copies of i] = n_out w_i / W); particle i gets either
/// floor(n_out w_i / W) or ceil(n_out w_i / W) copies; zero-weight particles are never
/// drawn; `indices_out` is ascending. Weights need not be normalised.
/// `indices_out` is resized to n_out (no allocation when its capacity suffices).
/// Throws std::invalid_argument for a negative or non-finite weight, a non-positive sum
/// with n_out > 0, or more than 2^32 - 1 weights.
void systematic_resample(std::span<const double> w, std::size_t n_out, Rng& rng,
                         std::vector<std::uint32_t>& indices_out);

/// out[k] = in[idx[k]]: applies resampled indices to one structure-of-arrays field.
/// `in` and `out` must not overlap (gather into a second buffer, then swap).
/// Call with an explicit T when passing containers: gather<float>(x, idx, x_new).
/// Throws std::invalid_argument if out.size() != idx.size(); indices are checked by assert.
template <class T>
void gather(std::span<const T> in, std::span<const std::uint32_t> idx, std::span<T> out) {
  if (out.size() != idx.size()) {
    throw std::invalid_argument("gather: output size differs from the index count");
  }
  assert(out.empty() || in.empty() || out.data() + out.size() <= in.data() ||
         in.data() + in.size() <= out.data());
  for (std::size_t k = 0; k < idx.size(); ++k) {
    assert(idx[k] < in.size());
    out[k] = in[idx[k]];
  }
}

}  // namespace pgmcl
