/// Whole runs: simulate a scenario, localise a log (pgmcl::replay, the loop of `pgmcl
/// localize`); results hand their arrays to numpy without copies.

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>

#include "bindings.hpp"
#include "pgmcl/config/scenario_yaml.hpp"
#include "pgmcl/eval/metrics.hpp"
#include "pgmcl/io/relations.hpp"
#include "pgmcl/io/sim_log_io.hpp"
#include "pgmcl/replay/replay.hpp"
#include "pgmcl/sims/scenario.hpp"

namespace pgmcl::python {
namespace {

using namespace pybind11::literals;

/// Updates between two looks for Ctrl-C during a localize() run.
constexpr std::size_t kSignalCheckPeriod = 64;

struct RunData {
  replay::ReplayResult result;
  LocalizerConfig config;
};

struct SimulationData {
  std::shared_ptr<LogData> log;
  io::Trajectory truth;
  std::shared_ptr<maps::OccupancyGrid> map;
  std::string name, description;
  std::vector<double> kidnap_times;
};

replay::InitialBelief initial_belief(py::handle init, py::handle sigma, bool have_truth) {
  replay::InitialBelief b;
  if (init.is_none()) {
    b.kind =
        have_truth ? replay::InitialBelief::Kind::kTruth : replay::InitialBelief::Kind::kGlobal;
  } else if (py::isinstance<py::str>(init)) {
    const auto s = init.cast<std::string>();
    if (s == "global") {
      b.kind = replay::InitialBelief::Kind::kGlobal;
    } else if (s == "truth" && have_truth) {
      b.kind = replay::InitialBelief::Kind::kTruth;
    } else {
      throw py::value_error("init: expected (x, y, theta), 'global', 'truth' (with truth=) " +
                            std::string("or None, got '") + s + "'");
    }
  } else {
    b.kind = replay::InitialBelief::Kind::kPose;
    b.pose = pose_arg(init, "init");
    b.pose.theta = wrap_angle(b.pose.theta);
  }
  if (sigma.is_none()) return b;
  std::vector<double> s;
  bool ok = py::isinstance<py::sequence>(sigma) && !py::isinstance<py::str>(sigma);
  try {
    if (ok)
      for (const py::handle v : py::reinterpret_borrow<py::sequence>(sigma))
        s.push_back(v.cast<double>());
  } catch (const py::cast_error&) {
    ok = false;
  }
  ok = ok && (s.size() == 2 || s.size() == 3) &&
       std::all_of(s.begin(), s.end(), [](double v) { return std::isfinite(v) && v > 0; });
  if (!ok) {
    throw py::value_error("init_sigma: expected (s_xy, s_theta) or (s_x, s_y, s_theta), " +
                          std::string("finite and > 0 (m, rad), got ") +
                          py::repr(sigma).cast<std::string>());
  }
  b.sigma_xy = s[0];
  b.sigma_y = s.size() == 3 ? s[1] : -1.0;
  b.sigma_theta = s.back();
  return b;
}

std::shared_ptr<RunData> localize(py::handle map, py::handle log, py::handle init,
                                  py::handle config, py::handle seed, py::handle threads,
                                  py::handle truth, py::handle relations, double time_offset,
                                  py::handle init_sigma) {
  replay::ReplayJob job;
  const auto grid = map_arg(map);
  const auto data = log_arg(log);
  job.config = config_arg(config);
  if (!seed.is_none()) apply_override(job.config, "seed", seed);  // as --set seed=...
  if (!threads.is_none()) apply_override(job.config, "threads", threads);
  if (!truth.is_none()) job.truth = trajectory_arg(truth, "truth");
  if (!relations.is_none()) {
    job.relations = io::read_relations(existing_file(relations));
    job.relations_time_offset = time_offset;
  }
  job.init = initial_belief(init, init_sigma, job.truth.has_value());
  job.map = grid.get();
  job.log = &data->log;
  job.log_name = data->source;

  std::atomic<bool> stop{false};
  bool interrupted = false;
  replay::ReplayHooks hooks;
  hooks.stop = &stop;
  hooks.on_update = [&](std::size_t done, std::size_t, const UpdateResult&) {
    if (done % kSignalCheckPeriod != 0) return;
    const py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) {  // Ctrl-C: stop, then raise KeyboardInterrupt
      interrupted = true;
      stop = true;
    }
  };
  auto run = std::make_shared<RunData>();
  run->config = job.config;
  {
    const py::gil_scoped_release release;
    run->result = replay::run(job, hooks);
  }
  if (interrupted) throw py::error_already_set();
  for (const std::string& w : run->result.warnings) warn(w);
  return run;
}

py::dict updates_dict(const std::vector<replay::UpdateRow>& rows) {
  const auto n = static_cast<py::ssize_t>(rows.size());
  py::array_t<double> stamp(n), x(n), y(n), theta(n), fit(n), n_eff(n), evidence(n);
  py::array_t<double> rotation_noise_factor(n), translation_noise_factor(n);
  py::array_t<bool> converged(n), switched(n), searched(n);
  py::array_t<std::int64_t> particles(n), competitors(n), seeded(n), injected(n);
  py::list skipped;
  for (py::ssize_t i = 0; i < n; ++i) {
    const replay::UpdateRow& u = rows[static_cast<std::size_t>(i)];
    stamp.mutable_at(i) = u.stamp;
    x.mutable_at(i) = u.estimate.x;
    y.mutable_at(i) = u.estimate.y;
    theta.mutable_at(i) = u.estimate.theta;
    skipped.append(u.skipped == SkipReason::kNone ? py::object(py::none())
                                                  : py::object(py::str(to_string(u.skipped))));
    converged.mutable_at(i) = u.converged;
    fit.mutable_at(i) = u.fit;
    n_eff.mutable_at(i) = u.n_eff;
    particles.mutable_at(i) = static_cast<std::int64_t>(u.particles);
    competitors.mutable_at(i) = static_cast<std::int64_t>(u.competitors);
    evidence.mutable_at(i) = u.evidence;
    seeded.mutable_at(i) = static_cast<std::int64_t>(u.seeded);
    injected.mutable_at(i) = static_cast<std::int64_t>(u.injected);
    switched.mutable_at(i) = u.switched;
    searched.mutable_at(i) = u.searched;
    rotation_noise_factor.mutable_at(i) = u.rotation_noise_factor;
    translation_noise_factor.mutable_at(i) = u.translation_noise_factor;
  }
  py::dict d;
  d["stamp"] = stamp;
  d["x"] = x;
  d["y"] = y;
  d["theta"] = theta;
  d["skipped"] = py::module_::import("numpy").attr("array")(skipped, "dtype"_a = "object");
  d["converged"] = converged;
  d["fit"] = fit;
  d["n_eff"] = n_eff;
  d["particles"] = particles;
  d["competitors"] = competitors;
  d["evidence"] = evidence;
  d["seeded"] = seeded;
  d["injected"] = injected;
  d["switched"] = switched;
  d["searched"] = searched;
  d["rotation_noise_factor"] = rotation_noise_factor;
  d["translation_noise_factor"] = translation_noise_factor;
  return d;
}

std::shared_ptr<SimulationData> simulate(py::handle scenario, py::handle seed,
                                         py::handle duration) {
  const std::string path = existing_file(scenario);
  auto map = std::make_shared<maps::OccupancyGrid>();
  io::ScenarioFile sf = io::read_scenario_file(path, *map);
  if (!seed.is_none()) sf.scenario.seed = seed_arg(seed);
  if (!duration.is_none()) {
    const auto d = duration.cast<double>();
    if (!std::isfinite(d) || d <= 0.0) {
      throw py::value_error("simulate: duration must be finite and > 0 (seconds), got " +
                            py::repr(duration).cast<std::string>());
    }
    sf.scenario.duration = d;
  }
  sims::SimulationLog log;
  {
    const py::gil_scoped_release release;
    log = sims::simulate(sf.scenario, *map);
  }
  if (log.records.empty()) {
    throw py::value_error(path + ": the simulation produced no scans (duration " +
                          std::to_string(sf.scenario.duration) + " s)");
  }
  auto out = std::make_shared<SimulationData>();
  out->log = std::make_shared<LogData>(io::to_carmen_log(log), path + " (simulated)");
  out->truth = io::sim_truth_trajectory(log);
  out->map = map;
  out->name = sf.name;
  out->description = sf.description;
  out->kidnap_times = log.kidnap_times;
  return out;
}

}  // namespace

