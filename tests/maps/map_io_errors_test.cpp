// Bad input: every case must throw MapError naming the file and the field (and the YAML
// line where there is one), never crash and never return a partial map.

#include <gtest/gtest.h>
#include <stb/stb_image_write.h>

#include <cstdint>
#include <string>
#include <vector>

#include "map_io_test_util.hpp"
#include "pgmcl/map_io/map_io.hpp"

namespace pgmcl::maps {
namespace {

using test::expect_map_error;
using test::TempDir;

// A directory with a valid 4x4 image; `yaml` is written as bad.yaml next to it.
class MapIoErrors : public ::testing::Test {
 protected:
  void SetUp() override {
    test::write_bytes(dir_.file("ok.pgm"), test::make_p5(4, 4, std::vector<std::uint8_t>(16, 254)));
  }
  std::string yaml(const std::string& text) {
    test::write_text(dir_.file("bad.yaml"), text);
    return dir_.file("bad.yaml");
  }
  void expect_yaml_error(const std::string& text, std::initializer_list<std::string> parts) {
    const std::string path = yaml(text);
    SCOPED_TRACE(text);
    expect_map_error([&] { (void)load_map(path); }, parts);
  }
  // An image file with these bytes, loaded through a good YAML.
  void expect_image_error(const std::string& name, const std::vector<std::uint8_t>& bytes,
                          std::initializer_list<std::string> parts) {
    test::write_bytes(dir_.file(name), bytes);
    const std::string path = yaml(test::map_yaml(name));
    SCOPED_TRACE(name);
    expect_map_error([&] { (void)load_map(path); }, parts);
  }
  TempDir dir_;
};

TEST_F(MapIoErrors, MissingYamlFile) {
  expect_map_error([&] { (void)load_map(dir_.file("nope.yaml")); },
                   {"nope.yaml", "cannot open map YAML file"});
}

TEST_F(MapIoErrors, MissingImageFileNamesImageAndYaml) {
  expect_yaml_error(test::map_yaml("absent.pgm"), {"absent.pgm", "image", "bad.yaml:1"});
}

TEST_F(MapIoErrors, ResolutionMustBePositiveNumber) {
  const std::string tail = "origin: [0, 0, 0]\n";
  expect_yaml_error("image: ok.pgm\nresolution: 0\n" + tail, {"bad.yaml:2", "resolution"});
  expect_yaml_error("image: ok.pgm\nresolution: -0.05\n" + tail, {"bad.yaml:2", "resolution"});
  expect_yaml_error("image: ok.pgm\nresolution: \"abc\"\n" + tail,
                    {"bad.yaml:2", "resolution", "expected a number", "abc"});
  expect_yaml_error("image: ok.pgm\nresolution: .nan\n" + tail, {"bad.yaml:2", "resolution"});
  expect_yaml_error("image: ok.pgm\nresolution: [0.1]\n" + tail, {"bad.yaml:2", "resolution"});
  expect_yaml_error("image: ok.pgm\nresolution:\n" + tail, {"bad.yaml:2", "resolution"});
}

TEST_F(MapIoErrors, OriginMustHoldThreeNumbers) {
  const std::string head = "image: ok.pgm\nresolution: 0.1\n";
  expect_yaml_error(head + "origin: [1.0, 2.0]\n", {"bad.yaml:3", "origin", "2 elements"});
  expect_yaml_error(head + "origin: [1, 2, 3, 4]\n", {"bad.yaml:3", "origin", "4 elements"});
  expect_yaml_error(head + "origin: 5\n", {"bad.yaml:3", "origin"});
  expect_yaml_error(head + "origin: [1, x, 0]\n", {"bad.yaml:3", "origin[1] (y)", "\"x\""});
}

TEST_F(MapIoErrors, ThresholdsMustBeOrderedAndInUnitInterval) {
  const std::string head = "image: ok.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nnegate: 0\n";
  expect_yaml_error(head + "occupied_thresh: 0.3\nfree_thresh: 0.5\n",
                    {"bad.yaml:6", "free_thresh", "occupied_thresh"});
  expect_yaml_error(head + "occupied_thresh: 0.5\nfree_thresh: 0.5\n",
                    {"bad.yaml:6", "free_thresh"});
  expect_yaml_error(head + "occupied_thresh: 1.5\nfree_thresh: 0.2\n",
                    {"bad.yaml:5", "occupied_thresh", "[0, 1]"});
  expect_yaml_error(head + "occupied_thresh: 0.65\nfree_thresh: -0.1\n",
                    {"bad.yaml:6", "free_thresh", "[0, 1]"});
  expect_yaml_error(head + "occupied_thresh: high\nfree_thresh: 0.2\n",
                    {"bad.yaml:5", "occupied_thresh", "high"});
}

TEST_F(MapIoErrors, MissingRequiredKeys) {
  expect_yaml_error("resolution: 0.1\norigin: [0, 0, 0]\n", {"bad.yaml", "image", "missing"});
  expect_yaml_error("image: ok.pgm\norigin: [0, 0, 0]\n", {"bad.yaml", "resolution", "missing"});
  expect_yaml_error("image: ok.pgm\nresolution: 0.1\n", {"bad.yaml", "origin", "missing"});
  expect_yaml_error("image: \"\"\nresolution: 0.1\norigin: [0, 0, 0]\n", {"bad.yaml:1", "image"});
}

TEST_F(MapIoErrors, NegateModeAndStructure) {
  expect_yaml_error(test::map_yaml("ok.pgm") + "mode: bogus\n",
                    {"bad.yaml:7", "mode", "bogus", "trinary"});
  expect_yaml_error("image: ok.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nnegate: 2\n",
                    {"bad.yaml:4", "negate", "2"});
  expect_yaml_error(test::map_yaml("ok.pgm") + "resolution: 0.2\n",
                    {"bad.yaml:7", "resolution", "duplicate"});
  expect_yaml_error("image: [ok.pgm\nresolution: 0.1\n", {"bad.yaml:", "yaml", "not valid YAML"});
  expect_yaml_error("- image\n- ok.pgm\n", {"bad.yaml", "yaml", "mapping"});
  expect_yaml_error("", {"bad.yaml", "yaml", "mapping"});
}

TEST_F(MapIoErrors, ValidYamlStillLoads) {
  // The fixture's control case: the same folder and image load fine.
  const OccupancyGrid grid = load_map(yaml(test::map_yaml("ok.pgm")));
  EXPECT_EQ(grid.width(), 4);
  EXPECT_EQ(grid.at(3, 3), kFree);
}

TEST_F(MapIoErrors, TruncatedAndMalformedPgm) {
  std::vector<std::uint8_t> p5 = test::make_p5(10, 10, std::vector<std::uint8_t>(100, 254));
  p5.resize(p5.size() - 50);
  expect_image_error("trunc.pgm", p5, {"trunc.pgm", "pixel data", "truncated", "100", "50"});
  // 16-bit: 10 x 10 needs 200 bytes.
  expect_image_error("trunc16.pgm", test::make_p5(10, 10, std::vector<std::uint8_t>(100, 0), 65535),
                     {"trunc16.pgm", "pixel data", "200"});
  const auto text = [](const std::string& s) {
    return std::vector<std::uint8_t>(s.begin(), s.end());
  };
  expect_image_error("h.pgm", text("P5\n10 x\n255\n"), {"h.pgm", "height"});
  expect_image_error("w.pgm", text("P5\n0 10\n255\n"), {"w.pgm", "width"});
  expect_image_error("m0.pgm", text("P5\n1 1\n0\n\x01"), {"m0.pgm", "maxval"});
  expect_image_error("m7.pgm", text("P5\n1 1\n70000\n\x01\x01"), {"m7.pgm", "maxval"});
  expect_image_error("hdr.pgm", text("P5\n10 10"), {"hdr.pgm", "maxval"});
  expect_image_error("huge.pgm", text("P5\n1000000 1000000\n255\n"), {"huge.pgm", "width"});
  expect_image_error("big.pgm", test::make_p5(2, 1, {200, 7}, 100),
                     {"big.pgm", "pixel data", "maxval"});
  expect_image_error("p4.pgm", text("P4\n8 1\n\xff"), {"p4.pgm", "magic", "P4"});
  expect_image_error("p2.pgm", text("P2\n3 1\n255\n0 1\n"), {"p2.pgm", "pixel data"});
  expect_image_error("p2x.pgm", text("P2\n3 1\n255\n0 1 x\n"), {"p2x.pgm", "pixel data"});
  expect_image_error("empty.pgm", {}, {"empty.pgm", "empty"});
}

TEST_F(MapIoErrors, CorruptPng) {
  const std::vector<std::uint8_t> png =
      test::read_bytes(test::data_dir() + "/nav2/testmap/testmap.png");
  ASSERT_GT(png.size(), 100u);
  // Cut inside the compressed pixel data.
  std::vector<std::uint8_t> cut(png.begin(), png.begin() + static_cast<long>(png.size() / 2));
  expect_image_error("cut.png", cut, {"cut.png", "pixel data", "corrupt"});
  // Keep the signature and IHDR, overwrite the IDAT payload with garbage.
  std::vector<std::uint8_t> garbage = png;
  for (std::size_t i = 41; i < garbage.size() - 12; ++i) garbage[i] = 0xA5;
  expect_image_error("garbage.png", garbage, {"garbage.png", "corrupt"});
  // A single flipped bit in the compressed pixels (stb alone would not notice: it does
  // not check CRCs).
  std::vector<std::uint8_t> flipped = png;
  flipped[png.size() - 20] ^= 0x01;
  expect_image_error("flip.png", flipped, {"flip.png", "pixel data", "CRC"});
  // Not an image at all.
  expect_image_error("text.png", std::vector<std::uint8_t>(64, 'z'),
                     {"text.png", "image", "not a PGM/PPM or PNG"});
}

// Bitwise CRC-32 (PNG spec, Annex D), to forge chunks with valid checksums.
std::uint32_t crc32_of(const std::uint8_t* p, std::size_t n) {
  std::uint32_t c = 0xffffffffu;
  for (std::size_t i = 0; i < n; ++i) {
    c ^= p[i];
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
  }
  return c ^ 0xffffffffu;
}

void put_be32(std::vector<std::uint8_t>& b, std::size_t at, std::uint32_t v) {
  for (int i = 0; i < 4; ++i)
    b[at + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(v >> (24 - 8 * i));
}

TEST_F(MapIoErrors, PngClaimingAHugeRasterIsRefusedBeforeDecoding) {
  // testmap.png with IHDR patched to 30000 x 30000 and a correct IHDR CRC: its 50-byte IDAT
  // cannot inflate to 900 MB, so the loader must refuse it without allocating that much.
  std::vector<std::uint8_t> png = test::read_bytes(test::data_dir() + "/nav2/testmap/testmap.png");
  ASSERT_GT(png.size(), 33u);
  put_be32(png, 16, 30000);
  put_be32(png, 20, 30000);
  put_be32(png, 29, crc32_of(&png[12], 17));
  expect_image_error("huge.png", png, {"huge.png", "pixel data", "30000 x 30000"});
}

TEST_F(MapIoErrors, OtherImageFormatsAreRefused) {
  const std::vector<std::uint8_t> px(4, 0);
  ASSERT_NE(stbi_write_bmp(dir_.file("m.bmp").c_str(), 2, 2, 1, px.data()), 0);
  const std::string path = yaml(test::map_yaml("m.bmp"));
  expect_map_error([&] { (void)load_map(path); }, {"m.bmp", "image", "PNG"});
}

TEST_F(MapIoErrors, CorruptGzip) {
  const std::vector<std::uint8_t> gz = test::read_bytes(test::data_dir() + "/nav2/depot.pgm.gz");
  ASSERT_GT(gz.size(), 1000u);
  std::vector<std::uint8_t> cut(gz.begin(), gz.begin() + static_cast<long>(gz.size() / 2));
  expect_image_error("cut.pgm.gz", cut, {"cut.pgm.gz", "gzip", "truncated"});
  std::vector<std::uint8_t> flipped = gz;
  for (std::size_t i = 200; i < 260; ++i) flipped[i] ^= 0x5A;
  expect_image_error("flip.pgm.gz", flipped, {"flip.pgm.gz", "gzip"});
}

TEST_F(MapIoErrors, LoadMapImageValidatesMetadata) {
  MapMetadata meta;
  meta.resolution = 0.0;
  expect_map_error([&] { (void)load_map_image(dir_.file("ok.pgm"), meta); },
                   {"ok.pgm", "resolution"});
  meta.resolution = 0.1;
  meta.free_thresh = 0.9;
  expect_map_error([&] { (void)load_map_image(dir_.file("ok.pgm"), meta); },
                   {"ok.pgm", "free_thresh"});
}

TEST_F(MapIoErrors, MapErrorCarriesItsParts) {
  try {
    (void)load_map(yaml("image: ok.pgm\nresolution: abc\norigin: [0, 0, 0]\n"));
    FAIL() << "no MapError";
  } catch (const MapError& e) {
    EXPECT_EQ(e.file(), dir_.file("bad.yaml"));
    EXPECT_EQ(e.line(), 2);
    EXPECT_EQ(e.field(), "resolution");
  }
}

}  // namespace
}  // namespace pgmcl::maps
