#include "sinew/run/selection_output.hpp"

#include <fmt/format.h>

#include "sinew/io/atomic_file.hpp"

namespace sinew {

nlohmann::json selections_json(const Scene& scene, const Model& model) {
  const VolumeMesh& mesh = model.disc->mesh();
  const std::string file = scene.file.string();
  auto selected = [&](const VertexSelector& s, const std::string& path) {
    return select_vertices(mesh, s, file + ": " + path + "/select");
  };
  nlohmann::json boundary = nlohmann::json::array(), loads = nlohmann::json::array();
  for (size_t i = 0; i < scene.boundary.size(); ++i) {
    const std::string path = fmt::format("/boundary/{}", i);
    boundary.push_back({{"name", scene.boundary[i].name}, {"path", path}, {"vertices", selected(scene.boundary[i].select, path)}});
  }
  for (size_t i = 0; i < scene.point_loads.size(); ++i) {
    const std::string path = fmt::format("/loads/point/{}", i);
    loads.push_back({{"path", path}, {"vertices", selected(scene.point_loads[i].select, path)}});
  }
  auto face_load = [&](const VertexSelector& s, const std::string& path) {
    const std::vector<int> v = selected(s, path);
    loads.push_back({{"path", path}, {"vertices", v}, {"faces", faces_within(model.surface, v, mesh.num_vertices())}});
  };
  for (size_t i = 0; i < scene.tractions.size(); ++i) face_load(scene.tractions[i].select, fmt::format("/loads/traction/{}", i));
  for (size_t i = 0; i < scene.pressures.size(); ++i) face_load(scene.pressures[i].select, fmt::format("/loads/pressure/{}", i));
  return {{"boundary", boundary}, {"loads", loads}};
}

void write_selections(const std::filesystem::path& path, const Scene& scene, const Model& model) {
  const nlohmann::json j = selections_json(scene, model);
  write_file_atomically(path, [&](std::ostream& os) { os << j.dump(1) << '\n'; });
}

}  // namespace sinew
