#pragma once
// Simulation output for ParaView: the deformed volume mesh as a VTK XML UnstructuredGrid
// (.vtu, inline base64 binary) and a ParaView collection (.pvd) that puts frames on a time
// axis. Every file is written through write_file_atomically.
#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "sinew/mesh/polygon_surface.hpp"
#include "sinew/mesh/triangle_surface.hpp"
#include "sinew/mesh/volume_mesh.hpp"

namespace sinew {

// An array of `components` values per vertex or element, flattened entity by entity:
// values[components * i + k]. Tensors have 9 components in row-major order (ParaView reads a
// 9-component array as a tensor and offers its eigenvalues, norm, ...).
struct VtuArray {
  std::string name;
  int components = 1;
  Eigen::VectorXd values;
};

// Named arrays written next to the mesh, in the order given.
struct VtuFields {
  // Per-vertex 3-vectors, flattened like positions: v[3 i + k] (size 3 * vertices).
  std::vector<std::pair<std::string, Eigen::VectorXd>> point_vectors;
  // Per-vertex scalars (size vertices).
  std::vector<std::pair<std::string, Eigen::VectorXd>> point_scalars;
  // Per-element scalars (size elements), e.g. J, energy_density, stress_norm, energy.
  std::vector<std::pair<std::string, Eigen::VectorXd>> cell_scalars;
  // Arrays with any number of components, written after the ones above.
  std::vector<VtuArray> point_arrays;
  std::vector<VtuArray> cell_arrays;
};

// Writes the mesh at positions x (x[3 v + i]) with point data "displacement" = x - rest
// followed by `fields`. Points and data are Float64, connectivity and offsets Int64, cell
// types UInt8 (12 hexahedron, 10 tetra), each array base64 with a UInt32 byte-count header.
// Throws sinew::Error (naming the file and the array) on a size mismatch, an empty, repeated
// or reserved name, or an array over 4 GiB.
void write_vtu(const std::filesystem::path& path, const VolumeMesh& mesh, const Eigen::VectorXd& x,
               const VtuFields& fields = {});

// A surface (obstacle, bone, render surface) as a VTK XML UnstructuredGrid of polygon cells
// (triangle 5, quad 9, polygon 7), points Float64, no data arrays. Throws sinew::Error naming
// the file on an index out of range or a size mismatch.
void write_surface_vtu(const std::filesystem::path& path, const PolygonSurface& surface,
                       const Eigen::MatrixX3d& positions);
void write_surface_vtu(const std::filesystem::path& path, const TriangleSurface& surface);

// What the DataSet timesteps of a .pvd mean; written into the file as a comment.
enum class PvdTime {
  Unstated,
  Seconds,  // simulated time (dynamic runs)
  Frames,   // frame numbers (quasistatic runs: frames are load steps, not time)
};

// Writes a ParaView collection: one DataSet per (time, file), the file relative to the
// .pvd's directory (as ParaView resolves it). Times must be finite.
void write_pvd(const std::filesystem::path& path,
               const std::vector<std::pair<double, std::string>>& time_and_relative_file,
               PvdTime meaning = PvdTime::Unstated);

// Characters &, <, >, " and ' as XML entities (for names and attribute values).
std::string xml_escape(const std::string& text);

}  // namespace sinew
