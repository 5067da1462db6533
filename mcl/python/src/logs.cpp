/// pgmcl.Log: a CARMEN log with its scans as numpy arrays (laid out once, then viewed), and
/// the TUM trajectory files: read_carmen, read_tum, write_tum.

#include <limits>

#include "bindings.hpp"
#include "pgmcl/io/carmen_writer.hpp"
#include "pgmcl/io/odometry_pairing.hpp"
#include "pgmcl/io/tum.hpp"

namespace pgmcl::python {
namespace {

constexpr const char* kLogDoc = R"doc(A CARMEN log (what read_carmen and simulate return).

Per scan, as numpy arrays that view the log's memory (read-only, no copy on access):
``stamps`` (N,), ``ranges`` (N, beams) float32 when every scan has the same beam count,
else a list of 1-D arrays, ``angle_min``, ``angle_increment``, ``range_min``, ``range_max``
(N,), ``sensor_pose`` (N, 3) the laser on the robot, ``odometry`` (N, 3) the odometry pose
at the scan as the filter gets it (interpolated between ODOM messages, else the scan's own
odometry fields; NaN rows where there is none, see ``has_odometry``) and ``poses`` (N, 3)
the robot pose of the logged laser pose (the ground truth of a corrected log; NaN for
RAWLASER scans). ``usable`` marks the scans pgmcl.localize feeds to the filter;
``scan(i)`` gives the keyword arguments of Localizer.update for scan i.)doc";

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void push(std::vector<double>& v, const Pose2& p) {
  v.insert(v.end(), {p.x, p.y, p.theta});
}

py::dict report_dict(const io::ParseReport& r) {
  py::dict d;
  d["lines"] = r.lines;
  d["records"] = r.records;
  d["skipped"] = r.skipped;
  d["malformed"] = r.malformed;
  py::list issues;
  for (const io::LineIssue& i : r.malformed_lines)
    issues.append(py::make_tuple(i.line, i.message_type, i.field, i.message));
  d["malformed_lines"] = issues;
  d["backwards"] = r.backwards;
  d["invalid_beams"] = r.invalid_beams;
  d["derived_front_mount"] =
      r.derived_front_mount ? py::object(pose_tuple(*r.derived_front_mount)) : py::none();
  return d;
}

/// An (N,) view of one column of the log's per-scan rows of `width` doubles.
py::array_t<double> column(const std::vector<double>& rows, std::size_t width, std::size_t col,
                           py::handle owner) {
  const auto n = static_cast<py::ssize_t>(rows.size() / width);
  return view<double>(rows.data() + col, {n}, {static_cast<py::ssize_t>(width * sizeof(double))},
                      owner);
}

py::array_t<double> poses_view(const std::vector<double>& rows, py::handle owner) {
  const auto n = static_cast<py::ssize_t>(rows.size() / 3);
  return view<double>(rows.data(), {n, 3}, {3 * sizeof(double), sizeof(double)}, owner);
}

/// An (N,) read-only numpy bool view of per-scan flags.
py::array flags_view(const std::vector<std::uint8_t>& flags, py::handle owner) {
  py::array a(py::dtype("bool"), {static_cast<py::ssize_t>(flags.size())}, {py::ssize_t{1}},
              flags.data(), owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

py::object ranges(py::object self) {
  const auto& d = self.cast<const LogData&>();
  const auto n = static_cast<py::ssize_t>(d.log.scans.size());
  if (d.beams > 0 || n == 0) {
    const auto b = static_cast<py::ssize_t>(d.beams);
    return view<float>(d.ranges.data(), {n, b}, {b * py::ssize_t{sizeof(float)}, sizeof(float)},
                       self);
  }
  py::list out;
  for (const io::CarmenScan& s : d.log.scans) {
    out.append(view<float>(s.scan.ranges.data(), {static_cast<py::ssize_t>(s.scan.ranges.size())},
                           {sizeof(float)}, self));
  }
  return out;
}

py::dict scan_kwargs(py::object self, py::ssize_t i) {
  const auto& d = self.cast<const LogData&>();
  const auto n = static_cast<py::ssize_t>(d.log.scans.size());
  if (i < 0) i += n;
  if (i < 0 || i >= n) throw py::index_error("Log.scan: index out of range");
  const auto k = static_cast<std::size_t>(i);
  const LaserScan& s = d.log.scans[k].scan;
  py::dict kw;
  kw["odom"] = py::make_tuple(d.odometry[3 * k], d.odometry[3 * k + 1], d.odometry[3 * k + 2]);
  kw["ranges"] = view<float>(s.ranges.data(), {static_cast<py::ssize_t>(s.ranges.size())},
                             {sizeof(float)}, self);
  kw["angle_min"] = s.angle_min;
  kw["angle_increment"] = s.angle_increment;
  kw["stamp"] = d.stamps[k];
  kw["range_min"] = s.range_min;
  kw["range_max"] = s.range_max;
  kw["sensor_pose"] = pose_tuple(s.sensor_pose);
  return kw;
}

}  // namespace

LogData::LogData(io::CarmenLog l, std::string src) : log(std::move(l)), source(std::move(src)) {
  const std::size_t n = log.scans.size();
  const io::PairedScans paired = io::pair_odometry(log);
  beams = n > 0 ? log.scans.front().scan.ranges.size() : 0;
  for (const io::CarmenScan& s : log.scans) {
    if (s.scan.ranges.size() != beams) beams = 0;
  }
  stamps.reserve(n);
  ranges.reserve(n * beams);
  scan_geometry.reserve(4 * n);
  sensor_pose.reserve(3 * n);
  odometry.reserve(3 * n);
  poses.reserve(3 * n);
  has_odometry.reserve(n);
  usable.reserve(n);
  double last_fed = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i) {
    const io::CarmenScan& s = log.scans[i];
    stamps.push_back(s.stamp);
    if (beams > 0) ranges.insert(ranges.end(), s.scan.ranges.begin(), s.scan.ranges.end());
    scan_geometry.insert(scan_geometry.end(), {s.scan.angle_min, s.scan.angle_increment,
                                               s.scan.range_min, s.scan.range_max});
    push(sensor_pose, s.scan.sensor_pose);
    const bool paired_ok = paired.scans[i].source != io::OdomSource::kNone;
    has_odometry.push_back(paired_ok ? 1 : 0);
    const bool fed = paired_ok && s.stamp >= last_fed;  // replay.cpp's rule
    usable.push_back(fed ? 1 : 0);
    if (fed) last_fed = s.stamp;
    push(odometry, paired_ok ? paired.scans[i].odom : Pose2{kNaN, kNaN, kNaN});
    push(poses, s.has_poses ? s.laser_pose.compose(s.scan.sensor_pose.inverse())
                            : Pose2{kNaN, kNaN, kNaN});
  }
}

std::shared_ptr<LogData> read_log_file(const std::string& path, bool strict) {
  io::CarmenReadOptions opt;
  opt.strict = strict;
  auto data = std::make_shared<LogData>(io::read_carmen(path, opt), path);
  const io::ParseReport& r = data->log.report;
  if (r.malformed > 0 && !r.malformed_lines.empty()) {
    const io::LineIssue& first = r.malformed_lines.front();
    warn(path + ": dropped " + std::to_string(r.malformed) +
         " malformed line(s) (strict=True makes this an error; Log.report lists them), the "
         "first: " +
         path + ":" + std::to_string(first.line) + ": " + first.field + ": " + first.message);
  }
  return data;
}

std::shared_ptr<LogData> log_arg(py::handle obj) {
  if (py::isinstance<LogData>(obj)) return obj.cast<std::shared_ptr<LogData>>();
  return read_log_file(existing_file(obj), false);
}

py::array_t<double> trajectory_array(const io::Trajectory& t) {
  static_assert(sizeof(io::StampedPose) == 4 * sizeof(double), "StampedPose is read as 4 doubles");
  const auto n = static_cast<py::ssize_t>(t.size());
  return py::array_t<double>({n, py::ssize_t{4}}, reinterpret_cast<const double*>(t.data()));
}

py::array_t<double> trajectory_view(const io::Trajectory& t, py::handle owner) {
  return view<double>(reinterpret_cast<const double*>(t.data()),
                      {static_cast<py::ssize_t>(t.size()), 4}, {4 * sizeof(double), sizeof(double)},
                      owner);
}

io::Trajectory trajectory_arg(py::handle obj, const char* name) {
  if (py::isinstance<py::str>(obj) || py::hasattr(obj, "__fspath__")) {
    const std::string path = existing_file(obj);
    if (!io::is_carmen_path(path)) return io::read_tum(path);
    return io::log_truth(read_log_file(path, false)->log, path);
  }
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(obj);
  if (!a || a.ndim() != 2 || a.shape(1) != 4) {
    throw py::value_error(std::string(name) +
                          ": expected an (N, 4) array of (t, x, y, theta) or a TUM path, got " +
                          py::repr(obj).cast<std::string>());
  }
  io::Trajectory t(static_cast<std::size_t>(a.shape(0)));
  const auto v = a.unchecked<2>();
  for (py::ssize_t i = 0; i < a.shape(0); ++i) {
    t[static_cast<std::size_t>(i)] = {v(i, 0), {v(i, 1), v(i, 2), v(i, 3)}};
  }
  return t;
}

void bind_logs(py::module_& m) {
  py::class_<LogData, std::shared_ptr<LogData>> log(m, "Log", kLogDoc);
  log.def("__len__", [](const LogData& d) { return d.log.scans.size(); })
      .def_property_readonly(
          "stamps",
          [](py::object self) {
            const auto& d = self.cast<const LogData&>();
            return view<double>(d.stamps.data(), {static_cast<py::ssize_t>(d.stamps.size())},
                                {sizeof(double)}, self);
          },
          "(N,) scan times, seconds.")
      .def_property_readonly("ranges", &ranges,
                             "(N, beams) float32 view when the beam count is fixed, else a list "
                             "of N 1-D views; metres.")
      .def_property_readonly(
          "has_odometry",
          [](py::object self) {
            return flags_view(self.cast<const LogData&>().has_odometry, self);
          },
          "(N,) bool: the scan has an odometry pose.")
      .def_property_readonly(
          "usable",
          [](py::object self) { return flags_view(self.cast<const LogData&>().usable, self); },
          "(N,) bool: the scans pgmcl.localize feeds to the filter, in order: with odometry "
          "and not stamped before the last one fed (the others it skips and reports).")
      .def("scan", &scan_kwargs, py::arg("i"),
           "The keyword arguments of Localizer.update for scan i: loc.update(**log.scan(i)).")
      .def(
          "truth",
          [](const LogData& d) { return trajectory_array(io::log_truth(d.log, d.source)); },
          "(M, 4) (t, x, y, theta): the robot poses of the first laser message type that logs "
          "poses, as `pgmcl localize --truth LOG` takes them. A new array.")
      .def_property_readonly(
          "report", [](const LogData& d) { return report_dict(d.log.report); },
          "What the reader saw: lines, records and skipped message types, malformed lines "
          "(dropped; the first ones as (line, type, field, message)), backwards stamps, "
          "invalid beams.")
      .def_property_readonly(
          "params", [](const LogData& d) { return py::cast(d.log.params); }, "PARAM name -> value.")
      .def_readonly("source", &LogData::source, "The file it was read from.")
      .def(
          "save",
          [](const LogData& d, py::handle path) { io::write_carmen(path_arg(path), d.log); },
          py::arg("path"), "Writes the log as CARMEN text (gzip when the path ends in .gz).")
      .def("__repr__", [](const LogData& d) {
        std::size_t with_odom = 0;
        for (const auto h : d.has_odometry) with_odom += h;
        return "pgmcl.Log(" + py::repr(py::str(d.source)).cast<std::string>() + ": " +
               std::to_string(d.log.scans.size()) + " scans" +
               (d.beams > 0 ? " of " + std::to_string(d.beams) + " beams" : std::string()) + ", " +
               std::to_string(with_odom) + " with odometry)";
      });

  // Per-scan scalars: columns of scan_geometry; per-scan poses: rows of three.
  struct Column {
    const char* name;
    std::size_t index;
    const char* doc;
  };
  for (const Column& c :
       {Column{"angle_min", 0, "(N,) first beam's angle in the sensor frame, radians."},
        Column{"angle_increment", 1, "(N,) angle between beams, radians."},
        Column{"range_min", 2, "(N,) shortest valid reading, metres."},
        Column{"range_max", 3, "(N,) 'no return' reading, metres."}}) {
    log.def_property_readonly(
        c.name,
        [index = c.index](py::object self) {
          return column(self.cast<const LogData&>().scan_geometry, 4, index, self);
        },
        c.doc);
  }
  struct Poses {
    const char* name;
    std::vector<double> LogData::*rows;
    const char* doc;
  };
  for (const Poses& p :
       {Poses{"sensor_pose", &LogData::sensor_pose, "(N, 3) the laser's pose on the robot."},
        Poses{"odometry", &LogData::odometry,
              "(N, 3) odometry pose at each scan as Localizer.update takes it (NaN without)."},
        Poses{"poses", &LogData::poses,
              "(N, 3) robot pose of the logged laser pose (ground truth of a corrected log; "
              "NaN for scans that log none)."}}) {
    log.def_property_readonly(
        p.name,
        [rows = p.rows](py::object self) {
          return poses_view(self.cast<const LogData&>().*rows, self);
        },
        p.doc);
  }

  m.def(
      "read_carmen",
      [](py::handle path, bool strict) { return read_log_file(existing_file(path), strict); },
      py::arg("path"), py::arg("strict") = false,
      R"doc(Reads a CARMEN log (.log, .clf, gzip or plain) into a Log.

Malformed lines are dropped and counted (one RuntimeWarning names the first; Log.report
lists them); strict=True makes them InputError ("file:line: field: problem"), as
``pgmcl localize --strict``. FileNotFoundError for a missing file.)doc");
  m.def(
      "read_tum",
      [](py::handle path) { return trajectory_array(io::read_tum(existing_file(path))); },
      py::arg("path"),
      "Reads a TUM trajectory (what evo reads) into an (N, 4) array of (t, x, y, theta).");
  m.def(
      "write_tum",
      [](py::handle path, py::handle trajectory) {
        io::write_tum(path_arg(path), trajectory_arg(trajectory, "trajectory"));
      },
      py::arg("path"), py::arg("trajectory"),
      "Writes an (N, 4) array of (t, x, y, theta) as a TUM file (gzip when the path ends in "
      ".gz), every number in its shortest exact form.");
}

}  // namespace pgmcl::python
