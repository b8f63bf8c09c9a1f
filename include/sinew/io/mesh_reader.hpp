#pragma once
// Volume mesh input. read_volume_mesh picks the reader by extension (case-insensitive) and
// validates the result with VolumeMesh::validate; every problem is a sinew::Error whose
// context names the file and, where there is one, the line or the XML array.
//
//   .mesh  MEDIT ASCII: Vertices + Hexahedra (or Hexaedra) or Tetrahedra, 1-based indices;
//          boundary sections (Edges, Triangles, Quadrilaterals, Corners, ...) are skipped.
//   .vtk   legacy VTK ASCII UNSTRUCTURED_GRID, file versions up to 4.2 (CELLS count lists)
//          and 5.1 (OFFSETS/CONNECTIVITY); cell types 12 (hexahedron) and 10 (tetra).
//   .vtu   VTK XML UnstructuredGrid, one Piece, inline DataArrays in ascii or base64 binary
//          (UInt32 or UInt64 headers, either byte order); appended or compressed data is
//          rejected as unsupported.
//   .msh   Gmsh ASCII, versions 2.2 and 4.1; tetrahedra (type 4) or hexahedra (type 5), other
//          element types (the boundary's triangles, lines, points) skipped.
//   .node/.ele  TetGen: either name reads both files (same stem), 0- or 1-based.
// A mesh is all hexahedra or all tetrahedra. Inverted elements are rejected with their index
// unless `reorient_inverted` renumbers them (sinew/element/reorient.hpp). See docs/file-formats.md.
#include <filesystem>

#include "sinew/mesh/volume_mesh.hpp"

namespace sinew {

struct MeshReadOptions {
  bool reorient_inverted = false;
};
VolumeMesh read_volume_mesh(const std::filesystem::path& path, const MeshReadOptions& options = {});

// The individual readers (no validation beyond index ranges and cell kinds).
VolumeMesh read_medit_mesh(const std::filesystem::path& path);
VolumeMesh read_vtk_legacy_mesh(const std::filesystem::path& path);
VolumeMesh read_vtu_mesh(const std::filesystem::path& path);
VolumeMesh read_gmsh_mesh(const std::filesystem::path& path);
VolumeMesh read_tetgen_mesh(const std::filesystem::path& path);  // path: the .node or the .ele

}  // namespace sinew
