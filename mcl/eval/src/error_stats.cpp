#include "pgmcl/eval/error_stats.hpp"

#include <algorithm>
#include <cmath>

namespace pgmcl::io {

ErrorStats error_stats(std::span<const double> values) noexcept {
  ErrorStats s;
  s.count = values.size();
  if (values.empty()) return s;
  double sum = 0.0, sum_sq = 0.0;
  for (const double v : values) {
    sum += v;
    sum_sq += v * v;
    s.max = std::max(s.max, v);
  }
  const double n = static_cast<double>(values.size());
  s.mean = sum / n;
  s.rms = std::sqrt(sum_sq / n);
  if (values.size() > 1) {
    double dev = 0.0;
    for (const double v : values) dev += (v - s.mean) * (v - s.mean);
    s.stddev = std::sqrt(dev / (n - 1.0));
  }
  return s;
}

}  // namespace pgmcl::io
