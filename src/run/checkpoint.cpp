#include "sinew/run/checkpoint.hpp"

#include <fmt/format.h>
#include <fstream>

#include "sinew/core/error.hpp"
#include "sinew/io/atomic_file.hpp"
#include "sinew/run/run_summary.hpp"

namespace sinew {
namespace {

Eigen::VectorXd read_vector(const nlohmann::json& j, const char* key, Eigen::Index dofs, const std::string& file) {
  const auto values = j.at(key).get<std::vector<double>>();
  if (static_cast<Eigen::Index>(values.size()) != dofs)
    throw Error(fmt::format("checkpoint {} has the wrong size (it belongs to a different mesh)", key), file);
  Eigen::VectorXd v = Eigen::Map<const Eigen::VectorXd>(values.data(), dofs);
  if (!v.allFinite()) throw Error(fmt::format("checkpoint {} is not finite", key), file);
  return v;
}

}  // namespace

void write_checkpoint(const std::filesystem::path& out, const std::string& scene_fingerprint,
                      const Integrator& integrator, const Checkpoint& c) {
  nlohmann::json frames = nlohmann::json::array();
  for (const auto& r : c.frames) frames.push_back(frame_to_json(r));
  nlohmann::json j = {{"format", 2},
                      {"integrator", integrator.name()},
                      {"scene_fingerprint", scene_fingerprint},
                      {"frame", c.frame},
                      {"integrator_state", c.integrator_state},
                      {"frames", frames},
                      {"pvd", c.pvd}};
  j["x"] = std::vector<double>(c.state.x.data(), c.state.x.data() + c.state.x.size());
  if (integrator.dynamic()) j["v"] = std::vector<double>(c.state.v.data(), c.state.v.data() + c.state.v.size());
  write_file_atomically(out / "checkpoint.json", [&](std::ostream& os) { os << j.dump() << '\n'; });
}

Checkpoint read_checkpoint(const std::filesystem::path& out, const std::string& scene_fingerprint,
                           const Integrator& integrator, Eigen::Index dofs) {
  const std::string file = (out / "checkpoint.json").string();
  std::ifstream in(file);
  if (!in) throw Error("no checkpoint to resume from (run without --resume first)", file);
  Checkpoint c;
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    const std::string written_by = j.contains("integrator") ? j.at("integrator").get<std::string>() : "an unknown kind";
    if (j.value("format", 0) != 2 || written_by != integrator.name())
      throw Error(fmt::format("checkpoint was written by {} run, this scene runs {} ({}); run again without --resume",
                              written_by == "an unknown kind" ? "an older or another kind of" : "a " + written_by,
                              integrator.name(), integrator.description()),
                  file);
    if (j.at("scene_fingerprint") != scene_fingerprint)
      throw Error("the scene file changed since the checkpoint was written; run again without --resume", file);
    c.state.x = read_vector(j, "x", dofs, file);
    if (integrator.dynamic()) c.state.v = read_vector(j, "v", dofs, file);
    c.integrator_state = j.at("integrator_state");
    for (const auto& f : j.at("frames")) c.frames.push_back(frame_from_json(f));
    for (const auto& p : j.at("pvd")) c.pvd.emplace_back(p.at(0).get<double>(), p.at(1).get<std::string>());
    c.frame = j.at("frame").get<int>();
  } catch (const nlohmann::json::exception& e) {
    throw Error(fmt::format("corrupt checkpoint: {}", e.what()), file);
  }
  return c;
}

}  // namespace sinew
