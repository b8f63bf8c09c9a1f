#include "sinew/solver/lattice_hierarchy.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <numeric>

#include "sinew/core/error.hpp"

namespace sinew {
namespace {

struct UnionFind {
  explicit UnionFind(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int i) {
    while (parent[static_cast<size_t>(i)] != i) {
      parent[static_cast<size_t>(i)] = parent[static_cast<size_t>(parent[static_cast<size_t>(i)])];
      i = parent[static_cast<size_t>(i)];
    }
    return i;
  }
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[static_cast<size_t>(std::max(a, b))] = std::min(a, b);
  }
  std::vector<int> parent;
};

int corner_index(const Eigen::Vector3i& bits) { return bits(0) + 2 * bits(1) + 4 * bits(2); }

}  // namespace

LatticeLevel lattice_level(const VolumeMesh& mesh) {
  if (!mesh.lattice) throw Error("the mesh has no lattice grid (only box, shape and voxelised lattices keep one)", "multigrid");
  if (mesh.kind != ElementKind::Hex8) throw Error("the lattice's elements are not hexahedra", "multigrid");
  const LatticeStructure& g = *mesh.lattice;
  LatticeLevel level;
  level.vertex_point.resize(static_cast<size_t>(mesh.num_vertices()));
  for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v) level.vertex_point[static_cast<size_t>(v)] = g.vertex_point.row(v).transpose();
  level.cell.resize(static_cast<size_t>(mesh.num_elements()));
  level.corners.resize(static_cast<size_t>(mesh.num_elements()));
  for (Eigen::Index e = 0; e < mesh.num_elements(); ++e) {
    const Eigen::Vector3i c = g.element_cell.row(e).transpose();
    level.cell[static_cast<size_t>(e)] = c;
    std::array<int, 8>& corners = level.corners[static_cast<size_t>(e)];
    corners.fill(-1);
    for (int a = 0; a < 8; ++a) {
      const int v = mesh.elements(e, a);
      const Eigen::Vector3i bits = level.vertex_point[static_cast<size_t>(v)] - c;
      if ((bits.array() < 0).any() || (bits.array() > 1).any() || corners[static_cast<size_t>(corner_index(bits))] >= 0)
        throw Error(fmt::format("element {}'s nodes are not the corners of its grid cell", e), "multigrid");
      corners[static_cast<size_t>(corner_index(bits))] = v;
    }
  }
  return level;
}

