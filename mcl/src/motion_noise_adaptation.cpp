#include "motion_noise_adaptation.hpp"

#include <algorithm>
#include <cmath>

namespace pgmcl::detail {
namespace {

// Median of a chi-square variable with one degree of freedom: the median of the squared
// residuals over their predicted variance when the model is right.
constexpr double kChiSquare1Median = 0.454936423119572;
// Along-track residuals need a translation to have a direction.
constexpr double kMinTranslation = 0.05;  // metres

// Table 5.6's variances: of the heading change (rot1 and rot2 each draw a1 rot^2 + a2
// trans^2) and of the translation (a3 trans^2 + a4 (rot1^2 + rot2^2)).
double heading_variance(const MotionNoise& a, const OdometryIncrement& inc) noexcept {
  return a.a1 * (inc.rot1 * inc.rot1 + inc.rot2 * inc.rot2) + 2.0 * a.a2 * inc.trans * inc.trans;
}
double translation_variance(const MotionNoise& a, const OdometryIncrement& inc) noexcept {
  return a.a3 * (inc.trans * inc.trans) + a.a4 * (inc.rot1 * inc.rot1 + inc.rot2 * inc.rot2);
}

}  // namespace

MotionNoise spanning_readings(MotionModelKind kind, const MotionNoise& noise,
                              const OdometryIncrement& inc, double moment) noexcept {
  const double own = rotation_moment(kind, inc);
  const double extra = moment - own;
  MotionNoise n = noise;
  if (!(extra > 0.0)) return n;
  const double t2 = inc.trans * inc.trans;
  if (t2 > 0.0) {
    // Carried by the translation terms, which every draw of this increment scales by t2:
    // rot1 and rot2 (Table 5.6) each draw a2 t2, the omnidirectional rotation once.
    const double draws = kind == MotionModelKind::kOmnidirectional ? 1.0 : 2.0;
    n.a2 += noise.a1 * extra / (draws * t2);
    n.a3 += noise.a4 * extra / t2;
    n.a5 += noise.a4 * extra / t2;
  } else if (own > 0.0) {  // a turn in place
    n.a1 *= moment / own;
    n.a4 *= moment / own;
  }
  return n;
}

MotionNoiseAdaptation::MotionNoiseAdaptation(const MotionConfig& motion) : cfg_(motion) {
  const std::size_t w = cfg_.adaptation.window;
  rotation_.ratios.assign(w, 0.0);
  translation_.ratios.assign(w, 0.0);
  scratch_.reserve(w);
}

void MotionNoiseAdaptation::Window::push(double v) noexcept {
  if (ratios.empty()) return;
  ratios[next] = v;
  next = (next + 1) % ratios.size();
  count = std::min(count + 1, ratios.size());
}

double MotionNoiseAdaptation::Window::factor(std::vector<double>& scratch, double margin,
                                             double max_factor) const {
  // A third of the window before the first estimate; a median, so the glitches the
  // competing hypotheses absorb do not count as noise.
  if (count == 0 || 3 * count < ratios.size()) return 1.0;
  scratch.assign(ratios.begin(), ratios.begin() + static_cast<std::ptrdiff_t>(count));
  const auto upper = scratch.begin() + static_cast<std::ptrdiff_t>(count / 2);
  std::nth_element(scratch.begin(), upper, scratch.end());
  double median = *upper;
  if (count % 2 == 0) median = 0.5 * (median + *std::max_element(scratch.begin(), upper));
  return std::clamp(margin * median / kChiSquare1Median, 1.0, max_factor);
}

void MotionNoiseAdaptation::observe(const Pose2& odom_delta, double moment, const Pose2& est_prev,
                                    const Eigen::Matrix3d& cov_prev, const Pose2& est_now,
                                    const Eigen::Matrix3d& cov_now) {
  if (!cfg_.adaptation.enabled) return;
  const OdometryIncrement inc = decompose_odometry(Pose2{}, odom_delta);
  const MotionNoise a = spanning_readings(cfg_.kind, cfg_.noise, inc, moment);
  const Pose2 moved = est_prev.between(est_now);   // what the filter found, robot frame
  const Eigen::Matrix3d cov = cov_prev + cov_now;  // the two estimates' own uncertainty

  const double var_rot = heading_variance(a, inc) + cov(2, 2);
  const double e_rot = wrap_angle(moved.theta - odom_delta.theta);
  if (var_rot > 0.0 && std::isfinite(e_rot)) rotation_.push(e_rot * e_rot / var_rot);

  if (inc.trans >= kMinTranslation) {
    const double ux = odom_delta.x / inc.trans, uy = odom_delta.y / inc.trans;
    const double c = std::cos(est_prev.theta), s = std::sin(est_prev.theta);
    const Eigen::Vector2d u_global(c * ux - s * uy, s * ux + c * uy);
    const double var_along =
        translation_variance(a, inc) + u_global.dot(cov.topLeftCorner<2, 2>() * u_global);
    const double e_along = (moved.x - odom_delta.x) * ux + (moved.y - odom_delta.y) * uy;
    if (var_along > 0.0 && std::isfinite(e_along)) translation_.push(e_along * e_along / var_along);
  }
  const MotionAdaptationConfig& ac = cfg_.adaptation;
  rotation_factor_ = rotation_.factor(scratch_, ac.margin, ac.max_inflation);
  translation_factor_ = translation_.factor(scratch_, ac.margin, ac.max_inflation);
}

double MotionNoiseAdaptation::heading_sigma(const Pose2& odom_delta, double moment) const noexcept {
  const OdometryIncrement inc = decompose_odometry(Pose2{}, odom_delta);
  return std::sqrt(heading_variance(spanning_readings(cfg_.kind, noise(), inc, moment), inc));
}

MotionNoise MotionNoiseAdaptation::noise() const noexcept {
  MotionNoise n = cfg_.noise;
  n.a1 *= rotation_factor_;
  n.a2 *= rotation_factor_;
  n.a3 *= translation_factor_;
  n.a4 *= translation_factor_;
  n.a5 *= translation_factor_;
  return n;
}

}  // namespace pgmcl::detail
