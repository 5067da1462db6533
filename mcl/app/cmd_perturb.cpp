/// pgmcl perturb: a "raw" log with noisy odometry (and optional stress conditions) from the
/// ground truth of a corrected log.
///
/// The `*-corrected` benchmark logs hold no raw odometry, only the corrected poses. This
/// command turns one into a "raw" log a filter can be tested on:
///  - truth: the robot poses of the log's laser scans (io::scan_truth), written as TUM; with
///    --laser-offset X the logged poses are the laser's and the robot base sits X metres
///    behind it (base = laser ∘ (-X, 0, 0));
///  - scan thinning (--min-scan-gap, --min-scan-travel) keeps a subset of the scans; the
///    others leave the output log and the truth;
///  - the odometry chain over the kept scans: noise model, bias, glitches
///    (odometry_perturbation.hpp);
///  - the raw log keeps the kept scans and every PARAM, replaces the ODOM messages by one per
///    scan carrying the chain at the scan's stamp, and replaces both the FLASER odometry fields
///    and its `x y theta` (the laser pose: chain * mounting offset). A filter that reads the
///    FLASER pose as odometry (as CARMEN tools and the corrected logs do) therefore sees the
///    noisy chain too, and no field of the raw log leaks the truth;
///  - --beam-dropout blanks sectors of each kept scan (scan_perturbation.hpp).

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "app_util.hpp"
#include "cli_errors.hpp"
#include "commands.hpp"
#include "interrupt.hpp"
#include "output_files.hpp"
#include "perturb_random.hpp"
#include "perturb_settings.hpp"
#include "pgmcl/io/carmen.hpp"
#include "pgmcl/io/carmen_writer.hpp"
#include "pgmcl/io/tum.hpp"
#include "pgmcl/io/values.hpp"

