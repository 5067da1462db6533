/// pgmcl._core: the compiled half of the Python package `pgmcl` (mcl/python/README.md).
/// The package's __init__.py re-exports everything defined here.

#include "bindings.hpp"

PYBIND11_MODULE(_core, m) {
  m.doc() =
      "pgmcl: Monte Carlo localisation for 2D laser rangefinders (Dekan et al.'s planar "
      "Gaussian beam model), its simulator and evaluation, with numpy arrays in and out.";
  m.attr("__version__") = PGMCL_VERSION;
  pgmcl::python::bind_errors(m);
  pgmcl::python::bind_maps(m);
  pgmcl::python::bind_config(m);
  pgmcl::python::bind_localizer(m);
  pgmcl::python::bind_logs(m);
  pgmcl::python::bind_runs(m);
  pgmcl::python::bind_evaluate(m);
}
