#include "sinew/mesh/surface.hpp"

#include <algorithm>
#include <array>
#include <map>

namespace sinew {
namespace {
constexpr int kHexFaces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                 {2, 3, 7, 6}, {0, 4, 7, 3}, {1, 2, 6, 5}};
constexpr int kTetFaces[4][3] = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
}  // namespace

BoundarySurface boundary_surface(const VolumeMesh& mesh) {
  const bool hex = mesh.kind == ElementKind::Hex8;
  const int faces_per = hex ? 6 : 4, nodes_per_face = hex ? 4 : 3;
  // Count each face by its sorted node set; boundary faces are seen once.
  std::map<std::array<int, 4>, std::pair<int, std::pair<Eigen::Index, int>>> count;
  for (Eigen::Index e = 0; e < mesh.num_elements(); ++e)
    for (int f = 0; f < faces_per; ++f) {
      std::array<int, 4> key{-1, -1, -1, -1};
      for (int k = 0; k < nodes_per_face; ++k) key[k] = mesh.elements(e, hex ? kHexFaces[f][k] : kTetFaces[f][k]);
      // Insertion sort (std::sort on a 4-array trips a GCC 12 -Warray-bounds false positive).
      for (int i = 1; i < nodes_per_face; ++i)
        for (int j = i; j > 0 && key[j - 1] > key[j]; --j) std::swap(key[j - 1], key[j]);
      auto& entry = count[key];
      entry.first += 1;
      entry.second = {e, f};
    }
  BoundarySurface s;
  std::vector<std::array<int, 3>> tris;
  for (const auto& [key, entry] : count) {
    if (entry.first != 1) continue;
    const auto [e, f] = entry.second;
    std::vector<int> face(nodes_per_face);
    for (int k = 0; k < nodes_per_face; ++k) face[k] = mesh.elements(e, hex ? kHexFaces[f][k] : kTetFaces[f][k]);
    tris.push_back({face[0], face[1], face[2]});
    if (hex) tris.push_back({face[0], face[2], face[3]});
    s.vertices.insert(s.vertices.end(), face.begin(), face.end());
    s.faces.push_back(std::move(face));
    s.face_element.push_back(e);
  }
  std::sort(s.vertices.begin(), s.vertices.end());
  s.vertices.erase(std::unique(s.vertices.begin(), s.vertices.end()), s.vertices.end());
  s.triangles.resize(static_cast<Eigen::Index>(tris.size()), 3);
  for (size_t t = 0; t < tris.size(); ++t)
    for (int k = 0; k < 3; ++k) s.triangles(t, k) = tris[t][k];
  return s;
}

std::vector<std::vector<int>> faces_within(const BoundarySurface& surface, const std::vector<int>& selected,
                                           Eigen::Index num_vertices) {
  std::vector<char> in(static_cast<std::size_t>(num_vertices), 0);
  for (int v : selected)
    if (v >= 0 && v < num_vertices) in[static_cast<std::size_t>(v)] = 1;
  std::vector<std::vector<int>> out;
  for (const auto& face : surface.faces)
    if (std::all_of(face.begin(), face.end(), [&](int v) { return in[static_cast<std::size_t>(v)] != 0; }))
      out.push_back(face);
  return out;
}

}  // namespace sinew
