#include "pgmcl/sims/surfaces.hpp"

#include <array>
#include <cmath>
#include <stdexcept>

namespace pgmcl::sims {

namespace {

constexpr std::array<const char*, sensor_model::kNumSurfaces> kNames = {
    "cardboard_box", "plastic_wicker", "fabric", "white_paper", "white_shiny", "shiny_black_metal"};

}  // namespace

SurfaceMaterial table2_material(sensor_model::Surface surface) {
  const int i = static_cast<int>(surface);
  if (i < 0 || i >= sensor_model::kNumSurfaces) {
    throw std::invalid_argument("table2_material: no such surface " + std::to_string(i));
  }
  SurfaceMaterial m;
  m.name = kNames[static_cast<std::size_t>(i)];
  m.sigma = sensor_model::IncidenceSigmaModel::for_surface(surface);
  m.specular = surface == sensor_model::Surface::kShinyBlackMetal;
  return m;
}

SurfaceMaterial average_material() {
  SurfaceMaterial m;
  m.name = "average";
  m.sigma.sigma_normal = sensor_model::paper::kSigmaAlong;
  m.sigma.sigma_45 = sensor_model::paper::kSigmaAlong;
  return m;
}

std::vector<SurfaceMaterial> default_materials() {
  std::vector<SurfaceMaterial> out{average_material()};
  for (int i = 0; i < sensor_model::kNumSurfaces; ++i) {
    out.push_back(table2_material(static_cast<sensor_model::Surface>(i)));
  }
  return out;
}

SurfaceField::SurfaceField(const SurfaceLayout& layout, const maps::OccupancyGrid& grid)
    : width_(grid.width()), materials_(layout.materials) {
  if (materials_.empty() || materials_.size() >= SurfaceLayout::kNoLabel) {
    throw std::invalid_argument("SurfaceLayout.materials: need 1..254 materials (got " +
                                std::to_string(materials_.size()) + ")");
  }
  for (std::size_t i = 0; i < materials_.size(); ++i) {
    const auto& m = materials_[i];
    if (m.name.empty()) {
      throw std::invalid_argument("SurfaceLayout.materials[" + std::to_string(i) +
                                  "].name is empty");
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (materials_[j].name == m.name) {
        throw std::invalid_argument("SurfaceLayout.materials: duplicate name '" + m.name + "'");
      }
    }
    try {
      m.sigma.validate();
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("SurfaceLayout.materials['" + m.name + "']: " + e.what());
    }
  }
  const std::uint8_t fallback = index_of(layout.default_material, "SurfaceLayout.default_material");
  cells_.assign(grid.size(), fallback);
  if (!layout.labels.empty()) {
    if (layout.labels.size() != grid.size()) {
      throw std::invalid_argument("SurfaceLayout.labels: " + std::to_string(layout.labels.size()) +
                                  " labels for a grid of " + std::to_string(grid.size()) +
                                  " cells");
    }
    for (std::size_t i = 0; i < cells_.size(); ++i) {
      const std::uint8_t l = layout.labels[i];
      if (l == SurfaceLayout::kNoLabel) continue;
      if (l >= materials_.size()) {
        throw std::invalid_argument("SurfaceLayout.labels[" + std::to_string(i) +
                                    "] = " + std::to_string(l) + " is not a material index");
      }
      cells_[i] = l;
    }
  }
  for (std::size_t k = 0; k < layout.regions.size(); ++k) {
    const auto& r = layout.regions[k];
    const std::string where = "SurfaceLayout.regions[" + std::to_string(k) + "]";
    if (!(r.x_min <= r.x_max && r.y_min <= r.y_max) || !std::isfinite(r.x_min) ||
        !std::isfinite(r.x_max) || !std::isfinite(r.y_min) || !std::isfinite(r.y_max)) {
      throw std::invalid_argument(where + ": need finite x_min <= x_max and y_min <= y_max");
    }
    const std::uint8_t idx = index_of(r.material, where + ".material");
    for (int row = 0; row < grid.height(); ++row) {
      for (int col = 0; col < grid.width(); ++col) {
        double gx = 0.0, gy = 0.0;
        grid.cell_center_global(col, row, gx, gy);
        if (gx >= r.x_min && gx <= r.x_max && gy >= r.y_min && gy <= r.y_max) {
          cells_[grid.index(col, row)] = idx;
        }
      }
    }
  }
}

std::uint8_t SurfaceField::index_of(const std::string& name, const std::string& context) const {
  for (std::size_t i = 0; i < materials_.size(); ++i) {
    if (materials_[i].name == name) return static_cast<std::uint8_t>(i);
  }
  std::string known;
  for (const auto& m : materials_) known += (known.empty() ? "" : ", ") + m.name;
  throw std::invalid_argument(context + ": unknown surface material '" + name +
                              "' (known: " + known + ")");
}

}  // namespace pgmcl::sims
