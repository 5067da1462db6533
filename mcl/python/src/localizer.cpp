/// The step API: pgmcl.Localizer drives pgmcl::Localizer one scan at a time, releasing the
/// GIL while the filter works; pgmcl.UpdateResult is what one update() said.

#include "pgmcl/mcl/localizer.hpp"

#include <Eigen/Core>
#include <cstring>
#include <mutex>

#include "bindings.hpp"

namespace pgmcl::python {
namespace {

constexpr const char* kLocalizerDoc = R"doc(Monte Carlo localisation on a map, one scan at a time.

Localizer(map, config=None): ``map`` a pgmcl.Map or a map YAML path, ``config`` a
pgmcl.Config, a dict of overrides, a filter YAML path or None (defaults). Builds the
likelihood tables (the GIL is released meanwhile) and starts with global localisation.

Same seed, same results as the C++ pgmcl::Localizer, for any thread count. update() and
the constructor release the GIL, so several Localizers run in parallel from Python threads;
one Localizer used from two threads serialises its calls.)doc";

constexpr const char* kUpdateDoc = R"doc(One filter step for a scan.

``odom``: the robot's odometry pose (x, y, theta) at the scan (any odometry frame: only
the increment since the last update is used). ``ranges``: the readings in metres (any 1-D
float array; NaN, inf and readings outside [range_min, range_max) are skipped and counted).
Beam i points at ``angle_min + i * angle_increment`` (radians) in the sensor frame,
``sensor_pose`` is the laser's pose on the robot, ``stamp`` the scan's time in seconds.

Returns an UpdateResult. Raises ValueError, before any state changes, for a malformed scan
(non-finite angles, odometry or stamp, range_max <= range_min, a beam count other than
likelihood.expected_beams) or a stamp earlier than the last one (time_backwards = throw).)doc";

/// A Localizer and the lock that serialises calls from several Python threads (the GIL is
/// released inside).
struct PyLocalizer {
  std::shared_ptr<maps::OccupancyGrid> map;
  std::unique_ptr<Localizer> loc;
  std::mutex mutex;
};

py::array_t<double> matrix3(const Eigen::Matrix3d& m) {
  py::array_t<double> a({3, 3});
  auto v = a.mutable_unchecked<2>();
  for (py::ssize_t r = 0; r < 3; ++r)
    for (py::ssize_t c = 0; c < 3; ++c) v(r, c) = m(r, c);
  return a;
}

Eigen::Matrix3d matrix3_arg(py::handle obj) {
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(obj);
  if (!a || a.ndim() != 2 || a.shape(0) != 3 || a.shape(1) != 3) {
    throw py::value_error("set_pose: covariance must be a 3x3 array (m², m², rad²), got " +
                          py::repr(obj).cast<std::string>());
  }
  Eigen::Matrix3d m;
  const auto v = a.unchecked<2>();
  for (py::ssize_t r = 0; r < 3; ++r)
    for (py::ssize_t c = 0; c < 3; ++c) m(r, c) = v(r, c);
  return m;
}

std::unique_ptr<PyLocalizer> make(py::handle map, py::handle config) {
  auto p = std::make_unique<PyLocalizer>();
  p->map = map_arg(map);
  const LocalizerConfig cfg = config_arg(config);
  py::gil_scoped_release release;
  p->loc = std::make_unique<Localizer>(*p->map, cfg);
  return p;
}

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

UpdateResult update(PyLocalizer& self, py::handle odom, const FloatArray& r, double angle_min,
                    double angle_increment, double stamp, double range_min, double range_max,
                    py::handle sensor_pose) {
  if (r.ndim() != 1) {
    throw py::value_error("update: ranges must be 1-D, got " + std::to_string(r.ndim()) +
                          " dimensions");
  }
  const Pose2 odometry = pose_arg(odom, "odom");
  LaserScan scan;
  scan.angle_min = angle_min;
  scan.angle_increment = angle_increment;
  scan.range_min = range_min;
  scan.range_max = range_max;
  scan.sensor_pose = pose_arg(sensor_pose, "sensor_pose");
  scan.ranges.assign(r.data(), r.data() + r.size());
  py::gil_scoped_release release;
  const std::lock_guard<std::mutex> lock(self.mutex);
  return self.loc->update(odometry, scan, stamp);
}

/// Runs `f` on the Localizer under its lock, without the GIL.
template <class F>
auto locked(PyLocalizer& self, F&& f) {
  py::gil_scoped_release release;
  const std::lock_guard<std::mutex> lock(self.mutex);
  return f(*self.loc);
}

