// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The Python module `roifem._roifem` (pybind11): one bind_* function per file, each adding its
/// part of the interface to the module. NumPy arrays handed out are views of roifem's own storage
/// wherever the layout allows (a mesh's nodes and tetrahedra, a simulation's u and v); each holds a
/// share of that storage's owner (owned_view), so a view never outlives what it shows.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>  // in every file: type casters must agree across the module
#include <pybind11/stl/filesystem.h>

#include <memory>
#include <string>
#include <vector>

namespace roifem::python {

namespace py = pybind11;

/// The Python type's name of a value, for messages.
inline std::string type_name(py::handle value) { return py::str(py::type::handle_of(value).attr("__name__")); }

void bind_errors(py::module_& m);
void bind_mesh(py::module_& m);
void bind_scenario(py::module_& m);
void bind_simulation(py::module_& m);
void bind_experiments(py::module_& m);

/// A read-only NumPy view of `rows` x `cols` values at `data` (row-major), keeping `owner` alive
/// for as long as the view (or any view derived from it) lives.
template <class T, class Owner>
py::array_t<T> owned_view(const T* data, py::ssize_t rows, py::ssize_t cols, std::shared_ptr<Owner> owner) {
  auto* keep = new std::shared_ptr<Owner>(std::move(owner));
  py::capsule base(keep, [](void* p) { delete static_cast<std::shared_ptr<Owner>*>(p); });
  std::vector<py::ssize_t> shape{rows}, strides{static_cast<py::ssize_t>(sizeof(T)) * cols};
  if (cols > 0) {
    shape.push_back(cols);
    strides.push_back(sizeof(T));
  } else {
    strides = {sizeof(T)};
  }
  py::array_t<T> view(shape, strides, data, base);
  py::detail::array_proxy(view.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return view;
}

/// A NumPy array holding a copy of the `n` values at `data` (rows x cols, row-major; cols = 0: a vector).
template <class T>
py::array_t<T> copied_array(const T* data, py::ssize_t n, py::ssize_t cols = 0) {
  py::array_t<T> out = cols > 0 ? py::array_t<T>({n / cols, cols}) : py::array_t<T>(n);
  std::copy(data, data + n, out.mutable_data());
  return out;
}
template <class T>
py::array_t<T> copied_array(const std::vector<T>& values, py::ssize_t cols = 0) {
  return copied_array(values.data(), static_cast<py::ssize_t>(values.size()), cols);
}

/// A NumPy structured array (numpy.rec.fromarrays) with the given column names and columns.
py::object structured_array(const std::vector<std::string>& names, const std::vector<py::object>& columns);

}  // namespace roifem::python
