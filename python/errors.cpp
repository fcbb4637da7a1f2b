// SPDX-License-Identifier: GPL-3.0-or-later
// roifem's errors as Python exceptions of the same names and messages:
//   Error(RuntimeError) > InputError (also a ValueError), ModelError, SolverError;
// a run stopped by Ctrl-C (roifem::Interrupted) is a KeyboardInterrupt.
#include "common/errors.hpp"
#include "bindings.hpp"

namespace roifem::python {

namespace {

void raise_as(const char* name, const std::exception& e) {
  const py::object type = py::module_::import("roifem._roifem").attr(name);
  PyErr_SetString(type.ptr(), e.what());
}

void translate(std::exception_ptr error) {
  try {
    if (error) std::rethrow_exception(error);
  } catch (const Interrupted& e) {
    PyErr_SetString(PyExc_KeyboardInterrupt, e.what());
  } catch (const InputError& e) {
    raise_as("InputError", e);
  } catch (const ModelError& e) {
    raise_as("ModelError", e);
  } catch (const SolverError& e) {
    raise_as("SolverError", e);
  } catch (const Error& e) {
    raise_as("Error", e);
  }
}

}  // namespace

void bind_errors(py::module_& m) {
  py::exception<Error> base(m, "Error", PyExc_RuntimeError);
  base.attr("__doc__") = "Any error roifem reports; its message names the file, key, element, node or step at fault.";
  py::exception<InputError>(m, "InputError", py::make_tuple(base, py::handle(PyExc_ValueError))).attr("__doc__") =
      "The input is wrong: a file, a scenario key, a parameter value.";
  py::exception<ModelError>(m, "ModelError", base).attr("__doc__") =
      "The input is well-formed, but the model it describes cannot be solved (nothing fixed, an empty ROI, ...).";
  py::exception<SolverError>(m, "SolverError", base).attr("__doc__") =
      "A numerical method failed (a factorization, a divergence) at a named step.";
  py::register_exception_translator(&translate);
}

}  // namespace roifem::python
