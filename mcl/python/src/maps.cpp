/// pgmcl.Map: an occupancy grid whose cells numpy sees in place; load_map / save_map read
/// and write ROS map_server files (pgmcl::map_io).

#include <cmath>
#include <cstdio>

#include "bindings.hpp"
#include "pgmcl/map_io/map_io.hpp"

namespace pgmcl::python {
namespace {

constexpr const char* kMapDoc = R"doc(An occupancy grid in ROS map_server conventions.

``cells[row, col]`` holds -1 (unknown), 0 (free) .. 100 (occupied); row 0 is the bottom
row (lowest y), so ``plt.imshow(m.cells, origin="lower", extent=m.extent)`` draws it the
right way up. ``origin`` is the pose (x, y, theta) of the outer corner of cell (0, 0) in
the map frame, ``resolution`` metres per cell.

Map(cells, resolution, origin=(0, 0, 0)) builds one from a 2-D integer array (copied once;
values must be -1 or 0..100). ``cells`` is then a writable view of the map's own memory:
changes show in every later use of the map (a Localizer made before keeps its tables).)doc";

std::shared_ptr<maps::OccupancyGrid> map_from_array(const py::array& cells, double resolution,
                                                    py::handle origin) {
  const char kind = cells.dtype().kind();
  if (kind != 'i' && kind != 'u') {
    throw py::type_error("Map: cells must be an integer array (-1 unknown, 0..100), got dtype " +
                         py::str(cells.dtype()).cast<std::string>());
  }
  if (cells.ndim() != 2) {
    throw py::value_error("Map: cells must be 2-D (rows, columns), got " +
                          std::to_string(cells.ndim()) + " dimension(s)");
  }
  if (!std::isfinite(resolution) || resolution <= 0.0) {
    throw py::value_error("Map: resolution must be finite and > 0 (metres per cell), got " +
                          py::repr(py::float_(resolution)).cast<std::string>());
  }
  const auto values =
      py::array_t<long long, py::array::c_style | py::array::forcecast>::ensure(cells);
  const auto rows = values.shape(0), cols = values.shape(1);
  auto grid = std::make_shared<maps::OccupancyGrid>(static_cast<int>(cols), static_cast<int>(rows),
                                                    resolution, pose_arg(origin, "origin"));
  const long long* v = values.data();
  for (py::ssize_t i = 0; i < rows * cols; ++i) {
    if (v[i] < -1 || v[i] > 100) {
      throw py::value_error("Map: cells[" + std::to_string(i / cols) + ", " +
                            std::to_string(i % cols) + "] = " + std::to_string(v[i]) +
                            ": values must be -1 (unknown) or 0..100 (occupancy in percent)");
    }
    grid->cells()[static_cast<std::size_t>(i)] = static_cast<std::int8_t>(v[i]);
  }
  return grid;
}

std::shared_ptr<maps::OccupancyGrid> load(const std::string& path) {
  maps::MapLoadReport report;
  auto grid = std::make_shared<maps::OccupancyGrid>(maps::load_map(path, &report));
  for (const std::string& w : report.warnings) warn(w);
  return grid;
}

void save(const maps::OccupancyGrid& grid, py::handle path, py::handle image,
          const std::string& mode) {
  const std::string image_name = image.is_none() ? std::string() : path_arg(image);
  maps::save_map(grid, path_arg(path), image_name, maps::map_mode_from_string(mode));
}

}  // namespace

std::shared_ptr<maps::OccupancyGrid> map_arg(py::handle obj) {
  if (py::isinstance<maps::OccupancyGrid>(obj)) {
    return obj.cast<std::shared_ptr<maps::OccupancyGrid>>();
  }
  return load(existing_file(obj));
}

void bind_maps(py::module_& m) {
  py::class_<maps::OccupancyGrid, std::shared_ptr<maps::OccupancyGrid>>(m, "Map", kMapDoc)
      .def(py::init(&map_from_array), py::arg("cells"), py::arg("resolution"),
           py::arg("origin") = py::make_tuple(0.0, 0.0, 0.0),
           "Builds a map from a 2-D integer array (rows, columns; row 0 at the bottom), "
           "metres per cell and the pose of cell (0, 0)'s outer corner.")
      .def_property_readonly("resolution", &maps::OccupancyGrid::resolution, "Metres per cell.")
      .def_property_readonly(
          "origin", [](const maps::OccupancyGrid& g) { return pose_tuple(g.origin()); },
          "(x, y, theta) of the outer corner of cell (0, 0) in the map frame (m, m, rad).")
      .def_property_readonly("width", &maps::OccupancyGrid::width, "Columns.")
      .def_property_readonly("height", &maps::OccupancyGrid::height, "Rows.")
      .def_property_readonly(
          "cells",
          [](py::object self) {
            auto& g = self.cast<maps::OccupancyGrid&>();
            const py::ssize_t w = g.width(), h = g.height();
            return view<std::int8_t>(g.cells().data(), {h, w}, {w, 1}, self, true);
          },
          "The cells as an int8 (height, width) numpy view of the map's memory (no copy; "
          "writable): -1 unknown, 0 free .. 100 occupied, row 0 at the bottom.")
      .def_property_readonly(
          "extent",
          [](const maps::OccupancyGrid& g) {
            const double x0 = g.origin().x, y0 = g.origin().y;
            return py::make_tuple(x0, x0 + g.width() * g.resolution(), y0,
                                  y0 + g.height() * g.resolution());
          },
          "(left, right, bottom, top) in metres for matplotlib's imshow (origin='lower'); "
          "exact for maps whose origin has no rotation.")
      .def_property(
          "occupied_threshold",
          [](const maps::OccupancyGrid& g) { return static_cast<int>(g.occupied_threshold()); },
          [](maps::OccupancyGrid& g, int t) {
            if (t < 1 || t > 100) {
              throw py::value_error("occupied_threshold must be in 1..100, got " +
                                    std::to_string(t));
            }
            g.set_occupied_threshold(static_cast<std::int8_t>(t));
          },
          "Cells with a value at or above this are obstacles (default 65).")
      .def("save", &save, py::arg("path"), py::arg("image") = py::none(),
           py::arg("mode") = "trinary", "The same as save_map(self, path, image, mode).")
      .def("__repr__", [](const maps::OccupancyGrid& g) {
        char buf[200];
        std::snprintf(buf, sizeof buf,
                      "pgmcl.Map(%d x %d cells, %.3g m, origin (%.3f, %.3f, %.3f))", g.width(),
                      g.height(), g.resolution(), g.origin().x, g.origin().y, g.origin().theta);
        return std::string(buf);
      });

  m.def(
      "load_map", [](py::handle path) { return load(existing_file(path)); }, py::arg("path"),
      R"doc(Loads a ROS map_server map: the YAML file and the image it names (PGM, PNG, gzip).

Unknown YAML keys and missing thresholds are reported as RuntimeWarning. Raises
FileNotFoundError for a missing file and InputError (a ValueError) naming the file, line
and key for a bad one.)doc");
  m.def("save_map", &save, py::arg("map"), py::arg("path"), py::arg("image") = py::none(),
        py::arg("mode") = "trinary",
        R"doc(Writes ``path`` (map_server YAML) and its image next to it, as nav2's map_saver.

``mode``: "trinary" (free 254, occupied 0, else 205; PGM by default) or "scale" (grey
levels keep intermediate occupancies; PNG with unknown cells transparent). ``image``: the
image's file name relative to the YAML (its extension, .pgm, .pgm.gz or .png, picks the
format); default the YAML's stem. Raises OSError when the files cannot be written.)doc");
}

}  // namespace pgmcl::python
