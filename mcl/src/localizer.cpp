// Localizer: construction and (re-)initialisation of the particle set.
#include "pgmcl/mcl/localizer.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

#include "hypothesis_tracker.hpp"
#include "motion_noise_adaptation.hpp"
#include "stream_keys.hpp"

namespace pgmcl {
namespace {

std::shared_ptr<const maps::LikelihoodField> build_field(const maps::OccupancyGrid& grid,
                                                         const LocalizerConfig& cfg) {
  cfg.validate();  // before the (possibly expensive) table build
  return std::make_shared<const maps::LikelihoodField>(grid, cfg.likelihood.beam,
                                                       cfg.likelihood.table);
}

bool finite(const Pose2& p) noexcept {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta);
}

}  // namespace

std::vector<std::uint32_t> free_cell_indices(const maps::OccupancyGrid& grid) {
  if (grid.size() > std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("free_cell_indices: grid has more than 2^32 cells");
  std::vector<std::uint32_t> out;
  for (int row = 0; row < grid.height(); ++row)
    for (int col = 0; col < grid.width(); ++col)
      if (grid.free(col, row)) out.push_back(static_cast<std::uint32_t>(grid.index(col, row)));
  return out;
}

Localizer::Localizer(const maps::OccupancyGrid& grid, const LocalizerConfig& cfg)
    // Braces sequence the arguments: the table size check throws before free cells are listed.
    : Localizer{build_field(grid, cfg), free_cell_indices(grid), cfg} {}

Localizer::Localizer(std::shared_ptr<const maps::LikelihoodField> field,
                     std::vector<std::uint32_t> free_cells, const LocalizerConfig& cfg)
    : cfg_(cfg), field_(std::move(field)), model_(field_), free_cells_(std::move(free_cells)) {
  cfg_.validate();
  thread_policy_ = ThreadPolicy(cfg_.adaptive_threads ? cfg_.threads : 1, &cores_taken);
  threads_ = cfg_.threads;
  init_geometry();
  motion_noise_ = std::make_unique<detail::MotionNoiseAdaptation>(cfg_.motion);
  if (cfg_.hypotheses.enabled)
    hypotheses_ = std::make_unique<detail::HypothesisTracker>(field_, free_cells_, cfg_.hypotheses,
                                                              cfg_.likelihood);
  global_localize();
}

Localizer::~Localizer() = default;
Localizer::Localizer(Localizer&&) noexcept = default;
Localizer& Localizer::operator=(Localizer&&) noexcept = default;

void Localizer::init_geometry() {
  origin_ = field_->origin();
  resolution_ = field_->resolution();
  width_ = field_->width();
  if (free_cells_.empty())
    throw std::invalid_argument("Localizer: the map has no free cells to put particles in");
  const auto cells =
      static_cast<std::uint64_t>(field_->width()) * static_cast<std::uint64_t>(field_->height());
  for (std::uint32_t c : free_cells_)
    if (c >= cells)
      throw std::invalid_argument("Localizer: free cell index " + std::to_string(c) +
                                  " is outside the " + std::to_string(field_->width()) + " x " +
                                  std::to_string(field_->height()) + " grid");
  clusterer_ =
      ParticleClusterer(ClusterConfig{cfg_.estimate.cluster_xy, cfg_.estimate.cluster_theta});
  const KldConfig& kc = cfg_.filter.kld;
  if (kc.enabled) {
    binner_ = KldBinner(kc.bin_xy, kc.bin_xy, kc.bin_theta);
    binner_.reserve(kc.max_particles);
    kld_z_ = normal_quantile(1.0 - kc.delta);
  }
  // Injected poses are collected during resampling's draws: room for all of them up front.
  const std::size_t max_out = kc.enabled ? kc.max_particles : cfg_.filter.particles;
  ws_.injected_x.reserve(max_out);
  ws_.injected_y.reserve(max_out);
  ws_.injected_theta.reserve(max_out);
}

Pose2 Localizer::random_free_pose(Rng& rng) const noexcept {
  const std::uint32_t cell = free_cells_[rng.below(free_cells_.size())];
  const auto w = static_cast<std::uint32_t>(width_);
  const double col = static_cast<double>(cell % w) + rng.uniform();
  const double row = static_cast<double>(cell / w) + rng.uniform();
  const double theta = wrap_angle(rng.uniform(-std::numbers::pi, std::numbers::pi));
  return {col * resolution_, row * resolution_, theta};
}

void Localizer::global_localize() {
  const std::size_t n = cfg_.filter.global_particles;
  p_.resize(n);
  Rng rng = Rng::for_block(cfg_.seed, next_step(), detail::kStreamInit);
  for (std::size_t i = 0; i < n; ++i) {
    const Pose2 q = random_free_pose(rng);
    p_.x[i] = static_cast<float>(q.x);
    p_.y[i] = static_cast<float>(q.y);
    p_.theta[i] = wrap_angle(static_cast<float>(q.theta));
  }
  if (hypotheses_) hypotheses_->reset(true);
  reset_after_init();
}

void Localizer::set_pose(const Pose2& mean, const Eigen::Matrix3d& cov) {
  if (!finite(mean)) throw std::invalid_argument("Localizer::set_pose: mean is not finite");
  if (!cov.allFinite())
    throw std::invalid_argument("Localizer::set_pose: covariance is not finite");
  const double scale = std::max(1.0, cov.cwiseAbs().maxCoeff());
  if ((cov - cov.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale)
    throw std::invalid_argument("Localizer::set_pose: covariance is not symmetric");
  // Rotate the covariance into the map-local frame: J = diag(R(-origin.theta), 1).
  const double c = std::cos(origin_.theta), s = std::sin(origin_.theta);
  Eigen::Matrix3d j = Eigen::Matrix3d::Identity();
  j.topLeftCorner<2, 2>() << c, s, -s, c;
  const Eigen::Matrix3d local_cov = j * cov * j.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(local_cov);
  if (eig.eigenvalues().minCoeff() < -1e-12 * scale)
    throw std::invalid_argument("Localizer::set_pose: covariance is not positive semidefinite");
  // Square root via the eigen-decomposition: also fine for singular (e.g. heading-only)
  // covariances, where a Cholesky factorisation would fail.
  const Eigen::Matrix3d sqrt_cov =
      eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).cwiseSqrt().asDiagonal();
  const Pose2 m = origin_.between(mean);

  const std::size_t n = cfg_.filter.particles;
  p_.resize(n);
  Rng rng = Rng::for_block(cfg_.seed, next_step(), detail::kStreamInit);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d z(rng.normal(), rng.normal(), rng.normal());
    const Eigen::Vector3d d = sqrt_cov * z;
    p_.x[i] = static_cast<float>(m.x + d.x());
    p_.y[i] = static_cast<float>(m.y + d.y());
    p_.theta[i] = wrap_angle(static_cast<float>(wrap_angle(m.theta + d.z())));
  }
  if (hypotheses_) hypotheses_->reset(false);
  reset_after_init();
}

