// io::detect_file_kind: every bundled input is recognised as what it is, each kind of
// small file too, and a file it cannot place is left to its reader.

#include "pgmcl/io/file_kind.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "io_test_util.hpp"
#include "pgmcl/io/line_io.hpp"
#include "pgmcl/io/values.hpp"

namespace pgmcl::io {
namespace {

namespace fs = std::filesystem;

void write(const std::string& path, const std::string& text) {
  LineWriter w(path);  // gzip when the name ends in .gz
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = text.find('\n', start);
    w.write_line(text.substr(start, end - start));
    start = end == std::string::npos ? text.size() : end + 1;
  }
  w.close();
}

TEST(FileKind, EveryBundledInputIsWhatItIs) {
  const std::string root = PGMCL_SOURCE_DIR;
  for (const char* log : {"/data/logs/intel-corrected.log.gz", "/data/logs/aces-corrected.log.gz"})
    EXPECT_EQ(detect_file_kind(root + log), FileKind::kCarmenLog) << log;
  EXPECT_EQ(detect_file_kind(root + "/data/relations/intel.relations.gz"), FileKind::kNumberTable);
  int maps = 0, images = 0;
  for (const auto& e : fs::recursive_directory_iterator(root + "/data/maps")) {
    const std::string p = e.path().string();
    if (p.ends_with(".yaml")) {
      EXPECT_EQ(detect_file_kind(p), FileKind::kMapYaml) << p;
      ++maps;
    } else if (p.ends_with(".pgm") || p.ends_with(".pgm.gz")) {
      EXPECT_EQ(detect_file_kind(p), FileKind::kPgmImage) << p;
      ++images;
    } else if (p.ends_with(".png")) {
      EXPECT_EQ(detect_file_kind(p), FileKind::kPngImage) << p;
    }
  }
  EXPECT_GE(maps, 8);
  EXPECT_GE(images, 8);
  const std::pair<const char*, FileKind> folders[] = {
      {"/configs/filters", FileKind::kFilterYaml},
      {"/configs/scenarios", FileKind::kScenario},
      {"/configs/experiments", FileKind::kExperiment}};
  for (const auto& [folder, kind] : folders) {
    int n = 0;
    for (const auto& e : fs::directory_iterator(root + folder)) {
      if (e.path().extension() != ".yaml") continue;
      EXPECT_EQ(detect_file_kind(e.path().string()), kind) << e.path();
      ++n;
    }
    EXPECT_GE(n, 2) << folder;
  }
}

TEST(FileKind, SmallFilesOfEachKind) {
  test::TempDir dir;
  struct Case {
    const char* name;
    const char* text;
    FileKind kind;
  };
  const Case cases[] = {
      {"a.pgm", "P2\n2 1\n255\n0 255\n", FileKind::kPgmImage},
      {"m.yaml", "image: a.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n", FileKind::kMapYaml},
      {"f.yaml", "# a filter\nfilter:\n  particles: 500\nseed: 3\n", FileKind::kFilterYaml},
      {"e.yaml", "name: x\nmap: m.yaml\ndata:\n  log: a.log\n", FileKind::kExperiment},
      {"s.yaml", "map: m.yaml\nduration: 5\nrobot:\n  start: [1, 1, 0]\n", FileKind::kScenario},
      {"o.yaml", "seed: 3\n", FileKind::kOtherYaml},
      {"l.log.gz", "# CARMEN\nPARAM robot_frontlaser_offset 0\nODOM 0 0 0 0 0 0 1.0 h 1.0\n",
       FileKind::kCarmenLog},
      {"t.tum", "# t x y z qx qy qz qw\n1.5 1 2 0 0 0 0 1\n2.5 1 2 0 0 0 0 1\n",
       FileKind::kNumberTable},
      {"empty.yaml", "# nothing\n\n", FileKind::kEmpty},
      {"prose.txt", "hello world\nthis is not an input\n", FileKind::kUnknown},
  };
  for (const Case& c : cases) {
    write(dir.file(c.name), c.text);
    EXPECT_EQ(detect_file_kind(dir.file(c.name)), c.kind) << c.name << ": " << describe(c.kind);
  }
  EXPECT_EQ(detect_file_kind(dir.file("missing.yaml")), FileKind::kUnknown);
}

TEST(FileKind, ExpectNamesTheOptionTheKindAndWhatToDo) {
  test::TempDir dir;
  write(dir.file("a.pgm"), "P5\n1 1\n255\n");
  try {
    expect_file_kind(dir.file("a.pgm"), "--map", {FileKind::kMapYaml}, "a map YAML");
    FAIL() << "expected UsageError";
  } catch (const UsageError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind("--map: '" + dir.file("a.pgm") + "' is a PGM image, not a map YAML; ", 0), 0u)
        << m;
    EXPECT_NE(m.find("a map is its YAML"), std::string::npos) << m;
  }
  // Accepted kinds, unknown and empty files pass: their readers decide.
  write(dir.file("m.yaml"), "image: a.pgm\nresolution: 0.05\n");
  write(dir.file("x.txt"), "???\n");
  write(dir.file("e.txt"), "\n");
  EXPECT_NO_THROW(expect_file_kind(dir.file("m.yaml"), "--map", {FileKind::kMapYaml}, "a map"));
  EXPECT_NO_THROW(expect_file_kind(dir.file("x.txt"), "--map", {FileKind::kMapYaml}, "a map"));
  EXPECT_NO_THROW(expect_file_kind(dir.file("e.txt"), "--map", {FileKind::kMapYaml}, "a map"));
  EXPECT_EQ(
      file_kind_problem(dir.file("m.yaml"), {FileKind::kCarmenLog}, "a CARMEN log")
          .rfind("'" + dir.file("m.yaml") + "' is a map YAML (map_server), not a CARMEN log", 0),
      0u);
}

TEST(FileKind, AFifoIsLeftUnread) {
  // Peeking at a FIFO would eat what the command reads next (perturb --log FIFO hung).
  test::TempDir dir;
  const std::string fifo = dir.file("in.log");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const int fd = ::open(fifo.c_str(), O_RDWR | O_NONBLOCK);  // never blocks on Linux
  ASSERT_GE(fd, 0);
  const std::string line = "ODOM 0 0 0 0 0 0 1.0 h 1.0\n";
  ASSERT_EQ(::write(fd, line.data(), line.size()), static_cast<ssize_t>(line.size()));
  EXPECT_EQ(detect_file_kind(fifo), FileKind::kUnknown);
  EXPECT_EQ(file_kind_problem(fifo, {FileKind::kMapYaml}, "a map YAML"), "");
  char buf[64];
  EXPECT_EQ(::read(fd, buf, sizeof buf), static_cast<ssize_t>(line.size()));
  ::close(fd);
}

}  // namespace
}  // namespace pgmcl::io
