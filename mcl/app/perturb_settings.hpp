#pragma once
/// `pgmcl perturb`'s option values: the texts as given and the checked settings they make.
/// Every value is checked here, before the command reads or writes anything; a bad one is an
/// io::UsageError naming the option and the value (exit code 2).

#include <string>

#include "odometry_perturbation.hpp"
#include "scan_perturbation.hpp"

namespace pgmcl::app {

/// The option texts ("" = not given; the defaults are the options' defaults).
struct PerturbTexts {
  std::string noise;  ///< --odom-noise A1,A2,A3,A4
  std::string scale_bias = "0";
  std::string scale_bias_name = "--scale-bias";  ///< the name the user gave, for errors
  std::string yaw_drift = "0";                   ///< degrees per metre
  std::string yaw_drift_name = "--yaw-drift";
  std::string odom_model = "pgmcl";
  std::string glitch;              ///< RATE,DEG
  std::string translation_glitch;  ///< RATE,M
  std::string min_scan_gap;        ///< S
  std::string min_scan_travel;     ///< M[,DEG]
  std::string laser_offset;        ///< X
  std::string beam_dropout;        ///< FRACTION[,SECTORS]
};

/// Every option value, checked and converted before anything is read or written.
struct PerturbSettings {
  OdometryPerturbation odometry;
  double yaw_drift_deg_per_m = 0.0;  ///< as given, for the log's header
  ScanThinning thinning;
  bool thinning_on = false;  ///< --min-scan-gap or --min-scan-travel given
  bool laser_offset_on = false;
  double laser_offset = 0.0;  ///< metres from the robot base forward to the laser
  BeamDropout dropout;        ///< fraction 0: off
};

[[nodiscard]] PerturbSettings parse_perturb_settings(const PerturbTexts& text);

}  // namespace pgmcl::app
