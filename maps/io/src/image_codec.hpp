#pragma once
/// Private to pgmcl::maps: raw image decoding/encoding for the map loader.
/// Every failure throws MapError naming the image file and the part that is wrong.

#include <cstdint>
#include <string>
#include <vector>

#include "pgmcl/map_io/map_io.hpp"

namespace pgmcl::maps::detail {

using Bytes = std::vector<std::uint8_t>;

/// A decoded image, top row first, channels interleaved.
struct Image {
  int width = 0;
  int height = 0;
  int channels = 0;  ///< 1 grey, 2 grey+alpha, 3 RGB, 4 RGBA
  int maxval = 255;  ///< full-scale sample value: 255 for 8-bit, up to 65535
  std::vector<std::uint16_t> samples;

  [[nodiscard]] bool has_alpha() const noexcept { return channels == 2 || channels == 4; }
};

/// Upper bound on decoded pixels (width * height): kMaxCells.
inline constexpr std::uint64_t kMaxPixels = kMaxCells;

/// Reads a whole file; `what` describes it in the error ("image file", "map YAML file").
[[nodiscard]] Bytes read_file_bytes(const std::string& path, const std::string& what);
void write_file_bytes(const std::string& path, const Bytes& bytes);

/// gzip (RFC 1952) detection, decompression and compression, via zlib.
[[nodiscard]] bool is_gzip(const Bytes& bytes) noexcept;
[[nodiscard]] Bytes gunzip(const Bytes& bytes, const std::string& path);
[[nodiscard]] Bytes gzip(const Bytes& bytes, const std::string& path);

/// Netpbm P2/P3/P5/P6. 16-bit samples (maxval > 255) are big-endian, as the format says.
[[nodiscard]] bool is_pnm(const Bytes& bytes) noexcept;
[[nodiscard]] Image decode_pnm(const Bytes& bytes, const std::string& path);
/// Writes an 8-bit single-channel image as binary P5.
[[nodiscard]] Bytes encode_pgm(const Image& image, const std::string& comment);

/// PNG (any colour type, 8 or 16 bits per sample), chunk CRCs verified.
[[nodiscard]] bool is_png(const Bytes& bytes) noexcept;
[[nodiscard]] Image decode_png(const Bytes& bytes, const std::string& path);
/// Writes an 8-bit image (1..4 channels) as PNG.
[[nodiscard]] Bytes encode_png(const Image& image, const std::string& path);

/// Sniffs the content: gzip is unwrapped first, then PNM or PNG; anything else is an error.
[[nodiscard]] Image decode_image(const Bytes& bytes, const std::string& path);

/// Shortest text that reads back as exactly `v`, and still reads as a float ("1.0").
[[nodiscard]] std::string format_double(double v);

/// YAML lines (1-based, 0 = unknown) of the metadata fields, for error messages.
struct MetadataLines {
  int resolution = 0;
  int origin = 0;
  int occupied_thresh = 0;
  int free_thresh = 0;
};

/// Checks resolution > 0, a finite origin, 0 <= free_thresh < occupied_thresh <= 1.
void validate_metadata(const MapMetadata& meta, const std::string& file,
                       const MetadataLines& lines = {});

}  // namespace pgmcl::maps::detail
