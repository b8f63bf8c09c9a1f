#pragma once
// Shared pieces of the Python bindings: JSON <-> Python objects, numpy arrays that own C++ data
// or view it, batches of 3x3 matrices, and the GIL-aware progress callbacks.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <Eigen/Core>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "sinew/core/types.hpp"
#include "sinew/material/spec.hpp"

namespace sinew::python {

namespace py = pybind11;
using RowMat3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;

// Python dicts, lists, strings, numbers, booleans, None, numpy arrays and scalars, and paths to
// JSON; anything else is a TypeError naming where it was (`where`, then the keys and indices).
nlohmann::json to_json(py::handle object, const std::string& where);
py::object from_json(const nlohmann::json& json);

// An array that owns `object` (moved to the heap, freed with the array): no copy of its data.
// `object.data()` must hold the elements in C order for `shape`.
template <class T>
py::array adopt(T&& object, std::vector<py::ssize_t> shape) {
  using Owned = std::decay_t<T>;
  using Scalar = typename Owned::Scalar;
  auto* heap = new Owned(std::forward<T>(object));
  py::capsule owner(heap, [](void* p) { delete static_cast<Owned*>(p); });
  return py::array_t<Scalar>(std::move(shape), heap->data(), owner);
}

// A read-only view of data owned by `parent` (kept alive by the array).
template <class Scalar>
py::array view(const Scalar* data, std::vector<py::ssize_t> shape, std::vector<py::ssize_t> strides,
               py::handle parent) {
  py::array_t<Scalar> a(std::move(shape), std::move(strides), data, parent);
  a.attr("setflags")(py::arg("write") = false);
  return a;
}

// "(n, 3)": an array's shape as Python writes it.
std::string shape_text(const py::array& a);
// A (n, 3) array of positions as the library's x[3 v + i] vector (one copy into the vector).
Eigen::VectorXd positions_vector(const py::array_t<double, py::array::c_style | py::array::forcecast>& a,
                                 py::ssize_t rows, const char* name);
// x[3 v + i] as an (n, 3) array that owns it.
inline py::array positions_array(Eigen::VectorXd x) {
  const auto rows = static_cast<py::ssize_t>(x.size() / 3);
  return adopt(std::move(x), {rows, 3});
}
inline py::array vector3(const Eigen::Vector3d& v) { return adopt(Eigen::VectorXd(v), {3}); }
Eigen::Vector3d to_vector3(py::handle object, const char* name);
Mat3 to_matrix3(py::handle object, const char* name);

// The message the CLI prints for a sinew::Error (its what() on one line).
std::string one_line(std::string text);

// sinew.Material: a material as the scene's "material" section describes it, and what building it
// resolved.
struct PyMaterial {
  MaterialSpec spec;
  BuiltMaterial built;
};

void bind_materials(py::module_& m);
void bind_meshes(py::module_& m);
void bind_scenes(py::module_& m);

}  // namespace sinew::python
