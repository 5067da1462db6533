// Node parameters: amcl's names mapped onto pgmcl's fields, pgmcl/... from the schema,
// precedence, and errors that name the parameter.
#include "pgmcl/nav/parameters.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <string>

namespace pgmcl::nav {
namespace {

using Params = std::map<std::string, ParamValue>;

NodeSettings read(const Params& p, const LocalizerConfig& base = {}) {
  std::vector<std::string> names;
  for (const auto& [k, v] : p) names.push_back(k);
  return read_node_settings(
      [&](const std::string& name) -> std::optional<ParamValue> {
        const auto it = p.find(name);
        return it == p.end() ? std::nullopt : std::optional<ParamValue>(it->second);
      },
      base, names);
}

std::string error_of(const Params& p) {
  try {
    (void)read(p);
  } catch (const ParameterError& e) {
    return e.what();
  }
  return "";
}

TEST(NodeParameters, NothingSetKeepsTheDefaults) {
  const NodeSettings s = read({});
  EXPECT_EQ(s.global_frame_id, "map");
  EXPECT_EQ(s.odom_frame_id, "odom");
  EXPECT_EQ(s.base_frame_id, "base_link");
  EXPECT_TRUE(s.tf_broadcast);
  EXPECT_FALSE(s.initial_pose.has_value());
  EXPECT_DOUBLE_EQ(s.nav.save_pose_period, 2.0);
  EXPECT_EQ(s.nav.filter.filter.kld.max_particles, LocalizerConfig{}.filter.kld.max_particles);
  EXPECT_TRUE(s.notes.empty());
}

TEST(NodeParameters, AmclNamesMapOntoPgmclFields) {
  const NodeSettings s = read({{"min_particles", std::int64_t{100}},
                               {"max_particles", 500.0},  // an integral double is accepted
                               {"kld_err", 0.02},
                               {"kld_z", 0.99},
                               {"update_min_d", 0.25},
                               {"update_min_a", std::int64_t{1}},
                               {"recovery_alpha_slow", 0.001},
                               {"recovery_alpha_fast", 0.1},
                               {"laser_max_beams", std::int64_t{60}},
                               {"laser_min_range", 0.2},
                               {"laser_max_range", 12.0},
                               {"laser_model_type", std::string("likelihood_field")},
                               {"odom_model_type", std::string("omni-corrected")},
                               {"odom_alpha1", 0.2},
                               {"odom_alpha5", 0.05},
                               {"odom_frame_id", std::string("/odom_combined")},
                               {"transform_tolerance", 0.3},
                               {"save_pose_rate", 0.25}});
  const LocalizerConfig& c = s.nav.filter;
  EXPECT_EQ(c.filter.kld.min_particles, 100u);
  EXPECT_EQ(c.filter.kld.max_particles, 500u);
  EXPECT_EQ(c.filter.particles, 500u);  // capped by max_particles, as amcl starts
  EXPECT_EQ(c.filter.global_particles, 500u);
  EXPECT_EQ(c.filter.kld.epsilon, 0.02);
  // amcl uses kld_z as the quantile itself: delta = 1 - Phi(0.99) = 0.16109.
  EXPECT_NEAR(c.filter.kld.delta, 0.161087, 1e-6);
  EXPECT_EQ(c.gating.d_min, 0.25);
  EXPECT_EQ(c.gating.theta_min, 1.0);
  EXPECT_TRUE(c.filter.recovery.enabled);
  EXPECT_EQ(c.filter.recovery.alpha_slow, 0.001);
  EXPECT_EQ(c.likelihood.selection.mode, BeamSelectionMode::kMaxBeams);
  EXPECT_EQ(c.likelihood.selection.max_beams, 60u);
  EXPECT_EQ(s.nav.ranges.min, 0.2);
  EXPECT_EQ(s.nav.ranges.max, 12.0);
  EXPECT_EQ(c.likelihood.beam.max_range, 12.0);
  EXPECT_EQ(c.likelihood.table.kind, maps::TableKind::kIsotropic);
  EXPECT_EQ(c.motion.kind, MotionModelKind::kOmnidirectional);
  EXPECT_EQ(c.motion.noise.a1, 0.2);
  EXPECT_EQ(c.motion.noise.a5, 0.05);
  EXPECT_EQ(s.odom_frame_id, "odom_combined");  // leading '/' dropped, as amcl does
  EXPECT_EQ(s.nav.transform_tolerance, 0.3);
  EXPECT_EQ(s.nav.save_pose_period, 4.0);
}

// amcl takes max_particles alone below pgmcl's lower bound (1000); so must the node.
TEST(NodeParameters, AmclMaxParticlesAloneAlsoBoundsTheLowerBound) {
  const LocalizerConfig c = read({{"max_particles", std::int64_t{500}}}).nav.filter;
  EXPECT_EQ(c.filter.kld.max_particles, 500u);
  EXPECT_EQ(c.filter.kld.min_particles, 500u);
  const LocalizerConfig wide = read({{"max_particles", std::int64_t{5000}}}).nav.filter;
  EXPECT_EQ(wide.filter.kld.min_particles, LocalizerConfig{}.filter.kld.min_particles);
}

TEST(NodeParameters, AmclDefaultsTurnRecoveryOffAndNotesNameDifferences) {
  const NodeSettings s = read({{"recovery_alpha_slow", 0.0},
                               {"recovery_alpha_fast", 0.0},
                               {"laser_model_type", std::string("beam")},
                               {"odom_model_type", std::string("diff")},
                               {"resample_interval", std::int64_t{2}},
                               {"laser_z_hit", 0.5}});
  EXPECT_FALSE(s.nav.filter.filter.recovery.enabled);
  EXPECT_EQ(s.nav.filter.likelihood.table.kind, maps::TableKind::kOrientedBins);
  EXPECT_EQ(s.nav.filter.motion.kind, MotionModelKind::kDifferentialDrive);
  ASSERT_EQ(s.notes.size(), 4u);
  const auto has = [&](const std::string& start) {
    return std::any_of(s.notes.begin(), s.notes.end(),
                       [&](const std::string& n) { return n.rfind(start, 0) == 0; });
  };
  EXPECT_TRUE(has("laser_model_type beam:"));
  EXPECT_TRUE(has("odom_model_type diff: read as diff-corrected"));
  EXPECT_TRUE(has("resample_interval: ignored"));
  EXPECT_TRUE(has("laser_z_hit: ignored"));
}

TEST(NodeParameters, InitialPoseWithAmclCovarianceDefaults) {
  const NodeSettings s = read({{"initial_pose_x", 2.0}, {"initial_pose_a", 7.0}});
  ASSERT_TRUE(s.initial_pose);
  EXPECT_EQ(s.initial_pose->pose.x, 2.0);
  EXPECT_EQ(s.initial_pose->pose.y, 0.0);
  EXPECT_NEAR(s.initial_pose->pose.theta, 7.0 - 2 * std::numbers::pi, 1e-12);
  EXPECT_EQ(s.initial_pose->cov_xx, 0.25);
  EXPECT_NEAR(s.initial_pose->cov_aa, 0.0685389, 1e-7);  // (pi/12)^2
  EXPECT_EQ(error_of({{"initial_pose_x", 1.0}, {"initial_cov_xx", -1.0}}),
            "parameter ~initial_pose_x: the initial pose must be finite and "
            "initial_cov_xx/yy/aa >= 0");
}

TEST(NodeParameters, EverySchemaFieldIsAPgmclParameter) {
  const std::vector<std::string> names = pgmcl_parameter_names();
  EXPECT_GT(names.size(), 60u);
  EXPECT_NE(std::find(names.begin(), names.end(), "pgmcl/filter/kld/epsilon"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "pgmcl/hypotheses/search/leaf_size"),
            names.end());
  EXPECT_EQ(names.back(), "pgmcl/seed");
  const NodeSettings s = read({{"pgmcl/filter/kld/epsilon", 0.1},
                               {"pgmcl/motion/kind", std::string("omni")},
                               {"pgmcl/hypotheses/enabled", false},
                               {"pgmcl/threads", std::int64_t{2}},
                               {"pgmcl/seed", std::int64_t{9}}});
  EXPECT_EQ(s.nav.filter.filter.kld.epsilon, 0.1);
  EXPECT_EQ(s.nav.filter.motion.kind, MotionModelKind::kOmnidirectional);
  EXPECT_FALSE(s.nav.filter.hypotheses.enabled);
  EXPECT_EQ(s.nav.filter.threads, 2);
  EXPECT_EQ(s.nav.filter.seed, 9u);
}

TEST(NodeParameters, PgmclNamesWinOverAmclNamesOverTheBase) {
  LocalizerConfig base;
  base.filter.kld.epsilon = 0.3;
  base.gating.d_min = 0.7;
  const NodeSettings s = read({{"kld_err", 0.2}, {"pgmcl/filter/kld/epsilon", 0.1}}, base);
  EXPECT_EQ(s.nav.filter.filter.kld.epsilon, 0.1);
  EXPECT_EQ(s.nav.filter.gating.d_min, 0.7);
}

TEST(NodeParameters, ErrorsNameTheParameter) {
  EXPECT_EQ(error_of({{"pgmcl/filter/kld/epsilon", -1.0}}),
            "parameter ~pgmcl/filter/kld/epsilon: must be finite and > 0 (got -1)");
  EXPECT_EQ(error_of({{"pgmcl/filter/kld/epsilon", std::string("big")}}),
            "parameter ~pgmcl/filter/kld/epsilon: expected a number, got a string");
  EXPECT_EQ(error_of({{"min_particles", 10.5}}),
            "parameter ~min_particles: expected an integer, got 10.5");
  EXPECT_EQ(error_of({{"min_particles", std::int64_t{0}}}),
            "parameter ~min_particles: must be an integer in [1, 10000000] (got 0)");
  EXPECT_EQ(error_of({{"laser_model_type", std::string("ray")}}),
            "parameter ~laser_model_type: 'ray' is not one of likelihood_field, "
            "likelihood_field_prob, beam");
  EXPECT_EQ(error_of({{"pgmcl/motion/kind", std::string("tank")}}),
            "parameter ~pgmcl/motion/kind: 'tank' is not one of differential_drive, "
            "omnidirectional, diff_drive, omni");
  EXPECT_EQ(error_of({{"tf_broadcast", std::int64_t{1}}}),
            "parameter ~tf_broadcast: expected true or false, got an integer");
  // A cross-field rule names the parameter that set the field it is reported at.
  EXPECT_EQ(error_of({{"min_particles", std::int64_t{900}}, {"max_particles", std::int64_t{500}}}),
            "parameter ~max_particles: must be >= filter.kld.min_particles");
  EXPECT_EQ(error_of({{"pgmcl/filter/kld/epsilonn", 0.1}}),
            "parameter ~pgmcl/filter/kld/epsilonn: unknown pgmcl setting (every key: "
            "configs/reference.md, with '/' for '.')");
  EXPECT_EQ(error_of({{"global_frame_id", std::string("/")}}),
            "parameter ~global_frame_id: must not be empty");
  EXPECT_EQ(error_of({{"scan_stride", std::int64_t{0}}}), "parameter ~scan_stride: must be >= 1");
}

}  // namespace
}  // namespace pgmcl::nav
