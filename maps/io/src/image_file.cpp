// File access, gzip and format sniffing for the map loader.

#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include "image_codec.hpp"
#include "pgmcl/map_io/map_io.hpp"

namespace pgmcl::maps::detail {

namespace {

// A gzipped map larger than this is certainly not a map: refuse before exhausting memory.
constexpr std::size_t kMaxInflated = std::size_t{1} << 30;

std::string zlib_problem(int code, const z_stream& zs) {
  std::string msg = zs.msg != nullptr ? zs.msg : zError(code);
  return msg + " (zlib error " + std::to_string(code) + ")";
}

}  // namespace

Bytes read_file_bytes(const std::string& path, const std::string& what) {
  // A folder opens as a stream of unknown size and a device or FIFO never ends: refuse
  // anything but a regular file (symbolic links followed) before reading.
  std::error_code ec;
  const std::filesystem::file_status st = std::filesystem::status(path, ec);
  if (std::filesystem::is_directory(st)) {
    throw MapError(path, 0, "", what + " is a folder, not a file");
  }
  if (std::filesystem::exists(st) && !std::filesystem::is_regular_file(st)) {
    throw MapError(path, 0, "", what + " is not a regular file (a device, FIFO or socket)");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw MapError(path, 0, "", "cannot open " + what + ": " + std::strerror(errno));
  }
  Bytes bytes;
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0) throw MapError(path, 0, "", "cannot determine the size of " + what);
  if (static_cast<std::uint64_t>(size) > kMaxInflated) {
    throw MapError(
        path, 0, "",
        what + " is " + std::to_string(size) + " bytes, more than the 1 GiB any map file may hold");
  }
  in.seekg(0, std::ios::beg);
  bytes.resize(static_cast<std::size_t>(size));
  if (size > 0 && !in.read(reinterpret_cast<char*>(bytes.data()), size)) {
    throw MapError(path, 0, "", "cannot read " + what);
  }
  return bytes;
}

void write_file_bytes(const std::string& path, const Bytes& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw MapError(path, 0, "", std::string("cannot create file: ") + std::strerror(errno));
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) throw MapError(path, 0, "", "write failed");
}

bool is_gzip(const Bytes& bytes) noexcept {
  return bytes.size() >= 2 && bytes[0] == 0x1f && bytes[1] == 0x8b;
}

Bytes gunzip(const Bytes& bytes, const std::string& path) {
  if (bytes.size() > std::numeric_limits<uInt>::max()) {
    throw MapError(path, 0, "gzip", "compressed file too large");
  }
  z_stream zs{};
  // 16 + MAX_WBITS: gzip wrapper only.
  int rc = inflateInit2(&zs, 16 + MAX_WBITS);
  if (rc != Z_OK) throw MapError(path, 0, "gzip", zlib_problem(rc, zs));
  zs.next_in = const_cast<Bytef*>(bytes.data());
  zs.avail_in = static_cast<uInt>(bytes.size());
  Bytes out;
  std::size_t chunk = std::max<std::size_t>(bytes.size() * 4, 1 << 16);
  do {
    if (out.size() >= kMaxInflated) {
      inflateEnd(&zs);
      throw MapError(path, 0, "gzip", "decompressed size exceeds 1 GiB");
    }
    const std::size_t old = out.size();
    chunk = std::min(chunk, kMaxInflated - old);
    out.resize(old + chunk);
    zs.next_out = out.data() + old;
    zs.avail_out = static_cast<uInt>(chunk);
    rc = inflate(&zs, Z_NO_FLUSH);
    out.resize(old + chunk - zs.avail_out);
    if (rc == Z_BUF_ERROR && zs.avail_in == 0) {
      inflateEnd(&zs);
      throw MapError(path, 0, "gzip", "truncated gzip stream");
    }
    if (rc != Z_OK && rc != Z_STREAM_END && rc != Z_BUF_ERROR) {
      const std::string problem = "corrupt gzip data: " + zlib_problem(rc, zs);
      inflateEnd(&zs);
      throw MapError(path, 0, "gzip", problem);
    }
    chunk *= 2;
  } while (rc != Z_STREAM_END);
  inflateEnd(&zs);
  return out;
}

Bytes gzip(const Bytes& bytes, const std::string& path) {
  if (bytes.size() > std::numeric_limits<uInt>::max() / 2) {
    throw MapError(path, 0, "gzip", "image too large to compress");
  }
  z_stream zs{};
  // 16 + MAX_WBITS: gzip wrapper, as `gzip -9` writes it.
  int rc = deflateInit2(&zs, 9, Z_DEFLATED, 16 + MAX_WBITS, 8, Z_DEFAULT_STRATEGY);
  if (rc != Z_OK) throw MapError(path, 0, "gzip", zlib_problem(rc, zs));
  Bytes out(deflateBound(&zs, static_cast<uLong>(bytes.size())));
  zs.next_in = const_cast<Bytef*>(bytes.data());
  zs.avail_in = static_cast<uInt>(bytes.size());
  zs.next_out = out.data();
  zs.avail_out = static_cast<uInt>(out.size());
  rc = deflate(&zs, Z_FINISH);
  const std::size_t produced = out.size() - zs.avail_out;
  deflateEnd(&zs);
  if (rc != Z_STREAM_END) throw MapError(path, 0, "gzip", "compression failed");
  out.resize(produced);
  return out;
}

Image decode_image(const Bytes& bytes, const std::string& path) {
  if (bytes.empty()) throw MapError(path, 0, "image", "file is empty");
  if (is_gzip(bytes)) {
    const Bytes inflated = gunzip(bytes, path);
    if (is_gzip(inflated)) throw MapError(path, 0, "gzip", "nested gzip is not supported");
    return decode_image(inflated, path);
  }
  if (is_pnm(bytes)) return decode_pnm(bytes, path);
  if (is_png(bytes)) return decode_png(bytes, path);
  throw MapError(path, 0, "image",
                 "not a PGM/PPM or PNG file (optionally gzipped); convert other formats to PNG");
}

}  // namespace pgmcl::maps::detail
