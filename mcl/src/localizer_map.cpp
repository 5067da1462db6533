// Localizer::replace_map(): a new map under the same particles.
#include <stdexcept>
#include <string>
#include <utility>

#include "hypothesis_tracker.hpp"
#include "pgmcl/mcl/localizer.hpp"

namespace pgmcl {

void Localizer::replace_map(std::shared_ptr<const maps::LikelihoodField> field,
                            std::vector<std::uint32_t> free_cells) {
  // Everything that can throw happens before any state changes.
  if (!field) throw std::invalid_argument("Localizer::replace_map: likelihood field is null");
  if (free_cells.empty())
    throw std::invalid_argument("Localizer::replace_map: the map has no free cells");
  const auto cells =
      static_cast<std::uint64_t>(field->width()) * static_cast<std::uint64_t>(field->height());
  for (std::uint32_t c : free_cells)
    if (c >= cells)
      throw std::invalid_argument("Localizer::replace_map: free cell index " + std::to_string(c) +
                                  " is outside the new grid");
  MeasurementModel model(field);
  std::unique_ptr<detail::HypothesisTracker> hypotheses;
  if (cfg_.hypotheses.enabled) {
    hypotheses = std::make_unique<detail::HypothesisTracker>(field, free_cells, cfg_.hypotheses,
                                                             cfg_.likelihood);
    hypotheses->reset(hypotheses_ && hypotheses_->global());
  }

  // Map-local poses follow the grid: new local = new_origin^-1 ∘ old_origin ∘ old local.
  const Pose2 old_origin = origin_;
  field_ = std::move(field);
  free_cells_ = std::move(free_cells);
  model_ = std::move(model);
  hypotheses_ = std::move(hypotheses);
  init_geometry();
  const Pose2 to_new = origin_.between(old_origin);
  for (std::size_t i = 0; i < p_.size(); ++i) {
    const Pose2 q = to_new.compose({static_cast<double>(p_.x[i]), static_cast<double>(p_.y[i]),
                                    static_cast<double>(p_.theta[i])});
    p_.x[i] = static_cast<float>(q.x);
    p_.y[i] = static_cast<float>(q.y);
    p_.theta[i] = wrap_angle(static_cast<float>(q.theta));
  }
  force_ = true;
}

}  // namespace pgmcl
