// SPDX-License-Identifier: GPL-3.0-or-later
// roifem._roifem: the compiled part of the Python package `roifem` (roifem/__init__.py).
#include "bindings.hpp"
#include "common/version.hpp"

namespace roifem::python {

py::object structured_array(const std::vector<std::string>& names, const std::vector<py::object>& columns) {
  py::list cols;
  for (const auto& c : columns) cols.append(py::module_::import("numpy").attr("asarray")(c));
  py::list labels;
  for (const auto& n : names) labels.append(n);
  return py::module_::import("numpy").attr("rec").attr("fromarrays")(cols, py::arg("names") = labels);
}

}  // namespace roifem::python

PYBIND11_MODULE(_roifem, m) {
  m.doc() = "roifem's compiled core: meshes, scenarios, simulations and experiments (see the package `roifem`)";
  m.attr("__version__") = std::string(roifem::version());
  roifem::python::bind_errors(m);
  roifem::python::bind_mesh(m);
  roifem::python::bind_scenario(m);
  roifem::python::bind_simulation(m);
  roifem::python::bind_experiments(m);
}
