#include "sinew/mesh/triangle_surface.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <map>
#include <utility>

#include "sinew/core/error.hpp"

namespace sinew {
namespace {

// Per unordered edge (lo, hi): faces using it as lo->hi and as hi->lo, and the first face.
struct EdgeUse {
  int forward = 0, backward = 0;
  Eigen::Index first_face = 0;
};

std::map<std::pair<int, int>, EdgeUse> edge_uses(const TriangleSurface& s) {
  std::map<std::pair<int, int>, EdgeUse> uses;
  for (Eigen::Index f = 0; f < s.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = s.faces(f, k), b = s.faces(f, (k + 1) % 3);
      auto [it, fresh] = uses.try_emplace({std::min(a, b), std::max(a, b)});
      if (fresh) it->second.first_face = f;
      (a < b ? it->second.forward : it->second.backward) += 1;
    }
  return uses;
}

}  // namespace

double TriangleSurface::volume() const {
  double six_v = 0.0;
  for (Eigen::Index f = 0; f < num_faces(); ++f) {
    const Eigen::Vector3d a = vertices.row(faces(f, 0)), b = vertices.row(faces(f, 1)), c = vertices.row(faces(f, 2));
    six_v += a.dot(b.cross(c));
  }
  return six_v / 6.0;
}

Eigen::AlignedBox3d TriangleSurface::bounds() const {
  Eigen::AlignedBox3d box;
  for (Eigen::Index v = 0; v < num_vertices(); ++v) box.extend(Eigen::Vector3d(vertices.row(v)));
  return box;
}

SurfaceTopology surface_topology(const TriangleSurface& surface) {
  SurfaceTopology t;
  for (const auto& [edge, use] : edge_uses(surface)) {
    ++t.edges;
    const int n = use.forward + use.backward;
    if (n == 1) ++t.boundary_edges;
    if (n >= 3) ++t.nonmanifold_edges;
    if (use.forward != use.backward) ++t.unbalanced_edges;
  }
  return t;
}

void TriangleSurface::validate(const std::string& source, bool require_closed) const {
  if (num_faces() == 0) throw Error("surface has no faces", source);
  for (Eigen::Index v = 0; v < num_vertices(); ++v)
    if (!vertices.row(v).allFinite()) throw Error(fmt::format("vertex {} has a non-finite coordinate", v), source);
  // Degenerate means an area below a relative floor: the squared length scale of the bounding box.
  const double scale = bounds().sizes().squaredNorm();
  for (Eigen::Index f = 0; f < num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int v = faces(f, k);
      if (v < 0 || v >= num_vertices())
        throw Error(fmt::format("face {} refers to vertex {} (surface has {} vertices)", f, v, num_vertices()), source);
    }
    if (faces(f, 0) == faces(f, 1) || faces(f, 1) == faces(f, 2) || faces(f, 0) == faces(f, 2))
      throw Error(fmt::format("face {} is degenerate: it repeats a vertex ({} {} {})", f, faces(f, 0), faces(f, 1),
                              faces(f, 2)),
                  source);
    const Eigen::Vector3d a = vertices.row(faces(f, 0)), b = vertices.row(faces(f, 1)), c = vertices.row(faces(f, 2));
    const double twice_area = (b - a).cross(c - a).norm();
    if (!(twice_area > 1e-14 * scale))
      throw Error(fmt::format("face {} is degenerate: zero area (vertices {} {} {})", f, faces(f, 0), faces(f, 1),
                              faces(f, 2)),
                  source);
  }
  if (!require_closed) return;
  // The first bad edge in face order, so the message points at the earliest face involved.
  const auto uses = edge_uses(*this);
  const std::pair<int, int>* worst = nullptr;
  Eigen::Index worst_face = num_faces();
  for (const auto& [edge, use] : uses)
    if ((use.forward + use.backward == 1 || use.forward != use.backward) && use.first_face < worst_face) {
      worst = &edge, worst_face = use.first_face;
    }
  if (worst) {
    const EdgeUse& use = uses.at(*worst);
    if (use.forward + use.backward == 1)
      throw Error(fmt::format("surface is not closed: edge ({}, {}) of face {} belongs to no other face", worst->first,
                              worst->second, worst_face),
                  source);
    throw Error(fmt::format("surface is not consistently oriented: edge ({}, {}) of face {} is used {} times in one "
                            "direction and {} in the other",
                            worst->first, worst->second, worst_face, use.forward, use.backward),
                source);
  }
  const double v = volume();
  if (!(v > 0.0))
    throw Error(fmt::format("surface encloses a non-positive volume ({:.6g}): its faces point inwards", v), source);
}

}  // namespace sinew
