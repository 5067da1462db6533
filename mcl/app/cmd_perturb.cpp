/// pgmcl perturb: noisy odometry from the ground-truth increments of a corrected log.
///
/// The `*-corrected` benchmark logs hold no raw odometry, only the corrected poses. This
/// command turns one into a "raw" log a filter can be tested on:
///  - truth: the robot poses of the log's laser scans (io::scan_truth), written as TUM;
///  - for each consecutive pair of truth poses a noisy increment is drawn from the odometry
///    model (Probabilistic Robotics, Table 5.6, differential drive, variance-form alphas;
///    sample_noisy_increment), optionally distorted by a systematic bias (a scale error on
///    the translation and a heading drift per metre), and integrated into an odometry chain
///    that starts at the first truth pose;
///  - the raw log keeps every scan and PARAM, replaces the ODOM messages by one per scan
///    carrying the chain at the scan's stamp, and replaces both the FLASER odometry fields
///    and its `x y theta` (the laser pose: chain * mounting offset). A filter that reads the
///    FLASER pose as odometry (as CARMEN tools and the corrected logs do) therefore sees the
///    noisy chain too, and no field of the raw log leaks the truth.

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "app_util.hpp"
#include "commands.hpp"
#include "pgmcl/io/carmen.hpp"
#include "pgmcl/io/carmen_writer.hpp"
#include "pgmcl/io/cli_errors.hpp"
#include "pgmcl/io/tum.hpp"
#include "pgmcl/mcl/motion_model.hpp"
#include "pgmcl/mcl/random.hpp"

