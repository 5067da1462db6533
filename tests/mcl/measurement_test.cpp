// Measurement model: beam policy, selection, the hot loop against oracles, and the
// paper-sigma stress case (1081 beams, 5 mm map).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <memory>
#include <numbers>
#include <span>
#include <utility>
#include <vector>

#include "pgmcl/mcl/beam_selection.hpp"
#include "pgmcl/mcl/localizer.hpp"
#include "pgmcl/mcl/measurement_model.hpp"
#include "synthetic_world.hpp"
#include "table_oracle.hpp"

namespace pgmcl {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

TEST(BeamSelection, InvalidReadingsFollowThePolicy) {
  LaserScan s;
  s.range_min = 0.1;
  s.range_max = 10.0;
  s.ranges = {1.0f,
              std::numeric_limits<float>::quiet_NaN(),
              std::numeric_limits<float>::infinity(),
              0.05f,
              10.0f,
              9.99f,
              0.1f,
              8.0f};
  std::vector<std::uint32_t> valid;
  valid_beam_indices(s, /*model_max_range=*/30.0, valid);
  // NaN, Inf, below range_min, at range_max are out; range_min itself is in.
  EXPECT_EQ(valid, (std::vector<std::uint32_t>{0, 5, 6, 7}));
  // The likelihood's max_range also bounds the usable readings.
  valid_beam_indices(s, /*model_max_range=*/5.0, valid);
  EXPECT_EQ(valid, (std::vector<std::uint32_t>{0, 6}));
}

TEST(BeamSelection, AllStrideAndMaxBeams) {
  std::vector<std::uint32_t> valid(100);
  for (std::uint32_t i = 0; i < 100; ++i) valid[i] = 2 * i;  // pretend odd beams were invalid
  std::vector<std::uint32_t> out;
  select_beams(valid, {BeamSelectionMode::kAll, 1, 1}, out);
  EXPECT_EQ(out, valid);
  select_beams(valid, {BeamSelectionMode::kStride, 30, 1}, out);
  EXPECT_EQ(out, (std::vector<std::uint32_t>{0, 60, 120, 180}));
  select_beams(valid, {BeamSelectionMode::kMaxBeams, 1, 4}, out);
  // Centres of 4 slices of 25 valid beams: valid[12], valid[37], valid[62], valid[87].
  EXPECT_EQ(out, (std::vector<std::uint32_t>{24, 74, 124, 174}));
  select_beams(valid, {BeamSelectionMode::kMaxBeams, 1, 500}, out);
  EXPECT_EQ(out, valid);  // fewer valid beams than the budget: all of them
  select_beams(valid, {BeamSelectionMode::kMaxBeams, 1, 99}, out);
  ASSERT_EQ(out.size(), 99u);
  for (std::size_t i = 1; i < out.size(); ++i) EXPECT_LT(out[i - 1], out[i]);  // no repeats
}

struct KindCase {
  maps::TableKind kind;
  double resolution;
  double oracle_tolerance;  // nats per beam, table vs exact model (see SumMatchesOracles)
};

class MeasurementKinds : public ::testing::TestWithParam<KindCase> {
 protected:
  /// The table of `kind` on the world's grid.
  static std::shared_ptr<const maps::LikelihoodField> table(
      const test::World& world, const sensor_model::BeamLikelihoodParams& params,
      maps::TableKind kind) {
    maps::LikelihoodFieldOptions opt;
    opt.kind = kind;
    return std::make_shared<const maps::LikelihoodField>(world.grid, params, opt);
  }
  /// The paper's sigmas with a 3 % model mismatch, except for the oriented kind: mismatch
  /// would make its kernel isotropic (and the table fall back).
  static sensor_model::BeamLikelihoodParams mismatched_params(maps::TableKind kind) {
    sensor_model::BeamLikelihoodParams params;
    params.model_mismatch = kind == maps::TableKind::kOrientedBins ? 0.0 : 0.03;
    return params;
  }
};

// Weights for the known pose beat a pose 5 cm off (along x and y) and 2 deg off.
TEST_P(MeasurementKinds, KnownPoseBeatsOffsets) {
  const KindCase kc = GetParam();
  const test::World world = test::make_room(kc.resolution);
  const sensor_model::BeamLikelihoodParams params;  // the paper's sigmas, no mismatch
  auto field = table(world, params, kc.kind);
  ASSERT_EQ(field->kind(), kc.kind);
  MeasurementModel model(field);

  const Pose2 truth{3.7, 4.3, 0.4};
  test::ScanSpec spec;
  spec.sensor_pose = {0.25, -0.05, 0.1};  // an off-centre, rotated mount
  const LaserScan scan = world.scan(truth, spec);
  std::vector<std::uint32_t> valid, sel;
  valid_beam_indices(scan, params.max_range, valid);
  select_beams(valid, {BeamSelectionMode::kAll, 1, 1}, sel);
  model.prepare(scan, sel);

  const std::vector<Pose2> poses = {truth,
                                    {truth.x + 0.05, truth.y, truth.theta},
                                    {truth.x - 0.05, truth.y, truth.theta},
                                    {truth.x, truth.y + 0.05, truth.theta},
                                    {truth.x, truth.y - 0.05, truth.theta},
                                    {truth.x, truth.y, truth.theta + 2 * kDeg},
                                    {truth.x, truth.y, truth.theta - 2 * kDeg}};
  std::vector<float> x, y, th;
  for (const Pose2& p : poses) {
    x.push_back(static_cast<float>(p.x));
    y.push_back(static_cast<float>(p.y));
    th.push_back(static_cast<float>(p.theta));
  }
  std::vector<std::uint32_t> q(poses.size());
  model.score_serial(x, y, th, q);
  const double ll_true = model.log_likelihood(q[0]);
  double min_loss = std::numeric_limits<double>::infinity();
  for (std::size_t i = 1; i < poses.size(); ++i) {
    SCOPED_TRACE(i);
    const double loss = ll_true - model.log_likelihood(q[i]);
    min_loss = std::min(min_loss, loss);
    // Seen: smallest loss over the six offsets 720 nats (isotropic, 5 cm cells) and
    // ~1500 nats (oriented / offset, 2 cm cells); 1081 beams, paper sigmas.
    EXPECT_GT(loss, 100.0);
  }
  RecordProperty("min_loss_nats", std::to_string(min_loss));
  // score_pose agrees with the batch path.
  EXPECT_EQ(model.score_pose(truth.x, truth.y, truth.theta).sum_q, q[0]);
}

// Brute force: the same table lookups with every endpoint transformed in double.
std::uint32_t brute_force_sum_q(const maps::LikelihoodField& f, const LaserScan& scan,
                                std::span<const std::uint32_t> sel, const Pose2& robot) {
  const Pose2 sensor = robot.compose(scan.sensor_pose);
  std::uint32_t sum = 0;
  for (std::uint32_t i : sel) {
    const double a = sensor.theta + scan.beam_angle(i), r = scan.ranges[i];
    const auto col = static_cast<float>((sensor.x + r * std::cos(a)) / f.resolution());
    const auto row = static_cast<float>((sensor.y + r * std::sin(a)) / f.resolution());
    sum += testkit::table_q(f, col, row, a);
  }
  return sum;
}

// The hot loop against two oracles: the same lookups done in double (must agree up to a
// beam whose endpoint sits on a cell edge), and the exact, unquantised model.
TEST_P(MeasurementKinds, SumMatchesOracles) {
  const KindCase kc = GetParam();
  const test::World world = test::make_room(kc.resolution);
  const sensor_model::BeamLikelihoodParams params = mismatched_params(kc.kind);
  auto field = table(world, params, kc.kind);
  ASSERT_EQ(field->kind(), kc.kind);
  MeasurementModel model(field);
  test::ScanSpec spec;
  spec.beams = 181;
  spec.sensor_pose = {0.2, 0.03, -0.2};
  const LaserScan scan = world.scan({6.0, 5.0, -2.0}, spec);
  std::vector<std::uint32_t> valid, sel;
  valid_beam_indices(scan, params.max_range, valid);
  select_beams(valid, {BeamSelectionMode::kAll, 1, 1}, sel);
  model.prepare(scan, sel);
  for (const Pose2 p : {Pose2{6.0, 5.0, -2.0}, Pose2{6.03, 4.98, -1.97}, Pose2{5.2, 6.1, 3.1}}) {
    SCOPED_TRACE(p.x);
    const std::uint32_t q = model.score_pose(p.x, p.y, p.theta).sum_q;
    const std::uint32_t q_brute = brute_force_sum_q(*field, scan, sel, p);
    EXPECT_LE(std::abs(static_cast<long>(q) - static_cast<long>(q_brute)), 255) << q_brute;
    double exact = 0.0;
    const Pose2 sensor = p.compose(scan.sensor_pose);
    const testkit::ExactLikelihood exact_ll(world.grid, field->model());
    for (std::uint32_t i : sel) {
      const double a = sensor.theta + scan.beam_angle(i), r = scan.ranges[i];
      exact += exact_ll(sensor.x + r * std::cos(a), sensor.y + r * std::sin(a), a);
    }
    const double per_beam = (model.log_likelihood(q) - exact) / static_cast<double>(sel.size());
    // Table sampling error (one value per cell; larger for kernels narrow against a cell).
    // Seen per beam: isotropic 5 cm (sigma_eff 34 mm) up to 0.34, oriented 2 cm (8 mm) up
    // to 0.99, offset 2 cm (31 mm) up to 0.05 nats.
    EXPECT_LT(std::abs(per_beam), kc.oracle_tolerance) << per_beam;
  }
}

// The hot loop's chunked passes against plain per-beam readers (testkit::reference_q) with
// the same float arithmetic: the sums must agree exactly, also for poses partly or wholly
// off the map, for every orientation bin, and for poses so far off (or NaN) that the kernels
// take their clamped path (the kernels skip the clamps below |cell| + reach < 5e8).
TEST_P(MeasurementKinds, KernelsMatchPlainLookupsExactly) {
  const KindCase kc = GetParam();
  const test::World world = test::make_room(kc.resolution);
  const sensor_model::BeamLikelihoodParams params = mismatched_params(kc.kind);
  auto field = table(world, params, kc.kind);
  ASSERT_EQ(field->kind(), kc.kind);
  MeasurementModel model(field);
  test::ScanSpec spec;
  spec.beams = 300;  // more than one chunk of beams, not a multiple of it
  spec.sensor_pose = {0.2, 0.03, -0.2};
  const LaserScan scan = world.scan({6.0, 5.0, -2.0}, spec);
  std::vector<std::uint32_t> valid, sel;
  valid_beam_indices(scan, params.max_range, valid);
  select_beams(valid, {BeamSelectionMode::kAll, 1, 1}, sel);
  model.prepare(scan, sel);
  const PreparedBeams& b = model.beams();
  const auto inv_res = static_cast<float>(1.0 / field->resolution());
  Rng rng(5);
  const double limit_m = 5.0e8 * field->resolution();  // where the clamped path starts
  const std::vector<std::pair<double, double>> far = {
      {limit_m * 0.999, 5.0}, {5.0, -limit_m * 1.001}, {limit_m * 4.0, limit_m * 4.0},
      {-1.0e12, 3.0},         {3.0e38, -3.0e38},       {std::nan(""), 2.0}};
  for (std::size_t trial = 0; trial < 200 + far.size(); ++trial) {
    float x = static_cast<float>(rng.uniform(-3.0, 14.0));
    float y = static_cast<float>(rng.uniform(-3.0, 12.0));
    if (trial >= 200) {
      x = static_cast<float>(far[trial - 200].first);
      y = static_cast<float>(far[trial - 200].second);
    }
    const auto th = static_cast<float>(rng.uniform(-std::numbers::pi, std::numbers::pi));
    const auto c = static_cast<float>(std::cos(static_cast<double>(th)));
    const auto s = static_cast<float>(std::sin(static_cast<double>(th)));
    const float px = x * inv_res, py = y * inv_res;
    std::uint32_t expect = 0;
    for (std::size_t j = 0; j < b.size(); ++j) {
      const float col = px + (c * b.ex[j] - s * b.ey[j]);
      const float row = py + (s * b.ex[j] + c * b.ey[j]);
      switch (field->kind()) {
        case maps::TableKind::kIsotropic:
          expect += testkit::reference_q(field->isotropic(), col, row);
          break;
        case maps::TableKind::kOrientedBins: {
          const maps::OrientedView v = field->oriented();
          float tb = th * v.bins_per_radian;
          tb += tb < 0.0f ? static_cast<float>(v.bins) : 0.0f;
          int bin = static_cast<int>(tb + b.bin[j]);
          while (bin >= v.bins) bin -= v.bins;
          expect += testkit::reference_q(v, col, row, bin);
          break;
        }
        case maps::TableKind::kOffsetField:
          expect += testkit::reference_q(field->offset(), col, row, c * b.ux[j] - s * b.uy[j],
                                         s * b.ux[j] + c * b.uy[j]);
          break;
      }
    }
    ASSERT_EQ(model.score_pose(x, y, th).sum_q, expect) << "trial " << trial;
  }
}

INSTANTIATE_TEST_SUITE_P(AllKinds, MeasurementKinds,
                         ::testing::Values(KindCase{maps::TableKind::kIsotropic, 0.05, 0.5},
                                           KindCase{maps::TableKind::kOrientedBins, 0.02, 1.5},
                                           KindCase{maps::TableKind::kOffsetField, 0.02, 0.15}),
                         [](const auto& info) {
                           return std::string(maps::to_string(info.param.kind));
                         });

// 1081 beams, the paper's sigma_x = 5.6894 mm on a 5 mm map, no tempering: log-likelihood
// spreads of ~1e4 nats must still give finite weights and N_eff >= 1.
TEST(MeasurementStress, PaperSigmaFiveMillimetreMapStaysFinite) {
  const test::World world = test::make_small_room(0.005);
  LocalizerConfig cfg;
  cfg.likelihood.beam =
      sensor_model::BeamLikelihoodParams{};  // sigma_along = 5.6894 mm, no mismatch
  cfg.likelihood.effective_beams = 0.0;      // plain product of 1081 beams
  cfg.likelihood.tempering = 1.0;
  cfg.likelihood.selection.mode = BeamSelectionMode::kAll;
  cfg.filter.particles = 500;
  cfg.filter.global_particles = 500;
  cfg.filter.kld.enabled = false;
  cfg.filter.resample_threshold = 0.0;  // keep the raw weights for inspection
  Localizer loc(world.grid, cfg);
  const Pose2 truth{2.0, 1.5, 0.7};
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  cov.diagonal() << 0.05 * 0.05, 0.05 * 0.05, std::pow(3 * kDeg, 2);
  loc.set_pose(truth, cov);
  test::ScanSpec spec;
  spec.noise_sigma = 0.0057;
  Rng noise(3);
  const UpdateResult r = loc.update({}, world.scan(truth, spec, &noise), 0.0);
  ASSERT_TRUE(r.measured());
  RecordProperty("n_eff", std::to_string(r.n_eff));  // seen: 1.0 (one particle wins)
  EXPECT_EQ(r.beams_used, 1081u);
  EXPECT_GE(r.n_eff, 1.0);
  EXPECT_TRUE(std::isfinite(r.n_eff));
  const ParticlesView pv = loc.particles();
  double sum = 0.0;
  for (std::size_t i = 0; i < pv.size(); ++i) {
    ASSERT_TRUE(std::isfinite(pv.weight[i]));
    ASSERT_GE(pv.weight[i], 0.0);
    sum += pv.weight[i];
  }
  EXPECT_NEAR(sum, 1.0, 1e-9);
  EXPECT_TRUE(std::isfinite(r.estimate.x) && std::isfinite(r.estimate.y) &&
              std::isfinite(r.estimate.theta));
  EXPECT_TRUE(r.covariance.allFinite());
  EXPECT_TRUE(r.mean_covariance.allFinite());
}

}  // namespace
}  // namespace pgmcl