py::tuple particles(PyLocalizer& self) {
  std::vector<Pose2> poses;
  std::vector<double> weights;
  locked(self, [&](const Localizer& loc) {
    const ParticlesView v = loc.particles();
    poses.reserve(v.size());
    for (std::size_t i = 0; i < v.size(); ++i) poses.push_back(v.global_pose(i));
    weights.assign(v.weight.begin(), v.weight.end());
  });
  const auto n = static_cast<py::ssize_t>(poses.size());
  py::array_t<double> p({n, py::ssize_t{3}});
  std::memcpy(p.mutable_data(), poses.data(), poses.size() * sizeof(Pose2));
  return py::make_tuple(p, py::array_t<double>(n, weights.data()));
}

void bind_result(py::module_& m) {
  static_assert(sizeof(Pose2) == 3 * sizeof(double), "Pose2 is read as 3 doubles");
  py::class_<UpdateResult>(m, "UpdateResult",
                           "What one Localizer.update() did: the estimate and diagnostics "
                           "(mcl/README.md, 'One update()').")
      .def_property_readonly(
          "estimate", [](const UpdateResult& r) { return pose_tuple(r.estimate); },
          "(x, y, theta) in the map frame: the weighted mean of the heaviest cluster (on "
          "skipped updates the last estimate moved by odometry).")
      .def_property_readonly(
          "covariance", [](const UpdateResult& r) { return matrix3(r.covariance); },
          "3x3 covariance of the estimate (x, y, theta; m², rad²), a new numpy array.")
      .def_property_readonly(
          "mean", [](const UpdateResult& r) { return pose_tuple(r.mean); },
          "(x, y, theta): the weighted mean of all particles.")
      .def_property_readonly(
          "mean_covariance", [](const UpdateResult& r) { return matrix3(r.mean_covariance); },
          "3x3 covariance of `mean`.")
      .def_readonly("cluster_weight", &UpdateResult::cluster_weight,
                    "Weight of the heaviest cluster, in [0, 1].")
      .def_readonly("clusters", &UpdateResult::clusters, "Number of clusters found.")
      .def_readonly("converged", &UpdateResult::converged,
                    "One dominant compact cluster and no competing hypothesis that fits better.")
      .def_property_readonly(
          "skipped",
          [](const UpdateResult& r) -> py::object {
            if (r.skipped == SkipReason::kNone) return py::none();
            return py::str(to_string(r.skipped));
          },
          "None for a full update, else why it was skipped: 'not_moved', 'no_valid_beams' "
          "or 'time_went_backwards'.")
      .def_property_readonly("measured", &UpdateResult::measured,
                             "The weights were updated from this scan.")
      .def_readonly("motion_applied", &UpdateResult::motion_applied,
                    "The odometry increment moved the particles (False when gated).")
      .def_readonly("resampled", &UpdateResult::resampled,
                    "The set was resampled (N_eff below the threshold, or injection due).")
      .def_readonly("n_eff", &UpdateResult::n_eff,
                    "Effective sample size 1 / sum w² after the measurement, before resampling.")
      .def_readonly("tempering", &UpdateResult::tempering,
                    "Exponent tau applied to this scan's log-likelihood (0 when not measured).")
      .def_readonly("particles", &UpdateResult::particles,
                    "Particle count after this update (KLD-sampling may change it).")
      .def_readonly("injected", &UpdateResult::injected,
                    "Particles redrawn over free space (augmented MCL).")
      .def_readonly("w_slow", &UpdateResult::w_slow,
                    "Augmented MCL's long-term average of the per-beam likelihood.")
      .def_readonly("w_fast", &UpdateResult::w_fast, "Augmented MCL's short-term average.")
      .def_readonly("beams_total", &UpdateResult::beams_total, "Readings in the scan.")
      .def_readonly("beams_invalid", &UpdateResult::beams_invalid,
                    "NaN, inf or out-of-range readings (skipped).")
      .def_readonly("beams_used", &UpdateResult::beams_used,
                    "Readings scored per particle after selection.")
      .def_readonly("beams_background", &UpdateResult::beams_background,
                    "Used beams whose endpoint, seen from the estimate, reads the table's "
                    "background (beyond the kernel's reach or off the map).")
      .def_readonly("fit", &UpdateResult::fit,
                    "Confidence: fraction of used beams within 3 sigma of a mapped obstacle, "
                    "seen from the estimate (near 1 on a well-mapped scene).")
      .def_readonly("competitors", &UpdateResult::competitors,
                    "Competing hypotheses tracked after this update.")
      .def_readonly("alternative_evidence", &UpdateResult::alternative_evidence,
                    "Largest evidence of a competitor (tempered nats; > 0: another place fits "
                    "better so far, and converged is False).")
      .def_readonly("seeded", &UpdateResult::seeded,
                    "Particles redrawn around searched hypotheses this update.")
      .def_readonly("switched", &UpdateResult::switched,
                    "The filter moved to a competitor that outweighed it.")
      .def_readonly("searched", &UpdateResult::searched,
                    "A scan-to-map search ran this update (global or rescue).")
      .def_readonly("rotation_noise_factor", &UpdateResult::rotation_noise_factor,
                    "Factor on the motion noise's rotation variances that the odometry's "
                    "residuals called for so far (1 = the configured noise).")
      .def_readonly("translation_noise_factor", &UpdateResult::translation_noise_factor,
                    "The same for the translation variances.")
      .def_property_readonly(
          "timings",
          [](const UpdateResult& r) {
            py::dict d;
            d["motion_ms"] = r.timings.motion_ms;
            d["measurement_ms"] = r.timings.measurement_ms;
            d["hypotheses_ms"] = r.timings.hypotheses_ms;
            d["free_space_ms"] = r.timings.free_space_ms;
            d["resample_ms"] = r.timings.resample_ms;
            d["estimate_ms"] = r.timings.estimate_ms;
            d["total_ms"] = r.timings.total_ms;
            return d;
          },
          "Wall time of each stage in milliseconds: motion_ms, measurement_ms (of which "
          "hypotheses_ms and free_space_ms), resample_ms, estimate_ms, total_ms.")
      .def("__repr__", [](const UpdateResult& r) {
        return "pgmcl.UpdateResult(estimate=" +
               py::repr(pose_tuple(r.estimate)).cast<std::string>() +
               ", skipped=" + (r.skipped == SkipReason::kNone ? "None" : to_string(r.skipped)) +
               ", converged=" + (r.converged ? "True" : "False") +
               ", particles=" + std::to_string(r.particles) + ")";
      });
}

}  // namespace

