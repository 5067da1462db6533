// OutputFiles: temporaries beside the targets, renamed together on commit; nothing changes
// without a commit; inputs and duplicate outputs refused; dropped targets removed.

#include "output_files.hpp"

#include <gtest/gtest.h>

#include <filesystem>

#include "pgmcl/io/errors.hpp"
#include "pgmcl/io/values.hpp"
#include "temp_files.hpp"

namespace pgmcl::app {
namespace {

namespace fs = std::filesystem;
using testkit::read_text;
using testkit::TempDir;
using testkit::write_text;

std::size_t temporaries(const fs::path& dir) {
  std::size_t n = 0;
  for (const auto& f : fs::recursive_directory_iterator(dir)) {
    n += f.path().filename().string().find(".pgmcl-") != std::string::npos ? 1 : 0;
  }
  return n;
}

TEST(OutputFiles, CommitRenamesEveryOutputAndRemovesDroppedOnes) {
  const TempDir dir("output_files");
  write_text(dir.file("out/a.txt"), "old a");
  write_text(dir.file("out/stale.png"), "old picture");
  {
    OutputFiles files;
    const std::string a = files.add(dir.file("out/a.txt"), "--out");
    const std::string b = files.add(dir.file("out/new/b.txt"), "--out");
    (void)files.add(dir.file("out/stale.png"), "--out");
    EXPECT_EQ(fs::path(a).parent_path(), fs::path(dir.file("out")));  // beside its target
    EXPECT_EQ(temporaries(dir.path()), 3u);
    write_text(a, "new a");
    write_text(b, "new b");
    files.drop(dir.file("out/stale.png"));
    EXPECT_EQ(read_text(dir.file("out/a.txt")), "old a");  // untouched until commit
    files.commit();
  }
  EXPECT_EQ(read_text(dir.file("out/a.txt")), "new a");
  EXPECT_EQ(read_text(dir.file("out/new/b.txt")), "new b");
  EXPECT_FALSE(fs::exists(dir.file("out/stale.png")));
  EXPECT_EQ(temporaries(dir.path()), 0u);
}

TEST(OutputFiles, WithoutCommitNothingChangesAndNoTemporaryStays) {
  const TempDir dir("output_files");
  write_text(dir.file("a.txt"), "old a");
  {
    OutputFiles files;
    write_text(files.add(dir.file("a.txt"), "--out"), "half written");
    write_text(files.add(dir.file("b.txt"), "--truth-out"), "half written");
  }  // a failure: the command threw before commit
  EXPECT_EQ(read_text(dir.file("a.txt")), "old a");
  EXPECT_FALSE(fs::exists(dir.file("b.txt")));
  EXPECT_EQ(temporaries(dir.path()), 0u);
}

TEST(OutputFiles, InputsAndSharedOutputsAreRefusedByAnySpelling) {
  const TempDir dir("output_files");
  write_text(dir.file("in.tum"), "input");
  fs::create_symlink(dir.file("in.tum"), dir.file("link.tum"));
  fs::create_directories(dir.file("sub"));
  OutputFiles files;
  files.input(dir.file("in.tum"), "--truth");
  EXPECT_THROW((void)files.add(dir.file("sub/../in.tum"), "--out"), io::UsageError);
  EXPECT_THROW((void)files.add(dir.file("link.tum"), "--out"), io::UsageError);
  (void)files.add(dir.file("x.log"), "--out");
  EXPECT_THROW((void)files.add(dir.file("./x.log"), "--truth-out"), io::UsageError);
  EXPECT_THROW(files.input(dir.file("x.log"), "--log"), io::UsageError);      // either order
  EXPECT_THROW((void)files.add(dir.file("sub"), "--out"), io::UsageError);    // a folder
  EXPECT_THROW((void)files.add(dir.file("in.tum/x"), "--out"), io::IoError);  // under a file
  EXPECT_EQ(read_text(dir.file("in.tum")), "input");
}

TEST(OutputFiles, SameFileSeesLinksAndSpellings) {
  const TempDir dir("output_files");
  write_text(dir.file("f"), "x");
  fs::create_hard_link(dir.file("f"), dir.file("hard"));
  EXPECT_TRUE(same_file(dir.file("f"), dir.file("hard")));
  EXPECT_TRUE(same_file(dir.file("f"), dir.path().string() + "/./f"));
  EXPECT_TRUE(same_file(dir.file("missing/../g"), dir.file("g")));
  EXPECT_FALSE(same_file(dir.file("f"), dir.file("g")));
}

}  // namespace
}  // namespace pgmcl::app
