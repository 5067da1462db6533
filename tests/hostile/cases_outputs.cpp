// Corpus cases: outputs. An output that is an input is refused, outputs are all or
// nothing, re-runs replace the whole set, and output folders are checked before any work.

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <functional>
#include <string>
#include <utility>

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

/// Copies the base file `file` to `name`, then runs `args` (which name the copy).
MakeArgs after_copy(const std::string Base::*file, std::string name, std::string args) {
  return [file, name = std::move(name), args = std::move(args)](const Env& e) {
    copy(e, e.b.*file, name);
    return args;
  };
}

/// eval of est.tum against truth.tum, both copies of the base truth, with `--out out`; `setup`
/// then makes whatever `out` names (a link, a folder).
MakeArgs eval_truth_copies(std::string out, std::function<void(const Env&)> setup = nullptr) {
  return [out = std::move(out), setup = std::move(setup)](const Env& e) {
    copy(e, e.b.truth, "truth.tum");
    copy(e, e.b.truth, "est.tum");
    if (setup) setup(e);
    return "eval --estimate est.tum --truth truth.tum --out " + out;
  };
}

/// A complete earlier run (with ground truth) in out/, for the re-run cases.
void earlier_run(const Env& e) {
  const RunResult r = run_pgmcl(e.localize("--truth " + e.b.truth), e.dir.path().string());
  ASSERT_EQ(r.code, 0) << r.err;
  ASSERT_TRUE(fs::exists(e.path("out/error.png")));
}

std::string perturb_args(const Env& e, const std::string& outs) {
  return "perturb --log " + e.b.log + " --odom-noise 0.01,0,0.01,0 --seed 1 " + outs;
}

}  // namespace

