#include "sinew/run/frame_output.hpp"

#include <fmt/format.h>
#include <optional>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

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

FrameOutput::FrameOutput(const Scene& scene, const Model& model, std::filesystem::path out)
    : scene_(scene), model_(model), out_(std::move(out)), embedded_(scene, model.disc->mesh()), shapes_(scene, model.disc->mesh()) {}

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
    const std::string name = fmt::format("frame_{:04d}.vtu", frame);
    write_vtu(out_ / name, mesh, state.x, vf);
    std::erase_if(pvd_, [&](const auto& e) { return e.second == name; });
    pvd_.emplace_back(time, name);
    // ParaView's time: seconds in dynamics, the frame number in quasistatics (stated in the file).
    write_pvd(out_ / "simulation.pvd", pvd_, model_.integrator->dynamic() ? PvdTime::Seconds : PvdTime::Frames);
  }
  if (scene_.output.obj) write_surface_obj(out_ / fmt::format("surface_{:04d}.obj", frame), mesh, model_.surface, state.x);
  if (embedded_.active())
    embedded_.write(out_, frame, state.x, *model_.disc, &fields->J, fields->stress_norm.size() ? &fields->stress_norm : nullptr);
  shapes_.write(out_, frame);
}

}  // namespace sinew
