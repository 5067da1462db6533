// Corpus cases: messages that name the real culprit, and files of the wrong kind for
// their option.

#include <gtest/gtest.h>

#include <filesystem>

#include "hostile_corpus.hpp"
#include "hostile_util.hpp"

namespace pgmcl::hostile {

namespace fs = std::filesystem;

std::vector<Case> message_cases() {
  std::vector<Case> c;
  c.push_back(error_case("map_origin_1e300", 1,
                         [](const Env& e) {
                           return e.localize("", "",
                                             e.map_yaml("o.yaml", map_keys("[1.0e300, 0, 0]")));
                         },
                         {"o.yaml:3", "origin", "1e+300"}));
  c.push_back(error_case("map_origin_1e9", 1,
                         [](const Env& e) {
                           return e.localize("", "",
                                             e.map_yaml("o.yaml", map_keys("[0, -1.0e9, 0]")));
                         },
                         {"origin"}));
  c.push_back(accepted_case("map_origin_utm_scale_accepted", [](const Env& e) {
    const Pose2 s = e.b.start;
    return e.localize("--init " + pose_text({s.x + 500020.9, s.y + 5000026.7, s.theta}), "",
                      e.map_yaml("o.yaml", map_keys("[500000, 5000000, 0]")));
  }));
  c.push_back(error_case("init_1e300", 2, localize_with("--init 1e300,0,0"),
                         {"--init", "outside the map"}));
  c.push_back(error_case("init_covariance_1e300", 2,
                         localize_with("--init 0.6,0,0,1e300,1e300,1e300"),
                         {"--init", "SX = 1e+300"}));
  c.push_back(error_case("init_sigma_theta_1e9", 2, localize_with("--init 0.6,0,0,0.1,0.1,1e9"),
                         {"--init", "STH"}));
  c.push_back(error_case("init_sigma_negative", 2, localize_with("--init 0.6,0,0,-1,0.1,0.1"),
                         {"--init", "must be > 0"}));
  c.push_back(error_case("experiment_init_sigma_1e300", 2,
                         [](const Env& e) {
                           e.write("exp.yaml",
                                   "name: x\nmap: " + e.b.map + "\ndata:\n  log: " + e.b.log +
                                       "\ninit: {pose: [0.6, 0, 0], sigma: [1.0e300, 1, 1]}\n"
                                       "out: out\n");
                           return std::string("run exp.yaml --quiet");
                         },
                         {"exp.yaml: init", "SX"}));
  c.push_back(error_case("map_resolution_1e300", 1,
                         [](const Env& e) {
                           return e.localize(
                               "", "", e.map_yaml("r.yaml", map_keys(kIntelOrigin, "1.0e300")));
                         },
                         {"r.yaml:2", "resolution", "1e+300"}));
  c.push_back(bad_setting("model_mismatch_1e200", "likelihood.beam.model_mismatch=1e200",
                          {"--set likelihood.beam.model_mismatch=1e200", "[0, 10]"}));
  c.push_back(bad_setting("sigma_along_1e200", "likelihood.beam.sigma_along=1e200",
                          {"likelihood.beam.sigma_along", "(0, 10]"}));
  c.push_back(bad_setting("reach_sigmas_1e9", "likelihood.table.reach_sigmas=1e9",
                          {"likelihood.table.reach_sigmas"}));
  c.push_back(error_case(
      "kernel_reach_names_model_mismatch", 2,
      localize_with(
          "--set likelihood.beam.model_mismatch=9 --set likelihood.table.reach_sigmas=50"),
      {"kernel would reach", "likelihood.beam.model_mismatch = 9 m"}));
  c.push_back(error_case(
      "kernel_reach_from_config_file", 2,
      localize_with_config("likelihood:\n  beam: {sigma_along: 8}\n  table: {reach_sigmas: 20}\n"),
      {"kernel would reach", "likelihood.beam.sigma_along = 8 m"}));
  c.push_back(error_case("image_is_a_folder", 1,
                         [](const Env& e) {
                           fs::create_directories(e.path("img"));
                           e.write("m.yaml", "image: img\n" + map_keys(kIntelOrigin));
                           return e.localize("", "", "m.yaml");
                         },
                         {"img", "is a folder", "m.yaml:1"}));
  c.push_back(error_case("image_is_dev_zero", 1,
                         localize_on_map_yaml("image: /dev/zero\n" + map_keys(kIntelOrigin)),
                         {"/dev/zero", "not a regular file"}));
  c.push_back(error_case("image_is_a_fifo", 1,
                         [](const Env& e) {
                           EXPECT_EQ(::mkfifo(e.path("pipe.pgm").c_str(), 0600), 0);
                           e.write("m.yaml", "image: pipe.pgm\n" + map_keys(kIntelOrigin));
                           return e.localize("", "", "m.yaml");
                         },
                         {"pipe.pgm", "not a regular file"}));
  c.push_back(error_case("image_missing", 1,
                         localize_on_map_yaml("image: nowhere.pgm\n" + map_keys(kIntelOrigin)),
                         {"nowhere.pgm", "cannot open"}));
  c.push_back(error_case("image_is_the_yaml", 1,
                         localize_on_map_yaml("image: m.yaml\n" + map_keys(kIntelOrigin)),
                         {"not a PGM/PPM or PNG"}));
  c.push_back(error_case("image_empty_file", 1,
                         [](const Env& e) {
                           e.write("empty.pgm", "");
                           e.write("m.yaml", "image: empty.pgm\n" + map_keys(kIntelOrigin));
                           return e.localize("", "", "m.yaml");
                         },
                         {"empty.pgm", "empty"}));
  // A file of the wrong kind for its option is a bad command line, named by the option.
  c.push_back(error_case("map_given_as_its_image", 2,
                         [](const Env& e) { return e.localize("", "", e.b.image); },
                         {"--map", "map.pgm", "is a PGM image", "not a map YAML"}));
  c.push_back(error_case("log_given_as_an_image", 2,
                         [](const Env& e) { return e.localize("", e.b.image); },
                         {"--log", "map.pgm", "is a PGM image", "not a CARMEN log"}));
  c.push_back(error_case("log_is_a_folder", 2,
                         [](const Env& e) {
                           fs::create_directories(e.path("d.log"));
                           return e.localize("", "d.log");
                         },
                         {"--log", "directory"}));
  c.push_back(error_case("kernel_sigma_1e300", 2,
                         [](const Env&) { return std::string("kernel --sigma-x 1e300"); },
                         {"--sigma-x"}));
  c.push_back(error_case("kernel_cell_1e_minus_300", 2,
                         [](const Env&) { return std::string("kernel --cell 1e-300"); },
                         {"--cell"}));
  c.push_back(warning_case(
      "kernel_radius_too_small_warns",
      [](const Env&) { return std::string("kernel --sigma-x 5000 --sigma-y 5000 --cell 10"); },
      {"of the kernel's mass", "--radius"}));
  c.push_back(error_case("map_command_resolution_1e300", 2,
                         map_base_log("--resolution 1e300 --out m.yaml"),
                         {"--resolution", "1000"}));
  // Under the 1000 m cap but coarser than localize accepts: refused before anything is written.
  c.push_back(
      error_case("map_command_resolution_10_m", 2, map_base_log("--resolution 10 --out m.yaml"),
                 {"--resolution 10 m", "x", "cells, too coarse for localize", "at most 7.5 m"}));
  c.push_back(error_case("map_command_resolution_999_m", 2,
                         map_base_log("--resolution 999 --out m.yaml"),
                         {"--resolution 999 m", "cells, too coarse for localize"}));
  c.push_back(error_case(
      "map_command_every_beam_no_return", 1,
      [](const Env& e) {
        e.write("n.log", "FLASER 3 5 5 5 0 0 0 0 0 0 1 h 1\nFLASER 3 5 5 5 1 0 0 1 0 0 2 h 2\n");
        return std::string("map --log n.log --out m.yaml");
      },
      {"no occupied cell", "nothing was written"}));
  c.push_back(error_case("perturb_map_erase_everything", 1,
                         perturb_base_map("--out p.yaml --erase 1,1"), {"no occupied cell"}));
  c.push_back(error_case("perturb_map_erase_block_1e300", 1,
                         perturb_base_map("--out p.yaml --erase 0.5,1e300"), {"no occupied cell"}));
  return c;
}

}  // namespace pgmcl::hostile
