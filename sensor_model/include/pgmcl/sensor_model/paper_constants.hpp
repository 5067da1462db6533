#pragma once
/// The published numbers of Dekan, Duchoň, Jurišica, Vitko, "Probabilistic model of laser
/// rangefinder" (Hokuyo UTM-30LX), kept as data so tests can check what follows from them.
///
/// Units: SI (metres, seconds, radians) unless a name ends in `_mm` or `_deg`; those keep the
/// paper's printed value and unit so the tables can be compared digit by digit. The paper
/// prints decimals with commas ("4,6533 mm"); they are written with points here.

#include <array>
#include <numbers>

namespace pgmcl::sensor_model {

/// The six surfaces measured in Dekan et al., Sec. 4 (Table 2), in the paper's order.
enum class Surface : int {
  kCardboardBox = 0,
  kPlasticWicker = 1,
  kFabric = 2,
  kWhitePaper = 3,
  kWhiteShiny = 4,
  kShinyBlackMetal = 5,
};
inline constexpr int kNumSurfaces = 6;

namespace paper {

inline constexpr double kDegToRad = std::numbers::pi / 180.0;

/// Dekan et al., Table 1: the manufacturer's UTM-30LX parameters (Hokuyo spec sheet [2]),
/// stated for a White Kent sheet perpendicular to the beam.
struct Utm30lxSpec {
  double guaranteed_range_min = 0.1;           ///< m (White Kent sheet)
  double guaranteed_range_max = 30.0;          ///< m (White Kent sheet)
  double max_range = 60.0;                     ///< m ("Maximum Range: 0.1 ~ 60 m")
  double min_detectable_width_at_10m = 0.130;  ///< m (varies with distance)
  double accuracy_3000lx = 0.030;              ///< m, +/- (0.1-10 m, under 3000 lx)
  double accuracy_100000lx = 0.050;            ///< m, +/- (0.1-10 m, under 100000 lx)
  double resolution = 0.001;                   ///< m (measurement resolution 1 mm)
  double repeatability_to_10m = 0.010;         ///< m, sigma < 10 mm for 0.1-10 m
  double repeatability_to_30m = 0.030;         ///< m, sigma < 30 mm for 10-30 m
  double repeatability_3000lx = 0.010;         ///< m, sigma = 10 mm under 3000 lx (to 10 m)
  double repeatability_100000lx = 0.030;       ///< m, sigma = 30 mm under 100000 lx (to 10 m)
  double scan_angle_deg = 270.0;               ///< deg, field of view
  double angular_step_deg = 0.25;              ///< deg (360 deg / 1440)
  double scan_time = 0.025;                    ///< s per scan (motor 2400 rpm)
  /// Not printed in Table 1: follows from it as 270 / 0.25 + 1 (both ends included).
  int beams_per_scan = 1081;

  [[nodiscard]] constexpr double scan_angle() const { return scan_angle_deg * kDegToRad; }  ///< rad
  [[nodiscard]] constexpr double angular_step() const {
    return angular_step_deg * kDegToRad;
  }  ///< rad
};
inline constexpr Utm30lxSpec kUtm30lx{};

/// Dekan et al., Table 2: standard deviation of the range (along the beam) per surface,
/// perpendicular and at 45 deg incidence; 20 runs x 500 readings each. Millimetres.
struct Table2Row {
  Surface surface;
  const char* name;
  double sigma_perpendicular_mm;
  double sigma_45deg_mm;
};
inline constexpr std::array<Table2Row, kNumSurfaces> kTable2{{
    {Surface::kCardboardBox, "cardboard box", 4.6533, 5.9321},
    {Surface::kPlasticWicker, "plastic wicker surface", 4.9129, 5.6927},
    {Surface::kFabric, "fabric", 4.9352, 6.1049},
    {Surface::kWhitePaper, "white paper", 5.3914, 6.2753},
    {Surface::kWhiteShiny, "white shiny surface", 5.0832, 5.8775},
    {Surface::kShinyBlackMetal, "shiny black metal", 4.7402, 8.6743},
}};

/// Dekan et al., Table 3: number of boundary shifts of a cardboard box edge out of
/// kTable3ReadingsPerRun readings, 10 runs at each of 4 distances.
inline constexpr int kTable3ReadingsPerRun = 500;
inline constexpr std::array<double, 4> kTable3Distance{0.5, 1.5, 2.5, 5.3};  ///< m
inline constexpr std::array<std::array<int, 10>, 4> kTable3Counts{{
    {161, 246, 197, 220, 180, 190, 146, 108, 136, 248},  // 50 cm
    {191, 27, 105, 211, 85, 90, 60, 31, 180, 33},        // 150 cm
    {44, 43, 48, 38, 160, 74, 39, 5, 142, 18},           // 250 cm
    {5, 32, 34, 0, 42, 74, 14, 2, 1, 0},                 // 530 cm
}};

/// Dekan et al., Table 4: boundary-shift Gaussian per distance. The paper heads the sigma
/// column "[mm]", but Eq. (5) reproduces the y column only if sigma is in units of the
/// angular step between beams (dimensionless), so it is stored as such.
struct Table4Row {
  double distance;     ///< m
  double sigma_beams;  ///< angular steps (printed with 4 decimals)
  double y_mm;         ///< mm, Eq. (5) (printed with 4 decimals)
};
inline constexpr std::array<Table4Row, 4> kTable4{{
    {0.5, 0.6078, 3.9783},
    {1.5, 0.4160, 8.1677},
    {2.5, 0.2907, 9.5131},
    {5.3, 0.1269, 8.8020},
}};

/// Dekan et al., Table 5: the model as a 3x3 grid on 5 mm cells, exactly as printed.
/// Row index = along-beam offset x, column index = across-beam offset y: the text says the
/// endpoint cell x = 40 gets 0.5416 and its along-beam neighbour x = 41 gets 0.1629, which is
/// the vertical neighbour in the printed table. Values are rounded to 4 decimals.
inline constexpr double kTable5CellSize = 0.005;  ///< m
inline constexpr std::array<std::array<double, 3>, 3> kTable5{{
    {0.0124, 0.1629, 0.0124},
    {0.0414, 0.5416, 0.0414},
    {0.0124, 0.1629, 0.0124},
}};
inline constexpr double kTable5Rounding = 0.5e-4;  ///< half a unit of the 4th decimal

/// Dekan et al., Sec. 5: the final model. Along the beam: "the average of standard deviations
/// of all types of measurements", 5.6894 mm (the mean of Table 2's twelve values). Across the
/// beam: 3 mm, "derived from the shift of object boundaries" (no formula given).
inline constexpr double kSigmaAlongMm = 5.6894;
inline constexpr double kSigmaAcrossMm = 3.0;
inline constexpr double kSigmaAlong = kSigmaAlongMm * 1e-3;    ///< m
inline constexpr double kSigmaAcross = kSigmaAcrossMm * 1e-3;  ///< m

}  // namespace paper
}  // namespace pgmcl::sensor_model
