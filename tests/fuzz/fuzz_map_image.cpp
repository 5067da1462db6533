// libFuzzer target: image decoding (PGM/PPM, PNG and the other stb formats, gzip-wrapped or
// not) and the occupancy semantics of pgmcl::maps::load_map_image.
// Input layout: 3 bytes of metadata (mode and negate; free_thresh; occupied_thresh), then
// the image file. Only MapError may escape (map_io.hpp).

#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_util.hpp"
#include "map_invariants.hpp"
#include "pgmcl/map_io/map_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace pgmcl;
  if (size < 3) return 0;
  maps::MapMetadata meta;
  meta.mode = static_cast<maps::MapMode>(data[0] % 3);
  meta.negate = ((data[0] >> 2) & 1) != 0;
  meta.free_thresh = 0.5 * data[1] / 256.0;            // [0, 0.5)
  meta.occupied_thresh = 0.5 + 0.5 * data[2] / 255.0;  // [0.5, 1]
  meta.image = "img";
  const std::string path = fuzz::write_scratch("img", fuzz::as_text(data + 3, size - 3));
  try {
    const maps::OccupancyGrid grid = maps::load_map_image(path, meta);
    fuzz::check_loaded_map(grid, meta);
  } catch (const maps::MapError&) {
    // Documented: malformed image.
  } catch (const std::exception& e) {
    fuzz::undocumented(e);
  }
  return 0;
}
