// sinew.Scene, sinew.run and sinew.Simulation (a scene stepped frame by frame), with results as
// arrays.
#include <Python.h>
#include <fmt/format.h>

#include "bindings.hpp"
#include "sinew/core/error.hpp"
#include "sinew/model/json_reader.hpp"
#include "sinew/run/element_stresses.hpp"
#include "sinew/run/frame_output.hpp"
#include "sinew/run/run_summary.hpp"
#include "sinew/run/session.hpp"
#include "sinew/run/simulation.hpp"

namespace sinew::python {
namespace {

using FloatArray = py::array_t<double, py::array::c_style | py::array::forcecast>;
using ScenePtr = std::shared_ptr<Scene>;

// Called from C++ (without the GIL) at every progress event: takes the GIL, lets Ctrl-C stop the
// run (KeyboardInterrupt), then calls the user's callback, if any. The callback is a borrowed
// handle, kept alive by the call that runs the simulation.
void python_callback(py::handle callback, const std::function<py::object()>& arguments) {
  py::gil_scoped_acquire gil;
  if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  if (!callback.is_none()) callback(*arguments());
}

// A progress event that owns its frame record (the run's own record moves on).
struct Progress {
  int frame = 0, frames = 0, newton_iteration = 0;
  double residual = 0.0, elapsed = 0.0;
  bool frame_done = false;
  std::optional<FrameRecord> record;
};

// A model warning as a Python warning (sinew.SceneWarning); with the GIL held. Raises if the
// warnings filter turns it into an error.
void warn(const std::string& message) {
  static py::object category = py::module_::import("sinew._sinew").attr("SceneWarning");
  if (PyErr_WarnEx(category.ptr(), message.c_str(), 2) != 0) throw py::error_already_set();
}

py::object scene_object(Scene scene, const nlohmann::json& data) {
  py::object object = py::cast(std::make_shared<Scene>(std::move(scene)));
  object.attr("data") = from_json(data);
  return object;
}

std::vector<std::string> boundary_names(const Scene& scene) {
  std::vector<std::string> names;
  for (const auto& b : scene.boundary) names.push_back(b.name);
  return names;
}

// A boundary condition by index (scene order) or name.
size_t boundary_index(const Scene& scene, const py::handle& which) {
  if (py::isinstance<py::str>(which)) {
    const std::string name = which.cast<std::string>();
    for (size_t i = 0; i < scene.boundary.size(); ++i)
      if (scene.boundary[i].name == name) return i;
    const std::vector<std::string> names = boundary_names(scene);
    throw Error(fmt::format("no boundary condition named '{}' (the scene has: {})", name,
                            names.empty() ? "none" : fmt::format("{}", fmt::join(names, ", "))),
                "boundary");
  }
  const long i = which.cast<long>();
  if (i < 0 || static_cast<size_t>(i) >= scene.boundary.size())
    throw Error(fmt::format("no boundary condition {} (the scene has {})", i, scene.boundary.size()), "boundary");
  return static_cast<size_t>(i);
}

py::array reactions_array(const std::vector<Eigen::Vector3d>& reactions) {
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> r(reactions.size(), 3);
  for (size_t i = 0; i < reactions.size(); ++i) r.row(i) = reactions[i].transpose();
  const auto n = static_cast<py::ssize_t>(reactions.size());
  return adopt(std::move(r), {n, 3});
}

py::array index_array(const std::vector<int>& indices) {
  Eigen::VectorXi v = Eigen::Map<const Eigen::VectorXi>(indices.data(), static_cast<Eigen::Index>(indices.size()));
  const auto n = static_cast<py::ssize_t>(indices.size());
  return adopt(std::move(v), {n});
}

py::dict fields_dict(const ElementFields& f) {
  py::dict d;
  auto add = [&](const char* name, const Eigen::VectorXd& v) {
    if (v.size()) d[name] = adopt(Eigen::VectorXd(v), {static_cast<py::ssize_t>(v.size())});
  };
  add("J", f.J);
  add("energy", f.energy);
  add("energy_density", f.energy_density);
  add("stress_norm", f.stress_norm);
  return d;
}

py::object mesh_of(const Model& model) {
  // Shares the model's discretisation, so the mesh outlives the simulation if kept.
  return py::cast(std::shared_ptr<VolumeMesh>(model.disc, const_cast<VolumeMesh*>(&model.disc->mesh())));
}

}  // namespace

void bind_scenes(py::module_& m) {
  py::class_<Scene, ScenePtr>(m, "Scene", py::dynamic_attr(), R"(A scene (docs/scene-format.md), read and checked as `sinew run` reads it. Scene.data
is the JSON as a dict: change a copy and build a new scene with Scene.from_dict.)")
      .def_static(
          "load",
          [](const std::filesystem::path& path) {
            const nlohmann::json json = read_json_file(path, "scene");
            return scene_object(parse_scene(json, path), json);
          },
          py::arg("path"), "Reads a scene file (errors as the CLI's).")
      .def_static(
          "from_dict",
          [](const py::object& data, const std::filesystem::path& path) {
            const nlohmann::json json = to_json(data, path.string());
            return scene_object(parse_scene(json, path), json);
          },
          py::arg("data"), py::arg("path") = "<dict>",
          "A scene from a dict in the scene file's form. `path` names it in errors and its folder resolves "
          "relative file names (default: the working directory).")
      .def_property_readonly("path", [](const Scene& s) { return s.file.string(); })
      .def_property_readonly("description", [](const Scene& s) { return s.description; })
      .def_property_readonly("frames", [](const Scene& s) { return s.frames; })
      .def_property_readonly("dynamic", [](const Scene& s) { return s.dynamics.has_value(); })
      .def_property_readonly("time_step", [](const Scene& s) -> py::object {
        return s.dynamics ? py::cast(s.dynamics->time_step) : py::none();
      })
      .def_property_readonly("boundary_names", [](const Scene& s) { return boundary_names(s); })
      .def(
          "mesh",
          [](const Scene& s) {
            py::gil_scoped_release release;
            return std::make_shared<VolumeMesh>(build_scene_mesh(s));
          },
          "The scene's mesh (generated, read or voxelised), validated.")
      .def(
          "material",
          [](const Scene& s) {
            PyMaterial p{s.material, {}};
            py::gil_scoped_release release;
            p.built = build_material_detailed(p.spec);
            return p;
          },
          "The scene's material.")
      .def("__repr__", [](const Scene& s) { return fmt::format("<sinew.Scene {}>", s.file.string()); });

  py::class_<FrameRecord>(m, "FrameRecord", "What one frame did and measured (a summary.json frame entry).")
      .def_readonly("frame", &FrameRecord::frame)
      .def_readonly("time", &FrameRecord::time, "Simulated seconds (dynamics) or the frame number (quasistatic).")
      .def_readonly("converged", &FrameRecord::converged)
      .def_readonly("failure", &FrameRecord::failure)
      .def_readonly("newton_iterations", &FrameRecord::newton_iterations)
      .def_readonly("linear_iterations", &FrameRecord::linear_iterations)
      .def_readonly("substeps", &FrameRecord::substeps)
      .def_readonly("residual", &FrameRecord::residual)
      .def_readonly("energy", &FrameRecord::energy)
      .def_readonly("seconds", &FrameRecord::seconds)
      .def_readonly("volume", &FrameRecord::volume)
      .def_readonly("min_J", &FrameRecord::min_J)
      .def_readonly("kinetic_energy", &FrameRecord::kinetic_energy)
      .def_readonly("potential_energy", &FrameRecord::potential_energy)
      .def_readonly("contacts", &FrameRecord::contacts)
      .def_readonly("max_penetration", &FrameRecord::max_penetration)
      .def_readonly("self_contacts", &FrameRecord::self_contacts)
      .def_readonly("self_penetration", &FrameRecord::self_penetration)
      .def_property_readonly("reactions", [](const FrameRecord& r) { return reactions_array(r.reactions); },
                             "(boundary conditions, 3): the force each boundary condition exerts on the body.")
      .def_property_readonly("external_force", [](const FrameRecord& r) { return vector3(r.external_force); },
                             "The sum of the loads at this frame's amplitudes.")
      .def_property_readonly("counters",
                             [](const FrameRecord& r) {
                               py::dict d;
                               for (const auto& c : r.counters) d[py::str(c.name)] = c.value;
                               return d;
                             })
      .def("to_dict", [](const FrameRecord& r) { return from_json(frame_to_json(r)); },
           "The frame as summary.json writes it.")
      .def("__repr__", [](const FrameRecord& r) {
        return fmt::format("<sinew.FrameRecord frame {}: {} Newton iterations, residual {:.3e}{}>", r.frame,
                           r.newton_iterations, r.residual, r.converged ? "" : ", not converged");
      });

  py::class_<RunSummary>(m, "RunSummary", "The result of sinew.run: the model's size and every frame's record.")
      .def_readonly("vertices", &RunSummary::vertices)
      .def_readonly("elements", &RunSummary::elements)
      .def_readonly("rest_volume", &RunSummary::rest_volume)
      .def_property_readonly("external_force", [](const RunSummary& s) { return vector3(s.external_force); })
      .def_readonly("frames", &RunSummary::frames)
      .def_property_readonly("positions", [](const RunSummary& s) { return positions_array(s.x); },
                             "Final positions (vertices, 3).")
      .def_property_readonly("all_converged", &RunSummary::all_converged)
      .def_readonly("warnings", &RunSummary::warnings, "The model's warnings (also issued as sinew.SceneWarning).")
      .def("__repr__", [](const RunSummary& s) {
        return fmt::format("<sinew.RunSummary {} vertices, {} elements, {} frames{}>", s.vertices, s.elements,
                           s.frames.size(), s.all_converged() ? "" : ", not converged");
      });

  py::class_<Progress>(m, "Progress", "A progress event of sinew.run (the CLI prints its progress lines from these).")
      .def_readonly("frame", &Progress::frame)
      .def_readonly("frames", &Progress::frames)
      .def_readonly("newton_iteration", &Progress::newton_iteration, "0 at the start of a frame.")
      .def_readonly("residual", &Progress::residual)
      .def_readonly("elapsed", &Progress::elapsed, "Seconds since the run started.")
      .def_readonly("frame_done", &Progress::frame_done)
      .def_readonly("record", &Progress::record, "The frame's FrameRecord when frame_done, else None.");

  m.def(
      "run",
      [](const Scene& scene, const std::optional<std::filesystem::path>& out, const std::optional<int>& frames, bool resume,
         const py::object& progress, bool strict, double checkpoint_seconds) {
        RunOptions options;
        if (out) options.out_dir = *out;
        if (frames) {
          if (*frames < 1 || *frames > 1000000)
            throw Error(fmt::format("must be between 1 and 1000000, got {}", *frames), "--frames");
          options.frames = *frames;
        }
        options.resume = resume;
        options.strict = strict;
        options.checkpoint_seconds = checkpoint_seconds;
        options.warning = [](const std::string& message) {
          py::gil_scoped_acquire gil;
          warn(message);
        };
        const py::handle callback = progress;
        options.progress = [callback](const ProgressEvent& e) {
          python_callback(callback, [&] {
            Progress p{e.frame, e.frames, e.newton_iteration, e.residual, e.elapsed, e.frame_done, {}};
            if (e.record) p.record = *e.record;
            return py::make_tuple(std::move(p));
          });
        };
        py::gil_scoped_release release;
        return run_scene(scene, options);
      },
      py::arg("scene"), py::arg("out") = py::none(), py::arg("frames") = py::none(), py::arg("resume") = false,
      py::arg("progress") = py::none(), py::arg("strict") = false, py::arg("checkpoint_seconds") = 1.0,
      "Runs a scene as `sinew run` does: with `out`, writes its outputs there (frames, surfaces, "
      "simulation.pvd, summary.json, checkpoint; `resume` continues from the checkpoint, written every "
      "`checkpoint_seconds` of wall clock and for the last converged frame), without it writes "
      "nothing. `frames` overrides the scene's frame count; `progress(event)` is called at every Newton "
      "iteration and frame end. The model's warnings are issued as sinew.SceneWarning (errors with `strict`, "
      "like --strict). Ctrl-C stops the run (KeyboardInterrupt).");

  py::class_<Session>(m, "Simulation", R"(A scene stepped frame by frame: read the state between frames, change boundary
motions or external forces, step again. Positions and other state arrays are copies (their values
at the time of the call), shaped (vertices, 3).)")
      .def(py::init([](const Scene& scene, const std::optional<std::filesystem::path>& out, bool strict) {
             std::unique_ptr<Session> s;
             {
               py::gil_scoped_release release;
               s = std::make_unique<Session>(scene, out.value_or(std::filesystem::path()), strict);
             }
             for (const auto& w : s->summary().warnings) warn(w);
             return s;
           }),
           py::arg("scene"), py::arg("out") = py::none(), py::arg("strict") = false,
           "Builds the scene's model (every input error is a sinew.Error here; its warnings are issued as "
           "sinew.SceneWarning, errors with `strict`). With `out`, frame 0 and every stepped frame's outputs and "
           "summary.json are written there, as by `sinew run` (no checkpoint).")
      .def_property_readonly("warnings", [](const Session& s) { return s.summary().warnings; })
      .def(
          "step",
          [](Session& s, const py::object& progress) {
            const py::handle callback = progress;
            const IterationProgress p = [callback](int iteration, double residual) {
              python_callback(callback, [&] { return py::make_tuple(iteration, residual); });
            };
            py::gil_scoped_release release;
            return s.step(p);
          },
          py::arg("progress") = py::none(),
          "Advances one frame and returns its FrameRecord; progress(iteration, residual) is called at every "
          "Newton iteration. A frame that did not converge is returned with converged False (its state kept).")
      .def_property_readonly("frame", &Session::frame, "Frames advanced so far.")
      .def_property_readonly("time", &Session::time)
      .def_property_readonly("dynamic", [](const Session& s) { return s.model().integrator->dynamic(); })
      .def_property_readonly("integrator", [](const Session& s) { return s.model().integrator->name(); })
      .def_property_readonly("frames", [](const Session& s) { return s.summary().frames; })
      .def_property_readonly("summary", [](const Session& s) { return s.summary(); })
      .def_property_readonly("scene", [](const Session& s) { return std::make_shared<Scene>(s.scene()); })
      .def_property_readonly("mesh", [](const Session& s) { return mesh_of(s.model()); })
      .def_property_readonly("material", [](const Session& s) { return PyMaterial{s.scene().material, s.model().material}; })
      .def_property_readonly("rest_volume", [](const Session& s) { return s.summary().rest_volume; })
      .def_property_readonly("positions", [](const Session& s) { return positions_array(s.state().x); })
      .def_property_readonly("rest_positions",
                             [](const Session& s) { return positions_array(s.model().initial.x); })
      .def_property_readonly("displacements",
                             [](const Session& s) { return positions_array(s.state().x - s.model().initial.x); })
      .def_property_readonly("velocities", [](const Session& s) -> py::object {
        if (s.state().v.size() != s.state().x.size()) return py::none();
        return positions_array(s.state().v);
      }, "Velocities (vertices, 3) of a dynamic scene; None for a quasistatic one.")
      .def(
          "element_fields",
          [](const Session& s) {
            ElementFields f;
            {
              py::gil_scoped_release release;
              f = element_fields(s.model(), s.state().x);
            }
            return fields_dict(f);
          },
          "Per element at the current state: J (volume-averaged), energy (integrated), energy_density and, "
          "for a hyperelastic material, stress_norm (volume-averaged |P|), as written to the VTU files.")
      .def(
          "stresses",
          [](const Session& s) {
            ElementStresses st;
            {
              py::gil_scoped_release release;
              st = element_stresses(s.model(), s.state().x);
            }
            const auto n = static_cast<py::ssize_t>(st.pk1.rows());
            return py::dict(py::arg("pk1") = adopt(std::move(st.pk1), {n, 3, 3}),
                            py::arg("cauchy") = adopt(std::move(st.cauchy), {n, 3, 3}));
          },
          "Per element at the current state, volume-averaged over its quadrature points: the first "
          "Piola-Kirchhoff stress pk1 and the Cauchy stress cauchy = P F^T / J, each (elements, 3, 3).")
      .def_property_readonly("boundary_names", [](const Session& s) { return boundary_names(s.scene()); })
      .def(
          "boundary_vertices",
          [](const Session& s, const py::object& which) {
            return index_array((*s.model().kinematics)[boundary_index(s.scene(), which)].vertices);
          },
          py::arg("boundary"), "The vertices a boundary condition (index or name) moves.")
      .def(
          "boundary_transform",
          [](const Session& s, const py::object& which, std::optional<double> frame) {
            const RigidTransform t = s.boundary_transform(boundary_index(s.scene(), which), frame.value_or(s.frame()));
            Eigen::Matrix<double, 3, 3, Eigen::RowMajor> R = t.R;
            return py::make_tuple(adopt(std::move(R), {3, 3}), vector3(t.t));
          },
          py::arg("boundary"), py::arg("frame") = py::none(),
          "(R, t): where the boundary condition puts its vertices (x = R X + t for rest position X) at a "
          "frame number (default: the current frame).")
      .def(
          "set_boundary_motion",
          [](Session& s, const py::object& which, const py::object& motion) {
            const size_t i = boundary_index(s.scene(), which);
            const std::string context = fmt::format("boundary '{}' motion", s.scene().boundary[i].name);
            s.set_boundary_motion(i, motion_from_json(to_json(motion, context), context));
          },
          py::arg("boundary"), py::arg("motion"),
          "The boundary condition (index or name) follows `motion`, a dict in the scene's motion form "
          "({'type': 'translate', 'per_frame': [dx, dy, dz]}, 'rotate', 'keyframes', 'pinned'), from the next "
          "frame on; motions are functions of the frame number, relative to the rest pose.")
      .def(
          "move_boundary",
          [](Session& s, const py::object& which, const py::object& translation, const py::object& rotation) {
            RigidTransform target;
            target.t = to_vector3(translation, "translation");
            if (!rotation.is_none()) target.R = to_matrix3(rotation, "rotation");
            s.move_boundary(boundary_index(s.scene(), which), target);
          },
          py::arg("boundary"), py::arg("translation"), py::arg("rotation") = py::none(),
          "The boundary condition reaches x = rotation X + translation (X: rest positions) at the end of the "
          "next frame, moving there from where it is now, and holds it afterwards.")
      .def_property(
          "external_forces", [](const Session& s) { return positions_array(s.external_forces()); },
          [](Session& s, const py::object& forces) {
            s.set_external_forces(
                positions_vector(FloatArray::ensure(forces), s.model().disc->mesh().num_vertices(), "external_forces"));
          },
          "The external force on each vertex (vertices, 3) at the current frame: gravity, point loads and "
          "tractions at their amplitudes; assign constant forces to replace them (and their amplitudes) from "
          "the next frame on.")
      .def("__repr__", [](const Session& s) {
        return fmt::format("<sinew.Simulation {} at frame {}>", s.scene().file.string(), s.frame());
      });
}

}  // namespace sinew::python
