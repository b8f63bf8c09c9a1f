// sinew.Material and the catalog, Lamé / (E, nu) conversions and normalisation.
#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "bindings.hpp"
#include "sinew/core/error.hpp"
#include "sinew/material/catalog.hpp"
#include "sinew/material/curve.hpp"
#include "sinew/material/lame.hpp"
#include "sinew/material/mixing.hpp"
#include "sinew/material/normalization.hpp"
#include "sinew/material/spec.hpp"

namespace sinew::python {
namespace {

using FloatArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

PyMaterial make_material(py::handle spec, const std::string& context) {
  nlohmann::json j = py::isinstance<py::str>(spec) ? nlohmann::json{{"family", spec.cast<std::string>()}}
                                                   : to_json(spec, context);
  PyMaterial m;
  m.spec = material_spec_from_json(j, context);
  py::gil_scoped_release release;  // normalising may run a few Newton steps
  m.built = build_material_detailed(m.spec);
  return m;
}

MaterialParameters parameters_from(const py::object& values, const py::object& functions) {
  MaterialParameters p;
  if (!values.is_none())
    for (auto item : values.cast<py::dict>()) p.values[item.first.cast<std::string>()] = item.second.cast<double>();
  if (!functions.is_none())
    for (auto item : functions.cast<py::dict>())
      p.functions[item.first.cast<std::string>()] = item.second.cast<std::string>();
  return p;
}

py::dict values_dict(const MaterialParameters& p) {
  py::dict d;
  for (const auto& [k, v] : p.values) d[py::str(k)] = v;
  return d;
}
py::dict functions_dict(const MaterialParameters& p) {
  py::dict d;
  for (const auto& [k, v] : p.functions) d[py::str(k)] = v;
  return d;
}

py::dict info_dict(const MaterialInfo& info) {
  py::list parameters, functions;
  for (const auto& p : info.parameters)
    parameters.append(py::dict(py::arg("key") = p.key, py::arg("default") = p.default_value, py::arg("meaning") = p.meaning));
  for (const auto& f : info.functions)
    functions.append(py::dict(py::arg("key") = f.key, py::arg("default") = f.default_expression,
                              py::arg("meaning") = f.meaning));
  return py::dict(py::arg("name") = info.name, py::arg("title") = info.title, py::arg("reference") = info.reference,
                  py::arg("formula") = info.formula, py::arg("parameters") = parameters,
                  py::arg("functions") = functions, py::arg("normalized") = info.normalized,
                  py::arg("separable") = info.separable, py::arg("rest_stable") = info.rest_stable);
}

// A batch of deformation gradients: (3, 3) or (n, 3, 3), read in place when it is C-ordered
// float64 (numpy converts anything else once).
struct Batch {
  FloatArray array;
  py::ssize_t n = 1;
  bool single = true;
  const double* data = nullptr;

