// Localizer: pose estimate, best hypothesis and the convergence flag.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

#include "pgmcl/mcl/localizer.hpp"
#include "pgmcl/mcl/pose_estimate.hpp"

namespace pgmcl {
namespace {

// Covariance of (x, y, theta) from the grid frame to the global frame: the position block
// rotates with the origin's yaw, the heading is unchanged. J C J^T keeps it symmetric PSD.
Eigen::Matrix3d to_global(const Eigen::Matrix3d& local, double origin_theta) {
  const double c = std::cos(origin_theta), s = std::sin(origin_theta);
  Eigen::Matrix3d j = Eigen::Matrix3d::Identity();
  j.topLeftCorner<2, 2>() << c, -s, s, c;
  Eigen::Matrix3d g = j * local * j.transpose();
  return 0.5 * (g + g.transpose());  // exact symmetry after the rotation's round-off
}

// A mode's extent, in multiples of the converged spread (EstimateConfig): what sparse
// scans leave of a settled cluster.
constexpr double kOneModeSpread = 4.0;

}  // namespace

Pose2 Localizer::within_best_cluster(const Pose2& tempered_mean, double withheld_tau) {
  // The tempering limit keeps other places alive for later scans; it is no reason to doubt
  // this scan inside the chosen place. So the place is chosen by the set's weights and the
  // pose near it is weighed by the scan's whole exponent, as tracking would. "Near": within
  // a mode's extent (a cloud spread over a room is one cluster too). Particles on probation
  // keep the capped weight they have (limit_probation_weight()).
  if (!(withheld_tau > 0.0)) return tempered_mean;
  const EstimateConfig& ec = cfg_.estimate;
  const auto reach_xy = static_cast<float>(kOneModeSpread * ec.converged_xy_std);
  const auto reach_theta = static_cast<float>(kOneModeSpread * ec.converged_theta_std);
  const auto mx = static_cast<float>(tempered_mean.x), my = static_cast<float>(tempered_mean.y);
  const auto mt = static_cast<float>(tempered_mean.theta);
  const std::span<const std::uint32_t> label = clusterer_.labels();
  const auto near = [&](std::size_t i) {
    return label[i] == 0 && std::abs(p_.x[i] - mx) <= reach_xy &&
           std::abs(p_.y[i] - my) <= reach_xy &&
           std::abs(wrap_angle(p_.theta[i] - mt)) <= reach_theta;
  };
  const auto sharp = [&](std::size_t i) {
    return p_.log_w[i] + (probation_[i] == 0 ? withheld_tau * ws_.scan_ll[i] : 0.0);
  };
  double top = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < p_.size(); ++i)
    if (near(i)) top = std::max(top, sharp(i));
  if (!std::isfinite(top)) return tempered_mean;
  ws_.estimate_w.assign(p_.size(), 0.0);
  for (std::size_t i = 0; i < p_.size(); ++i)
    if (near(i)) ws_.estimate_w[i] = std::exp(sharp(i) - top);
  return estimate_pose(p_.x, p_.y, p_.theta, ws_.estimate_w, threads_).mean;
}

void Localizer::compute_estimate(UpdateResult& r, double withheld_tau) {
  const PoseEstimate all = estimate_pose(p_.x, p_.y, p_.theta, p_.w, threads_);
  r.mean = origin_.compose(all.mean);
  r.mean_covariance = to_global(all.covariance, origin_.theta);

  // Best hypothesis: the heaviest cluster (the overall mean of a multi-modal cloud can sit
  // between modes, on no particle).
  const std::vector<Cluster>& clusters = clusterer_.cluster(p_.x, p_.y, p_.theta, p_.w);
  const Cluster& best = clusters.front();
  const Pose2 local = within_best_cluster(best.mean, withheld_tau);
  r.estimate = origin_.compose(local);
  // The cluster's spread about the reported pose: its covariance plus the shift's outer product.
  const Eigen::Vector3d shift(local.x - best.mean.x, local.y - best.mean.y,
                              wrap_angle(local.theta - best.mean.theta));
  r.covariance = to_global(best.covariance + shift * shift.transpose(), origin_.theta);
  r.cluster_weight = best.weight;
  r.clusters = clusters.size();

  // Converged: one dominant, compact hypothesis (EstimateConfig).
  const Eigen::Matrix2d pos = best.covariance.topLeftCorner<2, 2>();
  const double pos_std = std::sqrt(
      std::max(0.0, Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(pos).eigenvalues().maxCoeff()));
  const double theta_std = std::sqrt(std::max(0.0, best.covariance(2, 2)));
  const EstimateConfig& ec = cfg_.estimate;
  r.converged = best.weight > ec.converged_weight && pos_std < ec.converged_xy_std &&
                theta_std < ec.converged_theta_std;
  // One mode, not yet compact: what sparse scans leave of a settled cluster. A cloud that
  // still spans the map can be one big cluster too, hence the (wider) spread bound.
  one_mode_ = best.weight > ec.converged_weight && pos_std < kOneModeSpread * ec.converged_xy_std &&
              theta_std < kOneModeSpread * ec.converged_theta_std;
}

}  // namespace pgmcl
