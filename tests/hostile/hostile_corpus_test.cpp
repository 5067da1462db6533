// Runs every corpus case through the pgmcl binary and checks the class it must have
// (hostile_corpus.hpp), then the case's own oracles.

#include "hostile_corpus.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>

#include "pgmcl/io/tum.hpp"

namespace pgmcl::hostile {
namespace {

namespace fs = std::filesystem;

std::vector<Case> all_cases() {
  std::vector<Case> all;
  for (auto part : {resource_cases(), silent_cases(), start_and_map_cases(), output_cases(),
                    message_cases(), first_round_cases()}) {
    all.insert(all.end(), part.begin(), part.end());
  }
  return all;
}

/// Every regular file under `dir` with its content: a failed command must leave it as is.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& f : fs::recursive_directory_iterator(dir)) {
    if (f.is_regular_file() && !f.is_symlink()) {
      files[fs::relative(f.path(), dir).string()] = testkit::read_text(f.path().string());
    }
  }
  return files;
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

/// A localisation run's outputs, when the case made one: a readable trajectory of finite
/// poses and a complete metrics.yaml.
void expect_valid_outputs(const Env& e) {
  if (!fs::exists(e.path("out/trajectory.tum"))) return;
  io::Trajectory t;
  ASSERT_NO_THROW(t = io::read_tum(e.path("out/trajectory.tum")));
  EXPECT_FALSE(t.empty());
  for (const auto& p : t) {
    EXPECT_TRUE(std::isfinite(p.pose.x) && std::isfinite(p.pose.y) && std::isfinite(p.pose.theta));
  }
  for (const char* f : {"metrics.yaml", "config.yaml", "updates.csv", "overlay.png"}) {
    EXPECT_TRUE(fs::exists(e.path(std::string("out/") + f))) << f;
  }
  EXPECT_TRUE(has(testkit::read_text(e.path("out/metrics.yaml")), "complete: true"));
}

class Corpus : public ::testing::TestWithParam<Case> {};

}  // namespace

/// CTest names show the case, not its bytes.
void PrintTo(const Case& c, std::ostream* os) {
  *os << c.name;
}

namespace {

TEST_P(Corpus, BehavesAsItsClassSays) {
  const Case& c = GetParam();
  testkit::TempDir dir("hostile");
  const Env env{base(), dir};
  const std::string args = c.make(env);
  if (::testing::Test::HasFatalFailure()) return;
  const auto before = snapshot(dir.path());
  const RunResult r = run_pgmcl(args, dir.path().string());
  SCOPED_TRACE("pgmcl " + args + "\nexit " + std::to_string(r.code) + ", stderr:\n" + r.err);

  EXPECT_EQ(r.code, c.code);
  for (const char* crash : {"terminate called", "Segmentation", "Sanitizer",
                            "runtime error:", "out of memory", "Aborted"}) {
    EXPECT_FALSE(has(r.err, crash)) << crash;
  }
  for (const std::string& s : c.stderr_has) EXPECT_TRUE(has(r.err, s)) << "missing: " << s;
  for (const auto& f : fs::recursive_directory_iterator(dir.path())) {
    EXPECT_FALSE(has(f.path().filename().string(), ".pgmcl-")) << "left behind: " << f.path();
  }
  switch (c.expect) {
    case Expect::kError:
      EXPECT_TRUE(has(r.err, "pgmcl: error: "));
      EXPECT_TRUE(snapshot(dir.path()) == before) << "a failed command changed its folder";
      break;
    case Expect::kWarning:
      EXPECT_TRUE(has(r.err, "pgmcl: warning: "));
      EXPECT_FALSE(has(r.err, "pgmcl: error"));
      expect_valid_outputs(env);
      break;
    case Expect::kAccepted:
      EXPECT_FALSE(has(r.err, "pgmcl: warning")) << "accepted cases warn about nothing";
      EXPECT_FALSE(has(r.err, "pgmcl: error"));
      expect_valid_outputs(env);
      break;
  }
  if (c.check) c.check(env, r);
}

std::string case_name(const ::testing::TestParamInfo<Case>& info) {
  return info.param.name;
}

INSTANTIATE_TEST_SUITE_P(Hostile, Corpus, ::testing::ValuesIn(all_cases()), case_name);

TEST(HostileCorpus, HasOverAHundredUniquelyNamedCasesOfEveryClass) {
  const std::vector<Case> all = all_cases();
  EXPECT_GE(all.size(), 100u);
  std::map<Expect, int> per_class;
  std::map<std::string, int> names;
  for (const Case& c : all) {
    ++per_class[c.expect];
    ++names[c.name];
    EXPECT_TRUE(std::all_of(c.name.begin(), c.name.end(), [](char ch) {
      return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_';
    })) << c.name;
    EXPECT_EQ(c.expect == Expect::kError, c.code != 0) << c.name;
  }
  for (const auto& [name, n] : names) EXPECT_EQ(n, 1) << name;
  EXPECT_GE(per_class[Expect::kError], 50);
  EXPECT_GE(per_class[Expect::kWarning], 15);
  EXPECT_GE(per_class[Expect::kAccepted], 5);
}

}  // namespace
}  // namespace pgmcl::hostile
