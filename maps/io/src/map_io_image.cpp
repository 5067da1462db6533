// Image <-> occupancy values, following nav2_map_server's map_io.cpp (loadMapFromFile,
// saveMapToFile) so that maps mean here what they mean in ROS.

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <string>

#include "image_codec.hpp"
#include "pgmcl/common/enum_names.hpp"
#include "pgmcl/map_io/map_io.hpp"

namespace pgmcl::maps {

namespace {

std::string compose_message(const std::string& file, int line, const std::string& field,
                            const std::string& problem) {
  // Appended piecewise: GCC 12 reports a false -Wrestrict for `s += ":" + to_string(n)`.
  std::string msg = file;
  if (line > 0) {
    msg.push_back(':');
    msg.append(std::to_string(line));
  }
  msg.append(": ");
  if (!field.empty()) {
    msg.append(field);
    msg.append(": ");
  }
  msg.append(problem);
  return msg;
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// map_saver's trinary pixel values.
constexpr std::uint8_t kPixelFree = 254;
constexpr std::uint8_t kPixelOccupied = 0;
constexpr std::uint8_t kPixelUnknown = 205;
// map_saver's default free threshold (0.25) as a cell value.
constexpr std::int8_t kSaveFreeMax = 25;

}  // namespace

MapError::MapError(std::string file, int line, std::string field, const std::string& problem)
    : std::runtime_error(compose_message(file, line, field, problem)),
      file_(std::move(file)),
      line_(line),
      field_(std::move(field)),
      problem_(problem) {}

constexpr std::array<EnumName<MapMode>, 3> kMapModeNames{{
    {MapMode::kTrinary, "trinary"},
    {MapMode::kScale, "scale"},
    {MapMode::kRaw, "raw"},
}};

const char* to_string(MapMode mode) noexcept {
  return name_of(mode, kMapModeNames);
}

MapMode map_mode_from_string(const std::string& name) {
  if (const auto mode = value_of(name, kMapModeNames)) return *mode;
  throw std::invalid_argument("unknown map mode '" + name + "' (expected trinary, scale or raw)");
}

namespace detail {

std::string format_double(double v) {
  std::array<char, 64> buf{};
  const auto res = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  std::string s(buf.data(), res.ptr);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

void validate_metadata(const MapMetadata& meta, const std::string& file,
                       const MetadataLines& lines) {
  if (!std::isfinite(meta.resolution) || meta.resolution <= 0.0 ||
      meta.resolution > kMaxResolution) {
    throw MapError(file, lines.resolution, "resolution",
                   "must be a positive number of metres per cell up to " +
                       format_double(kMaxResolution) + ", got " + format_double(meta.resolution));
  }
  if (!std::isfinite(meta.origin.x) || !std::isfinite(meta.origin.y) ||
      !std::isfinite(meta.origin.theta)) {
    throw MapError(file, lines.origin, "origin", "must hold finite numbers");
  }
  if (std::abs(meta.origin.x) > kMaxOriginDistance ||
      std::abs(meta.origin.y) > kMaxOriginDistance) {
    throw MapError(file, lines.origin, "origin",
                   "[" + format_double(meta.origin.x) + ", " + format_double(meta.origin.y) +
                       "] is more than " + format_double(kMaxOriginDistance) +
                       " m from the map frame's origin (UTM coordinates stay below 1e7 m): a "
                       "unit or typing error?");
  }
  const auto in_unit = [](double v) { return std::isfinite(v) && v >= 0.0 && v <= 1.0; };
  if (!in_unit(meta.occupied_thresh)) {
    throw MapError(file, lines.occupied_thresh, "occupied_thresh",
                   "must be in [0, 1], got " + format_double(meta.occupied_thresh));
  }
  if (!in_unit(meta.free_thresh)) {
    throw MapError(file, lines.free_thresh, "free_thresh",
                   "must be in [0, 1], got " + format_double(meta.free_thresh));
  }
  if (meta.free_thresh >= meta.occupied_thresh) {
    throw MapError(file, lines.free_thresh, "free_thresh",
                   "must be below occupied_thresh (free_thresh " + format_double(meta.free_thresh) +
                       " >= occupied_thresh " + format_double(meta.occupied_thresh) + ")");
  }
}

}  // namespace detail

OccupancyGrid load_map_image(const std::string& image_path, const MapMetadata& meta) {
  detail::validate_metadata(meta, image_path);
  const detail::Image img =
      detail::decode_image(detail::read_file_bytes(image_path, "image file"), image_path);

  OccupancyGrid grid(img.width, img.height, meta.resolution, meta.origin, kUnknown);
  const int ch = img.channels;
  const bool alpha = img.has_alpha();
  const bool colour = ch >= 3;
  const double maxval = img.maxval;
  // nav2 averages R, G, B (grey counts three times) and, in trinary mode only, alpha too.
  const bool average_alpha = alpha && meta.mode == MapMode::kTrinary;
  const double n_avg = average_alpha ? 4.0 : 3.0;
  const double span = meta.occupied_thresh - meta.free_thresh;

  for (int y = 0; y < img.height; ++y) {
    const int row = img.height - 1 - y;  // image rows are top-down, grid row 0 is the bottom
    for (int x = 0; x < img.width; ++x) {
      const std::uint16_t* px =
          &img.samples[(static_cast<std::size_t>(y) * static_cast<std::size_t>(img.width) +
                        static_cast<std::size_t>(x)) *
                       static_cast<std::size_t>(ch)];
      double sum = colour ? static_cast<double>(px[0]) + px[1] + px[2] : 3.0 * px[0];
      const std::uint16_t a = alpha ? px[ch - 1] : static_cast<std::uint16_t>(img.maxval);
      if (average_alpha) sum += a;
      const double shade = sum / n_avg / maxval;  // 0 = black .. 1 = white
      const double occ = meta.negate ? shade : 1.0 - shade;

      std::int8_t cell = kUnknown;
      switch (meta.mode) {
        case MapMode::kTrinary:
          if (meta.occupied_thresh < occ) {
            cell = kOccupied;
          } else if (occ < meta.free_thresh) {
            cell = kFree;
          }
          break;
        case MapMode::kScale:
          if (a != img.maxval) {
            cell = kUnknown;
          } else if (meta.occupied_thresh < occ) {
            cell = kOccupied;
          } else if (occ < meta.free_thresh) {
            cell = kFree;
          } else {
            cell = static_cast<std::int8_t>(std::rint((occ - meta.free_thresh) / span * 100.0));
          }
          break;
        case MapMode::kRaw: {
          const double v = std::round(shade * 255.0);
          if (v >= 0.0 && v <= 100.0) cell = static_cast<std::int8_t>(v);
          break;
        }
      }
      grid.set(x, row, cell);
    }
  }
  return grid;
}

namespace {

/// map_saver's trinary pixel for a cell.
std::uint8_t trinary_pixel(std::int8_t v, std::int8_t occ_min) noexcept {
  if (v < 0 || v > kOccupied) return kPixelUnknown;
  if (v >= occ_min) return kPixelOccupied;
  if (v <= kSaveFreeMax) return kPixelFree;
  return kPixelUnknown;
}

bool is_known(std::int8_t v) noexcept {
  return v >= 0 && v <= kOccupied;
}

}  // namespace

void save_map_image(const OccupancyGrid& grid, const std::string& image_path, MapMode mode) {
  const bool gz = ends_with(image_path, ".pgm.gz");
  const bool png = ends_with(image_path, ".png");
  if (!gz && !png && !ends_with(image_path, ".pgm")) {
    throw MapError(image_path, 0, "image",
                   "unsupported extension for saving (use .pgm, .pgm.gz or .png)");
  }
  if (grid.empty()) throw MapError(image_path, 0, "image", "cannot save an empty grid");
  if (mode == MapMode::kRaw) {
    throw MapError(image_path, 0, "mode",
                   "saving raw maps is not supported (use trinary or scale)");
  }
  const bool scale = mode == MapMode::kScale;
  // Scale mode marks unknown cells transparent, as map_saver does; only PNG has alpha.
  const bool alpha = scale && !std::all_of(grid.cells().begin(), grid.cells().end(), is_known);
  if (alpha && !png) {
    throw MapError(image_path, 0, "image",
                   "a scale map with unknown cells needs an alpha channel: save it as .png");
  }
  detail::Image img;
  img.width = grid.width();
  img.height = grid.height();
  img.channels = alpha ? 2 : 1;
  img.maxval = 255;
  img.samples.resize(grid.size() * static_cast<std::size_t>(img.channels));
  const std::int8_t occ_min = grid.occupied_threshold();
  for (int row = 0; row < grid.height(); ++row) {
    const int y = grid.height() - 1 - row;
    for (int col = 0; col < grid.width(); ++col) {
      const std::int8_t v = grid.at(col, row);
      std::uint16_t* px =
          &img.samples[(static_cast<std::size_t>(y) * static_cast<std::size_t>(img.width) +
                        static_cast<std::size_t>(col)) *
                       static_cast<std::size_t>(img.channels)];
      if (!scale) {
        px[0] = trinary_pixel(v, occ_min);
      } else if (is_known(v)) {
        px[0] = static_cast<std::uint16_t>(std::lround(255.0 * (kOccupied - v) / kOccupied));
      } else {
        px[0] = kPixelUnknown;
      }
      if (alpha) px[1] = is_known(v) ? 255 : 0;
    }
  }
  detail::Bytes bytes;
  if (png) {
    bytes = detail::encode_png(img, image_path);
  } else {
    bytes = detail::encode_pgm(img, "pgmcl map, " + std::to_string(grid.resolution()) + " m/pix");
    if (gz) bytes = detail::gzip(bytes, image_path);
  }
  detail::write_file_bytes(image_path, bytes);
}

}  // namespace pgmcl::maps
