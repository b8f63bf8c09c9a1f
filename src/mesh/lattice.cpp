#include "sinew/mesh/lattice.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <vector>

#include "sinew/core/error.hpp"

namespace sinew {

void check_lattice_cells(const Eigen::Vector3i& cells, const std::string& where) {
  if ((cells.array() <= 0).any())
    throw Error(fmt::format("cell counts must be positive, got ({}, {}, {})", cells(0), cells(1), cells(2)), where);
  std::int64_t total = 1;
  for (int i = 0; i < 3; ++i) {
    total *= cells(i);  // each factor <= INT_MAX and the running product <= the limit: no overflow
    if (total > kMaxLatticeCells)
      throw Error(fmt::format("would make {:.3g} cells ({} x {} x {}; the limit is {})",
                              double(cells(0)) * double(cells(1)) * double(cells(2)), cells(0), cells(1), cells(2),
                              kMaxLatticeCells),
                  where);
  }
}

Eigen::Vector3i lattice_cell_counts(const Eigen::Vector3d& size, double h, bool ceil, const std::string& where) {
  if (!(h > 0.0 && std::isfinite(h))) throw Error(fmt::format("the cell size must be positive and finite, got {}", h), where);
  Eigen::Vector3d counts;
  for (int i = 0; i < 3; ++i) {
    const double r = size(i) / h;
    counts(i) = std::max(1.0, ceil ? std::ceil(r - 1e-9) : std::round(r));
  }
  const double total = counts.prod();
  if (!(total <= double(kMaxLatticeCells)))  // also catches inf and NaN
    throw Error(fmt::format("the lattice would have {:.3g} cells ({:.3g} x {:.3g} x {:.3g} at cell size {:.3g}; the "
                            "limit is {}); use a larger cell size",
                            total, counts(0), counts(1), counts(2), h, kMaxLatticeCells),
                where);
  return counts.cast<int>();  // each count <= the limit: exact
}

VolumeMesh box_lattice(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, const Eigen::Vector3i& cells) {
  return occupancy_lattice(Eigen::AlignedBox3d(lo, hi), cells, [](const Eigen::Vector3d&) { return true; });
}

VolumeMesh occupancy_lattice(const Eigen::AlignedBox3d& bounds, const Eigen::Vector3i& cells,
                             const std::function<bool(const Eigen::Vector3d&)>& inside) {
  check_lattice_cells(cells, "lattice");
  if (!((bounds.max() - bounds.min()).array() > 0.0).all()) throw Error("empty bounding box", "lattice");
  const Eigen::Vector3d h = (bounds.max() - bounds.min()).cwiseQuotient(cells.cast<double>());
  const Eigen::Vector3i nv = cells.array() + 1;
  auto grid_index = [&](int i, int j, int k) {
    return (static_cast<Eigen::Index>(k) * nv(1) + j) * nv(0) + i;
  };
  std::vector<std::array<Eigen::Index, 8>> kept;
  for (int k = 0; k < cells(2); ++k)
    for (int j = 0; j < cells(1); ++j)
      for (int i = 0; i < cells(0); ++i) {
        const Eigen::Vector3d c = bounds.min() + h.cwiseProduct(Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5));
        if (!inside(c)) continue;
        // VTK_HEXAHEDRON order: bottom face counter-clockwise, then top face.
        kept.push_back({grid_index(i, j, k), grid_index(i + 1, j, k), grid_index(i + 1, j + 1, k),
                        grid_index(i, j + 1, k), grid_index(i, j, k + 1), grid_index(i + 1, j, k + 1),
                        grid_index(i + 1, j + 1, k + 1), grid_index(i, j + 1, k + 1)});
      }
  if (kept.empty()) throw Error("no lattice cell lies inside the shape", "lattice");
  std::vector<Eigen::Index> remap(static_cast<size_t>(nv.prod()), -1);
  Eigen::Index next = 0;
  for (const auto& cell : kept)
    for (Eigen::Index g : cell)
      if (remap[g] < 0) remap[g] = next++;
  VolumeMesh mesh;
  mesh.kind = ElementKind::Hex8;
  mesh.vertices.resize(next, 3);
  LatticeStructure grid;
  grid.cells = cells;
  grid.origin = bounds.min();
  grid.spacing = h;
  grid.vertex_point.resize(next, 3);
  grid.vertex_copy = Eigen::VectorXi::Zero(next);
  for (int k = 0; k < nv(2); ++k)
    for (int j = 0; j < nv(1); ++j)
      for (int i = 0; i < nv(0); ++i) {
        const Eigen::Index r = remap[grid_index(i, j, k)];
        if (r < 0) continue;
        mesh.vertices.row(r) = (bounds.min() + h.cwiseProduct(Eigen::Vector3d(i, j, k))).transpose();
        grid.vertex_point.row(r) = Eigen::RowVector3i(i, j, k);
      }
  mesh.elements.resize(static_cast<Eigen::Index>(kept.size()), 8);
  grid.element_cell.resize(static_cast<Eigen::Index>(kept.size()), 3);
  for (size_t e = 0; e < kept.size(); ++e) {
    for (int a = 0; a < 8; ++a) mesh.elements(e, a) = static_cast<int>(remap[kept[e][a]]);
    grid.element_cell.row(e) = grid.vertex_point.row(mesh.elements(e, 0));
  }
  mesh.lattice = std::move(grid);
  return mesh;
}

SignedDistance sphere_sdf(const Eigen::Vector3d& center, double radius) {
  return [=](const Eigen::Vector3d& p) { return (p - center).norm() - radius; };
}

SignedDistance cylinder_sdf(const Eigen::Vector3d& center, double radius, double length, int axis) {
  return [=](const Eigen::Vector3d& p) {
    Eigen::Vector3d d = p - center;
    const double along = std::abs(d(axis)) - 0.5 * length;
    d(axis) = 0.0;
    const double radial = d.norm() - radius;
    const Eigen::Vector2d outside(std::max(radial, 0.0), std::max(along, 0.0));
    return std::min(std::max(radial, along), 0.0) + outside.norm();
  };
}

SignedDistance box_sdf(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  return [=](const Eigen::Vector3d& p) {
    const Eigen::Vector3d c = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
    const Eigen::Vector3d q = (p - c).cwiseAbs() - half;
    return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
  };
}

VolumeMesh tetrahedralize_hexes(const VolumeMesh& hexes) {
  if (hexes.kind != ElementKind::Hex8) throw Error("expected a hexahedral mesh", "tetrahedralize");
  // Six tetrahedra sharing the diagonal 0-6, each positively oriented for a right-handed hex.
  static constexpr int kTets[6][4] = {{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6},
                                      {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}};
  VolumeMesh tets;
  tets.kind = ElementKind::Tet4;
  tets.vertices = hexes.vertices;
  tets.elements.resize(6 * hexes.num_elements(), 4);
  for (Eigen::Index e = 0; e < hexes.num_elements(); ++e)
    for (int t = 0; t < 6; ++t)
      for (int a = 0; a < 4; ++a) tets.elements(6 * e + t, a) = hexes.elements(e, kTets[t][a]);
  return tets;
}

}  // namespace sinew
