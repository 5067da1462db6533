// Localizer::discount_blocked_readings(): the free space's say in the particles' weights
// while the scan does not fit the prediction.
#include <algorithm>
#include <cstdint>
#include <limits>
#include <span>

#include "hypothesis_tracker.hpp"
#include "parallel_blocks.hpp"
#include "pgmcl/maps/table_kernels.hpp"
#include "pgmcl/mcl/localizer.hpp"

namespace pgmcl {
namespace {

// Particles checked at most per update, heaviest first: each costs a ray per beam, some
// twenty lookups each. A quarter of the default lower bound on the count: 64 of 1000 lost
// fr079 runs amid people that 64 of 300 kept (bench/robustness/README.md).
constexpr std::size_t kMaxChecked = 256;
// Tempered nats: a particle this far below the best discounted one no longer matters.
constexpr double kNegligible = 20.0;
// With a team: particles worked out per parallel step, and per task within it. A step
// ends with a serial check, so a small one wastes little past the last particle needed.
constexpr std::size_t kChunk = 32;
constexpr std::size_t kSlice = 4;

// `from`'s beams `indices`, into `to`.
void gather(const PreparedBeams& from, std::span<const std::uint32_t> indices, PreparedBeams& to) {
  to.ex.clear();
  to.ey.clear();
  to.ux.clear();
  to.uy.clear();
  to.bin.clear();
  for (const std::uint32_t j : indices) {
    to.ex.push_back(from.ex[j]);
    to.ey.push_back(from.ey[j]);
    to.ux.push_back(from.ux[j]);
    to.uy.push_back(from.uy[j]);
    to.bin.push_back(from.bin[j]);
  }
  to.reach = from.reach;  // a bound for any subset
}

}  // namespace

void Localizer::discount_blocked_readings(double tau) {
  // The endpoint tables credit a reading that lands near a wall however it got there. Where
  // people or clutter hide most of the walls, a pose turned or shifted so that their
  // readings land on walls outscores the true one, though its rays pass through walls to
  // get there. Such a reading is no hit at that pose: it counts as background, the model's
  // value for a reading the map does not explain.
  // Only the tracked particles are checked: those on probation (random poses) hold a
  // bounded share anyway (limit_probation_weight()) and would use up the budget.
  std::vector<std::uint32_t>& order = ws_.by_weight;
  order.clear();
  for (std::size_t i = 0; i < p_.size(); ++i)
    if (probation_[i] == 0) order.push_back(static_cast<std::uint32_t>(i));
  const std::size_t n = order.size();
  const std::size_t checked = std::min(n, kMaxChecked);
  const PreparedBeams& all = model_.beams();
  if (checked == 0 || all.size() == 0 || !(tau > 0.0)) return;
  const auto heavier = [&](std::uint32_t a, std::uint32_t b) {
    return p_.log_w[a] > p_.log_w[b] || (p_.log_w[a] == p_.log_w[b] && a < b);
  };
  std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(checked),
                    order.end(), heavier);

  const sensor_model::BeamLikelihood& model = field_->model();
  const double nats_per_q = tau * model.nats_per_step();
  // Particle i's discount, with `scratch` to itself: the readings that crossed walls count
  // as background instead of what the tables credited them with.
  const auto discount_of = [&](std::uint32_t i, Workspace::BlockedReadings& scratch) {
    hypotheses_->blocked_beam_indices({p_.x[i], p_.y[i], p_.theta[i]}, all, scratch.indices);
    if (scratch.indices.empty()) return 0.0;
    gather(all, scratch.indices, scratch.beams);
    std::uint32_t credited = 0;  // the blocked readings' sum as the tables score them
    maps::with_kernel(*field_, scratch.beams.arrays(), 0, [&](const auto& kernel) {
      credited = maps::score_pose<false>(kernel, p_.x[i], p_.y[i], p_.theta[i], nullptr);
    });
    const double background = static_cast<double>(scratch.indices.size()) * model.background();
    return nats_per_q * (background - static_cast<double>(credited));
  };
  // Discounts are worked out a chunk at a time, in parallel slices, and taken in weight order
  // until the next particle is negligible: which ones count is the serial loop's choice for
  // any thread count. One thread works one particle at a time, so it never works one out
  // for nothing.
  const std::size_t chunk = threads_ == 1 ? 1 : kChunk;
  ws_.blocked.resize(kChunk / kSlice);
  ws_.discounts.resize(checked);
  double best = -std::numeric_limits<double>::infinity();
  double least = std::numeric_limits<double>::infinity();  // smallest discount found
  std::size_t taken = 0;
  for (bool negligible = false; taken < checked && !negligible;) {
    const std::size_t end = std::min(checked, taken + chunk);
    const std::size_t first = taken;
    detail::for_each_block((end - first + kSlice - 1) / kSlice, threads_, [&](std::size_t b) {
      const std::size_t lo = first + b * kSlice;
      for (std::size_t k = lo; k < std::min(end, lo + kSlice); ++k)
        ws_.discounts[k] = discount_of(order[k], ws_.blocked[b]);
    });
    for (; taken < end; ++taken) {
      const std::uint32_t i = order[taken];
      if (p_.log_w[i] < best - kNegligible) {
        negligible = true;
        break;
      }
      least = std::min(least, ws_.discounts[taken]);
      best = std::max(best, p_.log_w[i] - ws_.discounts[taken]);
    }
  }
  // Every particle not checked (the lighter ones, and those on probation) is taken to lose
  // the least any checked one lost, so that not checking never favours a particle; as a
  // shift common to all it drops out in normalisation, which leaves the checked ones' excess.
  for (std::size_t k = 0; k < taken; ++k) p_.log_w[order[k]] -= ws_.discounts[k] - least;
}

}  // namespace pgmcl
