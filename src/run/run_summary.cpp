#include "sinew/run/run_summary.hpp"

#include <limits>

#include "json_checks.hpp"
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

FrameRecord frame_from_json(const nlohmann::json& j, const std::string& path) {
  using namespace json_checks;
  constexpr long long kMaxCount = std::numeric_limits<int>::max();
  auto at = [&](const char* key) -> const nlohmann::json& { return member(j, key, path); };
  auto count = [&](const char* key) { return static_cast<int>(integer(at(key), 0, kMaxCount, path + "/" + key)); };
  auto real = [&](const char* key) { return number(at(key), path + "/" + key); };
  FrameRecord r;
  r.frame = static_cast<int>(integer(at("frame"), 0, kMaxFrames, path + "/frame"));
  r.time = real("time");
  r.converged = boolean(at("converged"), path + "/converged");
  r.newton_iterations = count("newton_iterations");
  r.linear_iterations = count("linear_iterations");
  r.substeps = count("substeps");
  r.residual = real("residual");
  if (j.contains("residuals")) {  // older checkpoints lack it
    const nlohmann::json& list = array(at("residuals"), path + "/residuals");
    for (size_t i = 0; i < list.size(); ++i) r.residuals.push_back(number(list[i], fmt::format("{}/residuals/{}", path, i)));
  }
  r.force_scale = j.contains("force_scale") ? real("force_scale") : 0.0;
  r.energy = real("energy");
  r.volume = real("volume");
  r.min_J = real("min_J");
  const nlohmann::json& reactions = array(at("reactions"), path + "/reactions");
  for (size_t i = 0; i < reactions.size(); ++i) {
    const std::string where = fmt::format("{}/reactions/{}", path, i);
    const nlohmann::json& f = array(reactions[i], where);
    if (f.size() != 3) throw Error(fmt::format("must hold 3 numbers, got {}", f.size()), where);
    r.reactions.emplace_back(number(f[0], where + "/0"), number(f[1], where + "/1"), number(f[2], where + "/2"));
  }
  if (j.contains("external_force")) {
    const std::string where = path + "/external_force";
    const nlohmann::json& f = array(at("external_force"), where);
    if (f.size() != 3) throw Error(fmt::format("must hold 3 numbers, got {}", f.size()), where);
    r.external_force = Eigen::Vector3d(number(f[0], where + "/0"), number(f[1], where + "/1"), number(f[2], where + "/2"));
  }
  r.kinetic_energy = real("kinetic_energy");
  r.potential_energy = real("potential_energy");
  r.contacts = count("contacts");
  r.max_penetration = real("max_penetration");
  r.self_contacts = count("self_contacts");
  r.self_penetration = real("self_penetration");
  r.seconds = real("seconds");
  r.assembly_seconds = real("assembly_seconds");
  r.solve_seconds = real("solve_seconds");
  // Stored by name: a counter named max_* is a maximum (StepStats::Counter).
  const nlohmann::json& counters = at("counters");
  if (!counters.is_object()) throw Error(fmt::format("must be an object, got {}", kind(counters)), path + "/counters");
  for (const auto& [name, value] : counters.items())
    r.counters.push_back({name, number(value, path + "/counters/" + name), name.rfind("max_", 0) == 0});
  r.failure = string(at("failure"), path + "/failure");
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
