// Netpbm greymaps and pixmaps (P2, P3, P5, P6), as map_server maps are usually PGM.
// Format: netpbm's pgm(5)/ppm(5) pages. The header is magic, width, height, maxval,
// separated by whitespace with '#' comments; binary rasters start after exactly one
// whitespace byte; samples wider than 8 bits are big-endian.

#include <cctype>
#include <cstdint>
#include <string>

#include "image_codec.hpp"
#include "pgmcl/map_io/map_io.hpp"

namespace pgmcl::maps::detail {

namespace {

class PnmReader {
 public:
  PnmReader(const Bytes& bytes, const std::string& path) : b_(bytes), path_(path) {}

  void skip_space_and_comments() {
    while (pos_ < b_.size()) {
      if (b_[pos_] == '#') {
        while (pos_ < b_.size() && b_[pos_] != '\n' && b_[pos_] != '\r') ++pos_;
      } else if (std::isspace(b_[pos_]) != 0) {
        ++pos_;
      } else {
        return;
      }
    }
  }

  /// An unsigned decimal number in [lo, hi]; `field` names it in errors.
  std::uint32_t number(const char* field, std::uint32_t lo, std::uint32_t hi) {
    skip_space_and_comments();
    if (pos_ >= b_.size()) fail(field, "missing (file ends in the header or raster)");
    if (std::isdigit(b_[pos_]) == 0) {
      fail(field, std::string("expected a decimal number, found byte ") +
                      std::to_string(static_cast<int>(b_[pos_])) + " at offset " +
                      std::to_string(pos_));
    }
    std::uint64_t v = 0;
    while (pos_ < b_.size() && std::isdigit(b_[pos_]) != 0) {
      v = v * 10 + static_cast<std::uint64_t>(b_[pos_] - '0');
      if (v > hi) fail(field, "value exceeds " + std::to_string(hi));
      ++pos_;
    }
    if (v < lo) fail(field, "value " + std::to_string(v) + " is below " + std::to_string(lo));
    if (pos_ < b_.size() && std::isspace(b_[pos_]) == 0 && b_[pos_] != '#') {
      fail(field, "number followed by unexpected byte at offset " + std::to_string(pos_));
    }
    return static_cast<std::uint32_t>(v);
  }

  /// Consumes the single whitespace byte that ends a binary header.
  void end_of_binary_header() {
    if (pos_ >= b_.size() || std::isspace(b_[pos_]) == 0) {
      fail("maxval", "expected one whitespace byte before the raster");
    }
    ++pos_;
  }

  [[noreturn]] void fail(const std::string& field, const std::string& problem) const {
    throw MapError(path_, 0, field, problem);
  }

  [[nodiscard]] std::size_t pos() const noexcept { return pos_; }
  [[nodiscard]] std::size_t remaining() const noexcept { return b_.size() - pos_; }
  [[nodiscard]] const std::uint8_t* here() const noexcept { return b_.data() + pos_; }
  void advance(std::size_t n) noexcept { pos_ += n; }

 private:
  const Bytes& b_;
  const std::string& path_;
  std::size_t pos_ = 0;
};

}  // namespace

bool is_pnm(const Bytes& bytes) noexcept {
  return bytes.size() >= 2 && bytes[0] == 'P' && bytes[1] >= '1' && bytes[1] <= '7';
}

Image decode_pnm(const Bytes& bytes, const std::string& path) {
  PnmReader r(bytes, path);
  const char type = static_cast<char>(bytes.at(1));
  if (type != '2' && type != '3' && type != '5' && type != '6') {
    r.fail("magic", std::string("Netpbm type P") + type +
                        " is not supported (use P2/P5 greymaps or P3/P6 pixmaps)");
  }
  r.advance(2);
  if (r.remaining() == 0 || std::isspace(*r.here()) == 0) {
    r.fail("magic", "expected whitespace after the magic number");
  }
  constexpr std::uint32_t kMaxSide = 1u << 20;
  Image img;
  img.width = static_cast<int>(r.number("width", 1, kMaxSide));
  img.height = static_cast<int>(r.number("height", 1, kMaxSide));
  img.maxval = static_cast<int>(r.number("maxval", 1, 65535));
  img.channels = (type == '3' || type == '6') ? 3 : 1;
  const std::uint64_t pixels =
      static_cast<std::uint64_t>(img.width) * static_cast<std::uint64_t>(img.height);
  if (pixels > kMaxPixels) {
    r.fail("width", std::to_string(img.width) + " x " + std::to_string(img.height) +
                        " pixels is more than this loader accepts");
  }
  const std::uint64_t count = pixels * static_cast<std::uint64_t>(img.channels);
  const auto maxval = static_cast<std::uint32_t>(img.maxval);

  if (type == '2' || type == '3') {
    // Each ASCII sample takes at least one byte: a cheap bound before allocating.
    if (count > r.remaining()) {
      r.fail("pixel data", "truncated: the header needs " + std::to_string(count) +
                               " samples but only " + std::to_string(r.remaining()) +
                               " bytes follow");
    }
    img.samples.reserve(static_cast<std::size_t>(count));
    for (std::uint64_t i = 0; i < count; ++i) {
      img.samples.push_back(static_cast<std::uint16_t>(r.number("pixel data", 0, maxval)));
    }
    return img;
  }

  r.end_of_binary_header();
  const std::uint64_t bytes_per_sample = maxval > 255 ? 2 : 1;
  const std::uint64_t need = count * bytes_per_sample;
  if (r.remaining() < need) {
    r.fail("pixel data", "truncated: the header (" + std::to_string(img.width) + " x " +
                             std::to_string(img.height) + ", maxval " + std::to_string(img.maxval) +
                             ") needs " + std::to_string(need) + " bytes of pixel data but only " +
                             std::to_string(r.remaining()) + " are present");
  }
  img.samples.resize(static_cast<std::size_t>(count));
  const std::uint8_t* p = r.here();
  for (std::size_t i = 0; i < img.samples.size(); ++i) {
    const std::uint32_t v =
        bytes_per_sample == 2 ? (std::uint32_t{p[2 * i]} << 8) | p[2 * i + 1] : p[i];
    if (v > maxval) {
      r.fail("pixel data", "sample " + std::to_string(i) + " has value " + std::to_string(v) +
                               " above maxval " + std::to_string(maxval));
    }
    img.samples[i] = static_cast<std::uint16_t>(v);
  }
  return img;
}

Bytes encode_pgm(const Image& image, const std::string& comment) {
  std::string header = "P5\n";
  if (!comment.empty()) header += "# " + comment + "\n";
  header += std::to_string(image.width) + " " + std::to_string(image.height) + "\n255\n";
  Bytes out(header.begin(), header.end());
  out.reserve(out.size() + image.samples.size());
  for (const std::uint16_t s : image.samples) out.push_back(static_cast<std::uint8_t>(s));
  return out;
}

}  // namespace pgmcl::maps::detail
