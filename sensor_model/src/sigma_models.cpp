#include "pgmcl/sensor_model/sigma_models.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace pgmcl::sensor_model {
namespace {

[[noreturn]] void bad(const char* type, const char* field, double value, const char* why) {
  std::ostringstream os;
  os << type << ": " << field << " = " << value << " " << why;
  throw std::invalid_argument(os.str());
}

bool finite_positive(double v) {
  return std::isfinite(v) && v > 0.0;
}
bool finite_non_negative(double v) {
  return std::isfinite(v) && v >= 0.0;
}

}  // namespace

IncidenceSigmaModel IncidenceSigmaModel::for_surface(Surface surface) {
  const int i = static_cast<int>(surface);
  if (i < 0 || i >= kNumSurfaces) bad("IncidenceSigmaModel", "surface", i, "is not in Table 2");
  IncidenceSigmaModel m;
  m.sigma_normal = paper::kTable2[static_cast<std::size_t>(i)].sigma_perpendicular_mm * 1e-3;
  m.sigma_45 = paper::kTable2[static_cast<std::size_t>(i)].sigma_45deg_mm * 1e-3;
  return m;
}

void IncidenceSigmaModel::validate() const {
  constexpr const char* kType = "IncidenceSigmaModel";
  if (!finite_positive(sigma_normal)) bad(kType, "sigma_normal", sigma_normal, "must be > 0 (m)");
  if (!(std::isfinite(sigma_45) && sigma_45 >= sigma_normal))
    bad(kType, "sigma_45", sigma_45, "must be finite and >= sigma_normal (m)");
  if (!(grazing_limit >= 45.0 * paper::kDegToRad && grazing_limit <= 89.0 * paper::kDegToRad))
    bad(kType, "grazing_limit", grazing_limit, "must be within [45, 89] deg (rad)");
}

double IncidenceSigmaModel::sigma(double incidence) const noexcept {
  // Fold onto [0, pi/2]: remainder(t, pi) lies in [-pi/2, pi/2].
  double t = std::abs(std::remainder(incidence, std::numbers::pi));
  if (!(t <= grazing_limit)) t = grazing_limit;  // also maps NaN to the limit
  const double tan_t = std::tan(t);
  const double excess = sigma_45 * sigma_45 - sigma_normal * sigma_normal;
  return std::sqrt(sigma_normal * sigma_normal + excess * tan_t * tan_t);
}

void RangeSigmaModel::validate() const {
  if (!finite_positive(sigma_short))
    bad("RangeSigmaModel", "sigma_short", sigma_short, "must be finite and > 0 (m)");
  if (!finite_non_negative(growth))
    bad("RangeSigmaModel", "growth", growth, "must be finite and >= 0 (m per m)");
}

double RangeSigmaModel::sigma(double range) const noexcept {
  return std::hypot(sigma_short, growth * std::max(range, 0.0));
}

void SensorNoiseModel::validate() const {
  constexpr const char* kType = "SensorNoiseModel";
  if (!finite_positive(sigma_along)) bad(kType, "sigma_along", sigma_along, "must be > 0 (m)");
  if (!finite_positive(sigma_across)) bad(kType, "sigma_across", sigma_across, "must be > 0 (m)");
  if (!finite_non_negative(mismatch_along))
    bad(kType, "mismatch_along", mismatch_along, "must be finite and >= 0 (m)");
  if (!finite_non_negative(mismatch_across))
    bad(kType, "mismatch_across", mismatch_across, "must be finite and >= 0 (m)");
}

double effective_sigma(double sigma, double resolution, double mismatch) noexcept {
  return std::sqrt(sigma * sigma + resolution * resolution / 12.0 + mismatch * mismatch);
}

EffectiveSigma effective_sigma(const SensorNoiseModel& model, double map_resolution) {
  model.validate();
  if (!finite_non_negative(map_resolution))
    bad("effective_sigma", "map_resolution", map_resolution, "must be finite and >= 0 (m)");
  return {effective_sigma(model.sigma_along, map_resolution, model.mismatch_along),
          effective_sigma(model.sigma_across, map_resolution, model.mismatch_across)};
}

}  // namespace pgmcl::sensor_model
