#pragma once
/// Loading and saving ROS map_server maps: a YAML file plus an image.
///
/// Semantics follow nav2_map_server's map_io.cpp (loadMapFromFile / saveMapToFile):
///  - shade = mean of the colour channels / maxval (for trinary mode the alpha channel is
///    averaged in as well, as nav2 does); occ = negate ? shade : 1 - shade.
///  - trinary: occ > occupied_thresh -> 100, occ < free_thresh -> 0, otherwise -1.
///  - scale:   a pixel that is not fully opaque -> -1; then as trinary, except that between
///             the thresholds occ is mapped linearly: rint((occ - free) / (occ_t - free) * 100).
///  - raw:     v = round(shade * 255); 0..100 is kept as is, anything else -> -1.
/// Image rows are top-down; grid row 0 is the bottom row, so rows are flipped on load/save.
///
/// Images: PGM/PPM (P2, P3, P5, P6; 8-bit, or 16-bit when maxval > 255) and PNG (grey,
/// grey+alpha, RGB, RGBA, palette; 8 or 16 bits), each optionally gzip-compressed (detected
/// from the content, e.g. `image: foo.pgm.gz`). Other formats (BMP, JPEG, ...) are refused:
/// they cannot be checked for truncation, and JPEG is lossy.
///
/// All validation is always on; every failure throws MapError naming the file, the YAML
/// line when there is one, and the field. No partial map is ever returned.

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "pgmcl/maps/occupancy_grid.hpp"

namespace pgmcl::maps {

/// Any map loading/saving failure. what() reads "<file>[:<line>]: <field>: <problem>".
class MapError : public std::runtime_error {
 public:
  MapError(std::string file, int line, std::string field, const std::string& problem);

  [[nodiscard]] const std::string& file() const noexcept { return file_; }
  [[nodiscard]] int line() const noexcept { return line_; }  ///< 1-based; 0 when unknown
  [[nodiscard]] const std::string& field() const noexcept { return field_; }
  [[nodiscard]] const std::string& problem() const noexcept { return problem_; }

 private:
  std::string file_;
  int line_ = 0;
  std::string field_;
  std::string problem_;
};

/// Limits every loaded map is checked against (and `pgmcl map` before it writes one): a
/// resolution or origin past them is a typo or a unit error, and the maps pgmcl writes
/// always load again.
inline constexpr double kMaxResolution = 1000.0;  ///< metres per cell
/// Metres from the map frame's origin: UTM northings stay below 10^7 m.
inline constexpr double kMaxOriginDistance = 1e8;
/// Cells (width * height) of a map image: 2^28, about 16 km square at 5 cm.
inline constexpr std::uint64_t kMaxCells = std::uint64_t{1} << 28;

/// map_server's `mode` key.
enum class MapMode : std::uint8_t { kTrinary, kScale, kRaw };

[[nodiscard]] const char* to_string(MapMode mode) noexcept;
/// Parses "trinary" | "scale" | "raw"; throws std::invalid_argument otherwise.
[[nodiscard]] MapMode map_mode_from_string(const std::string& name);

/// The contents of a map_server YAML file. Defaults are map_server's.
struct MapMetadata {
  std::string image;         ///< image path as written in the YAML (relative to it)
  double resolution = 0.05;  ///< metres per cell, in (0, kMaxResolution]
  Pose2 origin{};  ///< pose of the lower-left corner of cell (0, 0): m, m, rad; |x|, |y| <=
                   ///< kMaxOriginDistance
  double occupied_thresh = 0.65;  ///< occ above this -> occupied; in [0, 1]
  double free_thresh = 0.196;     ///< occ below this -> free; in [0, 1], < occupied_thresh
  bool negate = false;            ///< true: white is occupied, black is free
  MapMode mode = MapMode::kTrinary;
};

/// What load_map found besides the grid.
struct MapLoadReport {
  MapMetadata metadata;               ///< as parsed (image still as written in the YAML)
  std::string image_path;             ///< the image file actually read
  std::vector<std::string> warnings;  ///< non-fatal findings, e.g. unknown YAML keys
};

/// Parses and validates a map YAML file. Required keys: image, resolution, origin.
/// occupied_thresh, free_thresh, negate and mode default to map_server's values (with a
/// warning for the first three, which map_server itself requires).
[[nodiscard]] MapMetadata read_map_yaml(const std::string& yaml_path,
                                        MapLoadReport* report = nullptr);

/// Loads a map: YAML, then the image it names (relative paths are relative to the YAML).
[[nodiscard]] OccupancyGrid load_map(const std::string& yaml_path, MapLoadReport* report = nullptr);

/// Loads an image file as a grid using `meta` (meta.image is ignored; `image_path` is read).
[[nodiscard]] OccupancyGrid load_map_image(const std::string& image_path, const MapMetadata& meta);

/// Writes the grid as an image in `mode` (pixel values as in save_map); the format follows
/// the extension of `image_path`: ".pgm", ".pgm.gz" or ".png".
void save_map_image(const OccupancyGrid& grid, const std::string& image_path,
                    MapMode mode = MapMode::kTrinary);

/// Writes `yaml_path` and its image next to it, as nav2's map_saver does (saveMapToFile):
///  - trinary: free (0 .. 25) -> 254, occupied (>= grid.occupied_threshold()) -> 0, anything
///    else (unknown, out of range, in between) -> 205;
///  - scale: a cell v in 0 .. 100 (occupancy in percent) -> grey round(255 * (100 - v) / 100),
///    opaque, so intermediate probabilities are kept rather than thresholded; anything else
///    (unknown) -> transparent (alpha 0, grey 205). Unknown cells therefore need an alpha
///    channel: PNG (grey + alpha); a PGM is refused for a grid with unknown cells.
///  - raw: refused (MapError).
/// The YAML gets `mode`, occupied_thresh 0.65 and free_thresh 0.196, so a grid of -1/0/100
/// reloads identically in either mode; in scale mode a cell in between reloads through the
/// loader's scale rule (v = 50 -> occ 0.498 -> 67), as with map_server.
/// `image_name` (relative to the YAML's folder) defaults to the YAML's stem + ".pgm"
/// (trinary) or ".png" (scale); its extension picks the format: ".pgm" (P5), ".pgm.gz"
/// (gzipped P5) or ".png".
void save_map(const OccupancyGrid& grid, const std::string& yaml_path,
              const std::string& image_name = "", MapMode mode = MapMode::kTrinary);

/// The YAML text save_map writes for `grid` with the image `image_name`, for callers that
/// write the two files themselves (to temporary names, renamed together). Throws MapError
/// (`yaml_path` names the file) for a grid whose origin or resolution no loader accepts.
[[nodiscard]] std::string map_yaml_text(const OccupancyGrid& grid, const std::string& image_name,
                                        MapMode mode, const std::string& yaml_path);

}  // namespace pgmcl::maps
