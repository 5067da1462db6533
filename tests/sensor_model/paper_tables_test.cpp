// What does and does not follow from Dekan et al.'s Tables 1-4 and the final sigmas (Sec. 5).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "pgmcl/sensor_model/paper_constants.hpp"
#include "pgmcl/sensor_model/planar_gaussian_beam_model.hpp"

namespace pgmcl::sensor_model {
namespace {

using paper::kTable2;
using paper::kTable3Counts;
using paper::kTable4;

constexpr double kRound4 = 0.5e-4;  // half a unit of the 4th decimal, the paper's precision

// Standard normal quantile by bisection on erfc: slow but obviously right.
double normal_quantile(double p) {
  double lo = -40.0, hi = 40.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (0.5 * std::erfc(-mid / std::sqrt(2.0)) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(PaperTable1, DerivedScanGeometryIsConsistent) {
  const auto& s = paper::kUtm30lx;
  EXPECT_EQ(s.beams_per_scan,
            static_cast<int>(std::lround(s.scan_angle_deg / s.angular_step_deg)) + 1);
  EXPECT_DOUBLE_EQ(s.angular_step_deg, 360.0 / 1440.0);
  EXPECT_NEAR(s.scan_time, 60.0 / 2400.0, 1e-15);  // one scan per motor revolution
  EXPECT_NEAR(s.scan_angle(), 1.5 * std::numbers::pi, 1e-15);
  EXPECT_LT(s.guaranteed_range_max, s.max_range);
}

// Sec. 5: sigma_x = 5.6894 mm is "the average of standard deviations of all types of
// measurements", i.e. the mean of Table 2's twelve values, to the paper's 4 decimals.
TEST(PaperTable2, SigmaAlongIsTheMeanOfTheTwelveValues) {
  double sum = 0.0, sum_perp = 0.0, sum_45 = 0.0;
  for (const auto& row : kTable2) {
    sum_perp += row.sigma_perpendicular_mm;
    sum_45 += row.sigma_45deg_mm;
    EXPECT_GT(row.sigma_45deg_mm, row.sigma_perpendicular_mm) << row.name;  // 45 deg is worse
  }
  sum = sum_perp + sum_45;
  EXPECT_NEAR(sum / 12.0, paper::kSigmaAlongMm, kRound4);  // 5.689417
  // Column means, pinned for the incidence model: 4.9527 mm perpendicular, 6.4261 mm at 45.
  EXPECT_NEAR(sum_perp / 6.0, 4.9527, kRound4);
  EXPECT_NEAR(sum_45 / 6.0, 6.4261, kRound4);
}

// Eq. (5) with d = 0.25 deg maps Table 4's sigma column onto its y column. sigma is printed
// to 4 decimals, so the true sigma lies in [sigma - 0.00005, sigma + 0.00005] and the exact y
// in the image of that interval; the printed y must lie inside it. Where the printed y sits
// in its interval (0 = low end, 1 = high end): 50 cm 0.91 (tight: 0.06 um from the top),
// 150 cm 0.29, 250 cm 0.50, 530 cm 0.23. All four rows pass.
TEST(PaperTable4, YColumnFollowsFromSigmaThroughEq5) {
  const double d = paper::kUtm30lx.angular_step();
  for (const auto& row : kTable4) {
    const double dst_mm = row.distance * 1e3;
    const double lo = boundary_shift(row.sigma_beams - kRound4, d, dst_mm);
    const double hi = boundary_shift(row.sigma_beams + kRound4, d, dst_mm);
    EXPECT_GE(row.y_mm, lo) << row.distance;
    EXPECT_LE(row.y_mm, hi) << row.distance;
    // ...and y/(3 sin(d) dst) recovers the printed sigma to its 4 decimals.
    EXPECT_NEAR(row.y_mm / (3.0 * std::sin(d) * dst_mm), row.sigma_beams, kRound4);
  }
  // The 50 cm row is the tight one.
  const auto& r = kTable4[0];
  const double lo = boundary_shift(r.sigma_beams - kRound4, d, r.distance * 1e3);
  const double hi = boundary_shift(r.sigma_beams + kRound4, d, r.distance * 1e3);
  EXPECT_GT((r.y_mm - lo) / (hi - lo), 0.9);
}

// Sec. 5 gives sigma_y = 3 mm "derived from the shift of object boundaries" without a
// formula. Eq. (5) is a 3-sigma bound, so y/3 is the one-sigma lateral spread in mm:
// 1.3261, 2.7226, 3.1710, 2.9340 mm. Their mean is 2.5384 mm, not 3; the mean of the
// rows at >= 1.5 m is 2.9425 mm and 3 mm lies within their range [2.72, 3.17]; the 50 cm row
// (1.33 mm) is far below. So 3 mm is consistent with the longer distances, rounded, but the
// paper does not say how it was chosen.
TEST(PaperTable4, HowSigmaAcrossRelatesToTheYColumn) {
  const double expected_y3[4] = {1.3261, 2.7226, 3.1710, 2.9340};
  double all = 0.0, far = 0.0, far_min = 1e9, far_max = 0.0;
  for (int i = 0; i < 4; ++i) {
    const double y3 = kTable4[i].y_mm / 3.0;
    EXPECT_NEAR(y3, expected_y3[i], kRound4) << kTable4[i].distance;
    all += y3;
    if (i > 0) {
      far += y3;
      far_min = std::min(far_min, y3);
      far_max = std::max(far_max, y3);
    }
  }
  EXPECT_NEAR(all / 4.0, 2.5384, kRound4);
  EXPECT_GT(std::abs(all / 4.0 - paper::kSigmaAcrossMm), 0.4);  // not the plain mean
  EXPECT_NEAR(far / 3.0, 2.9425, kRound4);
  EXPECT_GT(paper::kSigmaAcrossMm, far_min);
  EXPECT_LT(paper::kSigmaAcrossMm, far_max);
  EXPECT_LT(kTable4[0].y_mm / 3.0, 0.5 * paper::kSigmaAcrossMm);
}

// Does Table 4's sigma follow from Table 3's counts? The paper fits "the Gaussian
// distribution" to the boundary-shift data (Fig. 10) but neither publishes the shift
// magnitudes nor says how sigma was obtained. From the counts alone, with p = mean shift
// fraction per distance:
//   p                                          = 0.3664, 0.2026, 0.1222, 0.0408
//   sqrt(p) (+/-1 step shifts, variance p)     = 0.6053, 0.4501, 0.3496, 0.2020
//   0.5 / z(1 - p/2) (jitter past half a step) = 0.5536, 0.3924, 0.3235, 0.2444
//   Table 4 sigma                              = 0.6078, 0.4160, 0.2907, 0.1269
// sqrt(p) fits the 50 cm row (-0.4 %) and nothing else (+8 %, +20 %, +59 %); the probit model
// is off by -9 % to +93 %; p itself by -40 % to -68 %. What the counts do support is the ordering:
// shifts become rarer with distance, as Table 4's sigma does. Table 4's sigma is therefore taken as
// published.
TEST(PaperTable3, CountsDoNotReproduceTable4Sigma) {
  const double expected_mean_count[4] = {183.2, 101.3, 61.1, 20.4};
  double p[4];
  for (int k = 0; k < 4; ++k) {
    double s = 0.0;
    for (int c : kTable3Counts[k]) {
      EXPECT_GE(c, 0);
      EXPECT_LE(c, paper::kTable3ReadingsPerRun);
      s += c;
    }
    EXPECT_NEAR(s / 10.0, expected_mean_count[k], 1e-12);
    p[k] = s / 10.0 / paper::kTable3ReadingsPerRun;
    if (k > 0) {
      EXPECT_LT(p[k], p[k - 1]);  // monotone, like Table 4's sigma
      EXPECT_LT(kTable4[k].sigma_beams, kTable4[k - 1].sigma_beams);
    }
  }
  auto worst_rel_error = [&](auto model) {
    double worst = 0.0;
    for (int k = 0; k < 4; ++k)
      worst = std::max(worst, std::abs(model(p[k]) / kTable4[k].sigma_beams - 1.0));
    return worst;
  };
  auto sqrt_model = [](double q) { return std::sqrt(q); };
  auto probit_model = [](double q) { return 0.5 / normal_quantile(1.0 - q / 2.0); };
  auto linear_model = [](double q) { return q; };
  EXPECT_NEAR(sqrt_model(p[0]), kTable4[0].sigma_beams, 0.005 * kTable4[0].sigma_beams);
  EXPECT_NEAR(worst_rel_error(sqrt_model), 0.59, 0.01);
  EXPECT_NEAR(worst_rel_error(probit_model), 0.93, 0.01);
  EXPECT_NEAR(worst_rel_error(linear_model), 0.68, 0.01);
}

}  // namespace
}  // namespace pgmcl::sensor_model