py::dict metrics_dict(const io::RunMetrics& m, bool run_figures) {
  py::dict d;
  for (const io::MetricEntry& e : io::metrics_entries(m, run_figures)) {
    switch (e.kind) {
      case io::MetricEntry::Kind::kCount:
        d[py::str(e.key)] = py::int_(e.count);
        break;
      case io::MetricEntry::Kind::kReal:
        d[py::str(e.key)] = py::float_(e.real);
        break;
      case io::MetricEntry::Kind::kNull:
        d[py::str(e.key)] = py::none();
        break;
      case io::MetricEntry::Kind::kFlag:
        d[py::str(e.key)] = py::bool_(e.count != 0);
        break;
    }
  }
  return d;
}

py::array_t<double> errors_view(const std::vector<io::PoseError>& errors, py::handle owner) {
  static_assert(sizeof(io::PoseError) == 3 * sizeof(double), "PoseError is read as 3 doubles");
  return view<double>(reinterpret_cast<const double*>(errors.data()),
                      {static_cast<py::ssize_t>(errors.size()), 3},
                      {3 * sizeof(double), sizeof(double)}, owner);
}

void bind_runs(py::module_& m) {
  py::class_<RunData, std::shared_ptr<RunData>>(
      m, "Run", "What pgmcl.localize returns: the run of `pgmcl localize`, in memory.")
      .def_property_readonly(
          "trajectory",
          [](py::object self) {
            return trajectory_view(self.cast<const RunData&>().result.trajectory, self);
          },
          "(N, 4) (t, x, y, theta): one estimate per scan with odometry (trajectory.tum); a "
          "view of the run's memory.")
      .def_property_readonly(
          "metrics", [](const RunData& d) { return metrics_dict(d.result.metrics, true); },
          "metrics.yaml as a dict, the same keys (mcl/eval/README.md): run figures, and with "
          "truth ate_rmse_m, heading_rmse_deg, ..., with relations relations_trans_m, ...")
      .def_property_readonly(
          "updates", [](const RunData& d) { return updates_dict(d.result.rows); },
          "updates.csv as a dict of (N,) arrays: stamp, x, y, theta, skipped (None or the "
          "reason), converged, fit, n_eff, particles, competitors, evidence, seeded, "
          "injected, switched, searched, rotation_noise_factor, translation_noise_factor "
          "(pandas.DataFrame(run.updates) makes the table).")
      .def_property_readonly(
          "errors",
          [](py::object self) -> py::object {
            const auto& d = self.cast<const RunData&>();
            if (!d.result.ate) return py::none();
            return errors_view(d.result.ate->errors, self);
          },
          "With truth, (M, 3) (t, position error m, heading error deg) per matched estimate; "
          "else None.")
      .def_property_readonly(
          "particles",
          [](py::object self) {
            const auto& p = self.cast<const RunData&>().result.particles;
            return view<double>(reinterpret_cast<const double*>(p.data()),
                                {static_cast<py::ssize_t>(p.size()), 3},
                                {3 * sizeof(double), sizeof(double)}, self);
          },
          "(K, 3) the final particle cloud (x, y, theta), map frame.")
      .def_property_readonly(
          "weights",
          [](py::object self) {
            const auto& w = self.cast<const RunData&>().result.weights;
            return view<double>(w.data(), {static_cast<py::ssize_t>(w.size())}, {sizeof(double)},
                                self);
          },
          "(K,) the final cloud's normalised weights.")
      .def_property_readonly(
          "start", [](const RunData& d) { return d.result.start; }, "How the filter started.")
      .def_property_readonly(
          "warnings", [](const RunData& d) { return py::cast(d.result.warnings); },
          "Skipped scans and the like (also emitted as RuntimeWarning).")
      .def_property_readonly(
          "complete", [](const RunData& d) { return d.result.complete; },
          "False if the run was stopped early.")
      .def_property_readonly(
          "config", [](const RunData& d) { return config_object(d.config); },
          "The effective Config (config.yaml).")
      .def("__repr__", [](const RunData& d) {
        std::string s = "pgmcl.Run(" + std::to_string(d.result.trajectory.size()) + " poses";
        if (d.result.metrics.accuracy) {
          char buf[64];
          std::snprintf(buf, sizeof buf, ", ATE RMSE %.3f m",
                        d.result.metrics.accuracy->ate_rmse_m);
          s += buf;
        }
        return s + ")";
      });

  py::class_<SimulationData, std::shared_ptr<SimulationData>>(
      m, "Simulation", "What pgmcl.simulate returns: the log, its ground truth and the map.")
      .def_readonly("log", &SimulationData::log, "The simulated scans and odometry (a Log).")
      .def_property_readonly(
          "truth",
          [](py::object self) {
            return trajectory_view(self.cast<const SimulationData&>().truth, self);
          },
          "(N, 4) (t, x, y, theta): the true robot poses at the scans.")
      .def_readonly("map", &SimulationData::map, "The scenario's map (a Map).")
      .def_readonly("name", &SimulationData::name, "The scenario's name (default its file's stem).")
      .def_readonly("description", &SimulationData::description,
                    "The scenario's description (may be empty).")
      .def_readonly("kidnap_times", &SimulationData::kidnap_times, "Seconds.");

  m.def("localize", &localize, py::arg("map"), py::arg("log"), py::arg("init") = py::none(),
        py::arg("config") = py::none(), py::arg("seed") = 1, py::arg("threads") = 1,
        py::arg("truth") = py::none(), py::arg("relations") = py::none(),
        py::arg("time_offset") = 0.0, py::arg("init_sigma") = py::none(),
        R"doc(Localises a whole log on a map, as ``pgmcl localize`` (pgmcl::replay), in memory.

``map``: a Map or map YAML path. ``log``: a Log or CARMEN path. ``config``: a Config, a
dict of overrides, a filter YAML path or None; ``seed`` and ``threads`` (default 1 each)
override it (as --seed, --threads), None keeps the config's. ``truth``: an (N, 4) array or a TUM / corrected CARMEN path
(adds the accuracy to the metrics). ``relations``: a benchmark relations file, with
``time_offset`` seconds added to the log's stamps (intel: 976052857.338).
``init``: (x, y, theta) (with ``init_sigma`` (s_xy, s_theta) or (s_x, s_y, s_theta),
default 0.25 m, 0.1 rad), 'global', 'truth' (the truth at the first scan), or None: the
truth when given, else global. Returns a Run. The GIL is released; Ctrl-C stops the run
and raises KeyboardInterrupt. Skipped scans are reported as RuntimeWarning.)doc");
  m.def("simulate", &simulate, py::arg("scenario"), py::arg("seed") = py::none(),
        py::arg("duration") = py::none(),
        R"doc(Simulates a scenario file (configs/scenarios/*.yaml), as ``pgmcl simulate``.

``seed`` and ``duration`` (seconds) override the file's. Returns a Simulation (log, truth,
map); ``pgmcl.localize(sim.map, sim.log, truth=sim.truth)`` localises it.)doc");
}

}  // namespace pgmcl::python
