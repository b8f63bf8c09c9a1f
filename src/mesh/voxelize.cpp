#include "sinew/mesh/voxelize.hpp"

#include <array>
#include <cmath>
#include <fmt/format.h>
#include <vector>

#include "sinew/core/error.hpp"
#include "sinew/mesh/lattice.hpp"

namespace sinew {
namespace {

// Corner a (VTK_HEXAHEDRON order) of a cell as offsets along x, y, z.
constexpr std::array<std::array<int, 3>, 8> kCorner = {
    {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}};

}  // namespace

double voxel_cell_size(const Eigen::AlignedBox3d& bounds, const VoxelizeOptions& options) {
  if (options.cell_size.has_value() == options.resolution.has_value())
    throw Error("give exactly one of cell_size or resolution", "voxelize");
  if (options.cell_size) {
    if (!(*options.cell_size > 0.0 && std::isfinite(*options.cell_size)))
      throw Error(fmt::format("cell_size must be a positive finite number, got {}", *options.cell_size), "voxelize");
    return *options.cell_size;
  }
  if (*options.resolution < 1) throw Error(fmt::format("resolution must be at least 1, got {}", *options.resolution), "voxelize");
  return bounds.sizes().maxCoeff() / *options.resolution;
}

VolumeMesh voxelize_surface(const InsideTest& shape, const VoxelizeOptions& options) {
  Eigen::AlignedBox3d bounds = shape.bounds();
  const double h = voxel_cell_size(bounds, options);
  if (options.grid_origin) {
    const Eigen::Vector3d& o = *options.grid_origin;
    if (!o.allFinite()) throw Error("grid_origin must be finite", "voxelize");
    // Snap the lattice's start down onto the grid through o (a hair of tolerance, so a bound
    // already on a grid plane stays there).
    const Eigen::Vector3d steps = ((bounds.min() - o) / h).array() + 1e-9;
    bounds.min() = o + h * steps.array().floor().matrix();
  }
  const Eigen::Vector3i cells = lattice_cell_counts(bounds.sizes(), h, /*ceil=*/true, "voxelize");
  const Eigen::Vector3d origin = bounds.min();
  auto cell_id = [&](int i, int j, int k) { return (static_cast<Eigen::Index>(k) * cells(1) + j) * cells(0) + i; };
  // Crossing test on a box shrunk by a hair: a cell that only touches the surface along its own
  // boundary (a lattice-aligned face of a cube) is not crossing it.
  const double shrink = 1e-7 * h;
  std::vector<char> kept(static_cast<size_t>(cells.prod()), 0);
  for (int k = 0; k < cells(2); ++k)
    for (int j = 0; j < cells(1); ++j)
      for (int i = 0; i < cells(0); ++i) {
        const Eigen::Vector3d lo = origin + h * Eigen::Vector3d(i, j, k);
        const Eigen::Vector3d hi = lo + Eigen::Vector3d::Constant(h);
        bool keep = shape.inside(0.5 * (lo + hi));
        if (!keep && options.keep_crossing)
          keep = shape.intersects(Eigen::AlignedBox3d(lo.array() + shrink, hi.array() - shrink));
        kept[cell_id(i, j, k)] = keep;
      }

  // Vertex copies. Grid vertex (i, j, k) has up to 8 cells around it (offset d in {0,1}^3 is
  // the cell (i - 1, j - 1, k - 1) + d); without the non-manifold option all of them share one
  // copy, with it each face-connected group (offsets differing in one bit share a face) gets
  // its own. Groups are recomputed when the elements are built, so only the first copy's index
  // is stored per grid vertex (4 bytes, not 8 per cell around it).
  const Eigen::Vector3i nv = cells.array() + 1;
  auto vertex_id = [&](int i, int j, int k) { return (static_cast<Eigen::Index>(k) * nv(1) + j) * nv(0) + i; };
  // group[d] for the kept cells around the vertex (-1: no kept cell there); returns the count.
  auto groups_at = [&](int i, int j, int k, std::array<int, 8>& group) {
    std::array<bool, 8> present{};
    for (int d = 0; d < 8; ++d) {
      const int ci = i - 1 + (d & 1), cj = j - 1 + ((d >> 1) & 1), ck = k - 1 + ((d >> 2) & 1);
      present[d] = ci >= 0 && cj >= 0 && ck >= 0 && ci < cells(0) && cj < cells(1) && ck < cells(2) &&
                   kept[cell_id(ci, cj, ck)];
    }
    group.fill(-1);
    int groups = 0;
    for (int d = 0; d < 8; ++d) {
      if (!present[d] || group[d] >= 0) continue;
      std::array<int, 8> stack{};  // flood fill; each cell is pushed once
      int top = 0;
      stack[top++] = d;
      group[d] = groups;
      while (top > 0) {
        const int c = stack[--top];
        for (int e = 0; e < 8; ++e) {
          if (!present[e] || group[e] >= 0) continue;
          const int diff = c ^ e;
          const bool face_neighbour = diff == 1 || diff == 2 || diff == 4;
          if (!options.non_manifold || face_neighbour) group[e] = groups, stack[top++] = e;
        }
      }
      ++groups;
    }
    return groups;
  };
  std::vector<int> first_copy(static_cast<size_t>(nv.prod()), -1);
  std::vector<Eigen::Vector3d> positions;
  std::vector<std::array<int, 4>> points;  // grid point and copy of each vertex (the lattice structure)
  std::array<int, 8> group;
  for (int k = 0; k < nv(2); ++k)
    for (int j = 0; j < nv(1); ++j)
      for (int i = 0; i < nv(0); ++i) {
        const int groups = groups_at(i, j, k, group);
        if (groups == 0) continue;
        first_copy[vertex_id(i, j, k)] = static_cast<int>(positions.size());
        for (int n = 0; n < groups; ++n) {
          positions.push_back(origin + h * Eigen::Vector3d(i, j, k));
          points.push_back({i, j, k, n});
        }
      }

  std::vector<std::array<int, 8>> elements;
  std::vector<Eigen::Vector3i> element_cells;
  for (int k = 0; k < cells(2); ++k)
    for (int j = 0; j < cells(1); ++j)
      for (int i = 0; i < cells(0); ++i) {
        if (!kept[cell_id(i, j, k)]) continue;
        element_cells.emplace_back(i, j, k);
        std::array<int, 8> e;
        for (int a = 0; a < 8; ++a) {
          const auto& c = kCorner[a];
          groups_at(i + c[0], j + c[1], k + c[2], group);
          // Seen from the vertex, this cell sits at offset 1 - c along each axis.
          const int d = (1 - c[0]) | ((1 - c[1]) << 1) | ((1 - c[2]) << 2);
          e[a] = first_copy[vertex_id(i + c[0], j + c[1], k + c[2])] + group[d];
        }
        elements.push_back(e);
      }
  if (elements.empty()) throw Error("no lattice cell lies inside or crosses the surface", "voxelize");
  VolumeMesh mesh;
  mesh.kind = ElementKind::Hex8;
  mesh.vertices.resize(static_cast<Eigen::Index>(positions.size()), 3);
  for (size_t v = 0; v < positions.size(); ++v) mesh.vertices.row(static_cast<Eigen::Index>(v)) = positions[v].transpose();
  mesh.elements.resize(static_cast<Eigen::Index>(elements.size()), 8);
  for (size_t e = 0; e < elements.size(); ++e)
    for (int a = 0; a < 8; ++a) mesh.elements(static_cast<Eigen::Index>(e), a) = elements[e][a];
  LatticeStructure grid;
  grid.cells = cells;
  grid.origin = origin;
  grid.spacing = Eigen::Vector3d::Constant(h);
  grid.non_manifold = options.non_manifold;
  grid.vertex_point.resize(mesh.num_vertices(), 3);
  grid.vertex_copy.resize(mesh.num_vertices());
  for (size_t v = 0; v < points.size(); ++v) {
    const auto r = static_cast<Eigen::Index>(v);
    grid.vertex_point.row(r) = Eigen::RowVector3i(points[v][0], points[v][1], points[v][2]);
    grid.vertex_copy(r) = points[v][3];
  }
  grid.element_cell.resize(mesh.num_elements(), 3);
  for (size_t e = 0; e < element_cells.size(); ++e) grid.element_cell.row(static_cast<Eigen::Index>(e)) = element_cells[e].transpose();
  mesh.lattice = std::move(grid);
  return mesh;
}

}  // namespace sinew
