// Localizer: pose estimate, best hypothesis and the convergence flag.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

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

}  // namespace

void Localizer::compute_estimate(UpdateResult& r) {
  const PoseEstimate all = estimate_pose(p_.x, p_.y, p_.theta, p_.w, threads_);
  r.mean = origin_.compose(all.mean);
  r.mean_covariance = to_global(all.covariance, origin_.theta);

  // Best hypothesis: the heaviest cluster (the overall mean of a multi-modal cloud can sit
  // between modes, on no particle).
  const std::vector<Cluster>& clusters = clusterer_.cluster(p_.x, p_.y, p_.theta, p_.w);
  const Cluster& best = clusters.front();
  r.estimate = origin_.compose(best.mean);
  r.covariance = to_global(best.covariance, origin_.theta);
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
  constexpr double kOneModeSpread = 4.0;
  one_mode_ = best.weight > ec.converged_weight && pos_std < kOneModeSpread * ec.converged_xy_std &&
              theta_std < kOneModeSpread * ec.converged_theta_std;
}

}  // namespace pgmcl
