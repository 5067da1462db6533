// Corpus cases: silent wrong results, each now an error or a counted, reported warning.

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "hostile_corpus.hpp"
#include "hostile_util.hpp"

namespace pgmcl::hostile {
namespace {

/// Which pose field jump_after shifts: its offset from x in a CARMEN pose (x y theta).
enum class PoseField : std::size_t { kX = 0, kTheta = 2 };

/// Adds `d` (metres in x, or radians to theta) to every ODOM and FLASER odometry pose from
/// the `k`-th scan on.
std::vector<std::string> jump_after(const std::vector<std::string>& lines, int k, double d,
                                    PoseField field = PoseField::kX) {
  std::vector<std::string> out;
  int scans = 0;
  bool after = false;
  for (const std::string& l : lines) {
    if (l.rfind("FLASER", 0) == 0 && ++scans == k) after = true;
    if (!after || (l.rfind("ODOM", 0) != 0 && l.rfind("FLASER", 0) != 0)) {
      out.push_back(l);
      continue;
    }
    std::vector<std::string> w = words(l);
    // ODOM x at 1; FLASER laser x and odom x at n + 2 and n + 5.
    const auto shift = [&](std::size_t i) {
      i += static_cast<std::size_t>(field);
      w[i] = number(std::stod(w[i]) + d);
    };
    if (w[0] == "ODOM") {
      shift(1);
    } else {
      const std::size_t n = std::stoul(w[1]);
      shift(n + 2);
      shift(n + 5);
    }
    out.push_back(join_words(w));
  }
  return out;
}

}  // namespace

std::vector<Case> silent_cases() {
  std::vector<Case> c;
  const auto near_end = [](const Env& e, const RunResult&) { expect_final_pose_near(e, 0.5); };
  // Equal timestamps: a group of scans used to get the group's last odometry.
  const auto near_raw_end = [](const Env& e, const RunResult&) {
    expect_final_pose_near(e, 0.5, true);
  };
  const auto rounded = [](bool odom, bool scans, double step) {
    return [odom, scans, step](const Env& e) {
      return e.localize(
          "", e.write("r.log",
                      join(restamp(
                          e.raw_lines(), [step](double t) { return step * std::floor(t / step); },
                          odom, scans))));
    };
  };
  c.push_back(warning_case("stamps_rounded_to_seconds", rounded(true, true, 1.0),
                           {"share their timestamp", "paired with the ODOM message before them"},
                           near_raw_end));
  c.push_back(warning_case("stamps_rounded_to_5_seconds", rounded(true, true, 5.0),
                           {"share their timestamp"}, near_raw_end));
  c.push_back(warning_case("scan_stamps_rounded_to_5_s_odom_exact", rounded(false, true, 5.0),
                           {"share their timestamp"}, near_raw_end));
  c.push_back(warning_case("odom_stamps_rounded_scans_exact", rounded(true, false, 1.0),
                           {"ODOM message(s) carry the same stamp"}, near_raw_end));
  c.push_back(accepted_case(
      "short_log_rounded_without_collisions",
      [](const Env& e) {
        return e.localize(
            "",
            e.write("r.log", join(restamp(e.log_lines(), [](double t) { return std::floor(t); }))));
      },
      near_end));
  c.push_back(warning_case(
      "every_stamp_identical",
      [](const Env& e) {
        return e.localize(
            "", e.write("r.log", join(restamp(e.log_lines(), [](double) { return 1000.0; }))));
      },
      {"share their timestamp"}, near_end));
  // Odometry jumps nobody drives.
  for (const auto& [name, d] :
       {std::pair{"odometry_jump_1e9_m", 1e9}, std::pair{"odometry_jump_1e6_m", 1e6},
        std::pair{"odometry_jump_500_m", 500.0}, std::pair{"odometry_jump_minus_1e30_m", -1e30}}) {
    const double jump = d;
    c.push_back(warning_case(name,
                             [jump](const Env& e) {
                               return e.localize(
                                   "", e.write("j.log", join(jump_after(e.log_lines(), 60, jump))));
                             },
                             {"odometry jump", "faster than 10 m/s"}));
  }
  // Heading jumps no robot turns: interpolation wraps them to an ordinary-looking angle.
  for (const auto& [name, d] : {std::pair{"odometry_heading_jump_1e6_rad", 1e6},
                                std::pair{"odometry_heading_jump_minus_100_rad", -100.0}}) {
    const double jump = d;
    c.push_back(warning_case(
        name,
        [jump](const Env& e) {
          return e.localize(
              "", e.write("j.log", join(jump_after(e.log_lines(), 60, jump, PoseField::kTheta))));
        },
        {"1 odometry heading jump(s)", "faster than 10 rad/s"}));
  }
  c.push_back(warning_case("odometry_heading_jump_scan_fields_only",
                           [](const Env& e) {
                             std::vector<std::string> l;
                             for (const std::string& s :
                                  jump_after(e.log_lines(), 60, 1e6, PoseField::kTheta))
                               if (s.rfind("ODOM", 0) != 0) l.push_back(s);
                             return e.localize("", e.write("j.log", join(l)));
                           },
                           {"1 odometry heading jump(s)"}));
  c.push_back(warning_case("odometry_jump_scan_fields_only",
                           [](const Env& e) {
                             std::vector<std::string> l;
                             for (const std::string& s : jump_after(e.log_lines(), 60, 1e9))
                               if (s.rfind("ODOM", 0) != 0) l.push_back(s);
                             return e.localize("", e.write("j.log", join(l)));
                           },
                           {"odometry jump"}));
  // Runs in which the filter hardly measured anything: the trajectory is dead reckoning.
  c.push_back(warning_case("everything_gated",
                           localize_with("--set gating.d_min=1e9 --set gating.theta_min=1e9"),
                           {"measured only 1 of 120 scans", "119 gated"}));
  c.push_back(warning_case("max_range_shorter_than_every_reading",
                           localize_with("--set likelihood.beam.max_range=0.2"),
                           {"measured only 0 of 120 scans", "without a valid reading"}));
  // Laser headers that disagree with their readings: the line is dropped and reported.
  // Every 10th scan with a header that disagrees: those are dropped and reported.
  const auto some_bad_headers = [](double fov, double res) {
    return [fov, res](const Env& e) {
      const std::vector<std::string> good = as_robotlaser(e.log_lines(), 3.124139);
      const std::vector<std::string> bad = as_robotlaser(e.log_lines(), fov, res);
      std::vector<std::string> l;
      int scans = 0;
      for (std::size_t i = 0; i < good.size(); ++i) {
        const bool scan = good[i].rfind("ROBOTLASER1", 0) == 0;
        l.push_back(scan && ++scans % 10 == 0 ? bad[i] : good[i]);
      }
      return e.localize("", e.write("rl.log", join(l)));
    };
  };
  c.push_back(warning_case(
      "robotlaser_fov_disagrees", some_bad_headers(1.0, 0.017453292519943295),
      {"dropped 12 malformed line", "field_of_view", "does not describe these readings"}));
  c.push_back(warning_case("robotlaser_resolution_zero", some_bad_headers(3.124139, 0.0),
                           {"dropped 12 malformed line", "field_of_view"}));
  c.push_back(error_case(
      "robotlaser_fov_disagrees_everywhere", 1,
      [](const Env& e) {
        return e.localize("", e.write("rl.log", join(as_robotlaser(e.log_lines(), 1.0))));
      },
      {"no laser scan with odometry", "120 malformed line(s)", "field_of_view"}));
  c.push_back(error_case(
      "robotlaser_fov_disagrees_strict", 1,
      [](const Env& e) {
        return e.localize("--strict", e.write("rl.log", join(as_robotlaser(e.log_lines(), 1.0))));
      },
      {"rl.log:", "field_of_view"}));
  c.push_back(accepted_case(
      "robotlaser_consistent",
      [](const Env& e) {
        return e.localize("", e.write("rl.log", join(as_robotlaser(e.log_lines(), 3.124139))));
      },
      near_end));
  c.push_back(warning_case("rawlaser_fov_disagrees",
                           [](const Env& e) {
                             std::vector<std::string> l = e.log_lines();
                             l.push_back(
                                 "RAWLASER1 0 -1.5 1.0 0.5 8 0.01 0 7 1 2 3 4 5 6 7 0 1e9 h 1e9");
                             return e.localize("", e.write("l.log", join(l)));
                           },
                           {"dropped 1 malformed line", "field_of_view"}));
  // Truth and relations that match nothing gave "ATE 0.000 m".
  c.push_back(warning_case(
      "truth_from_another_time",
      [](const Env& e) {
        return e.localize("--truth " + e.write("t.tum", "1 0 0 0 0 0 0 1\n2 1 0 0 0 0 0 1\n"));
      },
      {"matched none", "no accuracy figures"},
      [](const Env& e, const RunResult&) {
        EXPECT_EQ(testkit::read_text(e.path("out/metrics.yaml")).find("ate_rmse_m"),
                  std::string::npos);
      }));
  c.push_back(warning_case(
      "relations_without_time_offset",
      localize_with("--relations " PGMCL_SOURCE_DIR "/data/relations/intel.relations.gz"),
      {"relations matched", "time offset"}));
  // Seeds out of range, on every command that takes one.
  for (const auto& [name, args] :
       {std::pair{"seed_minus_one", "--seed -1"},
        std::pair{"seed_2_pow_64", "--seed 18446744073709551616"},
        std::pair{"seed_fraction", "--seed 1.5"}, std::pair{"seed_hex", "--seed 0x10"},
        std::pair{"seed_empty", "--seed ''"}}) {
    const std::string a = args;
    c.push_back(error_case(name, 2, localize_with(a),
                           {"--seed", "a whole number in [0, 18446744073709551615]"}));
  }
  c.push_back(accepted_case("seed_max_accepted", localize_with("--seed 18446744073709551615")));
  c.push_back(
      error_case("perturb_seed_minus_one", 2,
                 [](const Env& e) {
                   return "perturb --log " + e.b.log +
                          " --odom-noise 0.01,0,0.01,0 --seed -1 --out p.log --truth-out p.tum";
                 },
                 {"--seed"}));
  c.push_back(error_case("perturb_map_seed_too_big", 2,
                         perturb_base_map("--out p.yaml --erase 0.1,1 --seed 99999999999999999999"),
                         {"--seed"}));
  c.push_back(bad_setting("set_seed_minus_one", "seed=-1", {"--set seed=-1", "seed"}));
  // perturb values that wrote absurd logs.
  for (const auto& [name, args, opt] :
       {std::tuple{"perturb_noise_1e300", "--odom-noise 1e300,0,0,0", "--odom-noise"},
        std::tuple{"perturb_glitch_1e300_m",
                   "--odom-noise 0.01,0,0.01,0 --translation-glitch 1,1e300",
                   "--translation-glitch"},
        std::tuple{"perturb_laser_offset_1e300", "--odom-noise 0.01,0,0.01,0 --laser-offset 1e300",
                   "--laser-offset"},
        std::tuple{"perturb_scale_bias_1e300", "--odom-noise 0.01,0,0.01,0 --scale-bias 1e300",
                   "--scale-bias"},
        std::tuple{"perturb_yaw_drift_1e6", "--odom-noise 0.01,0,0.01,0 --yaw-drift 1e6",
                   "--yaw-drift"},
        std::tuple{"perturb_thinning_keeps_one_scan",
                   "--odom-noise 0.01,0,0.01,0 --min-scan-gap 1e300", "kept 1 of"}}) {
    const std::string a = args;
    c.push_back(error_case(name, 2,
                           [a](const Env& e) {
                             return "perturb --log " + e.b.log + " " + a +
                                    " --seed 1 --out p/raw.log --truth-out p/truth.tum";
                           },
                           {opt}));
  }
  return c;
}

}  // namespace pgmcl::hostile
