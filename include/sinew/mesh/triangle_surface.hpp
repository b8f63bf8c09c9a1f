#pragma once
// A triangle surface in plain Eigen types (what the surface readers return, what voxelisation,
// tetrahedralisation and embedding take), with the checks a closed surface must pass.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>

namespace sinew {

struct TriangleSurface {
  Eigen::MatrixX3d vertices;  // one row per vertex
  Eigen::MatrixX3i faces;     // 0-based vertex indices, counter-clockwise seen from outside

  Eigen::Index num_vertices() const { return vertices.rows(); }
  Eigen::Index num_faces() const { return faces.rows(); }

  // Rejects (sinew::Error naming `source` and the first bad vertex, face or edge): no faces,
  // non-finite coordinates, out-of-range indices, degenerate faces (a repeated vertex or zero
  // area), and, when `require_closed`, an open surface (an edge without a partner face),
  // inconsistent orientation (an edge used more often in one direction than the other) or a
  // negative enclosed volume (inside out). Edges shared by four or more faces are accepted:
  // a surface of two solids touching along an edge is closed but not manifold.
  void validate(const std::string& source, bool require_closed = true) const;

  // Enclosed volume by the divergence theorem (positive for an outward closed surface).
  double volume() const;
  Eigen::AlignedBox3d bounds() const;
};

// Edge statistics of a surface. An edge is an unordered vertex pair.
struct SurfaceTopology {
  Eigen::Index edges = 0;
  Eigen::Index boundary_edges = 0;     // in one face only
  Eigen::Index nonmanifold_edges = 0;  // in three or more faces
  Eigen::Index unbalanced_edges = 0;   // used more often in one direction than the other
  bool closed() const { return boundary_edges == 0 && unbalanced_edges == 0; }
  // Watertight 2-manifold: every edge in exactly two faces, oppositely oriented.
  bool watertight() const { return closed() && nonmanifold_edges == 0; }
};
SurfaceTopology surface_topology(const TriangleSurface& surface);

}  // namespace sinew
