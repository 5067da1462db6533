/// pgmcl kernel: prints the tabular form of the planar beam model (Dekan et al., Sec. 5,
/// Table 5) for given sigmas, cell size and beam angle.

#include <cstdio>
#include <memory>
#include <numbers>
#include <string>

#include "app_util.hpp"
#include "commands.hpp"
#include "pgmcl/sensor_model/kernel_table.hpp"

namespace pgmcl::app {
namespace {

struct KernelOptions {
  double sigma_x_mm = sensor_model::paper::kSigmaAlongMm;
  double sigma_y_mm = sensor_model::paper::kSigmaAcrossMm;
  double cell_mm = sensor_model::paper::kTable5CellSize * 1000.0;
  double angle_deg = 0.0;
  int radius = 1;
  bool integrated = false;
};

int run_kernel(const KernelOptions& o) {
  sensor_model::KernelSpec spec;
  spec.sigma_along = o.sigma_x_mm / 1000.0;
  spec.sigma_across = o.sigma_y_mm / 1000.0;
  spec.cell_size = o.cell_mm / 1000.0;
  spec.beam_angle = o.angle_deg * std::numbers::pi / 180.0;
  spec.radius = o.radius;
  spec.discretisation = o.integrated ? sensor_model::Discretisation::kCellIntegrated
                                     : sensor_model::Discretisation::kPointwise;
  const sensor_model::KernelTable t = sensor_model::make_kernel_table(spec);

  std::printf("Planar Gaussian beam kernel (Dekan et al., Eq. (6), Table 5 layout)\n");
  std::printf(
      "sigma_x %.4f mm (along the beam), sigma_y %.4f mm (across), cell %.4f mm, "
      "beam angle %.2f deg, %s\n",
      o.sigma_x_mm, o.sigma_y_mm, o.cell_mm, o.angle_deg,
      o.integrated ? "cell-integrated" : "pointwise (pdf at cell centres)");
  // Printed as the paper prints Table 5: row = offset along map x (the beam direction at
  // 0 deg), column = offset along map y; i.e. the transpose of KernelTable's layout.
  double sum = 0.0;
  for (int dx = -t.radius; dx <= t.radius; ++dx) {
    for (int dy = -t.radius; dy <= t.radius; ++dy) {
      const double m = t.at(dx, dy);
      sum += m;
      std::printf("%s%.4f", dy == -t.radius ? "" : "\t", m);
    }
    std::printf("\n");
  }
  std::printf(
      "sum %.4f (normalised over the %dx%d table; mass captured before normalising "
      "%.4f)\n",
      sum, t.side(), t.side(), t.captured_mass);
  if (t.captured_mass < 0.5) {
    std::fprintf(stderr,
                 "pgmcl: warning: the %dx%d table holds only %.1f %% of the kernel's mass, so "
                 "the normalised values above describe its centre, not the kernel: raise "
                 "--radius or --cell\n",
                 t.side(), t.side(), 100.0 * t.captured_mass);
  }
  return 0;
}

void add_kernel_options(CLI::App& sub, KernelOptions& o) {
  sub.description("Print the tabular beam model (Dekan et al., Table 5) for given sigmas");
  // Millimetres, as Dekan et al.'s tables; a unit may be given ("0.05m" is 50 mm). Sigmas up
  // to 10 m, the filter's bound on a sigma (config_schema::kSigma); cells from 1 µm to 1 km.
  const auto millimetres = [&sub](const std::string& name, double& value, const std::string& help,
                                  double min, double max) {
    sub.add_option(name, value, help)
        ->capture_default_str()
        ->transform(length_in("mm"))
        ->check(positive() & CLI::Range(min, max))
        ->type_name("MM");
  };
  millimetres("--sigma-x", o.sigma_x_mm, "Sigma along the beam, mm (or with a unit: 5.7mm)", 0.0,
              1e4);
  millimetres("--sigma-y", o.sigma_y_mm, "Sigma across the beam, mm (or with a unit)", 0.0, 1e4);
  millimetres("--cell", o.cell_mm,
              "Cell size, mm (or with a unit: 0.05m is pgmcl map --resolution 0.05)", 1e-3, 1e6);
  sub.add_option("--angle", o.angle_deg, "Beam angle in the map frame, degrees")
      ->capture_default_str();
  sub.add_option("--radius", o.radius, "Table radius in cells ((2r+1)^2 cells)")
      ->capture_default_str()
      ->check(CLI::Range(0, 50));
  sub.add_flag("--integrated", o.integrated,
               "Integrate Eq. (6) over each cell instead of sampling it at cell centres");
}

}  // namespace

Command add_kernel_command(CLI::App& app) {
  return make_command<KernelOptions>(app, "kernel", add_kernel_options, run_kernel);
}

}  // namespace pgmcl::app
