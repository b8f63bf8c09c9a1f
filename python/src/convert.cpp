#include <fmt/format.h>

#include "bindings.hpp"

namespace sinew::python {

nlohmann::json to_json(py::handle o, const std::string& where) {
  if (o.is_none()) return nullptr;
  if (py::isinstance<py::bool_>(o)) return o.cast<bool>();
  if (py::isinstance<py::int_>(o)) {
    try {
      return o.cast<long long>();
    } catch (const py::cast_error&) {
      throw py::type_error(fmt::format("{}: integer out of range", where));
    }
  }
  if (py::isinstance<py::float_>(o)) return o.cast<double>();
  if (py::isinstance<py::str>(o)) return o.cast<std::string>();
  if (py::isinstance<py::dict>(o)) {
    nlohmann::json j = nlohmann::json::object();
    for (auto item : o.cast<py::dict>()) {
      if (!py::isinstance<py::str>(item.first))
        throw py::type_error(fmt::format("{}: keys must be strings, got {}", where, std::string(py::repr(item.first))));
      const std::string key = item.first.cast<std::string>();
      j[key] = to_json(item.second, where + "/" + key);
    }
    return j;
  }
  if (py::isinstance<py::list>(o) || py::isinstance<py::tuple>(o)) {
    nlohmann::json j = nlohmann::json::array();
    size_t i = 0;
    for (auto item : o) j.push_back(to_json(item, fmt::format("{}/{}", where, i++)));
    return j;
  }
  if (py::isinstance<py::array>(o)) return to_json(o.attr("tolist")(), where);  // numpy arrays
  if (py::hasattr(o, "dtype") && py::hasattr(o, "item")) return to_json(o.attr("item")(), where);  // numpy scalars
  if (py::hasattr(o, "__fspath__")) return py::module_::import("os").attr("fspath")(o).cast<std::string>();
  throw py::type_error(fmt::format("{}: cannot be written as JSON: {}", where, std::string(py::str(o.get_type()))));
}

py::object from_json(const nlohmann::json& j) {
  switch (j.type()) {
    case nlohmann::json::value_t::null: return py::none();
    case nlohmann::json::value_t::boolean: return py::bool_(j.get<bool>());
    case nlohmann::json::value_t::number_integer: return py::int_(j.get<long long>());
    case nlohmann::json::value_t::number_unsigned: return py::int_(j.get<unsigned long long>());
    case nlohmann::json::value_t::number_float: return py::float_(j.get<double>());
    case nlohmann::json::value_t::string: return py::str(j.get<std::string>());
    case nlohmann::json::value_t::array: {
      py::list l;
      for (const auto& e : j) l.append(from_json(e));
      return l;
    }
    case nlohmann::json::value_t::object: {
      py::dict d;
      for (auto it = j.begin(); it != j.end(); ++it) d[py::str(it.key())] = from_json(it.value());
      return d;
    }
    default: return py::none();  // binary and discarded values: never produced by Sinew
  }
}

std::string shape_text(const py::array& a) {
  std::string text = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) text += (i ? ", " : "") + std::to_string(a.shape(i));
  return text + (a.ndim() == 1 ? ",)" : ")");
}

Eigen::VectorXd positions_vector(const py::array_t<double, py::array::c_style | py::array::forcecast>& a,
                                 py::ssize_t rows, const char* name) {
  if (a.ndim() != 2 || a.shape(1) != 3 || (rows >= 0 && a.shape(0) != rows))
    throw py::value_error(fmt::format("{} must have shape ({}, 3), got {}", name,
                                      rows >= 0 ? std::to_string(rows) : "n", shape_text(a)));
  return Eigen::Map<const Eigen::VectorXd>(a.data(), a.size());
}

Eigen::Vector3d to_vector3(py::handle o, const char* name) {
  auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(o);
  if (!a || a.size() != 3) throw py::value_error(fmt::format("{} must be 3 numbers", name));
  return Eigen::Map<const Eigen::Vector3d>(a.data());
}

Mat3 to_matrix3(py::handle o, const char* name) {
  auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(o);
  if (!a || a.ndim() != 2 || a.shape(0) != 3 || a.shape(1) != 3)
    throw py::value_error(fmt::format("{} must be a 3x3 matrix", name));
  return Eigen::Map<const RowMat3>(a.data());
}

}  // namespace sinew::python