  Batch(const py::handle& F, py::ssize_t rows, py::ssize_t cols, const char* name) {
    array = FloatArray::ensure(F);
    if (!array) throw py::type_error(fmt::format("{} must be an array of numbers", name));
    const auto nd = array.ndim();
    const bool one = cols == 0 ? (nd == 1 && array.shape(0) == rows)
                               : (nd == 2 && array.shape(0) == rows && array.shape(1) == cols);
    const bool many = cols == 0 ? (nd == 2 && array.shape(1) == rows)
                                : (nd == 3 && array.shape(1) == rows && array.shape(2) == cols);
    if (!one && !many) {
      const std::string single_shape = cols == 0 ? fmt::format("({},)", rows) : fmt::format("({}, {})", rows, cols);
      const std::string many_shape = cols == 0 ? fmt::format("(n, {})", rows) : fmt::format("(n, {}, {})", rows, cols);
      throw py::value_error(fmt::format("{} must have shape {} or {}, got {}", name, single_shape, many_shape,
                                        shape_text(array)));
    }
    single = one;
    n = one ? 1 : array.shape(0);
    data = array.data();
  }
  // The output shape: the batch dimension (unless a single input) then `tail`.
  std::vector<py::ssize_t> shape(std::vector<py::ssize_t> tail) const {
    if (!single) tail.insert(tail.begin(), n);
    return tail;
  }
  // fn(i) for every item, in parallel without the GIL; a sinew::Error names the item.
  template <class Fn>
  void each(Fn fn, const char* name) const {
    py::gil_scoped_release release;
    tbb::parallel_for(tbb::blocked_range<py::ssize_t>(0, n, 16), [&](const auto& r) {
      for (py::ssize_t i = r.begin(); i != r.end(); ++i) {
        try {
          fn(i);
        } catch (const Error& e) {
          throw e.within(single ? std::string(name) : fmt::format("{}[{}]", name, i));
        }
      }
    });
  }
  Mat3 F(py::ssize_t i) const { return Eigen::Map<const RowMat3>(data + 9 * i); }
};

Projection projection_from(const std::string& text) { return parse_projection(text); }

// H[a, b, c, d] = d2 psi / dF_ab dF_cd from the library's column-wise vec (F_ab at 3 b + a).
void write_hessian(const Mat9& H, double* out) {
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      for (int c = 0; c < 3; ++c)
        for (int d = 0; d < 3; ++d) out[27 * a + 9 * b + 3 * c + d] = H(3 * b + a, 3 * d + c);
}

}  // namespace

void bind_materials(py::module_& m) {
  m.def(
      "materials",
      [] {
        py::list out;
        for (const auto& info : MaterialCatalog::instance().all()) out.append(info_dict(info));
        return out;
      },
      "The catalog's material families: name, title, reference, formula, parameters (key, default, "
      "meaning), functions, normalized (the parameters set from E and nu), separable, rest_stable.");

  m.def(
      "lame_from_young_poisson",
      [](double E, double nu) {
        const Lame l = lame_from_young_poisson({E, nu});
        return py::make_tuple(l.lambda, l.mu);
      },
      py::arg("E"), py::arg("nu"), "(lambda, mu) from Young's modulus and Poisson's ratio (paper 002 Eq. 15).");
  m.def(
      "young_poisson",
      [](double lambda, double mu) {
        const YoungPoisson y = young_poisson({lambda, mu});
        return py::make_tuple(y.E, y.nu);
      },
      py::arg("lam"), py::arg("mu"), "(E, nu) from the Lamé parameters (paper 002 Eq. 14).");
  m.def(
      "normalize",
      [](const std::string& family, double E, double nu, const py::object& parameters, const py::object& functions) {
        const MaterialInfo& info = MaterialCatalog::instance().find(family);
        const MaterialParameters base = parameters_from(parameters, functions);
        MaterialParameters p;
        {
          py::gil_scoped_release release;
          p = normalize(info, base, YoungPoisson{E, nu});
        }
        return values_dict(p);
      },
      py::arg("family"), py::arg("E"), py::arg("nu"), py::arg("parameters") = py::none(),
      py::arg("functions") = py::none(),
      "The family's parameters (defaults, then `parameters`) with its normalized ones solved so that "
      "its Lamé parameters match (E, nu) (paper 002 §4).");
  m.def(
      "lambda_part_parameters",
      [](const std::string& family, const py::object& parameters) {
        return values_dict(
            lambda_part_parameters(MaterialCatalog::instance().find(family), parameters_from(parameters, py::none())));
      },
      py::arg("family"), py::arg("parameters") = py::none(),
      "The family normalised to (lambda, mu) = (1, 0): the volume part of a mix (paper 002 Eq. 19).");
  m.def(
      "mu_part_parameters",
      [](const std::string& family, const py::object& parameters) {
        return values_dict(
            mu_part_parameters(MaterialCatalog::instance().find(family), parameters_from(parameters, py::none())));
      },
      py::arg("family"), py::arg("parameters") = py::none(),
      "The family normalised to (lambda, mu) = (0, 1): the shear part of a mix (paper 002 Eq. 19).");

  py::class_<PyMaterial>(m, "Material", R"(A material: a catalog family with parameters, optionally set from (E, nu) and
given a nonlinearity exponent alpha, or a mix of two families (the scene's "material" section,
docs/materials.md). Evaluations take one deformation gradient F (3, 3) or a batch (n, 3, 3).)")
      .def(py::init([](const py::object& spec, const std::string& context) { return make_material(spec, context); }),
           py::arg("spec"), py::arg("context") = "material",
           "spec: a family name, or a dict in the scene's material form, e.g. {'family': 'neo_hookean', "
           "'E': 1e5, 'nu': 0.45, 'alpha': 2}. Errors (sinew.Error) name `context` and the field.")
      .def_property_readonly("name", [](const PyMaterial& p) { return p.built.material->name(); })
      .def_property_readonly("family", [](const PyMaterial& p) { return p.spec.mix ? std::string("mix") : p.spec.family; })
      .def_property_readonly("spec", [](const PyMaterial& p) { return from_json(material_spec_to_json(p.spec)); },
                             "The material in the scene's JSON form (a dict).")
      .def_property_readonly("lame", [](const PyMaterial& p) { return py::make_tuple(p.built.lame.lambda, p.built.lame.mu); },
                             "(lambda, mu) read off the energy (paper 002 Thm. 3.1).")
      .def_property_readonly("E", [](const PyMaterial& p) { return young_poisson(p.built.lame).E; })
      .def_property_readonly("nu", [](const PyMaterial& p) { return young_poisson(p.built.lame).nu; })
      .def_property_readonly("alpha", [](const PyMaterial& p) { return p.spec.alpha; },
                             "The nonlinearity exponent (paper 002 §5); 1 for a mix (its parts carry theirs).")
      .def_property_readonly("parameters", [](const PyMaterial& p) { return values_dict(p.built.parameters); },
                             "The family's complete (normalised) parameters; empty for a mix.")
      .def_property_readonly("functions", [](const PyMaterial& p) { return functions_dict(p.built.parameters); })
      .def_property_readonly("lambda_parameters", [](const PyMaterial& p) { return values_dict(p.built.lambda_parameters); },
                             "A mix: its lambda family's parameters at (lambda, mu) = (1, 0).")
      .def_property_readonly("mu_parameters", [](const PyMaterial& p) { return values_dict(p.built.mu_parameters); },
                             "A mix: its mu family's parameters at (lambda, mu) = (0, 1).")
      .def_property_readonly("domain", [](const PyMaterial& p) {
        return p.built.material->domain() == Domain::All ? "all" : "positive_J";
      })
      .def(
          "psi",
          [](const PyMaterial& p, const py::object& F) {
            const Batch b(F, 3, 3, "F");
            py::array_t<double> out(b.shape({}));
            double* o = out.mutable_data();
            b.each([&](py::ssize_t i) { o[i] = p.built.material->psi(b.F(i)); }, "F");
            return out;
          },
          py::arg("F"), "Energy density psi(F): a float array of shape () or (n,).")
      .def(
          "pk1",
          [](const PyMaterial& p, const py::object& F) {
            const Batch b(F, 3, 3, "F");
            py::array_t<double> out(b.shape({3, 3}));
            double* o = out.mutable_data();
            b.each([&](py::ssize_t i) { Eigen::Map<RowMat3>(o + 9 * i) = p.built.material->pk1(b.F(i)); }, "F");
            return out;
          },
          py::arg("F"), "First Piola-Kirchhoff stress P = dpsi/dF, shape (3, 3) or (n, 3, 3).")
      .def(
          "hessian",
          [](const PyMaterial& p, const py::object& F, const std::optional<std::string>& projection) {
            const Batch b(F, 3, 3, "F");
            const std::optional<Projection> mode =
                projection ? std::optional<Projection>(projection_from(*projection)) : std::nullopt;
            py::array_t<double> out(b.shape({3, 3, 3, 3}));
            double* o = out.mutable_data();
            b.each(
                [&](py::ssize_t i) {
                  const Material& mat = *p.built.material;
                  write_hessian(mode ? mat.projected_hessian(b.F(i), *mode) : mat.hessian(b.F(i)), o + 81 * i);
                },
                "F");
            return out;
          },
          py::arg("F"), py::arg("projection") = py::none(),
          "d2psi/dF2 as H[..., a, b, c, d] = d2psi / dF_ab dF_cd, shape (3, 3, 3, 3) or (n, 3, 3, 3, 3); "
          "H.reshape(-1, 9, 9) is the 9x9 Hessian in F.reshape(9)'s (row-major) order. projection: None "
          "(the true Hessian), 'clamp' (negative eigenvalues to 0), 'abs' or 'none'.")
      .def(
          "projected_hessian",
          [](const PyMaterial& p, const py::object& F, const std::string& projection) {
            const Batch b(F, 3, 3, "F");
            const Projection mode = projection_from(projection);
            py::array_t<double> out(b.shape({3, 3, 3, 3}));
            double* o = out.mutable_data();
            b.each([&](py::ssize_t i) { write_hessian(p.built.material->projected_hessian(b.F(i), mode), o + 81 * i); },
                   "F");
            return out;
          },
          py::arg("F"), py::arg("projection") = "clamp",
          "The Hessian made positive semi-definite through its analytic eigensystem (paper 000 §4).")
      .def(
          "eigensystem",
          [](const PyMaterial& p, const py::object& F) {
            const Batch b(F, 3, 3, "F");
            py::array_t<double> values(b.shape({9})), vectors(b.shape({9, 3, 3}));
            double* ov = values.mutable_data();
            double* oq = vectors.mutable_data();
            b.each(
                [&](py::ssize_t i) {
                  const Eigensystem es = p.built.material->eigensystem(b.F(i));
                  for (int k = 0; k < 9; ++k) {
                    ov[9 * i + k] = es.values(k);
                    for (int a = 0; a < 3; ++a)
                      for (int c = 0; c < 3; ++c) oq[81 * i + 9 * k + 3 * a + c] = es.vectors(3 * c + a, k);
                  }
                },
                "F");
            return py::make_tuple(values, vectors);
          },
          py::arg("F"),
          "(values, Q): the Hessian's nine eigenvalues and eigenmatrices Q[..., k, :, :] (orthonormal: "
          "H = sum_k values_k Q_k (x) Q_k); k = 0-2 scaling, 3-5 twist, 6-8 flip modes.")
      .def(
          "evaluate",
          [](const PyMaterial& p, const py::object& F, const std::string& projection) {
            const Batch b(F, 3, 3, "F");
            const Projection mode = projection_from(projection);
            py::array_t<double> psi(b.shape({})), P(b.shape({3, 3})), H(b.shape({3, 3, 3, 3}));
            double *o0 = psi.mutable_data(), *o1 = P.mutable_data(), *o2 = H.mutable_data();
            b.each(
                [&](py::ssize_t i) {
                  const Evaluation e = p.built.material->evaluate(b.F(i), mode);
                  o0[i] = e.psi;
                  Eigen::Map<RowMat3>(o1 + 9 * i) = e.P;
                  write_hessian(e.hessian, o2 + 81 * i);
                },
                "F");
            return py::make_tuple(psi, P, H);
          },
          py::arg("F"), py::arg("projection") = "clamp",
          "(psi, P, projected Hessian) from one SVD per F, as the solver evaluates them.")
      .def(
          "psi_stretch",
          [](const PyMaterial& p, const py::object& s) {
            const Batch b(s, 3, 0, "s");
            py::array_t<double> psi(b.shape({})), grad(b.shape({3})), hess(b.shape({3, 3}));
            double *o0 = psi.mutable_data(), *o1 = grad.mutable_data(), *o2 = hess.mutable_data();
            b.each(
                [&](py::ssize_t i) {
                  const Vec3 sigma = Eigen::Map<const Vec3>(b.data + 3 * i);
                  const Material& mat = *p.built.material;
                  o0[i] = mat.psi_stretch(sigma);
                  Eigen::Map<Vec3>(o1 + 3 * i) = mat.grad_stretch(sigma);
                  Eigen::Map<RowMat3>(o2 + 9 * i) = mat.hess_stretch(sigma);
                },
                "s");
            return py::make_tuple(psi, grad, hess);
          },
          py::arg("s"),
          "The stretch view at signed singular values s (3,) or (n, 3): (psi, principal stresses dpsi/ds, "
          "3x3 stretch Hessian).")
      .def(
          "curve",
          [](const PyMaterial& p, const std::string& mode, double start, double stop, int steps) {
            const CurveMode cm = parse_curve_mode(mode);
            std::vector<CurvePoint> points;
            {
              py::gil_scoped_release release;
              points = stress_stretch_curve(*p.built.material, cm, start, stop, steps);
            }
            const auto n = static_cast<py::ssize_t>(points.size());
            py::array_t<double> stretch(n), lateral(n), J(n), stress(n), psi(n);
            for (py::ssize_t i = 0; i < n; ++i) {
              stretch.mutable_at(i) = points[i].stretch;
              lateral.mutable_at(i) = points[i].lateral;
              J.mutable_at(i) = points[i].J;
              stress.mutable_at(i) = points[i].stress;
              psi.mutable_at(i) = points[i].psi;
            }
            return py::dict(py::arg("stretch") = stretch, py::arg("lateral") = lateral, py::arg("J") = J,
                            py::arg("stress") = stress, py::arg("psi") = psi);
          },
          py::arg("mode") = "uniaxial", py::arg("start") = 0.5, py::arg("stop") = 2.0, py::arg("steps") = 30,
          "A stress-stretch curve (as `sinew material curve`): mode 'uniaxial' (lateral stress solved to "
          "zero), 'biaxial' or 'shear'; a dict of arrays stretch, lateral, J, stress (nominal P00, P01 for "
          "shear) and psi.")
      .def("__repr__", [](const PyMaterial& p) {
        return fmt::format("<sinew.Material {} lambda={:.6g} mu={:.6g}>", p.built.material->name(), p.built.lame.lambda,
                           p.built.lame.mu);
      });
}

}  // namespace sinew::python
