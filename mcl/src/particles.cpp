#include "pgmcl/mcl/particles.hpp"

#include <algorithm>
#include <cmath>

namespace pgmcl {

void ParticleSet::set_uniform_weights() {
  const std::size_t n = size();
  if (n == 0) return;
  const double w_each = 1.0 / static_cast<double>(n);
  std::fill(w.begin(), w.end(), w_each);
  std::fill(log_w.begin(), log_w.end(), -std::log(static_cast<double>(n)));
}

}  // namespace pgmcl
