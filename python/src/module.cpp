// The extension module sinew._sinew; python/sinew/__init__.py is the package users import.
#include <memory>
#include <tbb/global_control.h>

#include "bindings.hpp"
#include "sinew/core/error.hpp"
#include "sinew/version.hpp"

namespace sinew::python {
namespace {

std::unique_ptr<tbb::global_control> thread_limit;

}  // namespace

std::string one_line(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

}  // namespace sinew::python

PYBIND11_MODULE(_sinew, m) {
  using namespace sinew::python;
  m.doc() = "Sinew: simulation of hyperelastic solids (the compiled part of the sinew package)";
  m.attr("__version__") = sinew::kVersion;

  // sinew.Error: every sinew::Error, with the CLI's message as str(e) (the CLI prints
  // "sinew: error: " + str(e)); .message and .context hold its two parts.
  static py::exception<sinew::Error> error(m, "Error", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const sinew::Error& e) {
      py::object instance = py::reinterpret_borrow<py::object>(error)(one_line(e.what()));
      instance.attr("message") = e.message();
      instance.attr("context") = e.context();
      PyErr_SetObject(error.ptr(), instance.ptr());
    }
  });

  // The model's warnings (a selector taking every vertex, ...): what the CLI prints as "warning:".
  m.attr("SceneWarning") = py::reinterpret_steal<py::object>(
      PyErr_NewExceptionWithDoc("sinew.SceneWarning", "Suspicious but legal scene input (the CLI's warnings).",
                                PyExc_UserWarning, nullptr));

  m.def(
      "set_threads",
      [](int threads) {
        if (threads < 0) throw py::value_error("threads must be >= 0 (0: all cores)");
        thread_limit.reset();
        if (threads > 0)
          thread_limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                               static_cast<size_t>(threads));
      },
      py::arg("threads"),
      "Limit the worker threads of every later call (0: all cores), like the CLI's --threads.");

  bind_materials(m);
  bind_meshes(m);
  bind_scenes(m);
}
