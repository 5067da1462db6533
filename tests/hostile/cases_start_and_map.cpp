// Corpus cases: start poses outside the map, in a wall or in degrees, and maps with nothing
// to match; silent wrong results once, each now an error or a reported warning.

#include <string>

#include "hostile_corpus.hpp"
#include "hostile_util.hpp"

namespace pgmcl::hostile {
namespace {

/// A 200 x 200 map at 5 cm whose every pixel is `value`, written as `name`.pgm and
/// `name`.yaml; returns the YAML's name.
std::string uniform_map(const Env& e, const std::string& name, char value) {
  e.write(name + ".pgm", "P5\n200 200\n255\n" + std::string(40000, value));
  e.write(name + ".yaml", "image: " + name + ".pgm\n" + map_keys("[-5, -5, 0]"));
  return name + ".yaml";
}

}  // namespace

std::vector<Case> start_and_map_cases() {
  std::vector<Case> c;
  // Start poses outside the map, in a wall, or in degrees.
  c.push_back(error_case("init_far_outside", 2, localize_with("--init 1e6,1e6,0"),
                         {"--init", "outside the map", "x in [-20.9, 21.55]"}));
  c.push_back(
      error_case("init_just_outside", 2, localize_with("--init 21.7,0,0"), {"--init", "outside"}));
  c.push_back(error_case("init_negative_far", 2, localize_with("--init -1e9,-1e9,1"), {"--init"}));
  c.push_back(warning_case("init_in_a_wall",
                           [](const Env& e) { return e.localize("--init " + pose_text(e.b.wall)); },
                           {"--init", "occupied cell"}));
  c.push_back(warning_case("init_heading_degrees_20", localize_with("--init 0.6,-0.03,20"),
                           {"--init", "beyond ±2π", "20 degrees"}));
  c.push_back(warning_case("init_heading_degrees_minus_340", localize_with("--init 0.6,-0.03,-340"),
                           {"beyond ±2π"}));
  c.push_back(error_case("init_empty", 2, localize_with("--init ''"), {"--init", "''"}));
  c.push_back(error_case("init_blank", 2, localize_with("--init ' '"), {"--init"}));
  c.push_back(
      error_case("init_two_numbers", 2, localize_with("--init 0.6,0"), {"--init", "2 values"}));
  c.push_back(error_case("init_nan", 2, localize_with("--init nan,0,0"), {"--init"}));
  c.push_back(
      error_case("init_and_global", 2, localize_with("--init 0.6,0,0 --global"), {"--global"}));
  c.push_back(error_case("experiment_init_outside", 2,
                         [](const Env& e) {
                           e.write("exp.yaml", "name: x\nmap: " + e.b.map +
                                                   "\ndata:\n  log: " + e.b.log +
                                                   "\ninit: [1.0e6, 1.0e6, 0]\nout: out\n");
                           return std::string("run exp.yaml --quiet");
                         },
                         {"exp.yaml: init", "outside the map"}));
  // Maps with nothing to match.
  c.push_back(error_case(
      "map_all_free", 1,
      [](const Env& e) { return e.localize("--init 0,0,0", "", uniform_map(e, "free", '\xfe')); },
      {"free.yaml", "no occupied cell", "40000 free"}));
  c.push_back(error_case(
      "map_all_unknown", 1,
      [](const Env& e) { return e.localize("--init 0,0,0", "", uniform_map(e, "u", '\xcd')); },
      {"no occupied cell"}));
  c.push_back(error_case(
      "map_raw_mode_on_trinary_image", 1,
      [](const Env& e) {
        return e.localize("", "", e.map_yaml("raw.yaml", "mode: raw\n" + map_keys(kIntelOrigin)));
      },
      {"raw.yaml", "no occupied cell", "`mode`"}));
  c.push_back(error_case(
      "map_occupied_thresh_1", 1,
      [](const Env& e) {
        return e.localize("", "", e.map_yaml("t.yaml", map_keys(kIntelOrigin, "0.05", "0", "1.0")));
      },
      {"no occupied cell"}));
  c.push_back(error_case("map_resolution_1e9", 1,
                         [](const Env& e) {
                           return e.localize("", "",
                                             e.map_yaml("r.yaml", map_keys(kIntelOrigin, "1.0e9")));
                         },
                         {"r.yaml:2", "resolution", "1e+09"}));
  c.push_back(error_case("map_resolution_20_m", 1,
                         [](const Env& e) {
                           return e.localize("", "",
                                             e.map_yaml("r.yaml", map_keys(kIntelOrigin, "20")));
                         },
                         {"r.yaml", "resolution", "spans fewer than 4 cells"}));
  c.push_back(warning_case("map_negated",
                           [](const Env& e) {
                             return e.localize(
                                 "", "", e.map_yaml("n.yaml", map_keys(kIntelOrigin, "0.05", "1")));
                           },
                           {"more occupied", "negate"}));
  c.push_back(
      warning_case("map_of_another_building",
                   localize_with("--init 5,5,0", "", PGMCL_SOURCE_DIR "/data/maps/nav2/depot.yaml"),
                   {"hardly matched the map"}));
  return c;
}

}  // namespace pgmcl::hostile
