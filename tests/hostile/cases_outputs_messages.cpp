// Corpus cases: outputs (in == out refused, all or nothing, re-runs, folders checked up
// front), messages that name the real culprit, and the first round's inputs (issue 6).

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>

#include "hostile_corpus.hpp"
#include "hostile_util.hpp"
#include "pgmcl/map_io/map_io.hpp"

namespace pgmcl::hostile {
namespace {

namespace fs = std::filesystem;

/// Copies a base file into the case folder.
std::string copy(const Env& e, const std::string& from, const std::string& name) {
  fs::create_directories(fs::path(e.path(name)).parent_path());
  fs::copy_file(from, e.path(name), fs::copy_options::overwrite_existing);
  return e.path(name);
}

/// A complete earlier run (with ground truth) in out/, for the re-run cases.
void earlier_run(const Env& e) {
  const RunResult r = run_pgmcl(e.localize("--truth " + e.b.truth), e.dir.path().string());
  ASSERT_EQ(r.code, 0) << r.err;
  ASSERT_TRUE(fs::exists(e.path("out/error.png")));
}

std::string map_keys(const std::string& origin, const std::string& resolution = "0.05") {
  return "resolution: " + resolution + "\norigin: " + origin +
         "\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";
}

const std::string kIntelOrigin = "[-20.9, -26.7, 0]";

std::string perturb_args(const Env& e, const std::string& outs) {
  return "perturb --log " + e.b.log + " --odom-noise 0.01,0,0.01,0 --seed 1 " + outs;
}

}  // namespace

std::vector<Case> output_cases() {
  std::vector<Case> c;
  // An output that is an input, by name, by another spelling, or by link.
  c.push_back({"eval_out_is_truth",
               Expect::kError,
               2,
               [](const Env& e) {
                 copy(e, e.b.truth, "truth.tum");
                 copy(e, e.b.truth, "est.tum");
                 return std::string("eval --estimate est.tum --truth truth.tum --out truth.tum");
               },
               {"--out", "is also the input --truth"}});
  c.push_back({"eval_out_is_estimate",
               Expect::kError,
               2,
               [](const Env& e) {
                 copy(e, e.b.truth, "est.tum");
                 return "eval --estimate est.tum --truth " + e.b.truth + " --out est.tum";
               },
               {"is also the input --estimate"}});
  c.push_back({"eval_out_is_truth_other_spelling",
               Expect::kError,
               2,
               [](const Env& e) {
                 copy(e, e.b.truth, "truth.tum");
                 copy(e, e.b.truth, "est.tum");
                 fs::create_directories(e.path("sub"));
                 return std::string(
                     "eval --estimate est.tum --truth truth.tum --out ./sub/../truth.tum");
               },
               {"is also the input --truth"}});
  c.push_back({"eval_out_symlink_to_truth",
               Expect::kError,
               2,
               [](const Env& e) {
                 copy(e, e.b.truth, "truth.tum");
                 copy(e, e.b.truth, "est.tum");
                 fs::create_symlink("truth.tum", e.path("link.yaml"));
                 return std::string("eval --estimate est.tum --truth truth.tum --out link.yaml");
               },
               {"is also the input --truth"}});
  c.push_back({"eval_out_hardlink_to_truth",
               Expect::kError,
               2,
               [](const Env& e) {
                 copy(e, e.b.truth, "truth.tum");
                 copy(e, e.b.truth, "est.tum");
                 fs::create_hard_link(e.path("truth.tum"), e.path("hard.yaml"));
                 return std::string("eval --estimate est.tum --truth truth.tum --out hard.yaml");
               },
               {"is also the input --truth"}});
  c.push_back({"map_out_is_log",
               Expect::kError,
               2,
               [](const Env& e) {
                 copy(e, e.b.log, "l.log");
                 return std::string("map --log l.log --out l.log");
               },
               {"--out", "is also the input --log"}});
  c.push_back({"map_out_named_like_its_image",
               Expect::kError,
               2,
               [](const Env& e) { return "map --log " + e.b.log + " --out m/map.pgm"; },
               {"would be one file", ".yaml"}});
  c.push_back({"map_image_not_an_image_name",
               Expect::kError,
               2,
               [](const Env& e) {
                 copy(e, e.b.log, "l.log");
                 return std::string("map --log l.log --out m.yaml --image l.log");
               },
               {"--image"}});
  c.push_back({"perturb_out_equals_truth_out",
               Expect::kError,
               2,
               [](const Env& e) { return perturb_args(e, "--out x.log --truth-out x.log"); },
               {"is also the output --out"}});
  c.push_back({"perturb_out_equals_deprecated_truth",
               Expect::kError,
               2,
               [](const Env& e) { return perturb_args(e, "--out x.log --truth x.log"); },
               {"--truth", "is also the output --out"}});
  c.push_back({"perturb_out_is_log",
               Expect::kError,
               2,
               [](const Env& e) {
                 copy(e, e.b.log, "l.log");
                 return std::string(
                     "perturb --log l.log --odom-noise 0.01,0,0.01,0 --seed 1 "
                     "--out l.log --truth-out t.tum");
               },
               {"is also the input --log"}});
  c.push_back({"perturb_truth_out_is_log",
               Expect::kError,
               2,
               [](const Env& e) {
                 copy(e, e.b.log, "l.log");
                 return std::string(
                     "perturb --log l.log --odom-noise 0.01,0,0.01,0 --seed 1 "
                     "--out o.log --truth-out l.log");
               },
               {"--truth-out", "is also the input --log"}});
  c.push_back({"localize_truth_is_an_output",
               Expect::kError,
               2,
               [](const Env& e) {
                 copy(e, e.b.truth, "out/trajectory.tum");
                 return e.localize("--truth out/trajectory.tum");
               },
               {"trajectory.tum is also the input --truth"}});
  c.push_back({"localize_map_image_is_an_output",
               Expect::kError,
               2,
               [](const Env& e) {
                 copy(e, e.b.image, "out/overlay.png");
                 e.write("m.yaml", "image: out/overlay.png\n" + map_keys(kIntelOrigin));
                 return e.localize("", "", "m.yaml");
               },
               {"overlay.png is also the input --map's image"}});
  c.push_back({"localize_config_is_an_output",
               Expect::kError,
               2,
               [](const Env& e) {
                 e.write("out/config.yaml", "threads: 1\n");
                 return e.localize("--config out/config.yaml");
               },
               {"is also the input --config"}});
  c.push_back({"simulate_out_is_scenario",
               Expect::kError,
               2,
               [](const Env& e) {
                 copy(e, PGMCL_SOURCE_DIR "/configs/scenarios/lab.yaml", "lab.yaml");
                 return std::string("simulate lab.yaml --out lab.yaml");
               },
               {"is also the input scenario"}});
  c.push_back({"run_truth_is_an_output",
               Expect::kError,
               2,
               [](const Env& e) {
                 copy(e, e.b.truth, "out/trajectory.tum");
                 e.write("exp.yaml", "name: x\nmap: " + e.b.map + "\ndata:\n  log: " + e.b.log +
                                         "\n  truth: out/trajectory.tum\nout: out\n");
                 return std::string("run exp.yaml --quiet");
               },
               {"is also the input data.truth"}});
  c.push_back({"perturb_map_out_is_input",
               Expect::kError,
               2,
               [](const Env& e) {
                 copy(e, e.b.map, "map.yaml");
                 copy(e, e.b.image, "map.pgm");
                 return std::string("perturb-map --map map.yaml --out map.yaml --thicken 1");
               },
               {"is also the input --map"}});
  // Re-runs replace the whole set or nothing.
  c.push_back({"rerun_without_truth_drops_error_png",
               Expect::kAccepted,
               0,
               [](const Env& e) {
                 earlier_run(e);
                 return e.localize("");
               },
               {},
               [](const Env& e, const RunResult&) {
                 EXPECT_FALSE(fs::exists(e.path("out/error.png")));
                 EXPECT_EQ(testkit::read_text(e.path("out/metrics.yaml")).find("ate_rmse_m"),
                           std::string::npos);
               }});
  c.push_back({"failed_rerun_bad_log_keeps_earlier_set",
               Expect::kError,
               1,
               [](const Env& e) {
                 earlier_run(e);
                 std::vector<std::string> l = e.log_lines();
                 l.push_back("FLASER 3 1 2");
                 return e.localize("--strict", e.write("bad.log", join(l)));
               },
               {"bad.log:"}});
  c.push_back({"failed_rerun_bad_map_keeps_earlier_set",
               Expect::kError,
               1,
               [](const Env& e) {
                 earlier_run(e);
                 return e.localize("", "",
                                   e.map_yaml("raw.yaml", "mode: raw\n" + map_keys(kIntelOrigin)));
               },
               {"no occupied cell"}});
  c.push_back({"failed_rerun_scan_rejected_keeps_earlier_set",
               Expect::kError,
               1,
               [](const Env& e) {
                 earlier_run(e);
                 return e.localize("--set likelihood.expected_beams=181");
               },
               {"rejected by the filter"}});
  c.push_back({"rerun_keeps_other_files_in_the_folder",
               Expect::kAccepted,
               0,
               [](const Env& e) {
                 e.write("out/notes.txt", "mine\n");
                 return e.localize("");
               },
               {},
               [](const Env& e, const RunResult&) {
                 EXPECT_EQ(testkit::read_text(e.path("out/notes.txt")), "mine\n");
               }});
  c.push_back({"perturb_map_rerun_png_then_pgm",
               Expect::kAccepted,
               0,
               [](const Env& e) {
                 const RunResult r = run_pgmcl("perturb-map --map " + e.b.map +
                                                   " --out p/m.yaml --thicken 1 --blur 1 --quiet",
                                               e.dir.path().string());
                 EXPECT_EQ(r.code, 0) << r.err;
                 EXPECT_TRUE(fs::exists(e.path("p/m.png")));
                 return "perturb-map --map " + e.b.map + " --out p/m.yaml --thicken 1 --quiet";
               },
               {},
               [](const Env& e, const RunResult&) {
                 EXPECT_FALSE(fs::exists(e.path("p/m.png")));
                 EXPECT_TRUE(fs::exists(e.path("p/m.pgm")));
                 EXPECT_NO_THROW((void)maps::load_map(e.path("p/m.yaml")));
               }});
  // Output folders are checked before any work.
  c.push_back({"out_folder_under_a_file",
               Expect::kError,
               1,
               [](const Env& e) {
                 e.write("f", "a file\n");
                 std::vector<std::string> l = e.log_lines();
                 l.push_back("FLASER 3 1 2");
                 // The log would fail too (--strict): the folder must be what is reported.
                 return e.localize("--strict --out f/sub", e.write("bad.log", join(l)));
               },
               {"--out", "cannot create the folder"}});
  c.push_back({"out_is_an_existing_file",
               Expect::kError,
               1,
               [](const Env& e) {
                 e.write("f", "a file\n");
                 return e.localize("--out f");
               },
               {"--out", "cannot create the folder"}});
  c.push_back({"localize_out_empty",
               Expect::kError,
               2,
               [](const Env& e) { return e.localize("--out ''"); },
               {"--out", "empty"}});
  c.push_back({"eval_out_is_a_folder",
               Expect::kError,
               2,
               [](const Env& e) {
                 fs::create_directories(e.path("d"));
                 return "eval --estimate " + e.b.truth + " --truth " + e.b.truth + " --out d";
               },
               {"--out", "is a folder"}});
  c.push_back({"eval_out_full_disk",
               Expect::kError,
               1,
               [](const Env& e) {
                 return "eval --estimate " + e.b.truth + " --truth " + e.b.truth +
                        " --out /dev/full";
               },
               {"/dev/full", "No space left on device"}});
  c.push_back({"eval_out_dev_null",
               Expect::kAccepted,
               0,
               [](const Env& e) {
                 return "eval --estimate " + e.b.truth + " --truth " + e.b.truth +
                        " --out /dev/null";
               },
               {}});
  c.push_back({"perturb_second_output_unwritable_writes_neither",
               Expect::kError,
               1,
               [](const Env& e) {
                 e.write("f", "a file\n");
                 return perturb_args(e, "--out p/raw.log --truth-out f/t.tum");
               },
               {"--truth-out", "cannot create the folder"}});
  c.push_back({"map_out_in_new_nested_folder",
               Expect::kAccepted,
               0,
               [](const Env& e) { return "map --log " + e.b.log + " --out a/b/c/m.yaml --quiet"; },
               {},
               [](const Env& e, const RunResult&) {
                 EXPECT_GT(maps::load_map(e.path("a/b/c/m.yaml")).size(), 0u);
               }});
  return c;
}

std::vector<Case> message_cases() {
  std::vector<Case> c;
  c.push_back({"map_origin_1e300",
               Expect::kError,
               1,
               [](const Env& e) {
                 return e.localize("", "", e.map_yaml("o.yaml", map_keys("[1.0e300, 0, 0]")));
               },
               {"o.yaml:3", "origin", "1e+300"}});
  c.push_back({"map_origin_1e9",
               Expect::kError,
               1,
               [](const Env& e) {
                 return e.localize("", "", e.map_yaml("o.yaml", map_keys("[0, -1.0e9, 0]")));
               },
               {"origin"}});
  c.push_back({"map_origin_utm_scale_accepted",
               Expect::kAccepted,
               0,
               [](const Env& e) {
                 const Pose2 s = e.b.start;
                 return e.localize(
                     "--init " + pose_text({s.x + 500020.9, s.y + 5000026.7, s.theta}), "",
                     e.map_yaml("o.yaml", map_keys("[500000, 5000000, 0]")));
               },
               {}});
  c.push_back({"init_1e300",
               Expect::kError,
               2,
               [](const Env& e) { return e.localize("--init 1e300,0,0"); },
               {"--init", "outside the map"}});
  c.push_back({"init_covariance_1e300",
               Expect::kError,
               2,
               [](const Env& e) { return e.localize("--init 0.6,0,0,1e300,1e300,1e300"); },
               {"--init", "SX = 1e+300"}});
  c.push_back({"init_sigma_theta_1e9",
               Expect::kError,
               2,
               [](const Env& e) { return e.localize("--init 0.6,0,0,0.1,0.1,1e9"); },
               {"--init", "STH"}});
  c.push_back({"init_sigma_negative",
               Expect::kError,
               2,
               [](const Env& e) { return e.localize("--init 0.6,0,0,-1,0.1,0.1"); },
               {"--init", "must be > 0"}});
  c.push_back({"experiment_init_sigma_1e300",
               Expect::kError,
               2,
               [](const Env& e) {
                 e.write("exp.yaml", "name: x\nmap: " + e.b.map + "\ndata:\n  log: " + e.b.log +
                                         "\ninit: {pose: [0.6, 0, 0], sigma: [1.0e300, 1, 1]}\n"
                                         "out: out\n");
                 return std::string("run exp.yaml --quiet");
               },
               {"exp.yaml: init", "SX"}});
  c.push_back({"map_resolution_1e300",
               Expect::kError,
               1,
               [](const Env& e) {
                 return e.localize("", "", e.map_yaml("r.yaml", map_keys(kIntelOrigin, "1.0e300")));
               },
               {"r.yaml:2", "resolution", "1e+300"}});
  c.push_back(
      {"model_mismatch_1e200",
       Expect::kError,
       1,
       [](const Env& e) { return e.localize("--set likelihood.beam.model_mismatch=1e200"); },
       {"--set likelihood.beam.model_mismatch=1e200", "[0, 10]"}});
  c.push_back({"sigma_along_1e200",
               Expect::kError,
               1,
               [](const Env& e) { return e.localize("--set likelihood.beam.sigma_along=1e200"); },
               {"likelihood.beam.sigma_along", "(0, 10]"}});
  c.push_back({"reach_sigmas_1e9",
               Expect::kError,
               1,
               [](const Env& e) { return e.localize("--set likelihood.table.reach_sigmas=1e9"); },
               {"likelihood.table.reach_sigmas"}});
  c.push_back(
      {"kernel_reach_names_model_mismatch",
       Expect::kError,
       2,
       [](const Env& e) {
         return e.localize(
             "--set likelihood.beam.model_mismatch=9 --set likelihood.table.reach_sigmas=50");
       },
       {"kernel would reach", "likelihood.beam.model_mismatch = 9 m"}});
  c.push_back({"kernel_reach_from_config_file",
               Expect::kError,
               2,
               [](const Env& e) {
                 e.write("cfg.yaml",
                         "likelihood:\n  beam: {sigma_along: 8}\n  table: {reach_sigmas: 20}\n");
                 return e.localize("--config cfg.yaml");
               },
               {"kernel would reach", "likelihood.beam.sigma_along = 8 m"}});
  c.push_back({"image_is_a_folder",
               Expect::kError,
               1,
               [](const Env& e) {
                 fs::create_directories(e.path("img"));
                 e.write("m.yaml", "image: img\n" + map_keys(kIntelOrigin));
                 return e.localize("", "", "m.yaml");
               },
               {"img", "is a folder", "m.yaml:1"}});
  c.push_back({"image_is_dev_zero",
               Expect::kError,
               1,
               [](const Env& e) {
                 e.write("m.yaml", "image: /dev/zero\n" + map_keys(kIntelOrigin));
                 return e.localize("", "", "m.yaml");
               },
               {"/dev/zero", "not a regular file"}});
  c.push_back({"image_is_a_fifo",
               Expect::kError,
               1,
               [](const Env& e) {
                 EXPECT_EQ(::mkfifo(e.path("pipe.pgm").c_str(), 0600), 0);
                 e.write("m.yaml", "image: pipe.pgm\n" + map_keys(kIntelOrigin));
                 return e.localize("", "", "m.yaml");
               },
               {"pipe.pgm", "not a regular file"}});
  c.push_back({"image_missing",
               Expect::kError,
               1,
               [](const Env& e) {
                 e.write("m.yaml", "image: nowhere.pgm\n" + map_keys(kIntelOrigin));
                 return e.localize("", "", "m.yaml");
               },
               {"nowhere.pgm", "cannot open"}});
  c.push_back({"image_is_the_yaml",
               Expect::kError,
               1,
               [](const Env& e) {
                 e.write("m.yaml", "image: m.yaml\n" + map_keys(kIntelOrigin));
                 return e.localize("", "", "m.yaml");
               },
               {"not a PGM/PPM or PNG"}});
  c.push_back({"image_empty_file",
               Expect::kError,
               1,
               [](const Env& e) {
                 e.write("empty.pgm", "");
                 e.write("m.yaml", "image: empty.pgm\n" + map_keys(kIntelOrigin));
                 return e.localize("", "", "m.yaml");
               },
               {"empty.pgm", "empty"}});
  c.push_back({"map_given_as_its_image",
               Expect::kError,
               1,
               [](const Env& e) { return e.localize("", "", e.b.image); },
               {"map.pgm", "is an image", "not a map YAML"}});
  c.push_back({"log_given_as_an_image",
               Expect::kError,
               2,
               [](const Env& e) { return e.localize("", e.b.image); },
               {"no laser scan with odometry"}});
  c.push_back({"log_is_a_folder",
               Expect::kError,
               2,
               [](const Env& e) {
                 fs::create_directories(e.path("d.log"));
                 return e.localize("", "d.log");
               },
               {"--log", "directory"}});
  c.push_back({"kernel_sigma_1e300",
               Expect::kError,
               2,
               [](const Env&) { return std::string("kernel --sigma-x 1e300"); },
               {"--sigma-x"}});
  c.push_back({"kernel_cell_1e_minus_300",
               Expect::kError,
               2,
               [](const Env&) { return std::string("kernel --cell 1e-300"); },
               {"--cell"}});
  c.push_back(
      {"kernel_radius_too_small_warns",
       Expect::kWarning,
       0,
       [](const Env&) { return std::string("kernel --sigma-x 5000 --sigma-y 5000 --cell 10"); },
       {"of the kernel's mass", "--radius"}});
  c.push_back(
      {"map_command_resolution_1e300",
       Expect::kError,
       2,
       [](const Env& e) { return "map --log " + e.b.log + " --resolution 1e300 --out m.yaml"; },
       {"--resolution", "1000"}});
  c.push_back({"map_command_every_beam_no_return",
               Expect::kError,
               1,
               [](const Env& e) {
                 e.write("n.log",
                         "FLASER 3 5 5 5 0 0 0 0 0 0 1 h 1\nFLASER 3 5 5 5 1 0 0 1 0 0 2 h 2\n");
                 return std::string("map --log n.log --out m.yaml");
               },
               {"no occupied cell", "nothing was written"}});
  c.push_back(
      {"perturb_map_erase_everything",
       Expect::kError,
       1,
       [](const Env& e) { return "perturb-map --map " + e.b.map + " --out p.yaml --erase 1,1"; },
       {"no occupied cell"}});
  c.push_back({"perturb_map_erase_block_1e300",
               Expect::kError,
               1,
               [](const Env& e) {
                 return "perturb-map --map " + e.b.map + " --out p.yaml --erase 0.5,1e300";
               },
               {"no occupied cell"}});
  return c;
}

std::vector<Case> first_round_cases() {
  std::vector<Case> c;
  const auto with_line = [](const std::string& extra) {
    return [extra](const Env& e) {
      std::vector<std::string> l = e.log_lines();
      l.insert(l.begin() + 40, extra);
      return e.localize("", e.write("l.log", join(l)));
    };
  };
  c.push_back({"log_nan_and_negative_ranges",
               Expect::kAccepted,
               0,
               [](const Env& e) {
                 std::vector<std::string> l;
                 for (const std::string& s : e.log_lines()) {
                   std::vector<std::string> w = words(s);
                   if (w[0] == "FLASER") w[5] = "nan", w[6] = "-1", w[7] = "inf";
                   l.push_back(join_words(w));
                 }
                 return e.localize("", e.write("l.log", join(l)));
               },
               {}});
  c.push_back({"log_malformed_line",
               Expect::kWarning,
               0,
               with_line("FLASER 180 1 2 oops"),
               {"dropped 1 malformed line", "l.log:41"}});
  c.push_back({"log_nul_bytes",
               Expect::kWarning,
               0,
               with_line(std::string("ODOM 1 2 \0 3", 12)),
               {"malformed line"}});
  c.push_back({"log_beam_count_disagrees",
               Expect::kWarning,
               0,
               with_line("FLASER 5 1 2 3 4 0 0 0 0 0 0 1 h 1"),
               {"num_readings"}});
  c.push_back({"log_malformed_line_strict",
               Expect::kError,
               1,
               [](const Env& e) {
                 std::vector<std::string> l = e.log_lines();
                 l.insert(l.begin() + 40, "ODOM 1 2 x 0 0 0 5 h 5");
                 return e.localize("--strict", e.write("l.log", join(l)));
               },
               {"l.log:41", "theta"}});
  c.push_back({"log_truncated_gzip",
               Expect::kError,
               1,
               [](const Env& e) {
                 std::string gz = testkit::read_text(e.b.raw);
                 gz.resize(gz.size() / 2);
                 return e.localize("", e.write("cut.log.gz", gz));
               },
               {"cut.log.gz"}});
  c.push_back({"log_stamps_go_backwards",
               Expect::kWarning,
               0,
               [](const Env& e) {
                 return e.localize("", e.write("b.log", join(restamp(e.log_lines(), [](double t) {
                                                 return t > 60.0 && t < 70.0 ? t - 30.0 : t;
                                               }))));
               },
               {"stamped before the previous one"}});
  c.push_back({"log_without_odometry",
               Expect::kError,
               2,
               [](const Env& e) {
                 e.write("raw.log", "RAWLASER1 0 -1.5 3 1.5 8 0.01 0 3 1 2 3 0 1 h 1\n");
                 return e.localize("", "raw.log");
               },
               {"no laser scan with odometry"}});
  c.push_back({"log_empty",
               Expect::kError,
               2,
               [](const Env& e) { return e.localize("", e.write("e.log", "")); },
               {"no laser scan with odometry"}});
  c.push_back({"log_crlf_line_ends",
               Expect::kAccepted,
               0,
               [](const Env& e) {
                 std::string text;
                 for (const std::string& s : e.log_lines()) text += s + "\r\n";
                 return e.localize("", e.write("crlf.log", text));
               },
               {}});
  c.push_back(
      {"truth_bad_quaternion",
       Expect::kError,
       1,
       [](const Env& e) { return e.localize("--truth " + e.write("t.tum", "1 0 0 0 0 0 0 0\n")); },
       {"t.tum:1", "quaternion"}});
  c.push_back({"truth_nan",
               Expect::kError,
               1,
               [](const Env& e) {
                 return e.localize("--truth " + e.write("t.tum", "1 nan 0 0 0 0 0 1\n"));
               },
               {"t.tum:1"}});
  c.push_back({"config_unknown_key",
               Expect::kError,
               1,
               [](const Env& e) {
                 e.write("cfg.yaml", "filter:\n  particels: 100\n");
                 return e.localize("--config cfg.yaml");
               },
               {"cfg.yaml:2", "particels", "particles"}});
  c.push_back({"config_not_yaml",
               Expect::kError,
               1,
               [](const Env& e) {
                 e.write("cfg.yaml", "filter: [\n");
                 return e.localize("--config cfg.yaml");
               },
               {"cfg.yaml"}});
  c.push_back({"set_unknown_key",
               Expect::kError,
               1,
               [](const Env& e) { return e.localize("--set filter.particle=10"); },
               {"filter.particle"}});
  c.push_back({"set_not_a_number",
               Expect::kError,
               1,
               [](const Env& e) { return e.localize("--set filter.particles=many"); },
               {"filter.particles"}});
  c.push_back(
      {"map_missing_resolution",
       Expect::kError,
       1,
       [](const Env& e) { return e.localize("", "", e.map_yaml("m.yaml", "origin: [0, 0, 0]\n")); },
       {"m.yaml", "resolution", "missing"}});
  c.push_back({"map_thresholds_swapped",
               Expect::kError,
               1,
               [](const Env& e) {
                 return e.localize("", "",
                                   e.map_yaml("m.yaml",
                                              "resolution: 0.05\norigin: [0, 0, 0]\n"
                                              "occupied_thresh: 0.1\nfree_thresh: 0.6\n"));
               },
               {"m.yaml", "free_thresh"}});
  c.push_back({"map_pgm_truncated",
               Expect::kError,
               1,
               [](const Env& e) {
                 std::string pgm = testkit::read_text(e.b.image);
                 pgm.resize(pgm.size() / 3);
                 e.write("cut.pgm", pgm);
                 e.write("m.yaml", "image: cut.pgm\n" + map_keys(kIntelOrigin));
                 return e.localize("", "", "m.yaml");
               },
               {"cut.pgm"}});
  c.push_back({"relations_garbage",
               Expect::kError,
               1,
               [](const Env& e) {
                 return e.localize("--relations " + e.write("r.txt", "this is not a relation\n"));
               },
               {"r.txt:1"}});
  c.push_back({"eval_estimate_garbage",
               Expect::kError,
               1,
               [](const Env& e) {
                 return "eval --estimate " + e.write("e.tum", "1 2 3\n") + " --truth " + e.b.truth;
               },
               {"e.tum:1"}});
  c.push_back({"eval_no_overlap",
               Expect::kError,
               1,
               [](const Env& e) {
                 return "eval --estimate " + e.write("e.tum", "1 0 0 0 0 0 0 1\n") + " --truth " +
                        e.b.truth;
               },
               {"no estimate pose matched"}});
  c.push_back({"unknown_command",
               Expect::kError,
               2,
               [](const Env&) { return std::string("localise"); },
               {"unknown command 'localise'"}});
  c.push_back({"baseline_run_is_clean",
               Expect::kAccepted,
               0,
               [](const Env& e) { return e.localize("--truth " + e.b.truth); },
               {},
               [](const Env& e, const RunResult&) {
                 expect_final_pose_near(e, 0.3);
                 EXPECT_TRUE(fs::exists(e.path("out/error.png")));
               }});
  return c;
}

}  // namespace pgmcl::hostile
