#pragma once
// Small text surgery on CARMEN lines and output checks for the corpus cases.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "hostile_corpus.hpp"
#include "pgmcl/io/tum.hpp"

namespace pgmcl::hostile {

inline std::vector<std::string> words(const std::string& line) {
  std::istringstream in(line);
  return {std::istream_iterator<std::string>(in), {}};
}

inline std::string join_words(const std::vector<std::string>& w) {
  std::string s;
  for (const std::string& x : w) s += (s.empty() ? "" : " ") + x;
  return s;
}

inline std::string number(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

/// FLASER lines rewritten as ROBOTLASER1 with the given field of view and angular
/// resolution (the SICK layout of 180 beams is -pi/2 in steps of pi/180: fov 3.124139).
inline std::vector<std::string> as_robotlaser(const std::vector<std::string>& lines, double fov,
                                              double resolution = 0.017453292519943295) {
  std::vector<std::string> out;
  for (const std::string& l : lines) {
    if (l.rfind("FLASER", 0) != 0) {
      out.push_back(l);
      continue;
    }
    const std::vector<std::string> w = words(l);
    const std::size_t n = std::stoul(w[1]);
    std::vector<std::string> r = {
        "ROBOTLASER1", "0", "-1.5707963267948966", number(fov), number(resolution), "81.83", "0.01",
        "0",           w[1]};
    r.insert(r.end(), w.begin() + 2, w.begin() + 2 + static_cast<std::ptrdiff_t>(n));
    r.push_back("0");  // no remissions
    r.insert(r.end(), w.begin() + 2 + static_cast<std::ptrdiff_t>(n),
             w.begin() + 8 + static_cast<std::ptrdiff_t>(n));  // laser pose, robot pose
    for (int i = 0; i < 5; ++i) r.push_back("0");              // tv rv safety dists turn axis
    r.insert(r.end(), w.end() - 3, w.end());
    out.push_back(join_words(r));
  }
  return out;
}

/// The last pose of out/trajectory.tum lies within `tol` metres of the truth at the last
/// scan: an oracle for the cases whose input still holds the whole motion.
inline void expect_final_pose_near(const Env& e, double tol, bool whole_log = false) {
  const io::Trajectory t = io::read_tum(e.path("out/trajectory.tum"));
  ASSERT_FALSE(t.empty());
  const Pose2& p = t.back().pose;
  const Pose2& end = whole_log ? e.b.raw_end : e.b.end;
  EXPECT_LT(std::hypot(p.x - end.x, p.y - end.y), tol)
      << "ends at (" << p.x << ", " << p.y << "), truth (" << end.x << ", " << end.y << ")";
}

/// A map YAML's keys after `image:` (trinary, Intel-style thresholds unless given).
inline std::string map_keys(const std::string& origin, const std::string& resolution = "0.05",
                            const std::string& negate = "0",
                            const std::string& occupied_thresh = "0.65") {
  return "resolution: " + resolution + "\norigin: " + origin + "\nnegate: " + negate +
         "\noccupied_thresh: " + occupied_thresh + "\nfree_thresh: 0.196\n";
}

inline const std::string kIntelOrigin = "[-20.9, -26.7, 0]";

}  // namespace pgmcl::hostile
