// Numerical stress of the likelihood tables (Dekan et al., Eq. (6)): 1081 beams at the
// paper's sigmas on a 5 mm map against the double-precision oracle, table memory per cell,
// a map too large for its table budget, and degenerate maps (1x1, all free, all occupied,
// UTM-scale origin).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "heap_usage.hpp"
#include "pgmcl/maps/likelihood_field.hpp"
#include "pgmcl/mcl/beam_selection.hpp"
#include "pgmcl/mcl/measurement_model.hpp"
#include "pgmcl/mcl/weights.hpp"
#include "stress_world.hpp"
#include "table_oracle.hpp"

namespace pgmcl::stress {
namespace {

using maps::LikelihoodField;
using maps::LikelihoodFieldOptions;
using maps::TableKind;
constexpr double kPi = std::numbers::pi;
constexpr double kPaperSigmaAlong = 5.6894e-3;  // metres, Dekan et al., Section 5

LikelihoodFieldOptions kind_opts(TableKind kind, int bins = 16) {
  LikelihoodFieldOptions o;
  o.kind = kind;
  o.orientation_bins = bins;
  return o;
}

// Distance of x to the nearest integer.
double edge_distance(double x) {
  return std::abs(x - std::round(x));
}

// 1081 beams, paper sigmas, 5 mm cells, oriented table (anisotropic at 5 mm: no fallback).
// Oracle: testkit::ExactLikelihood at the centre of the endpoint's cell and the
// centre of the beam's orientation bin, which is what a table entry samples. Tolerance:
// every beam within half a quantisation step (nats_per_step / 2); the sum over M beams
// within M * step / 2 (worst case) and within 6 standard deviations of the sum of M
// independent rounding errors, 6 sqrt(M / 12) step.
TEST(StressLikelihood, ExactSumOf1081BeamsAgreesWithQuantisedTable_5mm) {
  const double res = 0.005;
  const Room room = make_room(4.0, 3.0, res);
  const auto field = std::make_shared<const LikelihoodField>(
      room.grid, sensor_model::BeamLikelihoodParams{}, kind_opts(TableKind::kOrientedBins));
  ASSERT_EQ(field->kind(), TableKind::kOrientedBins);
  const maps::OrientedView v = field->oriented();
  const double step = field->model().nats_per_step();
  const testkit::ExactLikelihood exact_ll(room.grid, field->model());
  const Scanner scanner(room.grid, kPaperSigmaAlong);
  ASSERT_EQ(scanner.profile().beam_count, 1081);
  MeasurementModel model(field);
  Rng rng(7);
  std::vector<std::uint32_t> valid;
  for (const Pose2& pose :
       {Pose2{1.3, 1.1, 0.3}, Pose2{3.2, 2.5, -2.9}, Pose2{0.8, 2.9, kPi}, Pose2{2.6, 0.6, 1.6}}) {
    const LaserScan scan = scanner.scan(pose, rng);
    valid_beam_indices(scan, field->model().params().max_range, valid);
    ASSERT_GT(valid.size(), 1000u) << "closed room: nearly every beam hits";
    const Pose2 sensor = pose.compose(scan.sensor_pose);
    double sum_table = 0.0, sum_exact = 0.0, sum_sq = 0.0, sum_exact_endpoint = 0.0;
    std::uint64_t sum_q = 0;
    int near_edges = 0;
    for (const std::uint32_t j : valid) {
      const double a = sensor.theta + scan.beam_angle(j), r = scan.ranges[j];
      const double col = (sensor.x + r * std::cos(a)) / res;
      const double row = (sensor.y + r * std::sin(a)) / res;
      const int c = maps::floor_to_cell(static_cast<float>(col));
      const int rr = maps::floor_to_cell(static_cast<float>(row));
      const int b = static_cast<int>(maps::direction_in_bins(a, v.bins));
      const std::uint8_t q =
          testkit::reference_q(v, static_cast<float>(col), static_cast<float>(row), b);
      const double table = field->model().log_likelihood_of_q(q);
      const double exact = exact_ll((c + 0.5) * res, (rr + 0.5) * res, (b + 0.5) * kPi / v.bins);
      ASSERT_NEAR(table, exact, step / 2 + 1e-9) << "beam " << j << " cell " << c << "," << rr;
      sum_table += table;
      sum_exact += exact;
      sum_sq += (table - exact) * (table - exact);
      sum_q += q;
      sum_exact_endpoint += exact_ll(col * res, row * res, a);
      const double bin_pos = wrap_angle(a) * v.bins / kPi;
      near_edges +=
          (edge_distance(col) < 1e-3 || edge_distance(row) < 1e-3 || edge_distance(bin_pos) < 1e-3)
              ? 1
              : 0;
    }
    const double m = static_cast<double>(valid.size());
    EXPECT_LE(std::abs(sum_table - sum_exact), m * step / 2);
    EXPECT_LE(std::abs(sum_table - sum_exact), 6.0 * std::sqrt(m / 12.0) * step);
    EXPECT_LE(std::sqrt(sum_sq / m), step / 2);
    // The hot loop (float endpoints in cells, integer sum) reads the same entries, except
    // possibly for beams whose endpoint lies within 1e-3 cells of a cell or bin edge.
    model.prepare(scan, valid);
    const PoseScore s = model.score_pose(pose.x, pose.y, pose.theta);
    const double dq = std::abs(static_cast<double>(s.sum_q) - static_cast<double>(sum_q));
    EXPECT_LE(dq, 255.0 * near_edges);
    EXPECT_NEAR(model.log_likelihood(s.sum_q), sum_exact, m * step / 2 + dq * step + 1e-6);
    std::cout << "  pose (" << pose.x << ", " << pose.y << ", " << pose.theta << "): " << m
              << " beams, table " << sum_table << " nats, exact at cell centres " << sum_exact
              << " (diff " << sum_table - sum_exact << ", bound " << 6 * std::sqrt(m / 12) * step
              << "), exact at the endpoints " << sum_exact_endpoint << "\n";
  }
}

// The same scan scored at the true pose and at poses a few mm .. 1 m off: the log-likelihood
// spread is thousands of nats (exp() underflows for every weight but one), yet the
// log-sum-exp weights are finite, sum to 1, N_eff >= 1 and a pose near the truth wins.
TEST(StressLikelihood, WeightsOf1081BeamScoresStayFiniteAcrossThousandsOfNats) {
  const double res = 0.005;
  const Room room = make_room(4.0, 3.0, res);
  const auto field =
      std::make_shared<const LikelihoodField>(room.grid, sensor_model::BeamLikelihoodParams{});
  const Scanner scanner(room.grid, kPaperSigmaAlong);
  MeasurementModel model(field);
  Rng rng(11);
  const Pose2 truth{1.7, 1.4, 0.9};
  const LaserScan scan = scanner.scan(truth, rng);
  std::vector<std::uint32_t> valid;
  valid_beam_indices(scan, field->model().params().max_range, valid);
  model.prepare(scan, valid);
  std::vector<double> log_w;
  for (const Pose2& d : {Pose2{}, Pose2{0.003, 0, 0}, Pose2{0, 0.01, 0}, Pose2{0.03, 0.02, 0},
                         Pose2{0, 0, 0.02}, Pose2{0.1, 0, 0.1}, Pose2{1.0, -0.5, 2.0}}) {
    const Pose2 p = truth.compose(d);
    log_w.push_back(model.log_likelihood(model.score_pose(p.x, p.y, p.theta).sum_q));
  }
  const double spread = log_w.front() - log_w.back();
  EXPECT_GT(spread, 1500.0) << "the test must reach exp() underflow (745 nats)";
  std::vector<double> w(log_w.size());
  const double norm = normalise_log_weights(log_w, w);
  EXPECT_TRUE(std::isfinite(norm));
  double total = 0.0;
  for (std::size_t i = 0; i < w.size(); ++i) {
    EXPECT_TRUE(std::isfinite(w[i]) && w[i] >= 0.0) << i;
    total += w[i];
  }
  EXPECT_NEAR(total, 1.0, 1e-12);
  EXPECT_GE(effective_sample_size(w), 1.0 - 1e-12);
  // The winner is the truth or a pose within 1 cm of it. (At tau = 1 a 3 mm shift can beat
  // the truth: the ray caster returns the wall surface, the table models the obstacle at the
  // occupied cell's centre, half a cell behind it.)
  EXPECT_LE(std::max_element(w.begin(), w.end()) - w.begin(), 2);
  EXPECT_EQ(w[5], 0.0) << "10 cm / 0.1 rad off: underflows to exactly 0";
  EXPECT_EQ(w[6], 0.0);
  std::cout << "  log-likelihoods:";
  for (const double l : log_w) std::cout << " " << l + norm;
  std::cout << " nats; spread " << spread << " nats\n";
}

// Stated bytes per cell: isotropic 1, oriented K, offset 2 (+ its LUT). Where glibc's heap
// is measurable (not under ASan), the memory the field keeps is its tables, nothing
// proportional to the cells beyond that.
TEST(StressLikelihood, TableMemoryIsTheStatedBytesPerCell) {
  const Room room = make_room(4.0, 3.0, 0.005);
  const std::size_t cells = room.grid.size();
  struct Case {
    TableKind kind;
    double per_cell;
  };
  for (const Case k : {Case{TableKind::kIsotropic, 1.0}, Case{TableKind::kOrientedBins, 16.0},
                       Case{TableKind::kOffsetField, 2.0}}) {
    const auto before = heap_in_use();
    const auto field = std::make_unique<const LikelihoodField>(
        room.grid, sensor_model::BeamLikelihoodParams{}, kind_opts(k.kind));
    const auto after = heap_in_use();
    ASSERT_EQ(field->kind(), k.kind);
    const auto& st = field->stats();
    const double per_cell = static_cast<double>(st.bytes) / static_cast<double>(cells);
    EXPECT_GE(per_cell, k.per_cell);
    EXPECT_LT(per_cell, k.per_cell + 65536.0 / static_cast<double>(cells));
    std::cout << "  " << maps::to_string(k.kind) << ": " << st.bytes << " table bytes (" << per_cell
              << " per cell)";
    if (before && after) {
      const double kept = static_cast<double>(*after) - static_cast<double>(*before);
      std::cout << "; heap kept " << kept << " bytes";
      EXPECT_GE(kept, static_cast<double>(st.bytes));
      EXPECT_LE(kept, static_cast<double>(st.bytes) + 256.0 * 1024.0);
    }
    std::cout << "\n";
  }
}

// A 40000 x 40000 map (1.6e9 cells; 10000 x 10000 in Debug builds, which run under ASan:
// same code path, a 100 MB grid instead of 1.6 GB): the tables would need 1.6 GB
// (isotropic), 25.6 GB (16 orientation bins) or 3.2 GB (offset). With max_table_bytes below
// that, construction is a std::length_error naming the byte count, before any table memory
// is allocated; the default budget (8 GiB) already refuses the oriented table.
TEST(StressLikelihood, HugeMapIsACleanLengthErrorNotAnAllocation) {
  constexpr int kSide = kHugeMapSide;
  const maps::OccupancyGrid grid(kSide, kSide, 0.005, {}, maps::kUnknown);
  const std::size_t cells = grid.size();
  struct Case {
    TableKind kind;
    std::size_t cap;
    std::size_t bytes;  // cells * per-cell (the offset LUT comes on top)
  };
  LikelihoodFieldOptions dflt;
  for (const Case k : {Case{TableKind::kIsotropic, cells - 1, cells},
                       Case{TableKind::kOrientedBins, dflt.max_table_bytes, 16 * cells},
                       Case{TableKind::kOffsetField, 2 * cells, 2 * cells}}) {
    LikelihoodFieldOptions o = kind_opts(k.kind);
    o.max_table_bytes = k.cap;
    if (k.kind == TableKind::kOrientedBins && kSide < 40000) o.max_table_bytes = 16 * cells - 1;
    const auto before = heap_in_use();
    try {
      const LikelihoodField f(grid, sensor_model::BeamLikelihoodParams{}, o);
      ADD_FAILURE() << maps::to_string(k.kind) << ": built a " << f.stats().bytes
                    << "-byte table above max_table_bytes " << o.max_table_bytes;
    } catch (const std::length_error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(std::to_string(k.bytes)), std::string::npos) << what;
      EXPECT_NE(what.find("max_table_bytes"), std::string::npos) << what;
    }
    const auto after = heap_in_use();
    if (before && after) {
      EXPECT_LT(static_cast<double>(*after) - static_cast<double>(*before), 1 << 20);
    }
  }
}

// Degenerate maps, every table kind: 1x1 (occupied, free, unknown), all free, all occupied.
std::vector<LikelihoodField> all_kinds(const maps::OccupancyGrid& g) {
  std::vector<LikelihoodField> out;
  out.reserve(3);
  for (TableKind k : {TableKind::kIsotropic, TableKind::kOrientedBins, TableKind::kOffsetField}) {
    LikelihoodFieldOptions o = kind_opts(k);
    o.isotropy_tolerance = 0.0;  // keep the oriented kind even where the kernel is isotropic
    out.emplace_back(g, sensor_model::BeamLikelihoodParams{}, o);
    EXPECT_EQ(out.back().kind(), k);
  }
  return out;
}

using testkit::table_q;

TEST(StressLikelihood, OneByOneMaps) {
  for (const std::int8_t fill : {maps::kOccupied, maps::kFree, maps::kUnknown}) {
    const maps::OccupancyGrid g(1, 1, 0.05, {}, fill);
    for (const LikelihoodField& f : all_kinds(g)) {
      SCOPED_TRACE(std::string(maps::to_string(f.kind())) + " fill " + std::to_string(fill));
      const testkit::ExactLikelihood exact(g, f.model());
      for (const float a : {0.0f, 1.0f, -2.5f, 3.14159f}) {
        const std::uint8_t in = table_q(f, 0.5f, 0.5f, a);
        if (fill == maps::kOccupied) {
          EXPECT_EQ(in, 0) << "the cell centre is the obstacle: a perfect hit";
          EXPECT_NEAR(exact(0.025, 0.025, a), f.model().ll_max(), 1e-9);
        } else {
          EXPECT_EQ(in, 255) << "no obstacle: the background floor";
          EXPECT_NEAR(exact(0.025, 0.025, a), f.model().ll_background(), 1e-9);
          EXPECT_EQ(f.stats().sources_stamped, 0u);
          EXPECT_EQ(f.stats().cells_computed, 0u);
        }
        for (const auto& [c, r] : {std::pair{-0.5f, 0.5f},
                                   {1.5f, 0.5f},
                                   {0.5f, -0.01f},
                                   {0.5f, 1.0f},
                                   {-3000.0f, 1e9f}}) {
          EXPECT_EQ(table_q(f, c, r, a), 255) << "off the map at (" << c << ", " << r << ")";
        }
      }
      EXPECT_TRUE(std::isfinite(f.model().nats_per_step()) && f.model().nats_per_step() > 0.0);
    }
  }
}

TEST(StressLikelihood, AllFreeAndAllOccupiedMaps) {
  for (const std::int8_t fill : {maps::kFree, maps::kOccupied}) {
    const maps::OccupancyGrid g(120, 80, 0.05, {}, fill);
    for (const LikelihoodField& f : all_kinds(g)) {
      SCOPED_TRACE(std::string(maps::to_string(f.kind())) + " fill " + std::to_string(fill));
      const std::uint8_t want = fill == maps::kOccupied ? 0 : 255;
      int wrong = 0;
      for (int r = 0; r < g.height(); ++r)
        for (int c = 0; c < g.width(); ++c)
          for (const float a : {0.3f, 2.0f})
            wrong += table_q(f, c + 0.5f, r + 0.5f, a) != want ? 1 : 0;
      EXPECT_EQ(wrong, 0);
      const double want_ll =
          fill == maps::kOccupied ? f.model().ll_max() : f.model().ll_background();
      EXPECT_NEAR(testkit::ExactLikelihood(g, f.model())(3.025, 2.025, 0.4), want_ll, 1e-9);
      if (fill == maps::kFree) {
        EXPECT_EQ(f.stats().cells_computed, 0u);
      }
      if (fill == maps::kOccupied && f.kind() != TableKind::kOffsetField) {
        EXPECT_LT(f.stats().sources_stamped, g.size()) << "interior cells are never nearest";
      }
    }
  }
}

// Tables live in the map-local frame: a UTM-scale origin (5e5, 5e6) with a yaw changes no
// byte of the table, the model, or what the kernels read.
TEST(StressLikelihood, UtmOriginChangesNoTableByte) {
  const Room at0 = make_room(6.0, 4.0, 0.05);
  const Room utm = make_room(6.0, 4.0, 0.05, Pose2{5e5, 5e6, 0.7});
  const LikelihoodField a(at0.grid, sensor_model::BeamLikelihoodParams{});
  const LikelihoodField b(utm.grid, sensor_model::BeamLikelihoodParams{});
  ASSERT_EQ(a.width(), b.width());
  ASSERT_EQ(a.height(), b.height());
  EXPECT_EQ(std::memcmp(a.isotropic().q, b.isotropic().q,
                        static_cast<std::size_t>(a.width()) * static_cast<std::size_t>(a.height())),
            0);
  EXPECT_EQ(a.model().ll_max(), b.model().ll_max());
  EXPECT_EQ(a.model().nats_per_step(), b.model().nats_per_step());
  Rng rng(5);
  for (int i = 0; i < 200; ++i) {
    const auto col = static_cast<float>(rng.uniform(-2.0, 130.0));
    const auto row = static_cast<float>(rng.uniform(-2.0, 90.0));
    const double t = rng.uniform(-4, 4);
    EXPECT_EQ(table_q(a, col, row, t), table_q(b, col, row, t));
  }
  EXPECT_EQ(b.origin().x, 5e5);
  EXPECT_EQ(b.origin().y, 5e6);
}

// Regression (found by fuzz_config_yaml; fixed in f59d966): a kernel reach beyond int range
// was cast to int before the "reach exceeds" check (UB; on x86 INT_MIN, clamped to 1), so
// absurd sigmas built a table with a 1-cell reach instead of failing. Every such parameter
// set must be a clear std::invalid_argument. (Under UBSan the old code aborts here.)
TEST(StressLikelihood, AbsurdSigmasAreAClearErrorNotAOneCellReach) {
  const maps::OccupancyGrid g(40, 30, 0.05, {}, maps::kFree);
  for (const auto& [along, mismatch, reach] :
       {std::tuple{1e8, 0.0, 4.0}, std::tuple{1e300, 0.0, 4.0}, std::tuple{0.01, 1e300, 4.0},
        std::tuple{0.01, 0.0, 1e300}, std::tuple{1e200, 0.0, 1e200}}) {
    sensor_model::BeamLikelihoodParams p;
    p.sigma_along = along;
    p.model_mismatch = mismatch;
    LikelihoodFieldOptions o;
    o.reach_sigmas = reach;
    try {
      const LikelihoodField f(g, p, o);
      ADD_FAILURE() << "sigma_along " << along << ", mismatch " << mismatch << ", reach_sigmas "
                    << reach << ": built with a reach of " << f.stats().reach_cells << " cells";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("reach"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace pgmcl::stress
