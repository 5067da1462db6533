// Corpus cases: the first round's inputs (issue 6), still clear errors or counted skips.

#include <gtest/gtest.h>

#include <filesystem>

#include "hostile_corpus.hpp"
#include "hostile_util.hpp"

namespace pgmcl::hostile {

namespace fs = std::filesystem;

std::vector<Case> first_round_cases() {
  std::vector<Case> c;
  const auto with_line = [](const std::string& extra) {
    return [extra](const Env& e) {
      std::vector<std::string> l = e.log_lines();
      l.insert(l.begin() + 40, extra);
      return e.localize("", e.write("l.log", join(l)));
    };
  };
  c.push_back(accepted_case("log_nan_and_negative_ranges", [](const Env& e) {
    std::vector<std::string> l;
    for (const std::string& s : e.log_lines()) {
      std::vector<std::string> w = words(s);
      if (w[0] == "FLASER") w[5] = "nan", w[6] = "-1", w[7] = "inf";
      l.push_back(join_words(w));
    }
    return e.localize("", e.write("l.log", join(l)));
  }));
  c.push_back(warning_case("log_malformed_line", with_line("FLASER 180 1 2 oops"),
                           {"dropped 1 malformed line", "l.log:41"}));
  c.push_back(warning_case("log_nul_bytes", with_line(std::string("ODOM 1 2 \0 3", 12)),
                           {"malformed line"}));
  c.push_back(warning_case("log_beam_count_disagrees",
                           with_line("FLASER 5 1 2 3 4 0 0 0 0 0 0 1 h 1"), {"num_readings"}));
  c.push_back(error_case("log_malformed_line_strict", 1,
                         [](const Env& e) {
                           std::vector<std::string> l = e.log_lines();
                           l.insert(l.begin() + 40, "ODOM 1 2 x 0 0 0 5 h 5");
                           return e.localize("--strict", e.write("l.log", join(l)));
                         },
                         {"l.log:41", "theta"}));
  c.push_back(error_case("log_truncated_gzip", 1,
                         [](const Env& e) {
                           std::string gz = testkit::read_text(e.b.raw);
                           gz.resize(gz.size() / 2);
                           return e.localize("", e.write("cut.log.gz", gz));
                         },
                         {"cut.log.gz"}));
  c.push_back(warning_case("log_stamps_go_backwards",
                           [](const Env& e) {
                             return e.localize(
                                 "", e.write("b.log", join(restamp(e.log_lines(), [](double t) {
                                               return t > 60.0 && t < 70.0 ? t - 30.0 : t;
                                             }))));
                           },
                           {"stamped before the previous one"}));
  // A log without a scan with odometry is bad input (exit 1), not a bad command line.
  c.push_back(error_case("log_without_odometry", 1,
                         [](const Env& e) {
                           e.write("raw.log", "RAWLASER1 0 -1.5 3 1.5 8 0.01 0 3 1 2 3 0 1 h 1\n");
                           return e.localize("", "raw.log");
                         },
                         {"no laser scan with odometry"}));
  c.push_back(error_case("log_empty", 1,
                         [](const Env& e) { return e.localize("", e.write("e.log", "")); },
                         {"no laser scan with odometry"}));
  c.push_back(accepted_case("log_crlf_line_ends", [](const Env& e) {
    std::string text;
    for (const std::string& s : e.log_lines()) text += s + "\r\n";
    return e.localize("", e.write("crlf.log", text));
  }));
  c.push_back(error_case(
      "truth_bad_quaternion", 1,
      [](const Env& e) { return e.localize("--truth " + e.write("t.tum", "1 0 0 0 0 0 0 0\n")); },
      {"t.tum:1", "quaternion"}));
  c.push_back(error_case(
      "truth_nan", 1,
      [](const Env& e) { return e.localize("--truth " + e.write("t.tum", "1 nan 0 0 0 0 0 1\n")); },
      {"t.tum:1"}));
  c.push_back(error_case("config_unknown_key", 1,
                         localize_with_config("filter:\n  particels: 100\n"),
                         {"cfg.yaml:2", "particels", "particles"}));
  c.push_back(error_case("config_not_yaml", 1, localize_with_config("filter: [\n"), {"cfg.yaml"}));
  c.push_back(bad_setting("set_unknown_key", "filter.particle=10", {"filter.particle"}));
  c.push_back(bad_setting("set_not_a_number", "filter.particles=many", {"filter.particles"}));
  c.push_back(error_case(
      "map_missing_resolution", 1,
      [](const Env& e) { return e.localize("", "", e.map_yaml("m.yaml", "origin: [0, 0, 0]\n")); },
      {"m.yaml", "resolution", "missing"}));
  c.push_back(error_case("map_thresholds_swapped", 1,
                         [](const Env& e) {
                           return e.localize(
                               "", "",
                               e.map_yaml("m.yaml",
                                          "resolution: 0.05\norigin: [0, 0, 0]\n"
                                          "occupied_thresh: 0.1\nfree_thresh: 0.6\n"));
                         },
                         {"m.yaml", "free_thresh"}));
  c.push_back(error_case("map_pgm_truncated", 1,
                         [](const Env& e) {
                           std::string pgm = testkit::read_text(e.b.image);
                           pgm.resize(pgm.size() / 3);
                           e.write("cut.pgm", pgm);
                           e.write("m.yaml", "image: cut.pgm\n" + map_keys(kIntelOrigin));
                           return e.localize("", "", "m.yaml");
                         },
                         {"cut.pgm"}));
  c.push_back(error_case("relations_garbage", 1,
                         [](const Env& e) {
                           return e.localize("--relations " +
                                             e.write("r.txt", "this is not a relation\n"));
                         },
                         {"r.txt:1"}));
  c.push_back(error_case("eval_estimate_garbage", 1,
                         [](const Env& e) {
                           return "eval --estimate " + e.write("e.tum", "1 2 3\n") + " --truth " +
                                  e.b.truth;
                         },
                         {"e.tum:1"}));
  c.push_back(error_case("eval_no_overlap", 1,
                         [](const Env& e) {
                           return "eval --estimate " + e.write("e.tum", "1 0 0 0 0 0 0 1\n") +
                                  " --truth " + e.b.truth;
                         },
                         {"no estimate pose matched"}));
  c.push_back(error_case("unknown_command", 2, [](const Env&) { return std::string("localise"); },
                         {"unknown command 'localise'"}));
  c.push_back(accepted_case(
      "baseline_run_is_clean", [](const Env& e) { return e.localize("--truth " + e.b.truth); },
      [](const Env& e, const RunResult&) {
        expect_final_pose_near(e, 0.3);
        EXPECT_TRUE(fs::exists(e.path("out/error.png")));
      }));
  return c;
}

}  // namespace pgmcl::hostile
