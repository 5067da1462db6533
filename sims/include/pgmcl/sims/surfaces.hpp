#pragma once
/// Surface materials (Dekan et al., Table 2) and where they are in the simulated world.

#include <cstdint>
#include <string>
#include <vector>

#include "pgmcl/maps/occupancy_grid.hpp"
#include "pgmcl/sensor_model/paper_constants.hpp"
#include "pgmcl/sensor_model/sigma_models.hpp"

namespace pgmcl::sims {

/// How one surface scatters range readings.
struct SurfaceMaterial {
  std::string name;  ///< identifier used by scenarios ("cardboard_box", ...)
  /// Along-beam sigma by incidence angle, through the material's Table 2 row
  /// (sensor_model::IncidenceSigmaModel documents the interpolation).
  sensor_model::IncidenceSigmaModel sigma;
  /// Subject to SpecularLoss: Dekan et al. saw mirror reflection on shiny black metal at
  /// 45 deg (sigma 8.6743 mm, the worst of Table 2).
  bool specular = false;
};

/// Table 2's row for `surface`: name "cardboard_box", "plastic_wicker", "fabric",
/// "white_paper", "white_shiny" or "shiny_black_metal"; specular for shiny black metal.
[[nodiscard]] SurfaceMaterial table2_material(sensor_model::Surface surface);
/// The paper's final model (Sec. 5): 5.6894 mm at every incidence, name "average".
[[nodiscard]] SurfaceMaterial average_material();
/// The default palette: index 0 "average", then Table 2's six in the paper's order
/// (index = 1 + int(sensor_model::Surface)).
[[nodiscard]] std::vector<SurfaceMaterial> default_materials();

/// An axis-aligned rectangle of the global frame whose cells are made of `material`.
struct SurfaceRegion {
  std::string material;  ///< a name in SurfaceLayout::materials
  double x_min = 0.0;    ///< metres, global frame
  double y_min = 0.0;
  double x_max = 0.0;
  double y_max = 0.0;
};

/// Which material each occupied cell is made of. Precedence: the last region containing
/// the cell centre, then the label grid, then the default.
struct SurfaceLayout {
  std::vector<SurfaceMaterial> materials = default_materials();  ///< the palette, <= 255
  std::string default_material = "average";
  /// Optional per-cell palette indices, row-major like the grid (empty = unused);
  /// kNoLabel leaves a cell to the default.
  std::vector<std::uint8_t> labels;
  std::vector<SurfaceRegion> regions;
  static constexpr std::uint8_t kNoLabel = 255;
};

/// A SurfaceLayout resolved against a grid: one palette index per cell.
class SurfaceField {
 public:
  /// Validates the layout (unknown names, bad label indices, label grid size, materials)
  /// and throws std::invalid_argument naming the field.
  SurfaceField(const SurfaceLayout& layout, const maps::OccupancyGrid& grid);

  [[nodiscard]] std::uint8_t at(int col, int row) const noexcept {
    return cells_[static_cast<std::size_t>(row) * static_cast<std::size_t>(width_) +
                  static_cast<std::size_t>(col)];
  }
  [[nodiscard]] const SurfaceMaterial& material(std::uint8_t index) const noexcept {
    return materials_[index];
  }
  [[nodiscard]] const std::vector<SurfaceMaterial>& materials() const noexcept {
    return materials_;
  }
  /// Palette index of `name`; throws std::invalid_argument (with `context`) if absent.
  [[nodiscard]] std::uint8_t index_of(const std::string& name, const std::string& context) const;

 private:
  int width_ = 0;
  std::vector<std::uint8_t> cells_;
  std::vector<SurfaceMaterial> materials_;
};

}  // namespace pgmcl::sims
