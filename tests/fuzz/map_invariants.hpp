#pragma once
// Invariants every successfully loaded map must satisfy, and the save/reload oracle
// (nav2 map_saver trinary semantics, documented in maps/map_io.hpp).

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_util.hpp"
#include "pgmcl/map_io/map_io.hpp"

namespace pgmcl::fuzz {

inline void check_loaded_grid(const maps::OccupancyGrid& g, const maps::MapMetadata& meta) {
  if (g.width() <= 0 || g.height() <= 0) fail("loaded grid has no cells");
  if (g.size() != static_cast<std::size_t>(g.width()) * static_cast<std::size_t>(g.height()))
    fail("grid size != width * height");
  if (!(g.resolution() > 0.0) || !std::isfinite(g.resolution()) ||
      g.resolution() != meta.resolution)
    fail("resolution not the YAML's");
  if (!std::isfinite(g.origin().x) || !std::isfinite(g.origin().y) ||
      !std::isfinite(g.origin().theta))
    fail("origin not finite");
  for (const std::int8_t v : g.cells()) {
    if (v < -1 || v > 100) fail("cell value outside -1..100", std::to_string(v));
    if (meta.mode == maps::MapMode::kTrinary && v != -1 && v != 0 && v != 100)
      fail("trinary map cell not in {-1, 0, 100}", std::to_string(v));
  }
}

/// save_map then load_map: map_saver's trinary classes and the metadata come back exactly.
inline void check_save_reload(const maps::OccupancyGrid& g) {
  const std::string yaml = (scratch_dir() / "roundtrip.yaml").string();
  maps::save_map(g, yaml, "roundtrip.pgm");
  const maps::OccupancyGrid back = maps::load_map(yaml);
  if (back.width() != g.width() || back.height() != g.height()) fail("reload changed the size");
  if (back.resolution() != g.resolution()) fail("reload changed the resolution");
  if (back.origin().x != g.origin().x || back.origin().y != g.origin().y ||
      back.origin().theta != g.origin().theta)
    fail("reload changed the origin");
  for (std::size_t i = 0; i < g.size(); ++i) {
    const std::int8_t v = g.cells()[i];
    const std::int8_t want = v >= g.occupied_threshold() ? 100 : (v >= 0 && v <= 25 ? 0 : -1);
    if (back.cells()[i] != want)
      fail("reload changed a cell",
           std::to_string(i) + ": " + std::to_string(v) + " -> " + std::to_string(back.cells()[i]));
  }
}

/// Grids up to this many cells also go through the save/reload oracle; larger ones would cost
/// the fuzzer too much time per input.
inline constexpr std::size_t kMaxRoundTripCells = std::size_t{1} << 20;

/// check_loaded_grid, then check_save_reload for a grid of at most kMaxRoundTripCells.
inline void check_loaded_map(const maps::OccupancyGrid& g, const maps::MapMetadata& meta) {
  check_loaded_grid(g, meta);
  if (g.size() <= kMaxRoundTripCells) check_save_reload(g);
}

}  // namespace pgmcl::fuzz
