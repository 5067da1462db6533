// libFuzzer target: map_server YAML + image through pgmcl::maps::load_map.
// Input layout: the YAML text, then a line "#%IMAGE%", then the image bytes (PGM/PNG/gzip
// ...). Both are written to a private scratch directory as map.yaml and the YAML's image
// name. Only MapError may escape load_map (map_io.hpp: "every failure throws MapError").

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "fuzz_util.hpp"
#include "map_invariants.hpp"
#include "pgmcl/map_io/map_io.hpp"

namespace {

constexpr std::string_view kSeparator = "\n#%IMAGE%\n";

// The YAML may name any image; only plain names inside the scratch directory are read, so
// the fuzzer never opens /dev/zero or the user's files.
bool is_plain_name(const std::string& name) {
  return !name.empty() && name.find('/') == std::string::npos && name != "." && name != ".." &&
         name.rfind("roundtrip", 0) != 0;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace pgmcl;
  const std::string_view input = fuzz::as_text(data, size);
  const std::size_t sep = input.find(kSeparator);
  const std::string_view yaml = input.substr(0, sep);
  const std::string_view image =
      sep == std::string_view::npos ? std::string_view{} : input.substr(sep + kSeparator.size());

  const std::string yaml_path = fuzz::write_scratch("map.yaml", yaml);
  try {
    maps::MapLoadReport report;
    const maps::MapMetadata meta = maps::read_map_yaml(yaml_path, &report);
    if (!is_plain_name(meta.image)) return 0;
    if (meta.image == "map.yaml") return 0;  // the YAML as its own image: not interesting
    const fuzz::ScratchFile cleanup(meta.image);
    if (!fuzz::try_write_scratch(meta.image, image)) return 0;
    const maps::OccupancyGrid grid = maps::load_map(yaml_path, &report);
    fuzz::check_loaded_map(grid, meta);
  } catch (const maps::MapError&) {
    // Documented: malformed input.
  } catch (const std::exception& e) {
    fuzz::undocumented(e);
  }
  return 0;
}