namespace pgmcl::app {
namespace {

struct PerturbOptions {
  std::string log;
  std::uint64_t seed = 1;
  std::string out;
  std::string truth;  ///< --truth-out, or its deprecated name --truth
  PerturbTexts text;
  bool strict = false;
  bool quiet = false;
  DeprecatedName truth_name, scale_name, yaw_name;
  /// The condition options and their values, in the order of --help, for the log's header.
  std::vector<std::pair<const CLI::Option*, const std::string*>> conditions;
};

/// The scans the truth follows: those of the first laser message type with poses (FLASER in
/// the benchmark logs); other laser messages would interleave a second sensor's stamps.
/// `other` counts the laser messages left out.
std::vector<const io::CarmenScan*> truth_scans(const io::CarmenLog& log, const std::string& path,
                                               std::size_t& other) {
  const io::CarmenScan* first = nullptr;
  for (const auto& s : log.scans) {
    if (s.has_poses) {
      first = &s;
      break;
    }
  }
  if (first == nullptr) {
    throw io::UsageError(path + ": no laser scans with poses (FLASER, RLASER or ROBOTLASER1)");
  }
  std::vector<const io::CarmenScan*> scans;
  other = 0;
  for (const auto& s : log.scans) {
    if (s.has_poses && s.message == first->message) {
      scans.push_back(&s);
    } else {
      ++other;
    }
  }
  return scans;
}

/// --laser-offset needs a forward-facing laser logged without an offset of its own.
void check_laser_offset_input(const io::CarmenLog& log, const std::string& path,
                              const std::vector<const io::CarmenScan*>& scans) {
  const io::LaserMessage kind = scans.front()->message;
  if (kind != io::LaserMessage::kFlaser && kind != io::LaserMessage::kRobotLaser1) {
    throw io::UsageError("--laser-offset: " + path + " holds " +
                         std::string(io::message_name(kind)) +
                         " scans; only a front laser (FLASER or ROBOTLASER1) can be offset");
  }
  for (const io::CarmenScan* s : scans) {
    const Pose2& m = s->scan.sensor_pose;
    if (m.x == 0.0 && m.y == 0.0 && m.theta == 0.0) continue;
    const auto param = log.params.find("robot_frontlaser_offset");
    const std::string why =
        kind == io::LaserMessage::kFlaser && param != log.params.end()
            ? "PARAM robot_frontlaser_offset " + param->second
            : "the laser pose differs from the robot pose on line " + std::to_string(s->line);
    throw io::UsageError("--laser-offset: " + path + " already has a laser offset (" + why +
                         "); refusing to stack a second one on it");
  }
}

std::string shortest(double v) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

int run_perturb(const PerturbOptions& o) {
  PerturbTexts text = o.text;
  text.scale_bias_name = o.scale_name.used();
  text.yaw_drift_name = o.yaw_name.used();
  const PerturbSettings set = parse_perturb_settings(text);
  if (o.truth.empty()) {
    throw io::UsageError("--truth-out is required (the ground-truth TUM file to write)");
  }
  for (const DeprecatedName* d : {&o.truth_name, &o.scale_name, &o.yaw_name}) d->note_if_used();
  OutputFiles files;
  files.input(o.log, "--log");
  const std::string out_tmp = files.add(o.out, "--out");
  const std::string truth_tmp = files.add(o.truth, o.truth_name.used());

  io::CarmenLog log = read_log(o.log, {}, o.strict);
  std::size_t other_messages = 0;
  std::vector<const io::CarmenScan*> scans = truth_scans(log, o.log, other_messages);
  const io::Trajectory logged = io::scan_truth(log, scans.front()->message);
  if (logged.size() != scans.size()) {
    throw std::logic_error("perturb: scan_truth and scan selection disagree");
  }
  io::Trajectory truth = logged;
  const Pose2 mount{set.laser_offset, 0.0, 0.0};
  if (set.laser_offset_on) {
    check_laser_offset_input(log, o.log, scans);
    for (io::StampedPose& t : truth) t.pose = t.pose.compose(mount.inverse());
    log.params["robot_frontlaser_offset"] = shortest(set.laser_offset);
  }
  const std::size_t all_scans = scans.size();
  if (set.thinning_on) {
    const std::vector<std::size_t> kept = thin_scans(truth, set.thinning);
    std::vector<const io::CarmenScan*> kept_scans;
    io::Trajectory kept_truth;
    for (const std::size_t i : kept) {
      kept_scans.push_back(scans[i]);
      kept_truth.push_back(truth[i]);
    }
    scans = std::move(kept_scans);
    truth = std::move(kept_truth);
    if (scans.size() < 2) {
      throw io::UsageError("--min-scan-gap / --min-scan-travel: kept " +
                           std::to_string(scans.size()) + " of " + std::to_string(all_scans) +
                           " scans; a log needs at least 2 to localise in (thinning too strong)");
    }
  }
  const PerturbedOdometry chain = perturb_odometry(truth, set.odometry, o.seed);
  const io::Trajectory& odom = chain.odometry;

  io::CarmenWriter w(out_tmp);
  char header[512];
  std::snprintf(header, sizeof header,
                "pgmcl perturb: odometry = ground-truth increments + Table 5.6 noise "
                "(a1 %g a2 %g a3 %g a4 %g), bias scale %g yaw %g deg/m, seed %llu",
                set.odometry.noise.a1, set.odometry.noise.a2, set.odometry.noise.a3,
                set.odometry.noise.a4, set.odometry.scale_bias, set.yaw_drift_deg_per_m,
                static_cast<unsigned long long>(o.seed));
  w.comment(header);
  std::string conditions;
  for (const auto& [option, value] : o.conditions) {
    if (option->count() > 0) conditions += " " + option->get_name() + " " + *value;
  }
  // Only when a condition is given, so the cases made before they existed stay identical.
  if (!conditions.empty()) w.comment("pgmcl perturb: conditions:" + conditions);
  w.comment("source: " + o.log);
  for (const auto& [name, value] : log.params) w.param(name, value);
  Rng dropout_rng = perturb_rng(o.seed, PerturbStream::kBeamDropout);
  std::size_t blanked = 0;
  for (std::size_t i = 0; i < scans.size(); ++i) {
    check_interrupt();
    io::CarmenScan s = *scans[i];
    const Pose2& p = odom[i].pose;
    io::OdomRecord r;
    r.pose = p;
    r.stamp = s.stamp;
    r.logger_stamp = s.logger_stamp;
    r.host = s.host;
    if (i > 0) {
      const double dt = s.stamp - scans[i - 1]->stamp;
      const Pose2 d = odom[i - 1].pose.between(p);
      if (dt > 0.0) {
        r.tv = std::hypot(d.x, d.y) / dt;
        r.rv = d.theta / dt;
      }
    }
    w.odom(r);
    if (set.laser_offset_on) s.scan.sensor_pose = mount;
    if (set.dropout.fraction > 0.0) {
      blanked +=
          drop_beams(s.scan.ranges, set.dropout, no_return_reading(s.scan.range_max), dropout_rng);
    }
    s.odom_pose = p;
    s.laser_pose = p.compose(s.scan.sensor_pose);
    w.scan(s);
  }
  w.close();
  io::write_tum(truth_tmp, truth);
  files.commit();

  if (!o.quiet) {
    const Pose2 drift = truth.back().pose.between(odom.back().pose);
    std::printf(
        "perturb: kept %zu of %zu scans (%zu dropped), %.1f m travelled; %zu heading and %zu "
        "translation glitch(es); final dead-reckoning drift %.3f m, %.2f deg; wrote %s and %s\n",
        scans.size(), all_scans, all_scans - scans.size(), chain.travelled, chain.heading_glitches,
        chain.translation_glitches, std::hypot(drift.x, drift.y),
        std::abs(drift.theta) * 180.0 / std::numbers::pi, o.out.c_str(), o.truth.c_str());
    if (set.dropout.fraction > 0.0) {
      std::printf("perturb: beam dropout blanked %zu readings\n", blanked);
    }
    if (other_messages > 0) {
      std::printf("perturb: left out %zu laser message(s) of other types or without poses\n",
                  other_messages);
    }
  }
  return 0;
}

void add_perturb_options(CLI::App& sub, PerturbOptions& o) {
  sub.description(
      "Make a raw log with noisy odometry (and stress conditions) from a corrected log");
  add_input_file(sub, "--log", o.log, "Corrected CARMEN log", log_file())->required();
  sub.add_option("--odom-noise", o.text.noise,
                 "A1,A2,A3,A4: Probabilistic Robotics Table 5.6 alphas, variance form "
                 "(rad^2/rad^2, rad^2/m^2, m^2/m^2, m^2/rad^2)")
      ->required();
  add_seed_option(sub, o.seed, "Random seed (every random choice derives from it)")->required();
  sub.add_option("--out", o.out, "Output raw CARMEN log (.gz ok)")->required();
  CLI::Option* truth = sub.add_option("--truth-out", o.truth, "Output ground truth (TUM), required")
                           ->type_name("FILE");
  o.truth_name = DeprecatedName(sub, truth, "--truth", o.truth);
  CLI::Option* scale =
      sub.add_option("--scale-bias", o.text.scale_bias,
                     "Systematic translation scale error F (0.015 = odometry reads 1.5 % long)")
          ->type_name("F")
          ->capture_default_str();
  o.scale_name = DeprecatedName(sub, scale, "--bias-scale", o.text.scale_bias);
  CLI::Option* yaw = sub.add_option("--yaw-drift", o.text.yaw_drift,
                                    "Systematic heading drift, degrees per metre travelled")
                         ->type_name("DEG_PER_M")
                         ->capture_default_str();
  o.yaw_name = DeprecatedName(sub, yaw, "--bias-yaw-deg-per-m", o.text.yaw_drift);
  // Conditions: recorded in the output log's header when given.
  const auto condition = [&](const std::string& name, std::string& value, const std::string& help,
                             const std::string& type) {
    o.conditions.emplace_back(sub.add_option(name, value, help)->type_name(type), &value);
  };
  condition("--odom-model", o.text.odom_model,
            "pgmcl (default: sample_noisy_increment) or textbook (Table 5.6 literally: no "
            "backward-motion flip, no small-translation fade)",
            "pgmcl|textbook");
  condition("--glitch", o.text.glitch,
            "Heading glitches: each step with probability RATE gets a heading error of "
            "[0.8, 1] * DEG degrees, random sign, at the start of the step",
            "RATE,DEG");
  condition("--translation-glitch", o.text.translation_glitch,
            "Translation glitches: each step with probability RATE gets M metres extra in a "
            "random direction",
            "RATE,M");
  condition("--min-scan-gap", o.text.min_scan_gap,
            "Keep a scan only if S seconds of log time passed since the last kept one", "S");
  condition("--min-scan-travel", o.text.min_scan_travel,
            "Keep a scan only once the true pose moved M metres (or turned DEG degrees) since "
            "the last kept one",
            "M[,DEG]");
  condition("--laser-offset", o.text.laser_offset,
            "The logged poses are the laser's; the robot base is X metres behind it (truth = "
            "base; PARAM robot_frontlaser_offset X)",
            "X");
  condition("--beam-dropout", o.text.beam_dropout,
            "Per scan, FRACTION of the beams in SECTORS (3) random contiguous sectors read "
            "'no return'",
            "FRACTION[,SECTORS]");
  add_strict_flag(sub, o.strict);
  sub.add_flag("--quiet", o.quiet, "No summary line");
}

}  // namespace

Command add_perturb_command(CLI::App& app) {
  return make_command<PerturbOptions>(app, "perturb", add_perturb_options, run_perturb);
}

}  // namespace pgmcl::app
