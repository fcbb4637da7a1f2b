// SPDX-License-Identifier: GPL-3.0-or-later
// roifem.Scenario: a scenario from a TOML file, from a dict with the same keys, or either with
// keyword overrides, all through the strict reader `roifem run` uses (scenario_from_table), so a
// dict is checked exactly as a file is and an unknown key is named with the valid ones.
#include <toml++/toml.h>

#include <filesystem>
#include <variant>

#include "common/errors.hpp"
#include "scenario/scenario_table.hpp"
#include "scenario_handle.hpp"

namespace roifem::python {

namespace {

/// The TOML form of a Python value: bool, int, float, str, dict (a table), list or tuple (an
/// array); NumPy arrays and scalars through tolist(). `where` names the key in messages.
using TomlValue = std::variant<bool, int64_t, double, std::string, toml::array, toml::table>;
TomlValue toml_value(py::handle value, const std::string& where);

/// Puts a TOML value into a table or an array.
void insert(toml::table& t, const std::string& key, TomlValue&& v) {
  std::visit([&](auto&& x) { t.insert_or_assign(key, std::move(x)); }, std::move(v));
}
void append(toml::array& a, TomlValue&& v) {
  std::visit([&](auto&& x) { a.push_back(std::move(x)); }, std::move(v));
}

toml::table table_of(const py::dict& d, const std::string& where) {
  toml::table t;
  for (const auto& [key, value] : d) {
    const std::string name = py::str(key);
    const std::string path = where.empty() ? name : where + "." + name;
    if (value.is_none()) throw InputError("key '" + path + "' is None (leave it out instead)");
    insert(t, name, toml_value(value, path));
  }
  return t;
}

TomlValue toml_value(py::handle value, const std::string& where) {
  if (PyBool_Check(value.ptr())) return value.cast<bool>();
  if (PyLong_Check(value.ptr())) {
    int overflow = 0;
    const long long x = PyLong_AsLongLongAndOverflow(value.ptr(), &overflow);
    if (overflow != 0)
      throw InputError("key '" + where + "' = " + std::string(py::str(value)) + " does not fit a scenario's 64-bit integer");
    return static_cast<int64_t>(x);
  }
  if (PyFloat_Check(value.ptr())) return value.cast<double>();
  if (PyUnicode_Check(value.ptr())) return value.cast<std::string>();
  if (py::isinstance<py::dict>(value)) return table_of(value.cast<py::dict>(), where);
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    toml::array a;
    for (const py::handle item : value) {
      if (item.is_none()) throw InputError("key '" + where + "': None cannot be an array's element");
      append(a, toml_value(item, where));
    }
    return a;
  }
  if (py::hasattr(value, "tolist") && py::hasattr(value, "dtype")) return toml_value(value.attr("tolist")(), where);
  throw InputError("key '" + where + "': a value of type " + type_name(value) +
                   " cannot go into a scenario (numbers, strings, booleans, lists and dicts can)");
}

/// Overrides applied onto a table: a dict merges into a table of the same name, None removes the
/// key (roi=None: the full model), anything else replaces it.
void apply_overrides(toml::table& table, const py::dict& overrides, const std::string& where) {
  for (const auto& [key, value] : overrides) {
    const std::string name = py::str(key);
    const std::string path = where.empty() ? name : where + "." + name;
    if (value.is_none()) {
      table.erase(name);
    } else if (py::isinstance<py::dict>(value) && table.get(name) && table.get(name)->is_table()) {
      apply_overrides(*table.get(name)->as_table(), value.cast<py::dict>(), path);
    } else {
      insert(table, name, toml_value(value, path));
    }
  }
}

ScenarioHandle made(toml::table table, std::string source, std::filesystem::path directory) {
  scenario::Scenario sc = scenario::scenario_from_table(table, source, directory);
  return {std::move(sc), std::move(table), std::move(source), std::move(directory)};
}

ScenarioHandle from_file(const std::filesystem::path& file, const py::dict& overrides) {
  toml::table table = scenario::parse_scenario_table(scenario::read_scenario_text(file), file.string());
  apply_overrides(table, overrides, "");
  return made(std::move(table), file.string(), file.parent_path());
}

}  // namespace

ScenarioHandle with_overrides(const ScenarioHandle& base, const py::dict& overrides) {
  toml::table table = base.table;
  apply_overrides(table, overrides, "");
  return made(std::move(table), base.source, base.directory);
}

