// map_server's interpretation of pixel values (trinary / scale / raw, negate, alpha),
// on small images written by the test. Expected cells are worked out by hand from
// nav2_map_server's rules: occ = 1 - v/255 (v/255 if negate); trinary: occ > occupied_thresh
// -> 100, occ < free_thresh -> 0, else -1; scale: linear in between; raw: v itself.

#include <gtest/gtest.h>
#include <stb/stb_image_write.h>

#include <cstdint>
#include <string>
#include <vector>

#include "map_io_test_util.hpp"
#include "pgmcl/map_io/map_io.hpp"

namespace pgmcl::maps {
namespace {

using test::TempDir;

// Loads a one-row image through a YAML with the given extra keys; returns row 0.
std::vector<int> load_row(const TempDir& dir, const std::string& image,
                          const std::string& yaml_body) {
  test::write_text(dir.file("map.yaml"), "image: " + image + "\n" + yaml_body);
  const OccupancyGrid grid = load_map(dir.file("map.yaml"));
  EXPECT_EQ(grid.height(), 1);
  std::vector<int> row;
  for (int c = 0; c < grid.width(); ++c) row.push_back(grid.at(c, 0));
  return row;
}

const std::string kYaml =
    "resolution: 0.1\norigin: [0, 0, 0]\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";

// occ for v = 0, 89, 90, 204, 205, 206, 254, 255: 1, .651, .647, .2, .19608, .1922, .004, 0.
const std::vector<std::uint8_t> kGreys = {0, 89, 90, 204, 205, 206, 254, 255};

TEST(MapIoModes, TrinaryThresholdsAreStrict) {
  const TempDir dir;
  test::write_bytes(dir.file("g.pgm"), test::make_p5(8, 1, kGreys));
  EXPECT_EQ(load_row(dir, "g.pgm", kYaml + "negate: 0\nmode: trinary\n"),
            (std::vector<int>{100, 100, -1, -1, -1, 0, 0, 0}));
}

TEST(MapIoModes, NegateSwapsBlackAndWhite) {
  // occ = v/255: free below 0.196 (v <= 49), occupied above 0.65 (v >= 166).
  const TempDir dir;
  test::write_bytes(dir.file("g.pgm"), test::make_p5(8, 1, kGreys));
  EXPECT_EQ(load_row(dir, "g.pgm", kYaml + "negate: 1\n"),
            (std::vector<int>{0, -1, -1, 100, 100, 100, 100, 100}));
  EXPECT_EQ(load_row(dir, "g.pgm", kYaml + "negate: true\n"),
            (std::vector<int>{0, -1, -1, 100, 100, 100, 100, 100}));
}

TEST(MapIoModes, ScaleIsLinearBetweenThresholds) {
  // v = 100: occ = .60784, (occ - .196) / .454 * 100 = 90.71 -> 91; v = 150: 47.53 -> 48;
  // v = 200: 4.34 -> 4.
  const TempDir dir;
  test::write_bytes(dir.file("g.pgm"), test::make_p5(6, 1, {0, 50, 100, 150, 200, 255}));
  EXPECT_EQ(load_row(dir, "g.pgm", kYaml + "negate: 0\nmode: scale\n"),
            (std::vector<int>{100, 100, 91, 48, 4, 0}));
}

TEST(MapIoModes, ScaleTreatsAnyTransparencyAsUnknown) {
  const TempDir dir;
  // Grey + alpha PNG: (100, opaque) -> 91 as above; (100, 254) and (255, 0) -> unknown.
  const std::vector<std::uint8_t> ga = {100, 255, 100, 254, 255, 0, 255, 255};
  ASSERT_NE(stbi_write_png(dir.file("ga.png").c_str(), 4, 1, 2, ga.data(), 8), 0);
  EXPECT_EQ(load_row(dir, "ga.png", kYaml + "negate: 0\nmode: scale\n"),
            (std::vector<int>{91, -1, -1, 0}));
}

TEST(MapIoModes, TrinaryAveragesAlphaLikeNav2) {
  // nav2 averages R, G, B and alpha in trinary mode: for grey g and alpha a the shade is
  // (3g + a) / 4 / 255. (0, 0): 0 -> occupied. (255, 0): .75, occ .25 -> unknown.
  // (255, 255) -> free. (60, 255): .4265, occ .5735 -> unknown, where an opaque 60 without
  // alpha (occ .765) would be occupied.
  const TempDir dir;
  const std::vector<std::uint8_t> ga = {0, 0, 255, 0, 255, 255, 60, 255};
  ASSERT_NE(stbi_write_png(dir.file("ga.png").c_str(), 4, 1, 2, ga.data(), 8), 0);
  EXPECT_EQ(load_row(dir, "ga.png", kYaml + "negate: 0\n"), (std::vector<int>{100, -1, 0, -1}));
  test::write_bytes(dir.file("g.pgm"), test::make_p5(1, 1, {60}));
  EXPECT_EQ(load_row(dir, "g.pgm", kYaml + "negate: 0\n"), (std::vector<int>{100}));
}

TEST(MapIoModes, RgbAveragesTheChannels) {
  // (255, 0, 0): shade 1/3, occ .667 -> occupied; (255, 255, 0): occ .333 -> unknown;
  // white -> free.
  const TempDir dir;
  const std::vector<std::uint8_t> rgb = {255, 0, 0, 255, 255, 0, 255, 255, 255};
  ASSERT_NE(stbi_write_png(dir.file("rgb.png").c_str(), 3, 1, 3, rgb.data(), 9), 0);
  EXPECT_EQ(load_row(dir, "rgb.png", kYaml + "negate: 0\n"), (std::vector<int>{100, -1, 0}));
  // The same pixels as a binary PPM (P6).
  std::string ppm = "P6\n3 1\n255\n";
  std::vector<std::uint8_t> bytes(ppm.begin(), ppm.end());
  bytes.insert(bytes.end(), rgb.begin(), rgb.end());
  test::write_bytes(dir.file("rgb.ppm"), bytes);
  EXPECT_EQ(load_row(dir, "rgb.ppm", kYaml + "negate: 0\n"), (std::vector<int>{100, -1, 0}));
}

TEST(MapIoModes, RawKeepsValuesUpTo100AndIgnoresNegate) {
  const TempDir dir;
  test::write_bytes(dir.file("g.pgm"), test::make_p5(6, 1, {0, 37, 100, 101, 205, 255}));
  const std::vector<int> expected = {0, 37, 100, -1, -1, -1};
  EXPECT_EQ(load_row(dir, "g.pgm", kYaml + "negate: 0\nmode: raw\n"), expected);
  EXPECT_EQ(load_row(dir, "g.pgm", kYaml + "negate: 1\nmode: raw\n"), expected);
}

TEST(MapIoModes, SixteenBitPgmUsesMaxval) {
  // maxval 65535, big-endian samples: occ = 1 - v/65535.
  // 0 -> 1 (occupied), 13000 -> .802 (occupied), 32768 -> .49999 (unknown), 65535 -> free.
  const TempDir dir;
  std::string header = "P5\n4 1\n65535\n";
  std::vector<std::uint8_t> bytes(header.begin(), header.end());
  for (const unsigned v : {0u, 13000u, 32768u, 65535u}) {
    bytes.push_back(static_cast<std::uint8_t>(v >> 8));
    bytes.push_back(static_cast<std::uint8_t>(v & 0xff));
  }
  test::write_bytes(dir.file("w.pgm"), bytes);
  EXPECT_EQ(load_row(dir, "w.pgm", kYaml + "negate: 0\n"), (std::vector<int>{100, 100, -1, 0}));
  // Raw mode scales to 0..255 first: 13000 -> round(50.58) = 51.
  EXPECT_EQ(load_row(dir, "w.pgm", kYaml + "negate: 0\nmode: raw\n"),
            (std::vector<int>{0, 51, -1, -1}));
}

// Bitwise CRC-32 (PNG spec, Annex D).
std::uint32_t crc32_of(const std::vector<std::uint8_t>& b, std::size_t from) {
  std::uint32_t c = 0xffffffffu;
  for (std::size_t i = from; i < b.size(); ++i) {
    c ^= b[i];
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
  }
  return c ^ 0xffffffffu;
}

void append_be32(std::vector<std::uint8_t>& b, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) b.push_back(static_cast<std::uint8_t>(v >> (24 - 8 * i)));
}

void append_chunk(std::vector<std::uint8_t>& png, const char* type,
                  const std::vector<std::uint8_t>& data) {
  append_be32(png, static_cast<std::uint32_t>(data.size()));
  std::vector<std::uint8_t> body(type, type + 4);
  body.insert(body.end(), data.begin(), data.end());
  png.insert(png.end(), body.begin(), body.end());
  append_be32(png, crc32_of(body, 0));
}

// A 16-bit greyscale PNG (stbi_write_png only writes 8 bits): one row, the raster in a
// zlib stream made of a single stored (uncompressed) deflate block (RFC 1950/1951).
std::vector<std::uint8_t> png16_row(const std::vector<std::uint16_t>& px) {
  std::vector<std::uint8_t> raw = {0};  // filter type 0
  for (const std::uint16_t v : px) {
    raw.push_back(static_cast<std::uint8_t>(v >> 8));
    raw.push_back(static_cast<std::uint8_t>(v & 0xff));
  }
  const auto n = static_cast<std::uint16_t>(raw.size());
  std::vector<std::uint8_t> z = {0x78,
                                 0x01,
                                 0x01,
                                 static_cast<std::uint8_t>(n & 0xff),
                                 static_cast<std::uint8_t>(n >> 8),
                                 static_cast<std::uint8_t>(~n & 0xff),
                                 static_cast<std::uint8_t>((~n >> 8) & 0xff)};
  z.insert(z.end(), raw.begin(), raw.end());
  std::uint32_t a = 1, b = 0;  // Adler-32
  for (const std::uint8_t c : raw) {
    a = (a + c) % 65521;
    b = (b + a) % 65521;
  }
  append_be32(z, (b << 16) | a);
  std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  std::vector<std::uint8_t> ihdr;
  append_be32(ihdr, static_cast<std::uint32_t>(px.size()));
  append_be32(ihdr, 1);
  ihdr.insert(ihdr.end(), {16, 0, 0, 0, 0});  // depth 16, greyscale, no interlace
  append_chunk(png, "IHDR", ihdr);
  append_chunk(png, "IDAT", z);
  append_chunk(png, "IEND", {});
  return png;
}

TEST(MapIoModes, SixteenBitPngMatchesSixteenBitPgm) {
  const TempDir dir;
  test::write_bytes(dir.file("w.png"), png16_row({0, 13000, 32768, 65535}));
  EXPECT_EQ(load_row(dir, "w.png", kYaml + "negate: 0\n"), (std::vector<int>{100, 100, -1, 0}));
  EXPECT_EQ(load_row(dir, "w.png", kYaml + "negate: 0\nmode: raw\n"),
            (std::vector<int>{0, 51, -1, -1}));
}

TEST(MapIoModes, AsciiPgmWithCommentsAndSmallMaxval) {
  // maxval 15: 0 -> occupied, 8 -> occ .467 unknown, 15 -> free.
  const TempDir dir;
  test::write_text(dir.file("a.pgm"), "P2\n# a comment\n3 # width\n1\n15\n0 8\n15\n");
  EXPECT_EQ(load_row(dir, "a.pgm", kYaml + "negate: 0\n"), (std::vector<int>{100, -1, 0}));
}

TEST(MapIoModes, ImageRowsAreFlippedSoRowZeroIsTheBottom) {
  // 2 x 3 image, top row black, the rest white, plus one black pixel bottom-right.
  const TempDir dir;
  test::write_bytes(dir.file("f.pgm"), test::make_p5(2, 3, {0, 0, 255, 255, 255, 0}));
  test::write_text(dir.file("f.yaml"), test::map_yaml("f.pgm"));
  const OccupancyGrid grid = load_map(dir.file("f.yaml"));
  ASSERT_EQ(grid.width(), 2);
  ASSERT_EQ(grid.height(), 3);
  EXPECT_EQ(grid.at(0, 2), kOccupied);
  EXPECT_EQ(grid.at(1, 2), kOccupied);
  EXPECT_EQ(grid.at(0, 1), kFree);
  EXPECT_EQ(grid.at(0, 0), kFree);
  EXPECT_EQ(grid.at(1, 0), kOccupied);
}

TEST(MapIoModes, LoadMapImageTakesMetadataDirectly) {
  const TempDir dir;
  test::write_bytes(dir.file("g.pgm"), test::make_p5(8, 1, kGreys));
  MapMetadata meta;
  meta.resolution = 0.5;
  meta.origin = {1.0, 2.0, -0.5};
  meta.negate = true;
  const OccupancyGrid grid = load_map_image(dir.file("g.pgm"), meta);
  EXPECT_EQ(grid.at(0, 0), kFree);
  EXPECT_EQ(grid.at(7, 0), kOccupied);
  EXPECT_DOUBLE_EQ(grid.resolution(), 0.5);
  EXPECT_DOUBLE_EQ(grid.origin().theta, -0.5);
}

TEST(MapIoModes, DefaultsAndUnknownKeysAreReportedAsWarnings) {
  const TempDir dir;
  test::write_bytes(dir.file("g.pgm"), test::make_p5(8, 1, kGreys));
  test::write_text(dir.file("m.yaml"),
                   "image: g.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nfoo: 3\n");
  MapLoadReport report;
  const OccupancyGrid grid = load_map(dir.file("m.yaml"), &report);
  // map_server defaults: occupied 0.65, free 0.196, negate 0 -> same as the trinary test.
  std::vector<int> row;
  for (int c = 0; c < grid.width(); ++c) row.push_back(grid.at(c, 0));
  EXPECT_EQ(row, (std::vector<int>{100, 100, -1, -1, -1, 0, 0, 0}));
  ASSERT_EQ(report.warnings.size(), 4u);
  EXPECT_NE(report.warnings[0].find("m.yaml:4: unknown key 'foo'"), std::string::npos)
      << report.warnings[0];
  for (const char* key : {"occupied_thresh", "free_thresh", "negate"}) {
    bool found = false;
    for (const auto& w : report.warnings) found = found || w.find(key) != std::string::npos;
    EXPECT_TRUE(found) << key;
  }
}

}  // namespace
}  // namespace pgmcl::maps
