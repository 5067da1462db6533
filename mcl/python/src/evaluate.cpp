/// pgmcl.evaluate: a trajectory scored as `pgmcl eval` scores it (ATE, heading, lock-on,
/// benchmark relations), from arrays or files.

#include <cmath>
#include <cstdio>

#include "bindings.hpp"
#include "pgmcl/eval/evaluation.hpp"
#include "pgmcl/eval/metrics.hpp"
#include "pgmcl/io/relations.hpp"

namespace pgmcl::python {
namespace {

struct EvaluationData {
  io::AteResult ate;
  io::RunMetrics metrics;
};

std::shared_ptr<EvaluationData> evaluate(py::handle estimate, py::handle truth,
                                         py::handle relations, double time_offset,
                                         double converged_m, double converged_deg) {
  if (!(std::isfinite(converged_m) && converged_m > 0 && std::isfinite(converged_deg) &&
        converged_deg > 0)) {
    throw py::value_error("evaluate: converged_m and converged_deg must be finite and > 0");
  }
  const io::Trajectory est = trajectory_arg(estimate, "estimate");
  const io::Trajectory ref = trajectory_arg(truth, "truth");
  auto out = std::make_shared<EvaluationData>();
  io::AteOptions opt;
  opt.converged_translation = converged_m;
  opt.converged_rotation_deg = converged_deg;
  out->ate = io::evaluate_ate(est, ref, opt);
  out->metrics.accuracy = io::accuracy_metrics(out->ate);
  if (!relations.is_none()) {
    const std::string path = existing_file(relations);
    io::RelationOptions ro;
    ro.time_offset = time_offset;
    const io::RelationResult rel = io::evaluate_relations(est, io::read_relations(path), ro);
    out->metrics.relations = io::relations_metrics(rel);
    if (rel.matched == 0 && rel.relations > 0) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%.3f", io::kIntelRelationsTimeOffset);
      warn(path +
           ": no relation matched the estimate's stamps; does it need time_offset "
           "(intel: " +
           buf + ")?");
    }
  }
  if (out->ate.matched == 0) {
    throw py::value_error("evaluate: no estimate pose matched the ground truth in time (" +
                          std::to_string(est.size()) + " estimate and " +
                          std::to_string(ref.size()) + " truth poses)");
  }
  return out;
}

}  // namespace

void bind_evaluate(py::module_& m) {
  py::class_<EvaluationData, std::shared_ptr<EvaluationData>>(m, "Evaluation",
                                                              "What pgmcl.evaluate returns.")
      .def_property_readonly(
          "metrics", [](const EvaluationData& d) { return metrics_dict(d.metrics, false); },
          "The figures `pgmcl eval --out` writes: ate_rmse_m, ate_max_m, heading_rmse_deg, "
          "converged_after_s, truth_matched, lock_on_s, ..., and relations_* with relations.")
      .def_property_readonly(
          "errors",
          [](py::object self) {
            return errors_view(self.cast<const EvaluationData&>().ate.errors, self);
          },
          "(M, 3) (t, position error m, heading error deg) per matched estimate pose.")
      .def_property_readonly(
          "matched", [](const EvaluationData& d) { return d.ate.matched; },
          "Estimate poses with a truth pose.")
      .def_property_readonly(
          "unmatched", [](const EvaluationData& d) { return d.ate.unmatched; },
          "Estimate poses without one (not scored).");

  m.def("evaluate", &evaluate, py::arg("estimate"), py::arg("truth"),
        py::arg("relations") = py::none(), py::arg("time_offset") = 0.0,
        py::arg("converged_m") = 0.5, py::arg("converged_deg") = 10.0,
        R"doc(Scores a trajectory as ``pgmcl eval``: ATE (no alignment), heading error,
convergence and lock-on, and the relations error of Kümmerle et al. 2009 when
``relations`` is given (``time_offset`` seconds added to the estimate's stamps).
``estimate`` and ``truth``: (N, 4) arrays of (t, x, y, theta), TUM paths, or (truth) a
corrected CARMEN log. Returns an Evaluation; ValueError when no pose matches in time.)doc");
}

}  // namespace pgmcl::python
