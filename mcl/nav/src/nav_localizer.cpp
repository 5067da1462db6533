#include "pgmcl/nav/nav_localizer.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>

namespace pgmcl::nav {
namespace {

std::unique_ptr<Localizer> make_localizer(const maps::OccupancyGrid& grid, const NavConfig& cfg) {
  cfg.validate();
  return std::make_unique<Localizer>(grid, cfg.filter);
}

}  // namespace

void NavConfig::validate() const {
  const auto bad = [](const std::string& field, const std::string& problem) {
    throw std::invalid_argument("NavConfig: " + field + " " + problem);
  };
  if (!(std::isfinite(transform_tolerance) && transform_tolerance >= 0.0))
    bad("transform_tolerance", "must be finite and >= 0");
  if (scan_stride < 1) bad("scan_stride", "must be >= 1");
  if (std::isnan(ranges.min) || std::isnan(ranges.max)) bad("ranges", "must not be NaN");
  if (ranges.min > 0.0 && ranges.max > 0.0 && ranges.max <= ranges.min)
    bad("ranges.max", "must exceed ranges.min");
  if (!(max_mount_tilt >= 0.0 && max_mount_tilt <= std::numbers::pi / 2))
    bad("max_mount_tilt", "must be in [0, pi/2]");
  if (std::isnan(save_pose_period)) bad("save_pose_period", "must not be NaN");
  filter.validate();
}

NavLocalizer::NavLocalizer(const maps::OccupancyGrid& grid, NavConfig cfg)
    : cfg_(std::move(cfg)), loc_(make_localizer(grid, cfg_)) {}

ScanOutcome NavLocalizer::reject(ScanOutcome out, const std::string& why) {
  ++diag_.rejected;
  diag_.last_error = why;
  out.rejected = true;
  out.error = why;
  return out;
}

ScanOutcome NavLocalizer::process_scan(const ScanInput& in) {
  ++diag_.scans;
  ScanOutcome out;
  out.result = loc_->last_result();
  out.transform_ready = correction_.has_value();
  const std::size_t stride = cfg_.scan_stride;
  const bool take = forced_ || stride_counter_ == 0;
  if (!take) {
    stride_counter_ = (stride_counter_ + 1) % stride;
    ++diag_.stride_skipped;
    last_stamp_ = std::max(last_stamp_, in.stamp);
    return out;
  }
  UpdateResult r;
  try {
    const SensorMount mount = sensor_mount(in.base_T_laser, cfg_.max_mount_tilt);
    to_laser_scan(in.scan, mount, cfg_.ranges, scan_);
    if (pending_correction_ && !odom_ref_) apply_pending_pose(in.odom);
    r = loc_->update(in.odom, scan_, in.stamp);
  } catch (const std::invalid_argument& e) {
    return reject(std::move(out), e.what());
  }
  stride_counter_ = 1 % stride;
  forced_ = false;
  last_odom_ = in.odom;
  ++diag_.filtered;
  switch (r.skipped) {
    case SkipReason::kNotMoved:
      ++diag_.not_moved;
      break;
    case SkipReason::kNoValidBeams:
      ++diag_.no_valid_beams;
      break;
    case SkipReason::kTimeWentBackwards:
      ++diag_.time_resets;
      odom_ref_.reset();  // the filter starts a new odometry chain at the next scan
      break;
    case SkipReason::kNone:
      break;
  }
  // Every update that moved the filter re-anchors the correction at this scan's odometry;
  // a gated scan keeps it (its dead-reckoned estimate implies the same one).
  if (r.skipped == SkipReason::kNone || r.skipped == SkipReason::kNoValidBeams) {
    odom_ref_ = in.odom;
    correction_ = nav::map_to_odom(r.estimate, in.odom);
  }
  if (r.measured()) {
    ++diag_.measured;
    have_measured_ = true;
    pose_stamp_ = in.stamp;
    out.pose_ready = true;
  }
  last_stamp_ = std::max(last_stamp_, in.stamp);
  diag_.last_skip = r.skipped;
  diag_.update_ms = r.timings.total_ms;
  diag_.particles = r.particles;
  diag_.beams_total = r.beams_total;
  diag_.beams_invalid = r.beams_invalid;
  diag_.beams_used = r.beams_used;
  diag_.n_eff = r.n_eff;
  out.filtered = true;
  out.transform_ready = correction_.has_value();
  out.result = std::move(r);
  return out;
}

void NavLocalizer::apply_pending_pose(const Pose2& odom_now) {
  loc_->set_pose(pending_correction_->compose(odom_now), pending_covariance_);
  pending_correction_.reset();
}

void NavLocalizer::set_initial_pose(const Pose2& pose, const Eigen::Matrix3d& covariance,
                                    const std::optional<Pose2>& odom_at_pose) {
  const std::optional<Pose2> at = odom_at_pose ? odom_at_pose : last_odom_;
  if (!at) {  // nothing seen yet: the pose is the robot's at the first scan
    loc_->set_pose(pose, covariance);
    pending_correction_.reset();
  } else {
    // The pose fixes map_T_odom; the filter wants the pose at its own last odometry.
    const Pose2 correction = nav::map_to_odom(pose, *at);
    if (odom_ref_) {
      loc_->set_pose(correction.compose(*odom_ref_), covariance);
      pending_correction_.reset();
    } else {
      loc_->set_pose(pose, covariance);
      pending_correction_ = correction;
      pending_covariance_ = covariance;
    }
    correction_ = correction;
  }
  forced_ = true;
}

void NavLocalizer::global_localize() {
  loc_->global_localize();
  pending_correction_.reset();
  forced_ = true;
}

void NavLocalizer::request_nomotion_update() noexcept {
  loc_->force_update();
  forced_ = true;
}

MapChange NavLocalizer::replace_map(const maps::OccupancyGrid& grid, bool same_frame) {
  const LikelihoodConfig& l = cfg_.filter.likelihood;
  auto field = std::make_shared<const maps::LikelihoodField>(grid, l.beam, l.table);
  std::vector<std::uint32_t> free = free_cell_indices(grid);
  MapChange change;
  if (same_frame) {
    loc_->replace_map(std::move(field), std::move(free));
    change.kept_particles = true;
  } else {
    // Another frame: neither the particles nor the correction mean anything there.
    loc_ = std::make_unique<Localizer>(std::move(field), std::move(free), cfg_.filter);
    odom_ref_.reset();
    pending_correction_.reset();
    correction_.reset();
    have_measured_ = false;
  }
  forced_ = true;
  return change;
}

PoseOutput NavLocalizer::pose() const {
  const UpdateResult& r = loc_->last_result();
  PoseOutput p;
  p.pose = r.estimate;
  p.covariance = r.covariance;
  p.ros_covariance = to_ros_covariance(r.covariance);
  p.stamp = pose_stamp_;
  p.fit = r.fit;
  p.converged = r.converged;
  p.alternative_evidence = r.alternative_evidence;
  return p;
}

std::optional<TransformOutput> NavLocalizer::map_to_odom() const {
  if (!correction_) return std::nullopt;
  return TransformOutput{*correction_, last_stamp_ + cfg_.transform_tolerance};
}

void NavLocalizer::particles(std::vector<WeightedPose>& out) const {
  const ParticlesView v = loc_->particles();
  out.resize(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) out[i] = {v.global_pose(i), v.weight[i]};
}

std::optional<StoredPose> NavLocalizer::pose_to_store(double now) {
  if (!have_measured_ || !(cfg_.save_pose_period > 0.0)) return std::nullopt;
  if (last_saved_ && now >= *last_saved_ && now - *last_saved_ < cfg_.save_pose_period)
    return std::nullopt;
  last_saved_ = now;
  const UpdateResult& r = loc_->last_result();
  return StoredPose::of(r.estimate, r.covariance);
}

}  // namespace pgmcl::nav
