#include "sinew/run/run_summary.hpp"

#include "sinew/io/atomic_file.hpp"

namespace sinew {
namespace {

nlohmann::json vec_json(const Eigen::Vector3d& v) { return {v(0), v(1), v(2)}; }

}  // namespace

nlohmann::json frame_to_json(const FrameRecord& r) {
  nlohmann::json reactions = nlohmann::json::array();
  for (const auto& f : r.reactions) reactions.push_back(vec_json(f));
  nlohmann::json counters = nlohmann::json::object();
  for (const auto& c : r.counters) counters[c.name] = c.value;
  return {{"frame", r.frame},
          {"time", r.time},
          {"converged", r.converged},
          {"newton_iterations", r.newton_iterations},
          {"linear_iterations", r.linear_iterations},
          {"substeps", r.substeps},
          {"residual", r.residual},
          {"residuals", r.residuals},
          {"force_scale", r.force_scale},
          {"energy", r.energy},
          {"volume", r.volume},
          {"min_J", r.min_J},
          {"reactions", reactions},
          {"external_force", vec_json(r.external_force)},
          {"kinetic_energy", r.kinetic_energy},
          {"potential_energy", r.potential_energy},
          {"contacts", r.contacts},
          {"max_penetration", r.max_penetration},
          {"self_contacts", r.self_contacts},
          {"self_penetration", r.self_penetration},
          {"seconds", r.seconds},
          {"assembly_seconds", r.assembly_seconds},
          {"solve_seconds", r.solve_seconds},
          {"counters", counters},
          {"failure", r.failure}};
}

FrameRecord frame_from_json(const nlohmann::json& j) {
  FrameRecord r;
  r.frame = j.at("frame");
  r.time = j.at("time");
  r.converged = j.at("converged");
  r.newton_iterations = j.at("newton_iterations");
  r.linear_iterations = j.at("linear_iterations");
  r.substeps = j.at("substeps");
  r.residual = j.at("residual");
  if (j.contains("residuals")) r.residuals = j.at("residuals").get<std::vector<double>>();  // older checkpoints lack it
  r.force_scale = j.value("force_scale", 0.0);
  r.energy = j.at("energy");
  r.volume = j.at("volume");
  r.min_J = j.at("min_J");
  for (const auto& f : j.at("reactions")) r.reactions.emplace_back(f.at(0), f.at(1), f.at(2));
  if (j.contains("external_force")) {
    const auto& f = j.at("external_force");
    r.external_force = Eigen::Vector3d(f.at(0), f.at(1), f.at(2));
  }
  r.kinetic_energy = j.at("kinetic_energy");
  r.potential_energy = j.at("potential_energy");
  r.contacts = j.at("contacts");
  r.max_penetration = j.at("max_penetration");
  r.self_contacts = j.at("self_contacts");
  r.self_penetration = j.at("self_penetration");
  r.seconds = j.at("seconds");
  r.assembly_seconds = j.at("assembly_seconds");
  r.solve_seconds = j.at("solve_seconds");
  // Stored by name: a counter named max_* is a maximum (StepStats::Counter).
  for (const auto& [name, value] : j.at("counters").items())
    r.counters.push_back({name, value.get<double>(), name.rfind("max_", 0) == 0});
  r.failure = j.at("failure");
  return r;
}

void write_summary(const std::filesystem::path& out, const Scene& scene, const Model& model,
                   const RunSummary& summary, int frames_requested) {
  int newton = 0, linear = 0;
  StepStats totals;
  for (const auto& r : summary.frames) {
    newton += r.newton_iterations;
    linear += r.linear_iterations;
    for (const auto& c : r.counters)
      if (!c.maximum) totals.add_counter(c.name, c.value);
  }
  nlohmann::json boundary_names = nlohmann::json::array();
  for (const auto& b : scene.boundary) boundary_names.push_back(b.name);
  nlohmann::json frames = nlohmann::json::array();
  for (const auto& r : summary.frames) frames.push_back(frame_to_json(r));
  nlohmann::json total_counters = nlohmann::json::object();
  for (const auto& c : totals.counters) total_counters[c.name] = c.value;
  const Integrator& integrator = *model.integrator;
  nlohmann::json s = {{"scene", scene.file.string()},
                      {"description", scene.description},
                      {"integrator", integrator.name()},
                      {"integrator_description", integrator.description()},
                      {"frame_duration", integrator.frame_duration()},
                      {"elastic_model", model.elastic->name()},
                      {"vertices", summary.vertices},
                      {"elements", summary.elements},
                      {"element", to_string(model.disc->mesh().kind)},
                      {"material", model.material.material->name()},
                      {"lame", {{"lambda", model.material.lame.lambda}, {"mu", model.material.lame.mu}}},
                      {"density", scene.density},
                      {"rest_volume", summary.rest_volume},
                      {"external_force", vec_json(summary.external_force)},
                      {"boundary", boundary_names},
                      {"convergence_test", integrator.convergence_test()},
                      {"warnings", summary.warnings},
                      {"energy_limit", model.energy_limit ? nlohmann::json(model.energy_limit->max_energy) : nlohmann::json()},
                      {"frames_requested", frames_requested},
                      {"frames_completed", static_cast<int>(summary.frames.size())},
                      {"total_newton_iterations", newton},
                      {"total_linear_iterations", linear},
                      {"total_counters", total_counters},
                      {"all_converged", summary.all_converged()},
                      {"frames", frames}};
  write_file_atomically(out / "summary.json", [&](std::ostream& os) { os << s.dump(2) << '\n'; });
}

}  // namespace sinew