ScenarioHandle scenario_handle_of(py::handle scenario_or_file) {
  if (py::isinstance<ScenarioHandle>(scenario_or_file)) return scenario_or_file.cast<ScenarioHandle>();
  if (!PyUnicode_Check(scenario_or_file.ptr()) && !PyBytes_Check(scenario_or_file.ptr()) &&
      !py::hasattr(scenario_or_file, "__fspath__"))
    throw py::type_error("scenario: expected a roifem.Scenario or a scenario file's path (str or os.PathLike), got " +
                         type_name(scenario_or_file));
  return from_file(scenario_or_file.cast<std::filesystem::path>(), py::dict());
}

void bind_scenario(py::module_& m) {
  py::class_<ScenarioHandle>(
      m, "Scenario",
      "A simulation scenario, with the keys of a scenario file (scenarios/README.md): mesh, [material], "
      "[[material_region]], element, [boundary], [[load]], [[tool]], [roi] (with its reduction), [time] "
      "(integrator, dt_s, steps, rtol, atol), [output].\n\n"
      "Scenario(file, **overrides): read a TOML file; each keyword replaces a top-level key, a dict merging "
      "into the table of its name (roi={'nodes': 228}), None removing it (roi=None: the full model).\n"
      "Scenario.from_dict(d, directory='.'): the same keys as a dict (paths relative to `directory`).\n"
      "s.replace(**overrides): a new scenario with the overrides applied.\n"
      "Every key is checked as `roifem run` checks a file: InputError names the key.")
      .def(py::init([](const std::filesystem::path& file, const py::kwargs& overrides) { return from_file(file, overrides); }),
           py::arg("file"))
      .def_static(
          "from_dict",
          [](const py::dict& d, const std::filesystem::path& directory, const std::string& source) {
            return made(table_of(d, ""), source, directory);
          },
          py::arg("d"), py::arg("directory") = ".", py::arg("source") = "<dict>")
      .def(
          "replace", [](const ScenarioHandle& self, const py::kwargs& overrides) { return with_overrides(self, overrides); },
          "A new scenario: this one with the overrides applied (as in the constructor).")
      .def(
          "to_toml", [](const ScenarioHandle& h) { return h.scenario.resolved_toml(); },
          "The scenario resolved (defaults filled in), as TOML text: what results.h5 stores")
      .def_property_readonly(
          "file", [](const ScenarioHandle& h) { return h.scenario.file.string(); }, "the scenario file it was read from")
      .def_property_readonly(
          "mesh", [](const ScenarioHandle& h) { return h.scenario.mesh.string(); }, "the mesh file (resolved)")
      .def_property_readonly(
          "material", [](const ScenarioHandle& h) { return h.scenario.material_name; },
          "the [material] preset's name, or 'custom'")
      .def_property_readonly(
          "integrator", [](const ScenarioHandle& h) { return h.scenario.integrator; }, "[time] integrator")
      .def_property_readonly(
          "dt", [](const ScenarioHandle& h) { return h.scenario.dt; },
          "[time] dt_s (s): the step, or with rtol the output interval")
      .def_property_readonly(
          "steps", [](const ScenarioHandle& h) { return h.scenario.steps; }, "[time] steps")
      .def_property_readonly(
          "rtol", [](const ScenarioHandle& h) { return h.scenario.rtol; }, "[time] rtol (relative), or None: a fixed step")
      .def_property_readonly(
          "has_roi", [](const ScenarioHandle& h) { return h.scenario.roi.has_value(); },
          "whether it has an [roi] (else the full dynamic model)")
      .def_property_readonly(
          "roi", [](const ScenarioHandle& h) { return h.scenario.roi ? h.scenario.roi->describe() : std::string("none"); },
          "the [roi] in words ('306 nodes nearest (0, 0, 40) mm'), or 'none'")
      .def_property_readonly(
          "reduction", [](const ScenarioHandle& h) { return h.scenario.reduction.label(); },
          "the static part's reduction ('static', 'guyan', 'craig-bampton-10', 'pod-40')")
      .def("__repr__", [](const ScenarioHandle& h) {
        const scenario::Scenario& s = h.scenario;
        return "<roifem.Scenario " + s.file.string() + ": " + (s.roi ? s.roi->describe() : std::string("full model")) + ", " +
               s.integrator + ", dt = " + py::repr(py::float_(s.dt)).cast<std::string>() + " s, " + std::to_string(s.steps) +
               " steps>";
      });
}

}  // namespace roifem::python
