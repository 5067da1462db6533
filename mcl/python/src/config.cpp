/// pgmcl.Config: LocalizerConfig from Python. Keys, values and errors are the command
/// line's: fields are walked with the schema (config_schema.hpp), files are read by
/// read_localizer_config and every override goes through apply_localizer_override, the
/// code of `--set key=value`, so a bad value raises the message `pgmcl` prints.

#include <cmath>
#include <fstream>

#include "bindings.hpp"
#include "pgmcl/config/config_yaml.hpp"
#include "pgmcl/io/errors.hpp"
#include "pgmcl/mcl/config_schema.hpp"

namespace pgmcl::python {
namespace {

namespace schema = pgmcl::config_schema;

constexpr const char* kConfigDoc = R"doc(The filter configuration (pgmcl::LocalizerConfig).

Config(overrides=None, /, **kwargs) starts from the documented defaults (or from a copy
of ``overrides`` when that is a Config) and applies the overrides in order: dotted keys as
on the command line's ``--set`` (``Config({"filter.kld.max_particles": 5000})`` or
``Config(**{"filter.particles": 500})``) or nested dicts
(``Config(filter={"particles": 500}, seed=7)``). Values are numbers, bools
or str (enumerations by name, e.g. ``{"likelihood.table.kind": "oriented"}``); each is read
and validated exactly as ``--set key=value``, so a bad one raises InputError (a ValueError)
with the command line's message, field path included. Every key, its default, unit and
allowed values: ``Config.reference()`` (configs/reference.md).

``config["filter.particles"]`` reads a value, ``config["filter.particles"] = 500`` sets one
(validated), ``to_dict()`` gives the nested dict of every field, ``to_yaml()`` the filter
YAML that ``pgmcl localize --config`` and load_config read back identically.)doc";

/// Every field as a nested dict, in the YAML's order.
class DictVisitor {
 public:
  explicit DictVisitor(py::dict root) { stack_.push_back(std::move(root)); }
  template <class Body>
  void section(const char* name, Body&& body) {
    py::dict d;
    stack_.back()[name] = d;
    stack_.push_back(d);
    body();
    stack_.pop_back();
  }
  void number(const schema::Field& f, double v, const schema::Bounds&) { put(f, py::float_(v)); }
  void flag(const schema::Field& f, bool v) { put(f, py::bool_(v)); }
  template <class T>
  void integer(const schema::Field& f, T v, const schema::IntRange&) {
    put(f, py::int_(v));
  }
  template <class E, std::size_t N>
  void choice(const schema::Field& f, E v, const std::array<schema::EnumName<E>, N>& names) {
    put(f, py::str(schema::name_of(v, names)));
  }
  void rule(const char*, bool, const char*) const {}

 private:
  void put(const schema::Field& f, py::object v) { stack_.back()[f.name] = std::move(v); }
  std::vector<py::dict> stack_;
};

py::dict to_dict(const LocalizerConfig& c) {
  py::dict root;
  DictVisitor v(root);
  schema::describe_config(v, c);
  return root;
}

/// (dotted key, value) of a nested dict, in order.
void flatten(py::handle d, const std::string& prefix,
             std::vector<std::pair<std::string, py::object>>& out) {
  for (const auto& [k, v] : py::reinterpret_borrow<py::dict>(d)) {
    if (!py::isinstance<py::str>(k)) {
      throw py::type_error("Config: keys must be str, got " + py::repr(k).cast<std::string>());
    }
    const std::string key = prefix + k.cast<std::string>();
    if (py::isinstance<py::dict>(v)) {
      flatten(v, key + ".", out);
    } else {
      out.emplace_back(key, py::reinterpret_borrow<py::object>(v));
    }
  }
}

/// The text a user would type after `--set key=` for this value.
std::string value_text(const std::string& key, py::handle v) {
  if (py::isinstance<py::bool_>(v)) return v.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::str>(v)) return v.cast<std::string>();
  const py::module_ numbers = py::module_::import("numbers");
  if (py::isinstance(v, numbers.attr("Integral")))
    return py::str(py::int_(py::reinterpret_borrow<py::object>(v)));
  if (py::isinstance(v, numbers.attr("Real"))) {
    const double d = v.cast<double>();
    if (std::isnan(d)) return ".nan";
    if (std::isinf(d)) return d > 0 ? ".inf" : "-.inf";
    return py::repr(py::float_(d));  // the shortest text that reads back to the same double
  }
  throw py::type_error("Config: " + key + ": expected a number, bool or str, got " +
                       py::repr(v).cast<std::string>());
}

void apply_overrides(LocalizerConfig& cfg, py::handle overrides) {
  if (overrides.is_none()) return;
  if (!py::isinstance<py::dict>(overrides)) {
    throw py::type_error("Config: overrides must be a dict, got " +
                         py::repr(overrides).cast<std::string>());
  }
  std::vector<std::pair<std::string, py::object>> items;
  flatten(overrides, "", items);
  for (const auto& [key, value] : items) apply_override(cfg, key, value);
}

py::object lookup(const LocalizerConfig& c, const std::string& key) {
  std::vector<std::pair<std::string, py::object>> items;
  flatten(to_dict(c), "", items);
  for (const auto& [k, v] : items)
    if (k == key) return v;
  throw py::key_error("Config: unknown key '" + key + "' (Config.reference() lists them)");
}

