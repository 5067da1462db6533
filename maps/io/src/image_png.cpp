// PNG through Debian's libstb (the shared library holds the implementations, so no
// STB_*_IMPLEMENTATION here). stb's flip flag is process-global state; the loader flips
// rows itself. Only PNG goes to stb: its chunk structure lets us prove the file complete
// and intact first, whereas stb's readers for BMP, TGA, ... pad a truncated file with
// zeros and would return a partial map.

#include <stb/stb_image.h>
#include <stb/stb_image_write.h>
#include <zlib.h>

#include <climits>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>

#include "image_codec.hpp"
#include "pgmcl/map_io/map_io.hpp"

namespace pgmcl::maps::detail {

namespace {

struct StbFree {
  void operator()(void* p) const noexcept { stbi_image_free(p); }
};

std::string stb_reason() {
  const char* why = stbi_failure_reason();
  return why != nullptr ? why : "unknown error";
}

void append_bytes(void* context, void* data, int size) {
  auto* out = static_cast<Bytes*>(context);
  const auto* p = static_cast<const std::uint8_t*>(data);
  out->insert(out->end(), p, p + size);
}

}  // namespace

bool is_png(const Bytes& b) noexcept {
  static constexpr std::uint8_t kSig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (b.size() < 8) return false;
  for (int i = 0; i < 8; ++i) {
    if (b[static_cast<std::size_t>(i)] != kSig[i]) return false;
  }
  return true;
}

namespace {

std::uint32_t be32(const std::uint8_t* p) noexcept {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) |
         std::uint32_t{p[3]};
}

// stb_image does not verify PNG chunk CRCs, so a flipped byte would decode as a silently
// wrong map. Walk the chunks (PNG spec, section 5) and check every CRC up to IEND. Also
// refuse an IDAT too small to inflate to the raster IHDR promises (deflate cannot exceed
// 1032:1), before stb allocates that raster.
void check_png_chunks(const Bytes& b, const std::string& path) {
  if (b.size() < 8 + 25 || be32(&b[8]) != 13 || std::memcmp(&b[12], "IHDR", 4) != 0) {
    throw MapError(path, 0, "pixel data", "corrupt PNG: no IHDR chunk after the signature");
  }
  const std::uint64_t w = be32(&b[16]), h = be32(&b[20]);
  const unsigned depth = b[24], colour = b[25];
  const unsigned channels = colour == 2 ? 3 : colour == 4 ? 2 : colour == 6 ? 4 : 1;
  const std::uint64_t raw_bytes = h * ((w * channels * depth + 7) / 8);
  std::uint64_t idat = 0;
  std::size_t pos = 8;
  while (true) {
    if (b.size() - pos < 12) {
      throw MapError(path, 0, "pixel data",
                     "corrupt PNG: truncated at byte " + std::to_string(pos) + " before IEND");
    }
    const std::uint32_t len = be32(&b[pos]);
    const std::string type(reinterpret_cast<const char*>(&b[pos + 4]), 4);
    if (len > b.size() - pos - 12) {
      throw MapError(path, 0, "pixel data",
                     "corrupt PNG: chunk '" + type + "' at byte " + std::to_string(pos) +
                         " claims " + std::to_string(len) + " bytes, file is truncated");
    }
    const uLong crc = crc32(crc32(0L, Z_NULL, 0), &b[pos + 4], static_cast<uInt>(len) + 4);
    if (crc != be32(&b[pos + 8 + len])) {
      throw MapError(
          path, 0, "pixel data",
          "corrupt PNG: CRC mismatch in chunk '" + type + "' at byte " + std::to_string(pos));
    }
    if (type == "IDAT") idat += len;
    if (type == "IEND") break;
    pos += 12 + static_cast<std::size_t>(len);
  }
  if (idat * 1032 + 1024 < raw_bytes) {
    throw MapError(path, 0, "pixel data",
                   "corrupt PNG: " + std::to_string(idat) + " bytes of IDAT cannot hold a " +
                       std::to_string(w) + " x " + std::to_string(h) + " image");
  }
}

}  // namespace

Image decode_png(const Bytes& bytes, const std::string& path) {
  if (bytes.size() > static_cast<std::size_t>(INT_MAX)) {
    throw MapError(path, 0, "image", "file too large");
  }
  if (!is_png(bytes)) throw MapError(path, 0, "image", "not a PNG file");
  check_png_chunks(bytes, path);
  const auto* data = bytes.data();
  const int len = static_cast<int>(bytes.size());
  int w = 0, h = 0, comp = 0;
  if (stbi_info_from_memory(data, len, &w, &h, &comp) == 0) {
    throw MapError(path, 0, "pixel data", "corrupt PNG: " + stb_reason());
  }
  if (w <= 0 || h <= 0 || comp < 1 || comp > 4 ||
      static_cast<std::uint64_t>(w) * static_cast<std::uint64_t>(h) > kMaxPixels) {
    throw MapError(path, 0, "image",
                   "unsupported image size " + std::to_string(w) + " x " + std::to_string(h));
  }
  Image img;
  const bool wide = stbi_is_16_bit_from_memory(data, len) != 0;
  int dw = 0, dh = 0, dcomp = 0;
  std::unique_ptr<void, StbFree> pixels(
      wide ? static_cast<void*>(stbi_load_16_from_memory(data, len, &dw, &dh, &dcomp, 0))
           : static_cast<void*>(stbi_load_from_memory(data, len, &dw, &dh, &dcomp, 0)));
  if (!pixels) throw MapError(path, 0, "pixel data", "corrupt image: " + stb_reason());
  if (dw != w || dh != h || dcomp != comp) {
    throw MapError(path, 0, "pixel data", "decoder disagrees with the header");
  }
  img.width = w;
  img.height = h;
  img.channels = comp;
  img.maxval = wide ? 65535 : 255;
  const std::size_t n =
      static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * static_cast<std::size_t>(comp);
  img.samples.resize(n);
  if (wide) {
    const auto* p = static_cast<const std::uint16_t*>(pixels.get());
    img.samples.assign(p, p + n);
  } else {
    const auto* p = static_cast<const std::uint8_t*>(pixels.get());
    for (std::size_t i = 0; i < n; ++i) img.samples[i] = p[i];
  }
  return img;
}

Bytes encode_png(const Image& image, const std::string& path) {
  std::vector<std::uint8_t> raw(image.samples.size());
  for (std::size_t i = 0; i < raw.size(); ++i) raw[i] = static_cast<std::uint8_t>(image.samples[i]);
  Bytes out;
  const int stride = image.width * image.channels;
  if (stbi_write_png_to_func(&append_bytes, &out, image.width, image.height, image.channels,
                             raw.data(), stride) == 0) {
    throw MapError(path, 0, "image", "PNG encoding failed");
  }
  return out;
}

}  // namespace pgmcl::maps::detail
