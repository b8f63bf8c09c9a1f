#pragma once
// A render surface as an artist made it (docs/file-formats.md, "Render surfaces"): polygons of
// any corner count (quads stay quads), per-corner texture coordinates and normals, and the
// group, object, material and smoothing state of each face. io/obj_polygon_reader.hpp reads it
// from an OBJ, io/obj_polygon_writer.hpp writes it back with deformed positions.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "sinew/mesh/triangle_surface.hpp"

namespace sinew {

struct PolygonSurface {
  struct Corner {
    int position = 0;  // row of `positions`
    int uv = -1;       // row of `uvs`, -1: none
    int normal = -1;   // row of `normals`, -1: none
  };
  Eigen::MatrixX3d positions;
  Eigen::MatrixX2d uvs;      // "vt u v" (a third coordinate is dropped)
  Eigen::MatrixX3d normals;  // "vn", as read (not necessarily unit length)
  std::vector<Corner> corners;
  std::vector<int> face_start;  // face f owns corners [face_start[f], face_start[f + 1]); size faces + 1
  // Per face: index into the name lists below, -1 for none.
  std::vector<int> face_group, face_object, face_material;
  std::vector<int> face_smoothing;  // smoothing group ("s N"), 0 for off
  std::vector<std::string> groups, objects, materials;
  std::vector<std::string> material_libraries;  // "mtllib" file names as written (relative to the OBJ)

  PolygonSurface() : face_start{0} {}
  Eigen::Index num_positions() const { return positions.rows(); }
  Eigen::Index num_faces() const { return static_cast<Eigen::Index>(face_start.size()) - 1; }
  int face_size(Eigen::Index f) const { return face_start[f + 1] - face_start[f]; }

  // Appends a face (at least three corners) with the given state indices.
  void add_face(const std::vector<Corner>& face, int group = -1, int object = -1, int material = -1, int smoothing = 0);

  // Fan triangulation of every face over `positions` (for embedding, inside tests, PLY output).
  TriangleSurface triangulated() const;

  // Area-weighted normal of every face at `at` (rows like `positions`), by Newell's method, so
  // non-planar quads get their average normal; zero for a degenerate face.
  Eigen::MatrixX3d face_normals(const Eigen::MatrixX3d& at) const;

  // Positions no face uses; readers keep them, but Blender's OBJ importer drops them, so a
  // point cache must leave them out (io/point_cache.hpp).
  std::vector<int> unused_positions() const;

  // Rejects (sinew::Error naming `source`): non-finite values, a face with fewer than three
  // corners, an index out of range, or per-face lists of the wrong length.
  void validate(const std::string& source) const;
};

// The same surface with only the positions `keep` (sorted, each used position at most once;
// every position a face uses must be kept), renumbered in `keep` order.
PolygonSurface keep_positions(const PolygonSurface& surface, const std::vector<int>& keep);

}  // namespace sinew
