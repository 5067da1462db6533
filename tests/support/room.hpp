#pragma once
// The rectangular room the mapping and command-line suites scan: walls off the 5 cm cell
// lattice, so no wall coincides with a cell edge, and the exact range to them.

#include <algorithm>
#include <cmath>

namespace pgmcl::testkit {

/// A rectangular room [x0, x1] x [y0, y1].
struct Room {
  double x0 = 0.512, y0 = 0.371, x1 = 6.233, y1 = 4.907;

  /// Exact range from inside the room along heading a.
  [[nodiscard]] double range(double x, double y, double a) const {
    const double dx = std::cos(a), dy = std::sin(a);
    double t = 1e9;
    if (dx > 1e-12) t = std::min(t, (x1 - x) / dx);
    if (dx < -1e-12) t = std::min(t, (x0 - x) / dx);
    if (dy > 1e-12) t = std::min(t, (y1 - y) / dy);
    if (dy < -1e-12) t = std::min(t, (y0 - y) / dy);
    return t;
  }
};

}  // namespace pgmcl::testkit
