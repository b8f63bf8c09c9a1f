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
// A mesh is all hexahedra or all tetrahedra. See docs/file-formats.md.
#include <filesystem>

#include "sinew/mesh/volume_mesh.hpp"

namespace sinew {

VolumeMesh read_volume_mesh(const std::filesystem::path& path);

// The individual readers (no validation beyond index ranges and cell kinds).
VolumeMesh read_medit_mesh(const std::filesystem::path& path);
VolumeMesh read_vtk_legacy_mesh(const std::filesystem::path& path);
VolumeMesh read_vtu_mesh(const std::filesystem::path& path);

}  // namespace sinew
