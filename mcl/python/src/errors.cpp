/// Errors: pgmcl's C++ exceptions as the Python exceptions a user expects, with the
/// command line's messages (file, line, field), and the small argument conversions every
/// binding file uses.

#include "pgmcl/io/errors.hpp"

#include <cerrno>
#include <filesystem>
#include <stdexcept>

#include "bindings.hpp"
#include "pgmcl/io/values.hpp"
#include "pgmcl/map_io/map_io.hpp"

namespace pgmcl::python {
namespace {

/// pgmcl.InputError, created by bind_errors (module lifetime).
PyObject* input_error_type = nullptr;

void raise_input_error(const char* what, py::object file, std::size_t line,
                       const std::string& field, const std::string& problem) {
  py::object type = py::reinterpret_borrow<py::object>(input_error_type);
  py::object e = type(what);
  e.attr("file") = std::move(file);
  e.attr("line") = line;
  e.attr("field") = field;
  e.attr("problem") = problem;
  PyErr_SetObject(input_error_type, e.ptr());
}

/// FileNotFoundError(ENOENT, message, path): str() reads "[Errno 2] message: 'path'".
void raise_not_found(const std::string& message, const std::string& path) {
  py::object type = py::reinterpret_borrow<py::object>(PyExc_FileNotFoundError);
  PyErr_SetObject(PyExc_FileNotFoundError, type(ENOENT, message, path).ptr());
}

void translate(std::exception_ptr p) {
  try {
    std::rethrow_exception(p);
  } catch (const MissingFile& e) {
    raise_not_found("No such file or directory", e.path);
  } catch (const io::FormatError& e) {  // also ConfigError, ScenarioError
    raise_input_error(e.what(), py::str(e.file()), e.line(), e.field(), e.message());
  } catch (const maps::MapError& e) {
    if (!e.file().empty() && !std::filesystem::exists(e.file())) {  // the YAML or its image
      raise_not_found(e.what(), e.file());
    } else if (e.field().empty()) {  // reading or writing the file itself
      PyErr_SetString(PyExc_OSError, e.what());
    } else {
      raise_input_error(e.what(), py::str(e.file()), static_cast<std::size_t>(e.line()), e.field(),
                        e.problem());
    }
  } catch (const InvalidConfigField& e) {
    raise_input_error(e.what(), py::none(), 0, e.field(), e.problem());
  } catch (const io::UsageError& e) {
    PyErr_SetString(PyExc_ValueError, e.what());
  } catch (const io::IoError& e) {
    PyErr_SetString(PyExc_OSError, e.what());
  }
  // Anything else propagates to pybind11's own translation (std::invalid_argument and
  // std::length_error -> ValueError, std::bad_alloc -> MemoryError, ...).
}

}  // namespace

std::string path_arg(py::handle obj) {
  const py::object s = py::module_::import("os").attr("fspath")(obj);
  if (!py::isinstance<py::str>(s)) throw py::type_error("paths must be str or os.PathLike of str");
  return s.cast<std::string>();
}

std::string existing_file(py::handle obj) {
  std::string path = path_arg(obj);
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw MissingFile{path};
  return path;
}

Pose2 pose_arg(py::handle obj, const char* name) {
  const auto fail = [&] {
    return py::type_error(std::string(name) + ": expected (x, y, theta), got " +
                          py::repr(obj).cast<std::string>());
  };
  PyObject* items = PySequence_Tuple(obj.ptr());
  if (items == nullptr) {
    PyErr_Clear();
    throw fail();
  }
  const auto s = py::reinterpret_steal<py::tuple>(items);
  if (s.size() != 3) throw fail();
  try {
    return {s[0].cast<double>(), s[1].cast<double>(), s[2].cast<double>()};
  } catch (const py::cast_error&) {
    throw fail();
  }
}

std::uint64_t seed_arg(py::handle obj) {
  const py::module_ numbers = py::module_::import("numbers");
  if (!py::isinstance(obj, numbers.attr("Integral"))) {
    throw py::type_error("seed: expected a whole number, got " + py::repr(obj).cast<std::string>());
  }
  const auto v = py::reinterpret_borrow<py::object>(obj);
  if (v < py::int_(0) || v >= py::int_(1).attr("__lshift__")(64)) {
    throw py::value_error("seed: must be in [0, 2^64), got " + py::repr(obj).cast<std::string>());
  }
  return py::int_(v).cast<std::uint64_t>();
}

py::tuple pose_tuple(const Pose2& p) {
  return py::make_tuple(p.x, p.y, p.theta);
}

void warn(const std::string& message) {
  if (PyErr_WarnEx(PyExc_RuntimeWarning, message.c_str(), 1) != 0) throw py::error_already_set();
}

void bind_errors(py::module_& m) {
  input_error_type = PyErr_NewExceptionWithDoc(
      "pgmcl.InputError",
      "Bad input, raised with the command line's message: a file, config value or argument "
      "that cannot be used.\n\n"
      "A ValueError. Attributes: ``file`` (the file or '--set key=value' source, None when "
      "the input is not a file), ``line`` (1-based, 0 when unknown), ``field`` (the dotted "
      "key or record field) and ``problem`` (what is wrong). str() is the message "
      "``pgmcl`` prints after 'pgmcl: error: '.",
      PyExc_ValueError, nullptr);
  if (input_error_type == nullptr) throw py::error_already_set();
  m.attr("InputError") = py::reinterpret_borrow<py::object>(input_error_type);
  py::register_exception_translator(&translate);
}

}  // namespace pgmcl::python
