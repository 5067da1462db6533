// The configuration schema: every field it describes is checked by validate() under its
// own dotted path, errors are typed, and the defaults are valid.
#include "pgmcl/mcl/config_schema.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "pgmcl/mcl/localizer_config.hpp"

namespace pgmcl {
namespace {

namespace schema = config_schema;

// Collects the dotted path of every field; with `target` set, puts an invalid value into
// the field with that index (NaN for numbers, one past the range for integers).
class Probe {
 public:
  explicit Probe(std::size_t target = SIZE_MAX) : target_(target) {}

  template <class Body>
  void section(const char* name, Body&& body) {
    path_.push_back(name);
    body();
    path_.pop_back();
  }
  void number(const schema::Field& f, double& v, const schema::Bounds&) {
    if (visit(f)) v = std::numeric_limits<double>::quiet_NaN();
  }
  template <class T>
  void integer(const schema::Field& f, T& v, const schema::IntRange& r) {
    const bool can_exceed = r.hi < static_cast<std::uint64_t>(std::numeric_limits<T>::max());
    const bool can_undercut = r.lo > 0;
    if (!can_exceed && !can_undercut) {  // every value of T is allowed
      paths_.push_back("");
      return;
    }
    if (visit(f)) v = can_exceed ? static_cast<T>(r.hi + 1) : static_cast<T>(r.lo - 1);
  }
  void flag(const schema::Field&, bool&) { paths_.push_back(""); }
  template <class E, std::size_t N>
  void choice(const schema::Field& f, E& v, const std::array<schema::EnumName<E>, N>&) {
    if (visit(f)) v = static_cast<E>(200);  // no named value
  }
  void rule(const char*, bool, const char*) {}

  std::vector<std::string> paths_;  // "" for fields that have no invalid value
  std::vector<std::pair<const char*, const char*>> docs_;  // (name, doc): string literals

 private:
  bool visit(const schema::Field& f) {
    std::string p;
    for (const char* s : path_) p += std::string(s) + ".";
    paths_.push_back(p + f.name);
    docs_.emplace_back(f.name, f.doc);
    return paths_.size() - 1 == target_;
  }
  std::size_t target_;
  std::vector<const char*> path_;
};

TEST(ConfigSchema, DefaultsAreValidAndPathsAreUnique) {
  EXPECT_NO_THROW(LocalizerConfig{}.validate());
  LocalizerConfig c;
  Probe probe;
  schema::describe_config(probe, c);
  std::set<std::string> seen;
  std::size_t checked = 0;
  for (const std::string& p : probe.paths_) {
    if (p.empty()) continue;
    ++checked;
    EXPECT_TRUE(seen.insert(p).second) << "duplicate " << p;
  }
  EXPECT_GE(checked, 60u);
  for (const auto& [name, doc] : probe.docs_) EXPECT_GT(std::string(doc).size(), 5u) << name;
}

// Each field, made invalid on its own, is reported under its own path.
TEST(ConfigSchema, EveryFieldIsCheckedUnderItsOwnPath) {
  LocalizerConfig d;
  Probe all;
  schema::describe_config(all, d);
  for (std::size_t i = 0; i < all.paths_.size(); ++i) {
    if (all.paths_[i].empty()) continue;
    SCOPED_TRACE(all.paths_[i]);
    LocalizerConfig c;
    Probe breaker(i);
    schema::describe_config(breaker, c);
    try {
      c.validate();
      ADD_FAILURE() << "invalid value accepted";
    } catch (const InvalidConfigField& e) {
      EXPECT_EQ(e.field(), all.paths_[i]);
      EXPECT_EQ(std::string(e.what()), "LocalizerConfig: " + e.field() + " " + e.problem());
    }
  }
}

TEST(ConfigSchema, ProblemsSayWhatIsAllowedAndWhatWasGiven) {
  struct Case {
    void (*mutate)(LocalizerConfig&);
    const char* field;
    const char* problem;
  };
  const Case cases[] = {
      {[](LocalizerConfig& c) { c.motion.noise.a3 = -0.1; }, "motion.noise.a3",
       "must be in [0, 100] (got -0.1)"},
      {[](LocalizerConfig& c) { c.likelihood.beam.sigma_along = 0.0; },
       "likelihood.beam.sigma_along", "must be in (0, 10] (got 0)"},
      {[](LocalizerConfig& c) { c.likelihood.beam.w_hit = 0.9; }, "likelihood.beam.w_rand",
       "must make w_hit + w_rand = 1 within 1e-9"},
      {[](LocalizerConfig& c) { c.filter.kld.max_particles = 100; }, "filter.kld.max_particles",
       "must be >= filter.kld.min_particles"},
      {[](LocalizerConfig& c) { c.filter.particles = 0; }, "filter.particles",
       "must be an integer in [1, 10000000] (got 0)"},
      {[](LocalizerConfig& c) { c.threads = -1; }, "threads",
       "must be an integer in [0, 1024] (got -1)"},
      {[](LocalizerConfig& c) { c.hypotheses.drop_evidence = 1.0; }, "hypotheses.drop_evidence",
       "must be finite and < 0 (got 1)"},
      {[](LocalizerConfig& c) {
         c.likelihood.selection.mode = BeamSelectionMode::kStride;
         c.likelihood.selection.stride = 0;
       },
       "likelihood.selection.stride", "must be >= 1 with mode stride"},
  };
  for (const Case& k : cases) {
    LocalizerConfig c;
    k.mutate(c);
    try {
      c.validate();
      ADD_FAILURE() << k.field << ": accepted";
    } catch (const InvalidConfigField& e) {
      EXPECT_EQ(e.field(), k.field);
      EXPECT_EQ(e.problem(), k.problem);
    }
  }
  // A stride of 0 is harmless while another mode is selected.
  LocalizerConfig c;
  c.likelihood.selection.stride = 0;
  EXPECT_NO_THROW(c.validate());
}

TEST(ConfigSchema, BoundsTextMatchesContains) {
  EXPECT_EQ(schema::kPositive.text(), "finite and > 0");
  EXPECT_EQ(schema::kUpperUnit.text(), "in (0, 1]");
  EXPECT_EQ(schema::kLowerUnit.text(), "in [0, 1)");
  EXPECT_EQ(schema::kAnyFinite.text(), "finite");
  EXPECT_FALSE(schema::kUpperUnit.contains(0.0));
  EXPECT_TRUE(schema::kUpperUnit.contains(1.0));
  EXPECT_FALSE(schema::kLowerUnit.contains(1.0));
  EXPECT_FALSE(schema::kAnyFinite.contains(INFINITY));
  EXPECT_EQ(schema::IntRange{1}.text(), "an integer >= 1");
}

}  // namespace
}  // namespace pgmcl
