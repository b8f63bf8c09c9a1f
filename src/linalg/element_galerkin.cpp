#include "sinew/linalg/element_galerkin.hpp"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <bit>
#include <span>

#include "sinew/core/error.hpp"

namespace sinew {
namespace {

// A hexahedron's 8 vertices interpolate from at most 8 coarse vertices each.
constexpr int kMaxCoarse = 8 * kMaxElementMatrixVertices;
// Colours tracked per coarse vertex (a 2x-coarsened hexahedral lattice needs 64); elements that
// find none free are done serially at the end.
constexpr int kMaskWords = 4;

// The coarse vertices of an element's n vertices v: the union of their interpolation rows, sorted.
int coarse_set(const VertexInterpolation& P, const int* v, int n, std::array<int, kMaxCoarse>& out) {
  int m = 0;
  for (int a = 0; a < n; ++a)
    for (int k = P.offsets[static_cast<size_t>(v[a])]; k < P.offsets[static_cast<size_t>(v[a]) + 1]; ++k) {
      const int I = P.coarse[static_cast<size_t>(k)];
      if (std::find(out.begin(), out.begin() + m, I) == out.begin() + m) out[static_cast<size_t>(m++)] = I;
    }
  std::sort(out.begin(), out.begin() + m);
  return m;
}

}  // namespace

ElementGalerkin::ElementGalerkin(const ElementMatrices& A, const VertexInterpolation& P)
    : P_(&P), structure_id_(A.structure_id()) {
  const size_t nc = static_cast<size_t>(P.coarse_vertices);
  if (P.t_offsets.size() != nc + 1) throw Error("the interpolation is not prepared", "element Galerkin product");
  const Eigen::Index ne = A.count();
  // Each element's coarse vertices (CSR), then per coarse vertex its elements.
  std::vector<std::int64_t> set_offsets(static_cast<size_t>(ne) + 1, 0);
  std::vector<int> sets;
  sets.reserve(static_cast<size_t>(ne) * 8);
  std::vector<int> per_coarse(nc + 1, 0);
  std::array<int, kMaxCoarse> s{};
  for (Eigen::Index e = 0; e < ne; ++e) {
    int v[kMaxElementMatrixVertices];
    const int n = A.vertices(e, v);
    for (int a = 0; a < n; ++a)
      if (v[a] < 0 || v[a] >= P.fine_vertices())
        throw Error("an element's vertex is outside the interpolation's fine vertices", "element Galerkin product");
    const int m = coarse_set(P, v, n, s);
    sets.insert(sets.end(), s.begin(), s.begin() + m);
    set_offsets[static_cast<size_t>(e) + 1] = static_cast<std::int64_t>(sets.size());
    for (int k = 0; k < m; ++k) ++per_coarse[static_cast<size_t>(s[static_cast<size_t>(k)]) + 1];
  }
  for (size_t I = 0; I < nc; ++I) per_coarse[I + 1] += per_coarse[I];
  std::vector<Eigen::Index> elements_of(static_cast<size_t>(per_coarse[nc]));
  {
    std::vector<int> fill(per_coarse.begin(), per_coarse.end() - 1);
    for (Eigen::Index e = 0; e < ne; ++e)
      for (std::int64_t k = set_offsets[static_cast<size_t>(e)]; k < set_offsets[static_cast<size_t>(e) + 1]; ++k)
        elements_of[static_cast<size_t>(fill[static_cast<size_t>(sets[static_cast<size_t>(k)])]++)] = e;
  }
  // Pattern: row I holds every coarse vertex of every element that has I (and I itself, for the
  // identity rows of coarse DOFs without a free fine DOF).
  coarse_pattern_.assign(nc, {});
  tbb::parallel_for(size_t{0}, nc, [&](size_t I) {
    auto& row = coarse_pattern_[I];
    for (int k = per_coarse[I]; k < per_coarse[I + 1]; ++k) {
      const Eigen::Index e = elements_of[static_cast<size_t>(k)];
      row.insert(row.end(), sets.begin() + set_offsets[static_cast<size_t>(e)], sets.begin() + set_offsets[static_cast<size_t>(e) + 1]);
    }
    row.push_back(static_cast<int>(I));
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
  });
  // Groups: the elements with the same coarse vertices (on a lattice, the fine cells of one coarse
  // cell), in the order of their first elements. A group's elements run one after another in one
  // task, so only groups need colours: 8 on a lattice (coarse cells two apart share no corner)
  // instead of 64 for single elements, and each colour's pass visits the coarse cells in mesh
  // order, so the rows of C and the kept element matrices it touches come in cache-friendly order.
  auto set_of = [&](Eigen::Index e) {
    return std::span<const int>(sets.data() + set_offsets[static_cast<size_t>(e)],
                                static_cast<size_t>(set_offsets[static_cast<size_t>(e) + 1] - set_offsets[static_cast<size_t>(e)]));
  };
  std::vector<Eigen::Index> by_set(static_cast<size_t>(ne));
  for (Eigen::Index e = 0; e < ne; ++e) by_set[static_cast<size_t>(e)] = e;
  std::stable_sort(by_set.begin(), by_set.end(), [&](Eigen::Index a, Eigen::Index b) {
    const auto sa = set_of(a), sb = set_of(b);
    return std::lexicographical_compare(sa.begin(), sa.end(), sb.begin(), sb.end());
  });
  std::vector<std::pair<size_t, size_t>> groups;  // [begin, end) in by_set; members by element index
  for (size_t i = 0; i < by_set.size();) {
    size_t j = i + 1;
    while (j < by_set.size() && std::ranges::equal(set_of(by_set[i]), set_of(by_set[j]))) ++j;
    groups.emplace_back(i, j);
    i = j;
  }
  std::sort(groups.begin(), groups.end(), [&](const auto& a, const auto& b) { return by_set[a.first] < by_set[b.first]; });
  // Greedy colouring: a group takes the smallest colour none of its coarse vertices has seen.
  std::vector<std::array<std::uint64_t, kMaskWords>> used(nc, std::array<std::uint64_t, kMaskWords>{});
  std::vector<std::vector<int>> colored;
  std::vector<Eigen::Index> serial;
  group_offsets_.assign(1, 0);
  group_elements_.clear();
  group_elements_.reserve(static_cast<size_t>(ne));
  for (const auto& [begin, end] : groups) {
    const int g = static_cast<int>(group_offsets_.size()) - 1;
    group_elements_.insert(group_elements_.end(), by_set.begin() + static_cast<std::ptrdiff_t>(begin),
                           by_set.begin() + static_cast<std::ptrdiff_t>(end));
    group_offsets_.push_back(static_cast<std::int64_t>(group_elements_.size()));
    const auto set = set_of(by_set[begin]);
    std::array<std::uint64_t, kMaskWords> taken{};
    for (const int I : set)
      for (int w = 0; w < kMaskWords; ++w) taken[static_cast<size_t>(w)] |= used[static_cast<size_t>(I)][static_cast<size_t>(w)];
    int color = -1;
    for (int w = 0; w < kMaskWords && color < 0; ++w)
      if (~taken[static_cast<size_t>(w)]) color = 64 * w + std::countr_one(taken[static_cast<size_t>(w)]);
    if (color < 0) {
      serial.insert(serial.end(), by_set.begin() + static_cast<std::ptrdiff_t>(begin), by_set.begin() + static_cast<std::ptrdiff_t>(end));
      continue;
    }
    for (const int I : set) used[static_cast<size_t>(I)][static_cast<size_t>(color / 64)] |= std::uint64_t{1} << (color % 64);
    if (static_cast<size_t>(color) >= colored.size()) colored.resize(static_cast<size_t>(color) + 1);
    colored[static_cast<size_t>(color)].push_back(g);
  }
  colors_ = std::move(colored);
  serial_ = std::move(serial);
}

void ElementGalerkin::compute(const ElementMatrices& A, std::span<const char> fine_free, std::span<const char> coarse_free,
                              BlockSparseMatrix& C) const {
  if (!P_ || A.structure_id() != structure_id_)
    throw Error("the elements changed since the symbolic product", "element Galerkin product");
  if (fine_free.size() != static_cast<size_t>(3 * P_->fine_vertices()) ||
      coarse_free.size() != static_cast<size_t>(3 * P_->coarse_vertices) || C.block_rows() != P_->coarse_vertices)
    throw Error("the DOF masks or the coarse matrix do not match the interpolation", "element Galerkin product");
  const VertexInterpolation& P = *P_;
  C.set_zero();
  // Interpolation weights of the element's free fine DOFs into its coarse set: for vertex a, its
  // entries (position J in the set, weight), and which of its DOFs are free.
  struct Weights {
    int count[kMaxElementMatrixVertices];
    int J[kMaxElementMatrixVertices][kMaxElementMatrixVertices];
    double w[kMaxElementMatrixVertices][kMaxElementMatrixVertices];
    bool free[kMaxElementMatrixVertices][3];
  };
  struct Scratch {
    ElementMatrix K;
    Eigen::MatrixXd T{3 * kMaxElementMatrixVertices, 3 * kMaxCoarse};  // K P_e
    Eigen::MatrixXd Q{3 * kMaxCoarse, 3 * kMaxCoarse};                // P_e^T K P_e
    Eigen::Matrix<double, 24, 24> T24, Tt24, Q24;                     // the same, 8 coarse vertices
    Weights weights;
  };
  tbb::enumerable_thread_specific<Scratch> scratch;
  auto weights = [&](const int* v, int n, const std::array<int, kMaxCoarse>& set, int m, Weights& W) {
    for (int a = 0; a < n; ++a) {
      const size_t va = static_cast<size_t>(v[a]);
      W.count[a] = P.offsets[va + 1] - P.offsets[va];
      if (W.count[a] > kMaxElementMatrixVertices)
        throw Error("a fine vertex interpolates from more than 8 coarse vertices", "element Galerkin product");
      for (int k = 0; k < W.count[a]; ++k) {
        const size_t p = static_cast<size_t>(P.offsets[va] + k);
        W.J[a][k] = static_cast<int>(std::lower_bound(set.begin(), set.begin() + m, P.coarse[p]) - set.begin());
        W.w[a][k] = P.weight[p];
      }
      for (int i = 0; i < 3; ++i) W.free[a][i] = fine_free[3 * va + static_cast<size_t>(i)] != 0;
    }
  };
  auto scatter = [&](const std::array<int, kMaxCoarse>& set, int m, const auto& Q) {
    for (int I = 0; I < m; ++I)
      for (int J = 0; J < m; ++J) {
        const int slot = C.slot(set[static_cast<size_t>(I)], set[static_cast<size_t>(J)]);
        if (slot < 0) throw Error("the coarse matrix's pattern does not match", "element Galerkin product");
        C.block(slot) += Q.template block<3, 3>(3 * I, 3 * J);
      }
  };
  auto element = [&](Eigen::Index e, Scratch& w) {
    int v[kMaxElementMatrixVertices];
    const int n = A.vertices(e, v);
    std::array<int, kMaxCoarse> set{};
    const int m = coarse_set(P, v, n, set);
    A.matrix(e, w.K);
    weights(v, n, set, m, w.weights);
    const Weights& W = w.weights;
    if (n == kMaxElementMatrixVertices && m == kMaxElementMatrixVertices) {
      // A hexahedron inside one coarse cell (every element of a 2x coarsened lattice): fixed
      // sizes. T = K P_e column by column, then Q = P_e^T T = (T^T P_e)^T = T^T P_e (Q is
      // symmetric) column by column from T^T's columns.
      Eigen::Matrix<double, 24, 24>& T = w.T24;
      T.setZero();
      for (int b = 0; b < 8; ++b)
        for (int k = 0; k < W.count[b]; ++k)
          for (int j = 0; j < 3; ++j)
            if (W.free[b][j]) T.col(3 * W.J[b][k] + j) += W.w[b][k] * w.K.col(3 * b + j);
      Eigen::Matrix<double, 24, 24>& Tt = w.Tt24;
      Tt = T.transpose();
      Eigen::Matrix<double, 24, 24>& Q = w.Q24;
      Q.setZero();
      for (int a = 0; a < 8; ++a)
        for (int k = 0; k < W.count[a]; ++k)
          for (int i = 0; i < 3; ++i)
            if (W.free[a][i]) Q.col(3 * W.J[a][k] + i) += W.w[a][k] * Tt.col(3 * a + i);
      scatter(set, m, Q);
      return;
    }
    // T = K P_e: column 3J + j gathers the columns 3b + j of K weighted by w_bJ (free DOFs only).
    auto T = w.T.topLeftCorner(3 * n, 3 * m);
    T.setZero();
    for (int b = 0; b < n; ++b)
      for (int k = 0; k < W.count[b]; ++k)
        for (int j = 0; j < 3; ++j)
          if (W.free[b][j]) T.col(3 * W.J[b][k] + j) += W.w[b][k] * w.K.col(3 * b + j).head(3 * n);
    // Q = P_e^T T, row by row.
    auto Q = w.Q.topLeftCorner(3 * m, 3 * m);
    Q.setZero();
    for (int a = 0; a < n; ++a)
      for (int k = 0; k < W.count[a]; ++k)
        for (int i = 0; i < 3; ++i)
          if (W.free[a][i]) Q.row(3 * W.J[a][k] + i) += W.w[a][k] * T.row(3 * a + i);
    scatter(set, m, Q);
  };
  for (const auto& color : colors_)
    tbb::parallel_for(tbb::blocked_range<size_t>(0, color.size(), 8), [&](const auto& range) {
      Scratch& w = scratch.local();
      for (size_t i = range.begin(); i != range.end(); ++i) {
        const size_t g = static_cast<size_t>(color[i]);
        for (std::int64_t k = group_offsets_[g]; k < group_offsets_[g + 1]; ++k) element(group_elements_[static_cast<size_t>(k)], w);
      }
    });
  for (const Eigen::Index e : serial_) element(e, scratch.local());
  // Coarse DOFs without a free fine DOF: identity rows (their rows and columns are zero).
  for (Eigen::Index I = 0; I < C.block_rows(); ++I)
    for (int i = 0; i < 3; ++i)
      if (!coarse_free[static_cast<size_t>(3 * I + i)]) C.block(C.slot(static_cast<int>(I), static_cast<int>(I)))(i, i) = 1.0;
}

}  // namespace sinew
