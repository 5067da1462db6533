// Corpus cases: crashes and memory. Every count has a limit, and the error names the
// field, the value and the memory it would take.

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "hostile_corpus.hpp"
#include "hostile_util.hpp"

namespace pgmcl::hostile {
namespace {

/// A scenario file around the bundled lab scene with `extra` top-level keys overridden.
std::string scenario(const Env& e, const std::string& name, const std::string& keys) {
  return e.write(name,
                 "map: " PGMCL_SOURCE_DIR
                 "/data/maps/scenarios/lab_5mm.yaml\n"
                 "robot:\n  start: [1.8, 1.6, 0.0]\n  limits: {max_v: 0.3, max_omega: 0.8}\n" +
                     keys);
}

}  // namespace

std::vector<Case> resource_cases() {
  std::vector<Case> c;
  // Threads: libgomp segfaulted creating 65535; capped at 1024, warned above the cores.
  c.push_back(error_case("threads_flag_100000", 2, localize_with("--threads 100000"),
                         {"--threads", "100000", "[0, 1024]"}));
  c.push_back(error_case("threads_flag_65535", 2, localize_with("--threads 65535"), {"--threads"}));
  c.push_back(error_case("threads_flag_negative", 2, localize_with("--threads -4"), {"--threads"}));
  c.push_back(bad_setting("threads_set_65535", "threads=65535",
                          {"--set threads=65535", "threads", "1024"}));
  c.push_back(error_case("threads_config_file_5000", 1, localize_with_config("threads: 5000\n"),
                         {"cfg.yaml:1", "threads", "5000"}));
  c.push_back(warning_case("threads_above_cores_warns", localize_with("--threads 64"),
                           {"threads = 64 is more than the"}));
  // Particle counts: the field, the value and the memory.
  c.push_back(error_case(
      "particles_1e12_kld_off", 1,
      localize_with("--set filter.kld.enabled=false --set filter.particles=1000000000000"),
      {"filter.particles", "1000000000000", "10000000", "GB"}));
  c.push_back(error_case("global_particles_1e11_config", 1,
                         localize_with_config("filter:\n  global_particles: 100000000000\n"),
                         {"cfg.yaml:2", "filter.global_particles", "GB"}));
  c.push_back(bad_setting("kld_max_particles_1e10", "filter.kld.max_particles=10000000000",
                          {"filter.kld.max_particles", "GB"}));
  // Found by the config fuzzer: a scan of this many readings is 370 GB.
  c.push_back(bad_setting("expected_beams_92e9", "likelihood.expected_beams=92500000000",
                          {"likelihood.expected_beams", "92500000000", "1048576", "GB"}));
  // A gzipped log whose one line inflates past the line limit.
  c.push_back(error_case("gzip_bomb_one_line", 1,
                         [](const Env& e) {
                           e.write_gz("bomb.log.gz", repeat("aaaaaaaaaaaaaaaa", 65u << 20));
                           return e.localize("", "bomb.log.gz");
                         },
                         {"bomb.log.gz:1", "line", "64 MiB"}));
  c.push_back(error_case("gzip_bomb_after_valid_lines", 1,
                         [](const Env& e) {
                           std::vector<std::string> l = e.log_lines();
                           l.resize(40);
                           e.write_gz("bomb.log.gz",
                                      join(l) + "ODOM " + repeat("1111111111111111", 65u << 20));
                           return e.localize("", "bomb.log.gz");
                         },
                         {"bomb.log.gz:41", "line", "MiB"}));
  c.push_back(error_case("gzip_bomb_for_map", 1,
                         [](const Env& e) {
                           e.write_gz("bomb.log.gz", repeat("FLASER 1 ", 65u << 20));
                           return std::string("map --log bomb.log.gz --out m/map.yaml");
                         },
                         {"bomb.log.gz:1", "MiB"}));
  c.push_back(error_case("gzip_bomb_as_truth", 1,
                         [](const Env& e) {
                           e.write_gz("bomb.tum.gz", repeat("0 ", 65u << 20));
                           return e.localize("--truth bomb.tum.gz");
                         },
                         {"bomb.tum.gz:1", "MiB"}));
  // Scenarios whose duration asks for more scans or control steps than memory holds.
  c.push_back(error_case("scenario_1e15_scans", 1,
                         [](const Env& e) {
                           scenario(e, "s.yaml", "duration: 1.0e14\nscan_rate: 10\n");
                           return std::string("simulate s.yaml --out sim.log");
                         },
                         {"s.yaml:", "duration", "1e+15 scans", "GB"}));
  c.push_back(error_case("scenario_scan_rate_1e12", 1,
                         [](const Env& e) {
                           scenario(e, "s.yaml", "duration: 30\nscan_rate: 1.0e12\n");
                           return std::string("simulate s.yaml --out sim.log");
                         },
                         {"duration", "scan_rate 1e+12 Hz", "GB"}));
  c.push_back(error_case("scenario_control_steps_1e12", 1,
                         [](const Env& e) {
                           scenario(e, "s.yaml",
                                    "duration: 1.0e6\nscan_rate: 0.001\ncontrol_rate: 1.0e6\n");
                           return std::string("simulate s.yaml --out sim.log");
                         },
                         {"duration", "control steps"}));
  c.push_back(error_case("scenario_huge_in_experiment", 1,
                         [](const Env& e) {
                           scenario(e, "s.yaml", "duration: 1.0e14\n");
                           e.write("exp.yaml", "name: x\ndata:\n  scenario: s.yaml\nout: out\n");
                           return std::string("run exp.yaml --quiet");
                         },
                         {"duration", "GB"}));
  // Sizes that become memory in the other commands.
  c.push_back(error_case("map_resolution_1e_minus_6", 2,
                         map_base_log("--resolution 1e-6 --out m.yaml"),
                         {"--resolution", "cells", "GB"}));
  c.push_back(error_case("perturb_map_blur_1e12", 2, perturb_base_map("--out p.yaml --blur 1e12"),
                         {"--blur", "1e+12"}));
  c.push_back(error_case("perturb_map_thicken_1e9", 2,
                         perturb_base_map("--out p.yaml --thicken 1000000000"), {"--thicken"}));
  c.push_back(bad_setting("table_bytes_limit", "likelihood.table.max_table_bytes=1000",
                          {"max_table_bytes", "bytes"}));
  c.push_back(error_case(
      "calibrate_readings_1e12", 2,
      [](const Env&) { return std::string("calibrate range --simulate --readings 1000000000000"); },
      {"--readings"}));
  c.push_back(error_case("pgm_header_100000_square", 1,
                         [](const Env& e) {
                           e.write("huge.pgm",
                                   "P5\n100000 100000\n255\n" + std::string(16, '\xfe'));
                           e.write("huge.yaml", "image: huge.pgm\n" + map_keys("[0, 0, 0]"));
                           return e.localize("", "", "huge.yaml");
                         },
                         {"huge.pgm", "pixels"}));
  c.push_back(warning_case("num_readings_1e9_line_dropped",
                           [](const Env& e) {
                             std::vector<std::string> l = e.log_lines();
                             const std::string huge_count = "FLASER 1000000000 1 2 3";
                             l.push_back(huge_count);
                             return e.localize("", e.write("l.log", join(l)));
                           },
                           {"dropped 1 malformed line", "num_readings"}));
  return c;
}

}  // namespace pgmcl::hostile