std::vector<Case> output_cases() {
  std::vector<Case> c;
  // An output that is an input, by name, by another spelling, or by link.
  c.push_back(error_case("eval_out_is_truth", 2, eval_truth_copies("truth.tum"),
                         {"--out", "is also the input --truth"}));
  c.push_back(error_case("eval_out_is_estimate", 2,
                         [](const Env& e) {
                           copy(e, e.b.truth, "est.tum");
                           return "eval --estimate est.tum --truth " + e.b.truth + " --out est.tum";
                         },
                         {"is also the input --estimate"}));
  c.push_back(
      error_case("eval_out_is_truth_other_spelling", 2,
                 eval_truth_copies("./sub/../truth.tum",
                                   [](const Env& e) { fs::create_directories(e.path("sub")); }),
                 {"is also the input --truth"}));
  c.push_back(error_case(
      "eval_out_symlink_to_truth", 2,
      eval_truth_copies("link.yaml",
                        [](const Env& e) { fs::create_symlink("truth.tum", e.path("link.yaml")); }),
      {"is also the input --truth"}));
  c.push_back(error_case("eval_out_hardlink_to_truth", 2,
                         eval_truth_copies("hard.yaml",
                                           [](const Env& e) {
                                             fs::create_hard_link(e.path("truth.tum"),
                                                                  e.path("hard.yaml"));
                                           }),
                         {"is also the input --truth"}));
  c.push_back(error_case("map_out_is_log", 2,
                         after_copy(&Base::log, "l.log", "map --log l.log --out l.log"),
                         {"--out", "is also the input --log"}));
  c.push_back(error_case("map_out_named_like_its_image", 2, map_base_log("--out m/map.pgm"),
                         {"would be one file", ".yaml"}));
  c.push_back(error_case(
      "map_image_not_an_image_name", 2,
      after_copy(&Base::log, "l.log", "map --log l.log --out m.yaml --image l.log"), {"--image"}));
  c.push_back(
      error_case("perturb_out_equals_truth_out", 2,
                 [](const Env& e) { return perturb_args(e, "--out x.log --truth-out x.log"); },
                 {"is also the output --out"}));
  c.push_back(error_case("perturb_out_equals_deprecated_truth", 2,
                         [](const Env& e) { return perturb_args(e, "--out x.log --truth x.log"); },
                         {"--truth", "is also the output --out"}));
  c.push_back(error_case(
      "perturb_out_is_log", 2,
      after_copy(
          &Base::log, "l.log",
          "perturb --log l.log --odom-noise 0.01,0,0.01,0 --seed 1 --out l.log --truth-out t.tum"),
      {"is also the input --log"}));
  c.push_back(error_case(
      "perturb_truth_out_is_log", 2,
      after_copy(
          &Base::log, "l.log",
          "perturb --log l.log --odom-noise 0.01,0,0.01,0 --seed 1 --out o.log --truth-out l.log"),
      {"--truth-out", "is also the input --log"}));
  c.push_back(error_case("localize_truth_is_an_output", 2,
                         [](const Env& e) {
                           copy(e, e.b.truth, "out/trajectory.tum");
                           return e.localize("--truth out/trajectory.tum");
                         },
                         {"trajectory.tum is also the input --truth"}));
  c.push_back(error_case("localize_map_image_is_an_output", 2,
                         [](const Env& e) {
                           copy(e, e.b.image, "out/overlay.png");
                           e.write("m.yaml", "image: out/overlay.png\n" + map_keys(kIntelOrigin));
                           return e.localize("", "", "m.yaml");
                         },
                         {"overlay.png is also the input --map's image"}));
  c.push_back(error_case("localize_config_is_an_output", 2,
                         [](const Env& e) {
                           e.write("out/config.yaml", "threads: 1\n");
                           return e.localize("--config out/config.yaml");
                         },
                         {"is also the input --config"}));
  c.push_back(error_case("simulate_out_is_scenario", 2,
                         [](const Env& e) {
                           copy(e, PGMCL_SOURCE_DIR "/configs/scenarios/lab.yaml", "lab.yaml");
                           return std::string("simulate lab.yaml --out lab.yaml");
                         },
                         {"is also the input scenario"}));
  c.push_back(error_case("run_truth_is_an_output", 2,
                         [](const Env& e) {
                           copy(e, e.b.truth, "out/trajectory.tum");
                           e.write("exp.yaml", "name: x\nmap: " + e.b.map +
                                                   "\ndata:\n  log: " + e.b.log +
                                                   "\n  truth: out/trajectory.tum\nout: out\n");
                           return std::string("run exp.yaml --quiet");
                         },
                         {"is also the input data.truth"}));
  c.push_back(error_case("perturb_map_out_is_input", 2,
                         [](const Env& e) {
                           copy(e, e.b.map, "map.yaml");
                           copy(e, e.b.image, "map.pgm");
                           return std::string(
                               "perturb-map --map map.yaml --out map.yaml --thicken 1");
                         },
                         {"is also the input --map"}));
  // Re-runs replace the whole set or nothing.
  c.push_back(accepted_case(
      "rerun_without_truth_drops_error_png",
      [](const Env& e) {
        earlier_run(e);
        return e.localize("");
      },
      [](const Env& e, const RunResult&) {
        EXPECT_FALSE(fs::exists(e.path("out/error.png")));
        EXPECT_EQ(testkit::read_text(e.path("out/metrics.yaml")).find("ate_rmse_m"),
                  std::string::npos);
      }));
  c.push_back(error_case("failed_rerun_bad_log_keeps_earlier_set", 1,
                         [](const Env& e) {
                           earlier_run(e);
                           std::vector<std::string> l = e.log_lines();
                           l.push_back("FLASER 3 1 2");
                           return e.localize("--strict", e.write("bad.log", join(l)));
                         },
                         {"bad.log:"}));
  c.push_back(error_case(
      "failed_rerun_bad_map_keeps_earlier_set", 1,
      [](const Env& e) {
        earlier_run(e);
        return e.localize("", "", e.map_yaml("raw.yaml", "mode: raw\n" + map_keys(kIntelOrigin)));
      },
      {"no occupied cell"}));
  c.push_back(error_case("failed_rerun_scan_rejected_keeps_earlier_set", 1,
                         [](const Env& e) {
                           earlier_run(e);
                           return e.localize("--set likelihood.expected_beams=181");
                         },
                         {"rejected by the filter"}));
  c.push_back(accepted_case(
      "rerun_keeps_other_files_in_the_folder",
      [](const Env& e) {
        e.write("out/notes.txt", "mine\n");
        return e.localize("");
      },
      [](const Env& e, const RunResult&) {
        EXPECT_EQ(testkit::read_text(e.path("out/notes.txt")), "mine\n");
      }));
  c.push_back(accepted_case(
      "perturb_map_rerun_png_then_pgm",
      [](const Env& e) {
        const RunResult r = run_pgmcl(
            "perturb-map --map " + e.b.map + " --out p/m.yaml --thicken 1 --blur 1 --quiet",
            e.dir.path().string());
        EXPECT_EQ(r.code, 0) << r.err;
        EXPECT_TRUE(fs::exists(e.path("p/m.png")));
        return "perturb-map --map " + e.b.map + " --out p/m.yaml --thicken 1 --quiet";
      },
      [](const Env& e, const RunResult&) {
        EXPECT_FALSE(fs::exists(e.path("p/m.png")));
        EXPECT_TRUE(fs::exists(e.path("p/m.pgm")));
        EXPECT_NO_THROW((void)maps::load_map(e.path("p/m.yaml")));
      }));
  // Output folders are checked before any work.
  c.push_back(error_case("out_folder_under_a_file", 1,
                         [](const Env& e) {
                           e.write("f", "a file\n");
                           std::vector<std::string> l = e.log_lines();
                           l.push_back("FLASER 3 1 2");
                           // The log would fail too (--strict): the folder must be what is
                           // reported.
                           return e.localize("--strict --out f/sub", e.write("bad.log", join(l)));
                         },
                         {"--out", "cannot create the folder"}));
  c.push_back(error_case("out_is_an_existing_file", 1,
                         [](const Env& e) {
                           e.write("f", "a file\n");
                           return e.localize("--out f");
                         },
                         {"--out", "cannot create the folder"}));
  c.push_back(error_case("localize_out_empty", 2, localize_with("--out ''"), {"--out", "empty"}));
  c.push_back(error_case("eval_out_is_a_folder", 2,
                         [](const Env& e) {
                           fs::create_directories(e.path("d"));
                           return "eval --estimate " + e.b.truth + " --truth " + e.b.truth +
                                  " --out d";
                         },
                         {"--out", "is a folder"}));
  c.push_back(error_case("eval_out_full_disk", 1,
                         [](const Env& e) {
                           return "eval --estimate " + e.b.truth + " --truth " + e.b.truth +
                                  " --out /dev/full";
                         },
                         {"/dev/full", "No space left on device"}));
  c.push_back(accepted_case("eval_out_dev_null", [](const Env& e) {
    return "eval --estimate " + e.b.truth + " --truth " + e.b.truth + " --out /dev/null";
  }));
  c.push_back(error_case("perturb_second_output_unwritable_writes_neither", 1,
                         [](const Env& e) {
                           e.write("f", "a file\n");
                           return perturb_args(e, "--out p/raw.log --truth-out f/t.tum");
                         },
                         {"--truth-out", "cannot create the folder"}));
  c.push_back(accepted_case("map_out_in_new_nested_folder",
                            map_base_log("--out a/b/c/m.yaml --quiet"),
                            [](const Env& e, const RunResult&) {
                              EXPECT_GT(maps::load_map(e.path("a/b/c/m.yaml")).size(), 0u);
                            }));
  return c;
}

}  // namespace pgmcl::hostile
