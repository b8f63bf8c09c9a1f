#include "sinew/mesh/polygon_surface.hpp"

#include <fmt/format.h>

#include "sinew/core/error.hpp"

namespace sinew {

void PolygonSurface::add_face(const std::vector<Corner>& face, int group, int object, int material, int smoothing) {
  if (face.size() < 3) throw Error(fmt::format("a face needs at least 3 corners, got {}", face.size()));
  corners.insert(corners.end(), face.begin(), face.end());
  face_start.push_back(static_cast<int>(corners.size()));
  face_group.push_back(group);
  face_object.push_back(object);
  face_material.push_back(material);
  face_smoothing.push_back(smoothing);
}

TriangleSurface PolygonSurface::triangulated() const {
  Eigen::Index triangles = 0;
  for (Eigen::Index f = 0; f < num_faces(); ++f) triangles += face_size(f) - 2;
  TriangleSurface t;
  t.vertices = positions;
  t.faces.resize(triangles, 3);
  Eigen::Index row = 0;
  for (Eigen::Index f = 0; f < num_faces(); ++f) {
    const int s = face_start[f];
    for (int k = 1; k + 1 < face_size(f); ++k)
      t.faces.row(row++) << corners[s].position, corners[s + k].position, corners[s + k + 1].position;
  }
  return t;
}

Eigen::MatrixX3d PolygonSurface::face_normals(const Eigen::MatrixX3d& at) const {
  Eigen::MatrixX3d n = Eigen::MatrixX3d::Zero(num_faces(), 3);
  for (Eigen::Index f = 0; f < num_faces(); ++f) {
    const int s = face_start[f], size = face_size(f);
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int k = 0; k < size; ++k) {
      const Eigen::Vector3d a = at.row(corners[s + k].position), b = at.row(corners[s + (k + 1) % size].position);
      sum += a.cross(b);  // Newell: twice the vector area of the polygon
    }
    n.row(f) = 0.5 * sum.transpose();
  }
  return n;
}

std::vector<int> PolygonSurface::unused_positions() const {
  std::vector<char> used(static_cast<size_t>(positions.rows()), 0);
  for (const Corner& c : corners) used[static_cast<size_t>(c.position)] = 1;
  std::vector<int> unused;
  for (size_t v = 0; v < used.size(); ++v)
    if (!used[v]) unused.push_back(static_cast<int>(v));
  return unused;
}

void PolygonSurface::validate(const std::string& source) const {
  const auto faces = static_cast<size_t>(num_faces());
  if (face_start.empty() || face_start.front() != 0 || face_start.back() != static_cast<int>(corners.size()))
    throw Error("face offsets do not cover the corners", source);
  if (face_group.size() != faces || face_object.size() != faces || face_material.size() != faces ||
      face_smoothing.size() != faces)
    throw Error("per-face group/object/material/smoothing lists do not match the face count", source);
  if (!positions.allFinite()) throw Error("a vertex position is not finite", source);
  if (!uvs.allFinite()) throw Error("a texture coordinate is not finite", source);
  if (!normals.allFinite()) throw Error("a normal is not finite", source);
  auto check = [&](int index, Eigen::Index count, const char* what, size_t f) {
    if (index < -1 || index >= count)
      throw Error(fmt::format("face {} uses {} {} (there are {})", f, what, index, count), source);
  };
  for (size_t f = 0; f < faces; ++f) {
    if (face_size(static_cast<Eigen::Index>(f)) < 3)
      throw Error(fmt::format("face {} has {} corners (at least 3)", f, face_size(static_cast<Eigen::Index>(f))), source);
    for (int c = face_start[f]; c < face_start[f + 1]; ++c) {
      if (corners[c].position < 0) throw Error(fmt::format("face {} has a corner without a position", f), source);
      check(corners[c].position, positions.rows(), "vertex", f);
      check(corners[c].uv, uvs.rows(), "texture coordinate", f);
      check(corners[c].normal, normals.rows(), "normal", f);
    }
    check(face_group[f], static_cast<Eigen::Index>(groups.size()), "group", f);
    check(face_object[f], static_cast<Eigen::Index>(objects.size()), "object", f);
    check(face_material[f], static_cast<Eigen::Index>(materials.size()), "material", f);
  }
}

PolygonSurface keep_positions(const PolygonSurface& surface, const std::vector<int>& keep) {
  std::vector<int> renumber(static_cast<size_t>(surface.positions.rows()), -1);
  PolygonSurface out = surface;
  out.positions.resize(static_cast<Eigen::Index>(keep.size()), 3);
  for (size_t i = 0; i < keep.size(); ++i) {
    const int v = keep[i];
    if (v < 0 || v >= surface.positions.rows() || renumber[static_cast<size_t>(v)] >= 0)
      throw Error(fmt::format("position {} cannot be kept (out of range or repeated)", v));
    renumber[static_cast<size_t>(v)] = static_cast<int>(i);
    out.positions.row(static_cast<Eigen::Index>(i)) = surface.positions.row(v);
  }
  for (auto& c : out.corners) {
    const int r = renumber[static_cast<size_t>(c.position)];
    if (r < 0) throw Error(fmt::format("position {} is used by a face but not kept", c.position));
    c.position = r;
  }
  return out;
}

}  // namespace sinew
