#include "perturb_settings.hpp"

#include <algorithm>
#include <numbers>
#include <vector>

#include "app_util.hpp"
#include "cli_errors.hpp"
#include "pgmcl/io/values.hpp"
#include "pgmcl/mcl/config_schema.hpp"

namespace pgmcl::app {
namespace {

/// Degrees to radians as perturb always computed it (bit-identical cases).
double radians(double deg) {
  return deg * std::numbers::pi / 180.0;
}

struct PerturbOptions {
  std::string log;
  std::string noise;
  std::uint64_t seed = 1;
  std::string out;
  std::string truth;  ///< --truth-out, or its deprecated name --truth
  std::string scale_bias = "0";
  std::string yaw_drift = "0";
  std::string odom_model = "pgmcl";
  std::string glitch;
  std::string translation_glitch;
  std::string min_scan_gap;
  std::string min_scan_travel;
  std::string laser_offset;
  std::string beam_dropout;
  bool strict = false;
  bool quiet = false;
  DeprecatedName truth_name, scale_name, yaw_name;
  /// The condition options and their values, in the order of --help, for the log's header.
  std::vector<std::pair<const CLI::Option*, const std::string*>> conditions;
};

}  // namespace

PerturbSettings parse_perturb_settings(const PerturbTexts& o) {
  PerturbSettings s;
  const std::vector<double> a = io::parse_number_list(o.noise, "--odom-noise", {4}, "A1,A2,A3,A4");
  // The filter's own bound (config_schema::kMaxMotionAlpha): past it the noise dwarfs the
  // motion and the written odometry is noise, not a perturbation.
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!(a[i] >= 0.0 && a[i] <= config_schema::kMaxMotionAlpha)) {
      throw io::UsageError("--odom-noise: A" + std::to_string(i + 1) + " must be in [0, " +
                           std::to_string(static_cast<int>(config_schema::kMaxMotionAlpha)) +
                           "] (variance form), got '" + o.noise + "'");
    }
  }
  OdometryPerturbation& p = s.odometry;
  p.noise = {.a1 = a[0], .a2 = a[1], .a3 = a[2], .a4 = a[3], .a5 = 0.0};
  p.scale_bias = parse_checked_list(o.scale_bias, o.scale_bias_name,
                                    {{.name = "F", .lo = -1.0, .hi = 10.0, .lo_open = true}}, 1)[0];
  s.yaw_drift_deg_per_m = parse_checked_list(
      o.yaw_drift, o.yaw_drift_name, {{.name = "DEG_PER_M", .lo = -360.0, .hi = 360.0}}, 1)[0];
  p.yaw_drift = radians(s.yaw_drift_deg_per_m);
  if (o.odom_model == "textbook") {
    p.model = OdometryModel::kTextbook;
  } else if (o.odom_model != "pgmcl") {
    throw io::UsageError("--odom-model: expected pgmcl or textbook, got '" + o.odom_model + "'");
  }
  constexpr ValueRule kRate{.name = "RATE", .lo = 0.0, .hi = 1.0};
  if (!o.glitch.empty()) {
    const auto v = parse_checked_list(
        o.glitch, "--glitch", {kRate, {.name = "DEG", .lo = 0.0, .hi = 180.0, .lo_open = true}}, 2);
    p.heading_glitch = {.rate = v[0], .size = radians(v[1])};
  }
  if (!o.translation_glitch.empty()) {
    const auto v = parse_checked_list(o.translation_glitch, "--translation-glitch",
                                      {kRate, {.name = "M", .lo = 0.0, .hi = 100.0}}, 2);
    p.translation_glitch = {.rate = v[0], .size = v[1]};
  }
  if (!o.min_scan_gap.empty()) {
    s.thinning.min_gap =
        parse_checked_list(o.min_scan_gap, "--min-scan-gap", {{.name = "S", .lo = 0.0}}, 1)[0];
    s.thinning_on = true;
  }
  if (!o.min_scan_travel.empty()) {
    const auto v = parse_checked_list(o.min_scan_travel, "--min-scan-travel",
                                      {{.name = "M", .lo = 0.0}, {.name = "DEG", .lo = 0.0}}, 1);
    s.thinning.by_travel = true;
    s.thinning.min_travel = v[0];
    if (v.size() > 1) s.thinning.min_turn = radians(v[1]);
    s.thinning_on = true;
  }
  if (!o.laser_offset.empty()) {
    s.laser_offset = parse_checked_list(o.laser_offset, "--laser-offset",
                                        {{.name = "X", .lo = -10.0, .hi = 10.0}}, 1)[0];
    s.laser_offset_on = true;
  }
  if (!o.beam_dropout.empty()) {
    const auto v = parse_checked_list(o.beam_dropout, "--beam-dropout",
                                      {{.name = "FRACTION", .lo = 0.0, .hi = 1.0, .hi_open = true},
                                       {.name = "SECTORS", .lo = 1.0, .integer = true}},
                                      1);
    s.dropout.fraction = v[0];
    // More sectors than beams is the same as one sector per beam.
    if (v.size() > 1) s.dropout.sectors = static_cast<int>(std::min(v[1], 1e9));
  }
  return s;
}

}  // namespace pgmcl::app