std::string repr(const LocalizerConfig& c) {
  std::vector<std::pair<std::string, py::object>> items, defaults;
  flatten(to_dict(c), "", items);
  flatten(to_dict(LocalizerConfig{}), "", defaults);
  std::string changed;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (items[i].second.equal(defaults[i].second)) continue;
    changed += (changed.empty() ? "" : ", ") +
               py::repr(py::str(items[i].first)).cast<std::string>() + ": " +
               py::repr(items[i].second).cast<std::string>();
  }
  return "pgmcl.Config({" + changed + "})";
}

LocalizerConfig load(py::handle path, py::handle overrides) {
  LocalizerConfig cfg;
  io::read_localizer_config(existing_file(path), cfg);
  apply_overrides(cfg, overrides);
  return cfg;
}

}  // namespace

void apply_override(LocalizerConfig& cfg, const std::string& key, py::handle value) {
  io::apply_localizer_override(key, value_text(key, value), cfg);
}

LocalizerConfig config_arg(py::handle obj) {
  if (obj.is_none()) return {};
  if (py::isinstance<LocalizerConfig>(obj)) return obj.cast<LocalizerConfig>();
  if (py::isinstance<py::dict>(obj)) {
    LocalizerConfig cfg;
    apply_overrides(cfg, obj);
    return cfg;
  }
  if (py::isinstance<py::str>(obj) || py::hasattr(obj, "__fspath__")) return load(obj, py::none());
  throw py::type_error(
      "config: expected a pgmcl.Config, a dict of overrides, a YAML path or None, "
      "got " +
      py::repr(obj).cast<std::string>());
}

py::object config_object(const LocalizerConfig& cfg) {
  return py::cast(cfg);
}

void bind_config(py::module_& m) {
  py::class_<LocalizerConfig>(m, "Config", kConfigDoc)
      .def(py::init([](py::handle overrides, const py::kwargs& kw) {
             LocalizerConfig cfg;
             if (py::isinstance<LocalizerConfig>(overrides)) {  // a copy, then kwargs
               cfg = overrides.cast<LocalizerConfig>();
             } else {
               apply_overrides(cfg, overrides);
             }
             apply_overrides(cfg, kw);
             return cfg;
           }),
           py::arg("overrides") = py::none(), py::pos_only())
      .def("to_dict", &to_dict,
           "Every field as a nested dict ({'filter': {'particles': 2000, ...}, ...}); "
           "enumerations as their names.")
      .def("to_yaml", &io::localizer_config_yaml,
           "Every field as filter YAML (what `pgmcl localize --config` reads; each run "
           "stores it as config.yaml).")
      .def(
          "save",
          [](const LocalizerConfig& c, py::handle path) {
            const std::string p = path_arg(path);
            std::ofstream f(p);
            f << io::localizer_config_yaml(c);
            if (!f) throw io::IoError(p + ": write failed");
          },
          py::arg("path"), "Writes to_yaml() to a file (OSError when it cannot).")
      .def(
          "update",
          [](LocalizerConfig& c, py::handle overrides, const py::kwargs& kw) {
            LocalizerConfig next = c;  // all or nothing
            apply_overrides(next, overrides);
            apply_overrides(next, kw);
            c = next;
          },
          py::arg("overrides") = py::none(), py::pos_only(),
          "Applies overrides as the constructor does; on an error nothing changes.")
      .def(
          "keys",
          [](const LocalizerConfig& c) {
            std::vector<std::pair<std::string, py::object>> items;
            flatten(to_dict(c), "", items);
            py::list keys;
            for (const auto& kv : items) keys.append(kv.first);
            return keys;
          },
          "Every dotted key, in the YAML's order.")
      .def("__getitem__", &lookup, py::arg("key"),
           "The value of a dotted key (KeyError if unknown).")
      .def(
          "__setitem__",
          [](LocalizerConfig& c, const std::string& key, py::handle value) {
            apply_override(c, key, value);
          },
          py::arg("key"), py::arg("value"), "Sets one dotted key, validated like --set.")
      .def(
          "copy", [](const LocalizerConfig& c) { return c; }, "An independent copy.")
      .def("__copy__", [](const LocalizerConfig& c) { return c; })
      .def("__deepcopy__", [](const LocalizerConfig& c, py::handle) { return c; })
      .def("__eq__",
           [](const LocalizerConfig& a, py::handle b) {
             return py::isinstance<LocalizerConfig>(b) &&
                    io::localizer_config_yaml(a) ==
                        io::localizer_config_yaml(b.cast<const LocalizerConfig&>());
           })
      .def("__repr__", &repr)
      .def_static("reference", &io::localizer_config_reference,
                  "The Markdown table of every key: default, unit, allowed values, meaning.");

  m.def("load_config", &load, py::arg("path"), py::arg("overrides") = py::none(),
        R"doc(Reads a filter YAML file (as ``pgmcl localize --config``), then applies
``overrides`` (a dict, as Config's). Raises FileNotFoundError for a missing file and
InputError ("file:line: key: problem") for a bad one.)doc");
}

}  // namespace pgmcl::python
