#include "sinew/run/frame_output.hpp"

#include <fmt/format.h>
#include <optional>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "sinew/element/continuum_fields.hpp"
#include "sinew/io/obj_writer.hpp"
#include "sinew/io/vtk_writer.hpp"

namespace sinew {

ElementFields element_fields(const Model& model, const Eigen::VectorXd& x) {
  if (model.hyperelastic) {
    const auto f = model.hyperelastic->element_fields(x);
    return {f.energy, f.energy_density, f.J, f.stress_norm};
  }
  const Discretization& d = *model.disc;
  ElementFields f;
  const Eigen::Index m = d.num_elements();
  f.energy.resize(m);
  f.energy_density.resize(m);
  f.J.resize(m);
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, m, 256), [&](const auto& r) {
    for (Eigen::Index e = r.begin(); e != r.end(); ++e) {
      const Eigen::Matrix3Xd xe = d.element_positions(e, x);
      double J = 0.0, volume = 0.0;
      for (int q = 0; q < d.quadrature_points(); ++q) {
        J += d.weight(e, q) * (xe * d.gradients(e, q)).determinant();
        volume += d.weight(e, q);
      }
      f.energy(e) = model.elastic->element_value(e, x);
      f.energy_density(e) = f.energy(e) / volume;
      f.J(e) = J / volume;
    }
  });
  return f;
}

void add_continuum_fields(const Model& model, const Eigen::VectorXd& x, VtuFields& vf) {
  const Discretization& d = *model.disc;
  // Stresses need the material's P; the corotational model has none (its force is warped).
  const Material* material = model.hyperelastic ? &model.hyperelastic->material() : nullptr;
  const ContinuumFields c = continuum_fields(d, material, x);
  auto both = [&](const char* name, int components, const Eigen::VectorXd& values) {
    if (!values.size()) return;
    if (std::string(name) != "J") vf.cell_arrays.push_back({name, components, values});  // J is a cell scalar already
    vf.point_arrays.push_back({name, components, average_to_vertices(d, values, components)});
  };
  both("J", 1, c.J);
  both("principal_stretches", 3, c.principal_stretches);
  both("green_lagrange_strain", 9, c.green_lagrange);
  both("cauchy_stress", 9, c.cauchy);
  both("von_mises", 1, c.von_mises);
}

FrameOutput::FrameOutput(const Scene& scene, const Model& model, std::filesystem::path out)
    : scene_(scene), model_(model), out_(std::move(out)), embedded_(scene, model.disc->mesh()), shapes_(scene, model.disc->mesh()) {}

void FrameOutput::resume_after(int last_frame, const std::function<double(int)>& time_of) {
  pvd_.clear();
  pvd_changed_ = true;
  if (!scene_.output.vtu) return;
  for (int frame = 0; frame <= last_frame; frame += scene_.output.every)
    pvd_.emplace_back(time_of(frame), fmt::format("frame_{:04d}.vtu", frame));
}

void FrameOutput::write(int frame, double time, const State& state) {
  if (out_.empty() || frame % scene_.output.every != 0) return;
  const VolumeMesh& mesh = model_.disc->mesh();
  std::optional<ElementFields> fields;
  if (scene_.output.vtu || embedded_.active()) fields = element_fields(model_, state.x);
  if (scene_.output.vtu) {
    VtuFields vf;
    vf.cell_scalars = {{"J", fields->J}, {"energy_density", fields->energy_density}};
    if (fields->stress_norm.size()) vf.cell_scalars.push_back({"stress_norm", fields->stress_norm});
    vf.cell_scalars.push_back({"energy", fields->energy});
    if (model_.energy_limit) vf.cell_scalars.push_back({"energy_ratio", fields->energy / model_.energy_limit->max_energy});
    if (model_.integrator->dynamic() && state.v.size() == state.x.size()) vf.point_vectors = {{"velocity", state.v}};
    add_continuum_fields(model_, state.x, vf);
    const std::string name = fmt::format("frame_{:04d}.vtu", frame);
    write_vtu(out_ / name, mesh, state.x, vf);
    std::erase_if(pvd_, [&](const auto& e) { return e.second == name; });
    pvd_.emplace_back(time, name);
    pvd_changed_ = true;
  }
  if (scene_.output.obj) write_surface_obj(out_ / fmt::format("surface_{:04d}.obj", frame), mesh, model_.surface, state.x);
  if (embedded_.active())
    embedded_.write(out_, frame, state.x, *model_.disc, &fields->J, fields->stress_norm.size() ? &fields->stress_norm : nullptr);
  shapes_.write(out_, frame);
}

void FrameOutput::write_collection() {
  if (out_.empty() || !scene_.output.vtu || !pvd_changed_) return;
  // ParaView's time: seconds in dynamics, the frame number in quasistatics (stated in the file).
  write_pvd(out_ / "simulation.pvd", pvd_, model_.integrator->dynamic() ? PvdTime::Seconds : PvdTime::Frames);
  pvd_changed_ = false;
}

}  // namespace sinew
