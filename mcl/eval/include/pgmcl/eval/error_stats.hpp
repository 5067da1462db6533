#pragma once
/// Mean / standard deviation / maximum of a list of errors, as the evaluators report them.

#include <cstddef>
#include <span>

namespace pgmcl::io {

struct ErrorStats {
  std::size_t count = 0;
  double mean = 0.0;
  double stddev = 0.0;  ///< sample standard deviation (divides by count - 1); 0 if count < 2
  double rms = 0.0;     ///< sqrt(mean of squares)
  double max = 0.0;
};

/// Two-pass (numerically stable) statistics of `values`; all zero for an empty list.
[[nodiscard]] ErrorStats error_stats(std::span<const double> values) noexcept;

}  // namespace pgmcl::io