void bind_localizer(py::module_& m) {
  bind_result(m);
  py::class_<PyLocalizer>(m, "Localizer", kLocalizerDoc)
      .def(py::init(&make), py::arg("map"), py::arg("config") = py::none())
      .def("update", &update, kUpdateDoc, py::arg("odom"), py::arg("ranges"), py::kw_only(),
           py::arg("angle_min"), py::arg("angle_increment"), py::arg("stamp"),
           py::arg("range_min") = 0.1, py::arg("range_max") = 30.0,
           py::arg("sensor_pose") = py::make_tuple(0.0, 0.0, 0.0))
      .def(
          "set_pose",
          [](PyLocalizer& self, py::handle pose, py::handle covariance) {
            const Pose2 mean = pose_arg(pose, "pose");
            const Eigen::Matrix3d cov = matrix3_arg(covariance);
            locked(self, [&](Localizer& loc) { loc.set_pose(mean, cov); });
          },
          py::arg("pose"), py::arg("covariance"),
          "Re-initialises around pose (x, y, theta; map frame) with a 3x3 covariance "
          "(symmetric positive semi-definite; m², m², rad²), filter.particles particles. "
          "The next update measures whatever the motion.")
      .def(
          "global_localize",
          [](PyLocalizer& self) { locked(self, [](Localizer& loc) { loc.global_localize(); }); },
          "Re-initialises uniformly over the free cells with filter.global_particles.")
      .def(
          "force_update",
          [](PyLocalizer& self) { locked(self, [](Localizer& loc) { loc.force_update(); }); },
          "The next update measures even if the robot has not moved.")
      .def("particles", &particles,
           "(poses, weights): an (N, 3) array of (x, y, theta) in the map frame and the N "
           "normalised weights; new arrays (the filter's own are float, map-local).")
      .def_property_readonly(
          "last_result",
          [](PyLocalizer& self) {
            return locked(self, [](const Localizer& l) { return l.last_result(); });
          },
          "The UpdateResult of the last update (or of the initial state).")
      .def_property_readonly(
          "config", [](PyLocalizer& self) { return config_object(self.loc->config()); },
          "A copy of the Localizer's Config.")
      .def_property_readonly(
          "map", [](const PyLocalizer& self) { return self.map; }, "The pgmcl.Map it runs on.");
}

}  // namespace pgmcl::python