namespace pgmcl::app {
namespace {

struct PerturbOptions {
  std::string log;
  std::string noise;
  std::uint64_t seed = 1;
  std::string out;
  std::string truth;
  double bias_scale = 0.0;
  double bias_yaw_deg_per_m = 0.0;
  bool strict = false;
  bool quiet = false;
};

/// Systematic odometry error on one increment (robot frame at the previous pose): the
/// translation is scaled by (1 + scale) and the heading drifts by yaw_per_m per metre.
Pose2 apply_bias(const Pose2& inc, double scale, double yaw_per_m) {
  const double dist = std::hypot(inc.x, inc.y);
  return {inc.x * (1.0 + scale), inc.y * (1.0 + scale), wrap_angle(inc.theta + yaw_per_m * dist)};
}

int run_perturb(const PerturbOptions& o) {
  const std::vector<double> a = io::parse_number_list(o.noise, "--odom-noise", {4}, "A1,A2,A3,A4");
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i] < 0.0) {
      throw io::UsageError("--odom-noise: A" + std::to_string(i + 1) + " must be >= 0 (got " +
                           o.noise + ")");
    }
  }
  if (!std::isfinite(o.bias_scale) || o.bias_scale <= -1.0) {
    throw io::UsageError("--bias-scale: must be > -1");
  }
  const MotionNoise noise{.a1 = a[0], .a2 = a[1], .a3 = a[2], .a4 = a[3], .a5 = 0.0};
  const double yaw_per_m = o.bias_yaw_deg_per_m * std::numbers::pi / 180.0;

  io::CarmenLog log = read_log(o.log, {}, o.strict);
  // The truth chain follows the first laser message type with poses (FLASER in the
  // benchmark logs); other laser messages would interleave a second sensor's stamps.
  const io::CarmenScan* first = nullptr;
  for (const auto& s : log.scans) {
    if (s.has_poses) {
      first = &s;
      break;
    }
  }
  if (first == nullptr) {
    throw io::UsageError(o.log + ": no laser scans with poses (FLASER, RLASER or ROBOTLASER1)");
  }
  const io::LaserMessage kind = first->message;
  std::vector<const io::CarmenScan*> scans;
  std::size_t dropped = 0;
  for (const auto& s : log.scans) {
    if (s.has_poses && s.message == kind) {
      scans.push_back(&s);
    } else {
      ++dropped;
    }
  }
  const io::Trajectory truth = io::scan_truth(log, kind);
  if (truth.size() != scans.size()) {
    throw std::logic_error("perturb: scan_truth and scan selection disagree");
  }

  Rng rng(o.seed);
  io::Trajectory odom(truth.size());
  odom[0] = truth[0];
  double travelled = 0.0;
  for (std::size_t i = 1; i < truth.size(); ++i) {
    const Pose2 inc = sample_noisy_increment(MotionModelKind::kDifferentialDrive, noise,
                                             truth[i - 1].pose, truth[i].pose, rng);
    odom[i].stamp = truth[i].stamp;
    odom[i].pose = odom[i - 1].pose.compose(apply_bias(inc, o.bias_scale, yaw_per_m));
    travelled +=
        std::hypot(truth[i].pose.x - truth[i - 1].pose.x, truth[i].pose.y - truth[i - 1].pose.y);
  }

  ensure_parent_directory(o.out);
  ensure_parent_directory(o.truth);
  io::CarmenWriter w(o.out);
  char header[512];
  std::snprintf(header, sizeof header,
                "pgmcl perturb: odometry = ground-truth increments + Table 5.6 noise "
                "(a1 %g a2 %g a3 %g a4 %g), bias scale %g yaw %g deg/m, seed %llu",
                a[0], a[1], a[2], a[3], o.bias_scale, o.bias_yaw_deg_per_m,
                static_cast<unsigned long long>(o.seed));
  w.comment(header);
  w.comment("source: " + o.log);
  for (const auto& [name, value] : log.params) w.param(name, value);
  for (std::size_t i = 0; i < scans.size(); ++i) {
    io::CarmenScan s = *scans[i];
    const Pose2& p = odom[i].pose;
    io::OdomRecord r;
    r.pose = p;
    r.stamp = s.scan.stamp;
    r.logger_stamp = s.logger_stamp;
    r.host = s.host;
    if (i > 0) {
      const double dt = s.scan.stamp - scans[i - 1]->scan.stamp;
      const Pose2 d = odom[i - 1].pose.between(p);
      if (dt > 0.0) {
        r.tv = std::hypot(d.x, d.y) / dt;
        r.rv = d.theta / dt;
      }
    }
    w.odom(r);
    s.odom_pose = p;
    s.laser_pose = p.compose(s.scan.sensor_pose);
    w.scan(s);
  }
  w.close();
  io::write_tum(o.truth, truth);

  if (!o.quiet) {
    const Pose2 drift = truth.back().pose.between(odom.back().pose);
    std::printf(
        "perturb: %zu scans, %.1f m travelled; final odometry error %.3f m, %.2f deg; "
        "wrote %s and %s\n",
        scans.size(), travelled, std::hypot(drift.x, drift.y),
        std::abs(drift.theta) * 180.0 / std::numbers::pi, o.out.c_str(), o.truth.c_str());
    if (dropped > 0) {
      std::printf("perturb: dropped %zu laser message(s) of other types or without poses\n",
                  dropped);
    }
  }
  return 0;
}

}  // namespace

Command add_perturb_command(CLI::App& app) {
  auto o = std::make_shared<PerturbOptions>();
  CLI::App* sub = app.add_subcommand(
      "perturb", "Make a raw log with noisy odometry from a corrected log's poses");
  sub->add_option("--log", o->log, "Corrected CARMEN log")->required()->check(CLI::ExistingFile);
  sub->add_option("--odom-noise", o->noise,
                  "A1,A2,A3,A4: Probabilistic Robotics Table 5.6 alphas, variance form "
                  "(rad^2/rad^2, rad^2/m^2, m^2/m^2, m^2/rad^2)")
      ->required();
  sub->add_option("--seed", o->seed, "Random seed")->required();
  sub->add_option("--out", o->out, "Output raw CARMEN log (.gz ok)")->required();
  sub->add_option("--truth", o->truth, "Output ground truth (TUM)")->required();
  sub->add_option("--bias-scale", o->bias_scale,
                  "Systematic translation scale error (0.015 = odometry reads 1.5 % long)")
      ->capture_default_str();
  sub->add_option("--bias-yaw-deg-per-m", o->bias_yaw_deg_per_m,
                  "Systematic heading drift, degrees per metre travelled")
      ->capture_default_str();
  sub->add_flag("--strict", o->strict, "Malformed log lines are errors, not warnings");
  sub->add_flag("--quiet", o->quiet, "No summary line");
  return {sub, [o] { return run_perturb(*o); }};
}

}  // namespace pgmcl::app