LatticeLevel coarsen(const LatticeLevel& fine, VertexInterpolation& P) {
  const size_t nf_cells = fine.cell.size(), nf = fine.vertex_point.size();
  // Fine cells grouped by their coarse grid cell (the parent).
  auto parent = [&](size_t c) -> Eigen::Vector3i { return fine.cell[c].unaryExpr([](int i) { return i >> 1; }); };
  std::vector<int> order(nf_cells);
  std::iota(order.begin(), order.end(), 0);
  auto key = [&](int c) {
    const Eigen::Vector3i p = parent(static_cast<size_t>(c));
    return std::array<int, 3>{p(2), p(1), p(0)};
  };
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return key(a) < key(b); });

  // Connected components of each group: one coarse cell per component.
  std::vector<int> coarse_cell_of(nf_cells, -1);
  std::vector<Eigen::Vector3i> coarse_cell;
  UnionFind cells_uf(nf_cells);
  for (size_t begin = 0; begin < nf_cells;) {
    size_t end = begin + 1;
    while (end < nf_cells && key(order[end]) == key(order[begin])) ++end;
    for (size_t i = begin; i < end; ++i)
      for (size_t j = begin; j < i; ++j) {
        const auto& ci = fine.corners[static_cast<size_t>(order[i])];
        const auto& cj = fine.corners[static_cast<size_t>(order[j])];
        bool shared = false;
        for (int u : ci)
          for (int v : cj) shared |= (u == v);
        if (shared) cells_uf.unite(order[i], order[j]);
      }
    for (size_t i = begin; i < end; ++i) {
      const int root = cells_uf.find(order[i]);
      if (coarse_cell_of[static_cast<size_t>(root)] < 0) {
        coarse_cell_of[static_cast<size_t>(root)] = static_cast<int>(coarse_cell.size());
        coarse_cell.push_back(parent(static_cast<size_t>(order[i])));
      }
      coarse_cell_of[static_cast<size_t>(order[i])] = coarse_cell_of[static_cast<size_t>(root)];
    }
    begin = end;
  }

  // Cells around each fine vertex.
  std::vector<int> vc_offsets(nf + 1, 0), vc_cells;
  for (const auto& corners : fine.corners)
    for (int v : corners) ++vc_offsets[static_cast<size_t>(v) + 1];
  for (size_t v = 0; v < nf; ++v) vc_offsets[v + 1] += vc_offsets[v];
  vc_cells.resize(static_cast<size_t>(vc_offsets.back()));
  {
    std::vector<int> next(vc_offsets.begin(), vc_offsets.end() - 1);
    for (size_t c = 0; c < nf_cells; ++c)
      for (int v : fine.corners[c]) vc_cells[static_cast<size_t>(next[static_cast<size_t>(v)]++)] = static_cast<int>(c);
  }

  // The coarse grid points with a non-zero trilinear weight for fine grid point p, and the
  // weights: per axis, an even coordinate lies on a coarse point, an odd one halfway between two.
  auto for_each_weight = [](const Eigen::Vector3i& p, auto&& f) {
    for (int bz = 0; bz <= (p(2) & 1); ++bz)
      for (int by = 0; by <= (p(1) & 1); ++by)
        for (int bx = 0; bx <= (p(0) & 1); ++bx) {
          const Eigen::Vector3i g((p(0) >> 1) + bx, (p(1) >> 1) + by, (p(2) >> 1) + bz);
          const int odd = (p(0) & 1) + (p(1) & 1) + (p(2) & 1);
          f(g, 1.0 / static_cast<double>(1 << odd));
        }
  };

  // Corner nodes (coarse cell, corner) merged where a fine vertex lies on two coarse cells and
  // takes a weight from that corner in both.
  UnionFind nodes(8 * coarse_cell.size());
  std::vector<int> around;
  for (size_t v = 0; v < nf; ++v) {
    around.clear();
    for (int k = vc_offsets[v]; k < vc_offsets[v + 1]; ++k) around.push_back(coarse_cell_of[static_cast<size_t>(vc_cells[static_cast<size_t>(k)])]);
    std::sort(around.begin(), around.end());
    around.erase(std::unique(around.begin(), around.end()), around.end());
    for (size_t i = 1; i < around.size(); ++i)
      for_each_weight(fine.vertex_point[v], [&](const Eigen::Vector3i& g, double) {
        const int n0 = 8 * around[0] + corner_index(g - coarse_cell[static_cast<size_t>(around[0])]);
        const int ni = 8 * around[i] + corner_index(g - coarse_cell[static_cast<size_t>(around[i])]);
        nodes.unite(n0, ni);
      });
  }

  LatticeLevel coarse;
  coarse.cell = coarse_cell;
  coarse.corners.resize(coarse_cell.size());
  std::vector<int> vertex_of_root(8 * coarse_cell.size(), -1);
  for (size_t c = 0; c < coarse_cell.size(); ++c)
    for (int b = 0; b < 8; ++b) {
      const int root = nodes.find(static_cast<int>(8 * c) + b);
      int& v = vertex_of_root[static_cast<size_t>(root)];
      if (v < 0) {
        v = static_cast<int>(coarse.vertex_point.size());
        coarse.vertex_point.push_back(coarse_cell[c] + Eigen::Vector3i(b & 1, (b >> 1) & 1, (b >> 2) & 1));
      }
      coarse.corners[c][static_cast<size_t>(b)] = v;
    }

  // Each fine vertex interpolates from the corners of the first coarse cell around it.
  P = VertexInterpolation{};
  P.coarse_vertices = coarse.vertices();
  P.offsets.assign(nf + 1, 0);
  for (size_t v = 0; v < nf; ++v) {
    if (vc_offsets[v] < vc_offsets[v + 1]) {
      const int c = coarse_cell_of[static_cast<size_t>(vc_cells[static_cast<size_t>(vc_offsets[v])])];
      for_each_weight(fine.vertex_point[v], [&](const Eigen::Vector3i& g, double w) {
        P.coarse.push_back(coarse.corners[static_cast<size_t>(c)][static_cast<size_t>(corner_index(g - coarse_cell[static_cast<size_t>(c)]))]);
        P.weight.push_back(w);
      });
    }
    P.offsets[v + 1] = static_cast<int>(P.coarse.size());
  }
  P.prepare();
  return coarse;
}

LatticeHierarchy lattice_hierarchy(const VolumeMesh& mesh, Eigen::Index coarsest_vertices, int max_levels) {
  LatticeHierarchy h;
  h.levels.push_back(lattice_level(mesh));
  while (static_cast<int>(h.levels.size()) < max_levels && h.levels.back().vertices() > coarsest_vertices) {
    VertexInterpolation P;
    LatticeLevel next = coarsen(h.levels.back(), P);
    if (4 * next.vertices() > 3 * h.levels.back().vertices()) break;
    h.levels.push_back(std::move(next));
    h.interpolations.push_back(std::move(P));
  }
  return h;
}

}  // namespace sinew
