#include "sinew/scene/simulation.hpp"

#include <chrono>
#include <cstring>
#include <fmt/format.h>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "sinew/core/error.hpp"
#include "sinew/fem/elastic_form.hpp"
#include "sinew/fem/external_force_form.hpp"
#include "sinew/fem/mass.hpp"
#include "sinew/io/atomic_file.hpp"
#include "sinew/io/obj_writer.hpp"
#include "sinew/io/vtk_writer.hpp"
#include "sinew/mesh/surface.hpp"
#include "sinew/solver/newton.hpp"

namespace sinew {

bool RunSummary::all_converged() const {
  for (const auto& f : frames)
    if (!f.converged) return false;
  return true;
}

namespace {

using Clock = std::chrono::steady_clock;

// Nodal forces of a uniform traction on the boundary faces whose vertices are all selected
// (each triangle's force split equally among its corners; quads as two triangles).
Eigen::VectorXd traction_forces(const VolumeMesh& mesh, const BoundarySurface& surface,
                                const std::vector<int>& selected, const Eigen::Vector3d& traction) {
  std::vector<char> in(mesh.num_vertices(), 0);
  for (int v : selected) in[v] = 1;
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * mesh.num_vertices());
  for (Eigen::Index t = 0; t < surface.triangles.rows(); ++t) {
    const int a = surface.triangles(t, 0), b = surface.triangles(t, 1), c = surface.triangles(t, 2);
    if (!in[a] || !in[b] || !in[c]) continue;
    const Eigen::Vector3d pa = mesh.vertices.row(a), pb = mesh.vertices.row(b), pc = mesh.vertices.row(c);
    const double area = 0.5 * (pb - pa).cross(pc - pa).norm();
    for (int v : {a, b, c}) f.segment<3>(3 * v) += area / 3.0 * traction;
  }
  return f;
}

std::string scene_fingerprint(const Scene& scene) {
  std::ifstream in(scene.file, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return fmt::format("{:016x}", std::hash<std::string>{}(ss.str()));
}

nlohmann::json to_json(const FrameRecord& r) {
  return {{"frame", r.frame},
          {"converged", r.converged},
          {"newton_iterations", r.newton_iterations},
          {"linear_iterations", r.linear_iterations},
          {"substeps", r.substeps},
          {"residual", r.residual},
          {"energy", r.energy},
          {"volume", r.volume},
          {"min_J", r.min_J},
          {"seconds", r.seconds},
          {"assembly_seconds", r.assembly_seconds},
          {"solve_seconds", r.solve_seconds},
          {"failure", r.failure}};
}

FrameRecord frame_from_json(const nlohmann::json& j) {
  FrameRecord r;
  r.frame = j.at("frame");
  r.converged = j.at("converged");
  r.newton_iterations = j.at("newton_iterations");
  r.linear_iterations = j.at("linear_iterations");
  r.substeps = j.at("substeps");
  r.residual = j.at("residual");
  r.energy = j.at("energy");
  r.volume = j.at("volume");
  r.min_J = j.at("min_J");
  r.seconds = j.at("seconds");
  r.assembly_seconds = j.at("assembly_seconds");
  r.solve_seconds = j.at("solve_seconds");
  r.failure = j.at("failure");
  return r;
}

}  // namespace

RunSummary run_scene(const Scene& scene, const RunOptions& options) {
  const auto t_start = Clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - t_start).count(); };
  const int frames = options.frames.value_or(scene.frames);
  if (frames < 1) throw Error("must be at least 1", "--frames");

  // ---- model
  auto disc = std::make_shared<Discretization>(build_scene_mesh(scene), scene.file.string() + ": /mesh");
  const VolumeMesh& mesh = disc->mesh();
  const BuiltMaterial built = build_material_detailed(scene.material);
  auto elastic = std::make_shared<ElasticForm>(disc, built.material, scene.solver.projection);
  Problem problem(mesh.num_vertices());
  problem.add_form(elastic);
  const BoundarySurface surface = boundary_surface(mesh);

  Eigen::VectorXd forces = Eigen::VectorXd::Zero(disc->num_dofs());
  if (scene.gravity.squaredNorm() > 0.0) forces += gravity_forces(lumped_mass(*disc, scene.density), scene.gravity);
  for (size_t i = 0; i < scene.point_loads.size(); ++i) {
    for (int v : select_vertices(mesh.vertices, scene.point_loads[i].select, fmt::format("{}: /loads/point/{}/select", scene.file.string(), i)))
      forces.segment<3>(3 * v) += scene.point_loads[i].force;
  }
  for (size_t i = 0; i < scene.tractions.size(); ++i) {
    const auto sel = select_vertices(mesh.vertices, scene.tractions[i].select,
                                     fmt::format("{}: /loads/traction/{}/select", scene.file.string(), i));
    forces += traction_forces(mesh, surface, sel, scene.tractions[i].traction);
  }
  if (forces.squaredNorm() > 0.0) problem.add_form(std::make_shared<ExternalForceForm>(forces));

  std::vector<KinematicCondition> kinematics;
  for (size_t i = 0; i < scene.boundary.size(); ++i) {
    const auto& b = scene.boundary[i];
    kinematics.push_back({select_vertices(mesh.vertices, b.select,
                                          fmt::format("{}: /boundary/{}/select ({})", scene.file.string(), i, b.name)),
                          b.motion});
  }
  auto linear = make_linear_solver(scene.solver.linear);

  RunSummary summary;
  summary.vertices = mesh.num_vertices();
  summary.elements = mesh.num_elements();
  for (Eigen::Index e = 0; e < disc->num_elements(); ++e) summary.rest_volume += disc->rest_volume(e);
  Eigen::VectorXd x = mesh.rest_positions();
  int first_frame = 1;

  // ---- outputs and checkpoint
  const bool writing = !options.out_dir.empty();
  const std::filesystem::path& out = options.out_dir;
  const std::string fingerprint = scene_fingerprint(scene);
  std::vector<std::pair<double, std::string>> pvd_entries;
  if (writing) ensure_directory(out);
  if (options.resume) {
    if (!writing) throw Error("resuming needs an output directory", "--resume");
    const auto cp = out / "checkpoint.json";
    std::ifstream in(cp);
    if (!in) throw Error("no checkpoint to resume from (run without --resume first)", cp.string());
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(in);
      if (j.at("scene_fingerprint") != fingerprint)
        throw Error("the scene file changed since the checkpoint was written; run again without --resume", cp.string());
      if (j.at("vertices").get<Eigen::Index>() != mesh.num_vertices())
        throw Error("checkpoint belongs to a different mesh", cp.string());
      const auto& xs = j.at("x");
      if (static_cast<Eigen::Index>(xs.size()) != x.size()) throw Error("checkpoint state has the wrong size", cp.string());
      for (Eigen::Index i = 0; i < x.size(); ++i) x(i) = xs[static_cast<size_t>(i)].get<double>();
      for (const auto& f : j.at("frames")) summary.frames.push_back(frame_from_json(f));
      for (const auto& p : j.at("pvd")) pvd_entries.emplace_back(p.at(0).get<double>(), p.at(1).get<std::string>());
      first_frame = j.at("frame").get<int>() + 1;
    } catch (const nlohmann::json::exception& e) {
      throw Error(fmt::format("corrupt checkpoint: {}", e.what()), cp.string());
    }
  }

  auto write_frame = [&](int frame) {
    if (!writing || frame % scene.output.every != 0) return;
    if (scene.output.vtu) {
      const auto fields = elastic->element_fields(x);
      VtuFields vf;
      vf.cell_scalars = {{"J", fields.J}, {"energy_density", fields.energy_density},
                         {"stress_norm", fields.stress_norm}, {"energy", fields.energy}};
      const std::string name = fmt::format("frame_{:04d}.vtu", frame);
      write_vtu(out / name, mesh, x, vf);
      pvd_entries.emplace_back(frame, name);
      write_pvd(out / "simulation.pvd", pvd_entries);
    }
    if (scene.output.obj) write_surface_obj(out / fmt::format("surface_{:04d}.obj", frame), mesh, surface, x);
  };

  auto write_reports = [&](int frame) {
    if (!writing) return;
    nlohmann::json frames_json = nlohmann::json::array();
    for (const auto& r : summary.frames) frames_json.push_back(to_json(r));
    const nlohmann::json s = {{"scene", scene.file.string()},
                              {"vertices", summary.vertices},
                              {"elements", summary.elements},
                              {"element", to_string(mesh.kind)},
                              {"material", built.material->name()},
                              {"lame", {{"lambda", built.lame.lambda}, {"mu", built.lame.mu}}},
                              {"rest_volume", summary.rest_volume},
                              {"frames", frames_json},
                              {"all_converged", summary.all_converged()}};
    write_file_atomically(out / "summary.json", [&](std::ostream& os) { os << s.dump(2) << '\n'; });
    nlohmann::json cp = {{"scene_fingerprint", fingerprint}, {"frame", frame}, {"vertices", summary.vertices},
                         {"frames", frames_json}, {"pvd", pvd_entries}};
    cp["x"] = std::vector<double>(x.data(), x.data() + x.size());
    write_file_atomically(out / "checkpoint.json", [&](std::ostream& os) { os << cp.dump() << '\n'; });
  };

  if (first_frame == 1) {
    write_frame(0);
  }

  // ---- load stepping
  for (int frame = first_frame; frame <= frames; ++frame) {
    const auto t_frame = Clock::now();
    FrameRecord record;
    record.frame = frame;
    if (options.progress) options.progress({frame, frames, 0, 0.0, elapsed(), false, nullptr});
    auto newton_progress = [&](const NewtonIterate& it) {
      if (options.progress) options.progress({frame, frames, it.iteration, it.residual, elapsed(), false, nullptr});
    };
    // Solve at the frame's boundary positions; if the jump is too large (invalid start or no
    // convergence), split the motion since the last solved state into halves.
    double solved = frame - 1.0;
    int splits = 0;
    double step = 1.0;
    while (solved < frame) {
      const double target = std::min<double>(frame, solved + step);
      Eigen::VectorXd trial = x;
      std::vector<char> fixed(trial.size(), 0);
      apply_kinematics(kinematics, mesh.vertices, target, trial, fixed);
      problem.set_fixed(fixed);
      const NewtonReport r = newton_solve(problem, trial, *linear, scene.solver.newton, newton_progress);
      record.newton_iterations += r.iterations;
      record.linear_iterations += r.linear_iterations;
      record.assembly_seconds += r.assembly_seconds;
      record.solve_seconds += r.solve_seconds;
      record.residual = r.residual;
      record.energy = r.energy;
      if (r.converged) {
        x = trial;
        solved = target;
        if (target < frame) record.substeps += 1;
      } else if (splits < 6) {
        ++splits;
        step *= 0.5;
      } else {
        x = trial;  // keep the best effort for inspection, but report it
        record.failure = r.failure;
        break;
      }
    }
    record.converged = record.failure.empty();
    const auto fields = elastic->element_fields(x);
    record.volume = 0.0;
    for (Eigen::Index e = 0; e < disc->num_elements(); ++e) record.volume += fields.J(e) * disc->rest_volume(e);
    record.min_J = fields.J.minCoeff();
    record.seconds = std::chrono::duration<double>(Clock::now() - t_frame).count();
    summary.frames.push_back(record);
    write_frame(frame);
    write_reports(frame);
    if (options.progress) options.progress({frame, frames, record.newton_iterations, record.residual, elapsed(), true, &summary.frames.back()});
  }
  summary.x = x;
  return summary;
}

}  // namespace sinew
