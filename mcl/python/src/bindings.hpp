#pragma once
/// The pieces the binding files of pgmcl._core share: argument conversions (paths, poses,
/// maps, configs, trajectories) and numpy views whose memory a Python object owns.
/// Each binding file adds one part of the API to the module (bind_*).

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "pgmcl/common/se2.hpp"
#include "pgmcl/eval/evaluation.hpp"
#include "pgmcl/eval/metrics.hpp"
#include "pgmcl/io/carmen.hpp"
#include "pgmcl/io/trajectory.hpp"
#include "pgmcl/maps/occupancy_grid.hpp"
#include "pgmcl/mcl/localizer_config.hpp"

namespace pgmcl::python {

namespace py = pybind11;

void bind_errors(py::module_& m);
void bind_maps(py::module_& m);
void bind_config(py::module_& m);
void bind_localizer(py::module_& m);
void bind_logs(py::module_& m);
void bind_runs(py::module_& m);
void bind_evaluate(py::module_& m);

/// A path the user named that does not exist: raised as FileNotFoundError.
struct MissingFile {
  std::string path;
};

/// os.fspath(obj) as UTF-8 (str or os.PathLike).
[[nodiscard]] std::string path_arg(py::handle obj);
/// The same, after checking that the file exists (else MissingFile).
[[nodiscard]] std::string existing_file(py::handle obj);

/// (x, y, theta) from any sequence of three numbers; `name` is the argument, for messages.
[[nodiscard]] Pose2 pose_arg(py::handle obj, const char* name);
[[nodiscard]] py::tuple pose_tuple(const Pose2& p);

/// A map given as a pgmcl.Map or as the path of a map_server YAML file.
[[nodiscard]] std::shared_ptr<maps::OccupancyGrid> map_arg(py::handle obj);
/// A filter configuration given as a pgmcl.Config, a dict of overrides (Config(**d)), the
/// path of a filter YAML file, or None (the defaults).
[[nodiscard]] LocalizerConfig config_arg(py::handle obj);
[[nodiscard]] py::object config_object(const LocalizerConfig& cfg);
/// One override, read and validated as `--set key=value` (InputError with its message).
void apply_override(LocalizerConfig& cfg, const std::string& key, py::handle value);
/// A random seed: a whole number in [0, 2^64).
[[nodiscard]] std::uint64_t seed_arg(py::handle obj);

/// A whole CARMEN log and the per-scan arrays Python sees, laid out once so that every
/// access returns a view, never a copy.
struct LogData {
  io::CarmenLog log;
  std::string source;          ///< file name, for messages
  std::vector<double> stamps;  ///< seconds
  std::size_t beams = 0;       ///< beams per scan when fixed, else 0
  std::vector<float> ranges;   ///< scans x beams when fixed
  std::vector<double>
      scan_geometry;                ///< per scan: angle_min, angle_increment, range_min, range_max
  std::vector<double> sensor_pose;  ///< per scan: x, y, theta
  std::vector<double> odometry;     ///< per scan: paired odometry (NaN without)
  std::vector<std::uint8_t> has_odometry;  ///< per scan: 1 when paired (numpy bool)
  /// per scan: 1 when pgmcl::replay feeds it to the filter (paired, not stamped before the
  /// last scan fed)
  std::vector<std::uint8_t> usable;
  std::vector<double> poses;  ///< per scan: robot pose from the logged laser pose (NaN without)

  LogData(io::CarmenLog l, std::string src);
};

/// A log given as a pgmcl.Log or as the path of a CARMEN file (read like `pgmcl localize`).
[[nodiscard]] std::shared_ptr<LogData> log_arg(py::handle obj);
/// Reads a CARMEN file; malformed lines become one Python warning, as on the command line.
[[nodiscard]] std::shared_ptr<LogData> read_log_file(const std::string& path, bool strict);

/// A trajectory given as an (N, 4) array of (t, x, y, theta) or as the path of a TUM file
/// or, like `--truth`, of a corrected CARMEN log.
[[nodiscard]] io::Trajectory trajectory_arg(py::handle obj, const char* name);
/// An (N, 4) array of (t, x, y, theta), copied.
[[nodiscard]] py::array_t<double> trajectory_array(const io::Trajectory& t);
/// The same as a read-only view of `t`, kept alive by `owner`.
[[nodiscard]] py::array_t<double> trajectory_view(const io::Trajectory& t, py::handle owner);

/// metrics.yaml as a dict: the same keys (io::metrics_entries), counts as int, `null` as
/// None; `run_figures` as in io::metrics_yaml.
[[nodiscard]] py::dict metrics_dict(const io::RunMetrics& m, bool run_figures);
/// An (M, 3) view of per-pose errors (t, metres, degrees), kept alive by `owner`.
[[nodiscard]] py::array_t<double> errors_view(const std::vector<io::PoseError>& errors,
                                              py::handle owner);

/// A numpy view of `data` with `shape` and byte `strides`, kept alive by `owner`;
/// read-only unless `writable`.
template <class T>
[[nodiscard]] py::array_t<T> view(const T* data, std::vector<py::ssize_t> shape,
                                  std::vector<py::ssize_t> strides, py::handle owner,
                                  bool writable = false) {
  py::array_t<T> a(std::move(shape), std::move(strides), data, owner);
  if (!writable) {
    py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  }
  return a;
}

/// Emits a Python warning (RuntimeWarning), as the command line prints "pgmcl: warning:".
void warn(const std::string& message);

}  // namespace pgmcl::python