void Localizer::reset_after_init() {
  p_.set_uniform_weights();
  probation_.assign(p_.size(), 0);
  force_ = true;
  have_averages_ = false;
  UpdateResult r;
  r.particles = p_.size();
  r.n_eff = static_cast<double>(p_.size());
  compute_estimate(r);
  clustered_ = r.converged;
  unimodal_ = 0;
  adaptable_ = false;  // the noise factors learnt so far stay: the same odometry
  have_usual_fit_ = false;
  r.rotation_noise_factor = motion_noise_->rotation_factor();
  r.translation_noise_factor = motion_noise_->translation_factor();
  anchor_ = r.estimate;
  last_ = r;
}

std::size_t Localizer::seed_particles(const detail::SeedRequest& seed) {
  // The `count` lightest particles (ties by index), an equal share around each pose, at
  // the uniform weight, in free space only (a few tries; near a tiny free region a
  // particle stays put).
  const std::size_t n = p_.size();
  const std::size_t count = std::min(seed.count, n);
  if (count == 0 || seed.poses.empty()) return 0;
  ws_.seed_victims.resize(n);
  std::iota(ws_.seed_victims.begin(), ws_.seed_victims.end(), 0u);
  std::nth_element(ws_.seed_victims.begin(),
                   ws_.seed_victims.begin() + static_cast<std::ptrdiff_t>(count - 1),
                   ws_.seed_victims.end(), [&](std::uint32_t a, std::uint32_t b) {
                     return p_.log_w[a] != p_.log_w[b] ? p_.log_w[a] < p_.log_w[b] : a < b;
                   });
  Rng rng = Rng::for_block(cfg_.seed, next_step(), detail::kStreamSeed);
  const double lw = -std::log(static_cast<double>(n));
  for (std::size_t k = 0; k < count; ++k) {
    const std::uint32_t i = ws_.seed_victims[k];
    const Pose2& c = seed.poses[k % seed.poses.size()];
    for (int attempt = 0; attempt < 8; ++attempt) {
      const double x = c.x + rng.normal(seed.sigma_xy), y = c.y + rng.normal(seed.sigma_xy);
      const double th = wrap_angle(c.theta + rng.normal(seed.sigma_theta));
      if (!hypotheses_->is_free(x, y)) continue;
      p_.x[i] = static_cast<float>(x);
      p_.y[i] = static_cast<float>(y);
      p_.theta[i] = wrap_angle(static_cast<float>(th));
      p_.log_w[i] = lw;
      probation_[i] = 0;
      break;
    }
  }
  return count;
}

ParticlesView Localizer::particles() const noexcept {
  return ParticlesView{p_.x, p_.y, p_.theta, p_.w, origin_};
}

}  // namespace pgmcl
